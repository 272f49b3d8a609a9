#pragma once
// Multibody models of the two casting-extractor manipulators (SPEC §1, §2),
// built from the synthesis geometry, the links' mass properties and a motion
// law of lever 1.
//
// Body frames (the FE meshes of the links use the same frames):
//   frame  (ground)  world frame: origin A0, pin axes along z; B0 = (r, a - b0)
//   lever  (link 1)  origin at A0; A at (0, a): the lever lies on +y in the
//                    design position (dphi = 0)
//   arm    (link 2)  origin at A (the roller centre / coupler pin); in the
//                    design position its axes are the world's: C = (-c, 0),
//                    H = (-c, h); lever manipulator: B = (r, 0)
//   rocker (link 3, lever manipulator only) origin at B0; B at (0, b0): on +y
//                    in the design position
// Joints: "A0" (frame-lever), "A" (lever-arm), and either "chain" (frame B0 to
// the arm's roller of radius r, SPEC §1) or "B" (arm-rocker) and "B0"
// (frame-rocker) for the four-bar (SPEC §2). Drive "lever_drive": the lever's
// angle against the frame follows dphi(t) = law(t) from the design position.
// Point masses "gripper" and "casting" sit at H on the arm.
#include <memory>

#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"

namespace kinetofem::mech {

enum class ManipulatorType { LeverChain, Lever };

struct LinkInertia {
  double mass_kg = 0.0;
  Eigen::Vector2d com_body = Eigen::Vector2d::Zero();
  double inertia_kgm2 = 0.0;  // about the centre of mass, axis z
};

struct ManipulatorDefinition {
  ManipulatorType type = ManipulatorType::LeverChain;
  LeverChainGeometry geometry;  // a, c, h, r and the derived b0, l0, alpha0
  LinkInertia lever, arm, rocker;  // rocker: lever manipulator only
  double gripper_mass_kg = 0.0;
  double casting_mass_kg = 0.0;
  Eigen::Vector2d gravity_m_s2{0.0, -9.80665};  // world frame
  std::shared_ptr<const MotionLaw> lever_motion;  // dphi(t), rad
};

MultibodyModel make_manipulator_model(const ManipulatorDefinition& definition);

}  // namespace kinetofem::mech
