#pragma once
// Joint types of the planar multibody model and every fact about a type that
// a module outside the constraint equations needs: its case-file name and
// keys, its constraint rows, its reaction, how a part's loads treat it and how
// the 3D elastic assembly ties the two bodies through it.
//
// One table: adding a joint type means a row here and its equations in
// multibody/system.cpp (docs/architecture.md, "How to add"). A `switch` over
// JointType has no `default:`, so a new value is a -Wswitch warning wherever
// a decision is needed.
//
// Usage:
//   const mech::JointFacts& facts = mech::joint_facts(joint.type);
//   if (facts.bearing_pressure) ...; for (int c = 0; c < facts.assembly_held; ++c) ...
//   std::optional<JointType> t = mech::joint_type_named("revolute");
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kinetofem::mech {

enum class JointType {
  Revolute,   // point_i of body_i coincides with point_j of body_j (2 equations)
  Prismatic,  // point_j slides on the line through point_i along axis_i (body_i frame); no relative rotation (2)
  Fixed,      // points coincide and the relative angle stays at its assembled value (3)
  Chain,      // flexible chain hinged to body_i at point_i, wrapped on a roller of radius radius_m
              // fixed to body_j with centre point_j: free length + r * wrapped angle = const (1)
};

inline constexpr std::array all_joint_types = {JointType::Revolute, JointType::Prismatic,
                                               JointType::Fixed, JointType::Chain};

// What Joint::reference holds for a type (and the case-file key that sets it).
enum class JointReference {
  None,   // the type has no reference value
  Angle,  // relative angle theta_j - theta_i, rad (case file: reference_deg)
  Length  // chain: free length + r * wrap angle, m (case file: reference_mm)
};

// How the 3D elastic assembly ties the interfaces of the two bodies.
enum class AssemblyTie {
  None,        // not modelled: the assembly refuses a mechanism with this joint
  Rigid,       // the first assembly_held components (x, y, z, rx, ry, rz, at the joint point)
               // of body_j's interface equal those of body_i's, carried rigidly across
  ChainSpring,  // a tension-only axial spring (EA / free length) from the hinge on the ground
                // to the tangent point on body_j's roller
  Slide         // prismatic: body_j's interface follows body_i's carried rigidly across in the
                // translations across the slide (in the plane and along z) and the three rotations;
                // the translation along the slide (axis_i turned into world) is free, held by a
                // displacement drive on it if any. An elastic body_i (the guide) is tied along
                // its face set at the slider's position (docs/elastic_assembly.md, "Sliders")
};

struct JointFacts {
  const char* name;  // in the case file (joint[].type) and the console

  // Planar constraint: rows, and which of them measure a length (m; else an
  // angle, rad), in the order system.cpp writes them.
  int rows;
  std::array<bool, 3> length_row;

  // Case-file parameters besides the two bodies and points.
  bool has_axis;            // axis_i (joint[].axis)
  bool has_roller;          // radius_m and wrap_ccw (joint[].radius_mm, joint[].wrap)
  JointReference reference;

  // The reaction on body_j carries a moment about the joint point (a
  // revolute joint transmits force only).
  bool reaction_moment;

  // Parts: a bearing pressure may model the pin in its bore; the joint is a
  // pin that carries a part's out-of-plane loads; its end on body_j is always
  // loaded through a distributing coupling (joint[].load does not apply).
  bool bearing_pressure;
  bool out_of_plane_pin;
  bool always_distributing;
  // The joint point on body_i / body_j is a pivot centre (bore or roller)
  // between which a part's span is measured; a chain's hinge end is not.
  bool pivot_i, pivot_j;

  // 3D elastic assembly.
  AssemblyTie assembly_tie;
  int assembly_held;  // Rigid: components held, 6 (welded) or 5 (rotation about z free); Slide: 5
};

namespace joint_tables {
inline constexpr JointFacts revolute{.name = "revolute",
                                     .rows = 2,
                                     .length_row = {true, true, false},
                                     .has_axis = false,
                                     .has_roller = false,
                                     .reference = JointReference::None,
                                     .reaction_moment = false,
                                     .bearing_pressure = true,
                                     .out_of_plane_pin = true,
                                     .always_distributing = false,
                                     .pivot_i = true,
                                     .pivot_j = true,
                                     .assembly_tie = AssemblyTie::Rigid,
                                     .assembly_held = 5};
inline constexpr JointFacts prismatic{.name = "prismatic",
                                      .rows = 2,
                                      .length_row = {true, false, false},
                                      .has_axis = true,
                                      .has_roller = false,
                                      .reference = JointReference::Angle,
                                      .reaction_moment = true,
                                      .bearing_pressure = false,
                                      .out_of_plane_pin = false,
                                      .always_distributing = false,
                                      .pivot_i = false,
                                      .pivot_j = false,
                                      .assembly_tie = AssemblyTie::Slide,
                                      .assembly_held = 5};
inline constexpr JointFacts fixed{.name = "fixed",
                                  .rows = 3,
                                  .length_row = {true, true, false},
                                  .has_axis = false,
                                  .has_roller = false,
                                  .reference = JointReference::Angle,
                                  .reaction_moment = true,
                                  .bearing_pressure = false,
                                  .out_of_plane_pin = false,
                                  .always_distributing = false,
                                  .pivot_i = false,
                                  .pivot_j = false,
                                  .assembly_tie = AssemblyTie::Rigid,
                                  .assembly_held = 6};
inline constexpr JointFacts chain{.name = "chain",
                                  .rows = 1,
                                  .length_row = {true, false, false},
                                  .has_axis = false,
                                  .has_roller = true,
                                  .reference = JointReference::Length,
                                  .reaction_moment = true,
                                  .bearing_pressure = false,
                                  .out_of_plane_pin = false,
                                  .always_distributing = true,
                                  .pivot_i = false,
                                  .pivot_j = true,
                                  .assembly_tie = AssemblyTie::ChainSpring,
                                  .assembly_held = 0};
}  // namespace joint_tables

constexpr const JointFacts& joint_facts(JointType type) {
  switch (type) {
    case JointType::Revolute: return joint_tables::revolute;
    case JointType::Prismatic: return joint_tables::prismatic;
    case JointType::Fixed: return joint_tables::fixed;
    case JointType::Chain: return joint_tables::chain;
  }
  return joint_tables::revolute;  // unreachable for a valid enum value
}

// The type whose case-file name is `name`, if any.
constexpr std::optional<JointType> joint_type_named(std::string_view name) {
  for (JointType type : all_joint_types)
    if (name == joint_facts(type).name) return type;
  return std::nullopt;
}

// Case-file names of the types whose facts pass `takes`, in table order
// (a schema's allowed values, an error message's list).
template <typename Predicate>
std::vector<std::string> joint_type_names(Predicate takes) {
  std::vector<std::string> names;
  for (JointType type : all_joint_types)
    if (takes(joint_facts(type))) names.emplace_back(joint_facts(type).name);
  return names;
}

// The same names as prose: "revolute", "revolute and chain", "revolute, fixed and chain".
template <typename Predicate>
std::string joint_type_list(Predicate takes) {
  const std::vector<std::string> names = joint_type_names(takes);
  std::string text;
  for (std::size_t k = 0; k < names.size(); ++k)
    text += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  return text;
}

}  // namespace kinetofem::mech
