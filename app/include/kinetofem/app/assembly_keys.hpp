#pragma once
// Case-file keys of the elastic assembly (structure/assembly_over_motion.hpp:
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

// The default chain of the SPEC §1 lever-chain manipulator, a catalogue
// choice (cases/lever_chain_manipulator/README.md): an ISO 606 08B-1 simplex
// roller chain, pitch 12.70 mm, minimum tensile strength 17.8 kN (ISO
// 606:2015, table 1), about 10 times the largest chain tension of the case
// (1.81 kN). ISO 606 gives no stiffness: EA is estimated from the two link
// plates' section at the pin hole, 2 x 1.6 mm x (11.81 - 4.45) mm = 23.6 mm^2
// (plate depth h2 and pin diameter d2 of ISO 606; plate thickness 1.6 mm of
// manufacturers' catalogues) times E = 210 GPa: 4.95e6 N, rounded to 5e6 N.
// An upper estimate: pin-bush contact and clearance add compliance; the
// sensitivity table of docs/verification.md spans 0.25x to 4x.
struct CatalogueChain {
  const char* designation;
  double pitch_m, min_tensile_strength_n, ea_per_strand_n;
};
inline constexpr CatalogueChain kDefaultManipulatorChain{"ISO 606 08B-1", 12.70e-3, 17.8e3, 5.0e6};

void add_manipulator_assembly_keys(std::vector<KeySpec>& schema);
// Empty when assembly.enabled is false. `chain_name`: the model's chain joint
// (empty: the mechanism has none, and chain keys set in the file are an
// error); `drive_name`: the lever's motion drive; H is tracked on `arm_body`
// through the face set `gripper_face`.
std::optional<structure::AssemblyOptions> read_manipulator_assembly(const CaseFile& c, const std::string& chain_name,
                                                                     const std::string& drive_name,
                                                                     const std::string& arm_body,
                                                                     const std::string& gripper_face);

void add_linkage_assembly_keys(std::vector<KeySpec>& schema);
// Empty when assembly.enabled is false. Throws Error naming the key for a
// chain without EA, stiffness keys on joints or drives they do not apply to,
// an assembly point on an unknown body or without its face on a part body.
std::optional<structure::AssemblyOptions> read_linkage_assembly(const CaseFile& c, const mech::MultibodyModel& model,
                                                                 const std::vector<std::string>& bodies_with_parts);

}  // namespace kinetofem::app
