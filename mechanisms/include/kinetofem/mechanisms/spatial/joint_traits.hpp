#pragma once
// Joint types of the spatial multibody core and the facts about each type in
// one table: its name, its constraint rows (and which of them measure a
// length), which drives it takes and which reaction components it carries.
// Adding a type means a row here and its equations in spatial/system.cpp; a
// `switch` over JointType has no `default:`, so a new value is a -Wswitch
// warning wherever a decision is needed.
//
// Joint frame (model.hpp): body_i carries the point P_i and the unit axis h_i
// with two perpendicular unit vectors f_i, g_i = h_i x f_i; body_j carries P_j,
// h_j and f_j (all in body axes, turned into world by the body's rotation).
#include <array>
#include <optional>
#include <string_view>

namespace kinetofem::mech::spatial {

enum class JointType {
  Spherical,    // P_i = P_j (3 rows)
  Revolute,     // P_i = P_j, h_j parallel to h_i (5)
  Prismatic,    // P_j on the line through P_i along h_i, h_j parallel to h_i, no rotation about h_i (5)
  Cylindrical,  // P_j on the line through P_i along h_i, h_j parallel to h_i (4)
  Universal,    // P_i = P_j, the cross axes h_i and h_j stay perpendicular (4)
  Fixed,        // P_i = P_j, no relative rotation (6)
  Chain,        // SPEC §1's chain in the plane normal to h_i: hinged to body_i at P_i, wrapped on a
                // roller of radius r fixed to body_j with centre P_j; free length + r * wrapped angle
                // is constant (1)
};

inline constexpr std::array all_joint_types = {JointType::Spherical,   JointType::Revolute,  JointType::Prismatic,
                                               JointType::Cylindrical, JointType::Universal, JointType::Fixed,
                                               JointType::Chain};

struct JointFacts {
  const char* name;
  // Constraint rows in the order system.cpp writes them, and which of them
  // measure a length (m); the others are dot products or angles (1, rad).
  int rows;
  std::array<bool, 6> length_row;
  // The relative coordinates a motion drive can act on.
  bool drives_rotation;     // angle of f_j from f_i about h_i (rad)
  bool drives_translation;  // h_i . (P_j - P_i) (m)
  // A rotation reference about h_i (rad): the relative angle the joint holds.
  bool holds_rotation;
  // A length reference (m): the chain's free length + r * wrapped angle.
  bool holds_length;
  // Reaction components carried (forces + moments = rows): forces across the
  // axis (f_i, g_i) and, when 3, along h_i; moments about f_i, g_i and, when 3,
  // about h_i; the universal joint's one moment is about h_i x h_j. The others
  // are zero in the reaction to round-off. The chain's one force is its
  // tension along the chain; on the roller it acts at the tangent point, so its
  // moment about the roller centre P_j (r times the tension) is that force's
  // arm, not a component of its own (zero for r = 0, a plain tie).
  int forces;
  int moments;
};

namespace joint_tables {
inline constexpr JointFacts spherical{.name = "spherical",
                                      .rows = 3,
                                      .length_row = {true, true, true, false, false, false},
                                      .drives_rotation = false,
                                      .drives_translation = false,
                                      .holds_rotation = false,
                                      .holds_length = false,
                                      .forces = 3,
                                      .moments = 0};
inline constexpr JointFacts revolute{.name = "revolute",
                                     .rows = 5,
                                     .length_row = {true, true, true, false, false, false},
                                     .drives_rotation = true,
                                     .drives_translation = false,
                                     .holds_rotation = false,
                                     .holds_length = false,
                                     .forces = 3,
                                     .moments = 2};
inline constexpr JointFacts prismatic{.name = "prismatic",
                                      .rows = 5,
                                      .length_row = {false, false, true, true, false, false},
                                      .drives_rotation = false,
                                      .drives_translation = true,
                                      .holds_rotation = true,
                                      .holds_length = false,
                                      .forces = 2,
                                      .moments = 3};
inline constexpr JointFacts cylindrical{.name = "cylindrical",
                                        .rows = 4,
                                        .length_row = {false, false, true, true, false, false},
                                        .drives_rotation = true,
                                        .drives_translation = true,
                                        .holds_rotation = false,
                                        .holds_length = false,
                                        .forces = 2,
                                        .moments = 2};
inline constexpr JointFacts universal{.name = "universal",
                                      .rows = 4,
                                      .length_row = {true, true, true, false, false, false},
                                      .drives_rotation = false,
                                      .drives_translation = false,
                                      .holds_rotation = false,
                                      .holds_length = false,
                                      .forces = 3,
                                      .moments = 1};
inline constexpr JointFacts fixed{.name = "fixed",
                                  .rows = 6,
                                  .length_row = {true, true, true, false, false, false},
                                  .drives_rotation = false,
                                  .drives_translation = false,
                                  .holds_rotation = true,
                                  .holds_length = false,
                                  .forces = 3,
                                  .moments = 3};
inline constexpr JointFacts chain{.name = "chain",
                                  .rows = 1,
                                  .length_row = {true, false, false, false, false, false},
                                  .drives_rotation = false,
                                  .drives_translation = false,
                                  .holds_rotation = false,
                                  .holds_length = true,
                                  .forces = 1,
                                  .moments = 0};
}  // namespace joint_tables

constexpr const JointFacts& joint_facts(JointType type) {
  switch (type) {
    case JointType::Spherical: return joint_tables::spherical;
    case JointType::Revolute: return joint_tables::revolute;
    case JointType::Prismatic: return joint_tables::prismatic;
    case JointType::Cylindrical: return joint_tables::cylindrical;
    case JointType::Universal: return joint_tables::universal;
    case JointType::Fixed: return joint_tables::fixed;
    case JointType::Chain: return joint_tables::chain;
  }
  return joint_tables::spherical;  // unreachable for a valid enum value
}

constexpr std::optional<JointType> joint_type_named(std::string_view name) {
  for (JointType type : all_joint_types)
    if (name == joint_facts(type).name) return type;
  return std::nullopt;
}

}  // namespace kinetofem::mech::spatial
