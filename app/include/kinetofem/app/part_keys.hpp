#pragma once
// Case-file keys of the FE parts of a linkage, declared once, and their
// reader: [[part]] (a body's part: a parametric link or a geometry file, its
// length unit, placement and mass properties), [[face_set]] (named faces of a
// CAD file without names, by bounding box), and the face keys of the tables
// that act on a part: [[joint]] face_i / face_j / load, [[motion_drive]] and
// [[force_drive]] face_i / face_j, [[transmission]] input.face_i / input.face_j /
// output.face_i / output.face_j, [[point_mass]] face, [[spring]] face_i /
// face_j, [[point_force]] face. Every key, unit and default: docs/cases.md.
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/pipeline/part_model.hpp"

namespace kinetofem::app {

void add_part_keys(std::vector<KeySpec>& schema);

// One PartSpec per [[part]], with the attachments of every table that acts on
// its body. A load on a body with a part that names no face is an error (the
// part could not carry it); so is a face key on a body without a part.
std::vector<pipeline::PartSpec> read_parts(const CaseFile& c, const mech::MultibodyModel& model);

}  // namespace kinetofem::app
