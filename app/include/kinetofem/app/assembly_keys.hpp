#pragma once
// Case-file keys of the elastic assembly (pipeline/assembly_over_motion.hpp:
// the linkage as one structure held by the ground), declared once, and their
// readers. Every key, unit and default: docs/cases.md.
//
//   manipulator  [assembly] enabled, coupling, chain_ea_per_strand_n,
//                chain_strands, drive_stiffness_n_m_per_rad (the gripper
//                point H is tracked on the arm's gripper mount)
//   linkage      [assembly] enabled, coupling; [[joint]] ea_per_strand_n,
//                strands (chains); [[motion_drive]] stiffness_n_m_per_rad;
//                [[assembly_point]] name, body, point, face
#include <optional>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::app {

void add_manipulator_assembly_keys(std::vector<KeySpec>& schema);
// Empty when assembly.enabled is false. The preset's names
// (mechanisms/manipulator_names.hpp): `with_chain`: the lever-chain
// manipulator's chain joint (false: the lever manipulator, and chain keys set
// in the file are an error); the lever's drive; H tracked on the arm through
// its gripper mount.
std::optional<structure::AssemblyOptions> read_manipulator_assembly(const CaseFile& c, bool with_chain);

void add_linkage_assembly_keys(std::vector<KeySpec>& schema);
// Empty when assembly.enabled is false. Throws Error naming the key for a
// chain without EA, stiffness keys on joints or drives they do not apply to,
// an assembly point on an unknown body or without its face on a part body.
std::optional<structure::AssemblyOptions> read_linkage_assembly(const CaseFile& c, const mech::MultibodyModel& model,
                                                                 const std::vector<std::string>& bodies_with_parts);

}  // namespace kinetofem::app
