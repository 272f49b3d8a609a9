#pragma once
// The names of the SPEC §1/§2 manipulator preset, written once: its bodies,
// joints, drive and points (make_manipulator_model, manipulator_models.hpp),
// the face sets of its link meshes that the preset's parts attach to
// (meshes/lever.hpp, meshes/arm.hpp), and its default chain. The preset's
// parts (pipeline/manipulator_preset.hpp), the manipulator case type and the
// post-processor use these; the results file shows them as body, history and
// point names, so they are part of its layout (docs/results.md).
namespace kinetofem::mech::manipulator {

// Bodies (also the part and results body names).
inline constexpr const char* kFrame = "frame";
inline constexpr const char* kLever = "lever";    // link 1
inline constexpr const char* kArm = "arm";        // link 2 (with roller, or the coupler)
inline constexpr const char* kRocker = "rocker";  // link 3, lever manipulator only

// Joints: A0 (frame-lever), A (lever-arm); the lever-chain manipulator adds
// the chain (frame B0 to the arm's roller), the lever manipulator B
// (arm-rocker) and B0 (frame-rocker).
inline constexpr const char* kJointA0 = "A0";
inline constexpr const char* kJointA = "A";
inline constexpr const char* kChain = "chain";
inline constexpr const char* kJointB = "B";
inline constexpr const char* kJointB0 = "B0";

// The motion drive of the lever's angle against the frame.
inline constexpr const char* kLeverDrive = "lever_drive";

// Points of the bodies (frames: manipulator_models.hpp). H: the gripper point
// on the arm, where the payload sits and whose path the study is about.
inline constexpr const char* kOrigin = "origin";
inline constexpr const char* kPointA = "A";
inline constexpr const char* kPointB = "B";
inline constexpr const char* kPointB0 = "B0";
inline constexpr const char* kPointC = "C";
inline constexpr const char* kPointH = "H";

// Point masses at H.
inline constexpr const char* kGripperMass = "gripper";
inline constexpr const char* kCastingMass = "casting";

// Face sets of the link meshes the preset's joints and masses attach to.
inline constexpr const char* kBoreA0 = "bore_A0";  // lever and rocker: the bore at the frame pin
inline constexpr const char* kBoreA = "bore_A";    // lever and rocker: the far bore; arm: the bore at A
inline constexpr const char* kBoreB = "bore_B";    // coupler: the bore at B
inline constexpr const char* kRollerRim = "roller_rim";
inline constexpr const char* kGripperMount = "gripper_mount";

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
inline constexpr CatalogueChain kDefaultChain{"ISO 606 08B-1", 12.70e-3, 17.8e3, 5.0e6};

}  // namespace kinetofem::mech::manipulator
