#pragma once
// The layout of a kinetofem results file (HDF5): group and dataset names,
// shared by ResultsWriter and ResultsFile. These names are a stable interface
// (ParaView state files, h5py scripts and the batch summary depend on them);
// docs/results.md describes the whole layout. Change them only together with
// kFormatVersion.
//
//   /                                attrs format = "kinetofem-results", format_version
//   /provenance                      attrs kinetofem_version, git_commit, created_utc,
//                                    case_path, command_line, units_note; dataset case_text
//   /bodies/<body>/mesh/nodes                          (N, 3) m
//   /bodies/<body>/mesh/blocks/block_<i>/connectivity      (E_i, n) Gmsh order
//   /bodies/<body>/mesh/blocks/block_<i>/connectivity_vtk  (E_i, n) VTK/XDMF order
//   /bodies/<body>/mesh/xdmf_mixed_topology            (only for bodies with > 1 block)
//   /bodies/<body>/mesh/{node_sets,element_sets}/<set>, face_sets/<set>/block_<i>/connectivity
//   /bodies/<body>/static/<field>                      (N, c)   nodal fields
//   /bodies/<body>/element_fields/<field>              (E, c)   one row per element
//   /bodies/<body>/series/time                         (T)      s
//   /bodies/<body>/series/<field>                      (T, N, c) chunked per time step;
//                                                      attr xdmf_geometry = 1 on the (T, N, 3)
//                                                      field that is the per-step geometry
//   /bodies/<body>/envelopes/<field>/value, /step      (N, c), step: index into series/time
//   /mechanism/time                                    (T_m)    s
//   /mechanism/<quantity>                              (T_m, c)
//   /tables/<name>                                     (rows, c) any size; attrs units, components
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post {

inline constexpr const char* kFormatName = "kinetofem-results";
inline constexpr std::int64_t kFormatVersion = 1;

// Row-major values of a field: one row per node (or element, or time), one column per component.
using FieldMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using IndexMatrix = Eigen::Matrix<fem::Index, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Component names for the usual fields (attribute `components` of a dataset).
inline const std::vector<std::string> kVectorComponents = {"x", "y", "z"};
// Stress/strain in Voigt order (xx, yy, zz, xy, yz, zx); the XDMF file writes them as a 6-component
// Matrix (not Tensor6, which the Xdmf2 and Xdmf3 libraries order differently), shown by ParaView as
// XX, YY, ZZ, XY, YZ, XZ.
inline const std::vector<std::string> kVoigtComponents = {"xx", "yy", "zz", "xy", "yz", "zx"};
inline const std::vector<std::string> kPrincipalComponents = {"1", "2", "3"};
// A rotation as Euler parameters (e0 the scalar part) and as a 3x3 matrix written row by row
// (component "xy": row x, column y).
inline const std::vector<std::string> kEulerParameterComponents = {"e0", "e1", "e2", "e3"};
inline const std::vector<std::string> kRotationComponents = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};

namespace layout {
inline constexpr const char* kProvenance = "provenance";
inline constexpr const char* kCaseText = "case_text";
inline constexpr const char* kBodies = "bodies";
inline constexpr const char* kMesh = "mesh";
inline constexpr const char* kNodes = "nodes";
inline constexpr const char* kBlocks = "blocks";
inline constexpr const char* kConnectivity = "connectivity";
inline constexpr const char* kConnectivityVtk = "connectivity_vtk";
inline constexpr const char* kMixedTopology = "xdmf_mixed_topology";
inline constexpr const char* kNodeSets = "node_sets";
inline constexpr const char* kFaceSets = "face_sets";
inline constexpr const char* kElementSets = "element_sets";
inline constexpr const char* kStatic = "static";
inline constexpr const char* kElementFields = "element_fields";
inline constexpr const char* kSeries = "series";
inline constexpr const char* kTime = "time";
inline constexpr const char* kEnvelopes = "envelopes";
inline constexpr const char* kEnvelopeValue = "value";
inline constexpr const char* kEnvelopeStep = "step";
inline constexpr const char* kMechanism = "mechanism";
// Tables of any size (ResultsWriter::write_table); optional, an addition to format version 1.
inline constexpr const char* kTables = "tables";
// Unit-load superposition of a body's motion (load_patterns.hpp).
inline constexpr const char* kLoadPatterns = "load_patterns";
inline constexpr const char* kPatternNames = "names";  // attribute of the group
inline constexpr const char* kPatternCoefficients = "coefficients";
inline constexpr const char* kPatternDisplacement = "elastic_displacement";
inline constexpr const char* kPatternStress = "stress";
inline constexpr const char* kDimensionless = "1";
// Attribute (int64, 1) of the series dataset whose values are also the body's per-step geometry
// (SeriesField::geometry).
inline constexpr const char* kXdmfGeometry = "xdmf_geometry";

// The elastic assembly (pipeline/assembly_over_motion.hpp): its bodies are
// "assembly.<b>", its histories "assembly.*" (docs/results.md).
inline constexpr const char* kAssemblyBodyPrefix = "assembly.";
inline constexpr const char* kAssemblyPointPrefix = "assembly.point.";      // + <P>.displacement, ...
inline constexpr const char* kAssemblyMaxDisplacement = "assembly.max_displacement";
// The elastic pins (joints whose bores sit at different z): "assembly.pin.<joint>." + one of these.
inline constexpr const char* kAssemblyPinPrefix = "assembly.pin.";
inline constexpr const char* kPinBendingStress = "bending_stress";  // Pa, 32 M/(pi d^3), the larger end
inline constexpr const char* kPinShearStress = "shear_stress";      // Pa, 16 V/(3 pi d^2)
inline constexpr const char* kPinDeflection = "deflection";         // m, the pin's own bending and shear

// The vibration of the manipulator over the motion (pipeline/vibration_over_motion.hpp,
// docs/results.md): bodies "vibration.static.<b>", "vibration.lowest.<b>" (mode shapes: meshes
// placed in world coordinates at the pose, static fields mode_<i> and mode_<i>_magnitude,
// i = 1..m), the history kVibrationFrequency (T_m x m, Hz) and tables.
inline constexpr const char* kVibrationBodyPrefix = "vibration.";
inline constexpr const char* kVibrationStaticBodyPrefix = "vibration.static.";  // + <b>: at the static pose
inline constexpr const char* kVibrationLowestBodyPrefix = "vibration.lowest.";  // + <b>: at the lowest pose
inline constexpr const char* kModePrefix = "mode_";  // static fields mode_<i>, mode_<i>_magnitude (i from 1)
inline constexpr const char* kVibrationFrequency = "vibration.frequency";                // history, Hz
inline constexpr const char* kVibrationStaticFrequency = "vibration.static_frequency";   // table m x 1, Hz
inline constexpr const char* kVibrationResponseTime = "vibration.response.time";         // table n x 1, s
inline constexpr const char* kVibrationStopTime = "vibration.response.stop_time";        // table 1 x 1, s
// Tables + <P>.displacement, <P>.quasi_static (n x 3, m, world axes).
inline constexpr const char* kVibrationResponsePointPrefix = "vibration.response.point.";
// Tables (1 x 1) + <P>.settling_time (s after the stop, may be inf), .settling_tolerance (m),
// .amplitude_at_stop (m), .dynamic_amplification (1).
inline constexpr const char* kVibrationPointPrefix = "vibration.point.";
// Optional table (1 x 1, 1): the modal damping ratio zeta of the response.
inline constexpr const char* kVibrationDampingRatio = "vibration.damping_ratio";

// The spatial mechanism (pipeline/spatial_histories.hpp, docs/results.md): the histories
// kBodyHistoryPrefix + <b> + "." + a body quantity,
// kJointHistoryPrefix + <j> + "." + kOnBodyPrefix + <b> + "." + a load quantity,
// kDriveHistoryPrefix + <d> + "." + a drive quantity (or kOnBodyPrefix + <b> + "." + a load quantity),
// the energies and checks below, and per rigid body a moving skeleton body kSkeletonBodyPrefix + <b>.
// The planar histories (pipeline/histories.hpp) use the same prefixes and, where the quantity is
// the same, the same names.
inline constexpr const char* kBodyHistoryPrefix = "body.";
inline constexpr const char* kJointHistoryPrefix = "joint.";
inline constexpr const char* kDriveHistoryPrefix = "drive.";
inline constexpr const char* kOnBodyPrefix = "on_";
// Body quantities (world axes).
inline constexpr const char* kOrigin = "origin";                            // m, the body frame's origin
inline constexpr const char* kEulerParameters = "euler_parameters";         // 1, kEulerParameterComponents
inline constexpr const char* kRotation = "rotation";                        // 1, kRotationComponents: body axes -> world
inline constexpr const char* kVelocity = "velocity";                        // m/s (also a skeleton's nodal field)
inline constexpr const char* kAcceleration = "acceleration";                // m/s^2
inline constexpr const char* kAngularVelocity = "angular_velocity";         // rad/s
inline constexpr const char* kAngularAcceleration = "angular_acceleration"; // rad/s^2
inline constexpr const char* kComPosition = "com_position";                 // m, centre of mass with point masses
inline constexpr const char* kComVelocity = "com_velocity";                 // m/s
inline constexpr const char* kComAcceleration = "com_acceleration";         // m/s^2
// Load quantities: a joint's (or drive's) load on one of its bodies, world axes.
inline constexpr const char* kForceWorld = "force_world";    // N
inline constexpr const char* kMomentWorld = "moment_world";  // N*m, about kLoadPoint
inline constexpr const char* kLoadPoint = "point";           // m, the joint point on that body
// Drive quantities: the driven coordinate (rad or m), its rates, the effort (N*m or N) and power (W).
inline constexpr const char* kDriveCoordinate = "s";
inline constexpr const char* kDriveRate = "s_dot";
inline constexpr const char* kDriveAcceleration = "s_ddot";
inline constexpr const char* kDriveEffort = "effort";
inline constexpr const char* kDrivePower = "power";
// Energies and checks of the run.
inline constexpr const char* kKineticEnergy = "energy.kinetic";                   // J
inline constexpr const char* kPotentialEnergy = "energy.potential";               // J, gravity and springs
inline constexpr const char* kDriftPosition = "check.drift_position";             // m
inline constexpr const char* kDriftVelocity = "check.drift_velocity";             // m/s
inline constexpr const char* kEquilibriumResidual = "check.equilibrium_residual"; // 1
inline constexpr const char* kRedundantRows = "check.redundant_rows";             // 1, constraint rows
// The skeleton of a rigid body: a mesh in its body frame whose series field kPosition (the
// nodes' world coordinates) is its geometry at each output time, so ParaView shows it moving;
// series fields kVelocity and its magnitude (magnitude_name), static field kBodyPosition (the
// nodes' body-frame coordinates, m).
inline constexpr const char* kSkeletonBodyPrefix = "skeleton.";
inline constexpr const char* kBodyPosition = "body_position";

// The fatigue check (pipeline/part_fatigue.hpp): static nodal fields of each
// part's body (docs/results.md).
inline constexpr const char* kFatigueDamage = "fatigue_damage_per_cycle";     // 1
inline constexpr const char* kFatigueLifeCycles = "fatigue_life_cycles";      // cycles, inf: no damage
inline constexpr const char* kFatigueLifeHours = "fatigue_life_h";            // h (the file's edge unit)
inline constexpr const char* kFatigueUtilization = "fatigue_utilization";     // 1
inline constexpr const char* kFatigueDetailCategory = "fatigue_detail_category";  // Pa
inline constexpr const char* kFatigueMaxRange = "fatigue_max_range";          // Pa
inline constexpr const char* kFatiguePlaneNormal = "fatigue_plane_normal";    // 1, 3 components

// Field names: the nodal fields (static/, series/, element_fields/) and envelopes the writers
// put on a body and the readers (post, PNG, CSV, hot spots, XDMF) look up.
inline constexpr const char* kDisplacement = "displacement";                    // m, 3 components
inline constexpr const char* kDisplacementMagnitude = "displacement_magnitude";  // m, |u|
inline constexpr const char* kPosition = "position";        // m, world axes (the assembly's geometry)
inline constexpr const char* kStress = "stress";             // Pa, Voigt (kVoigtComponents)
inline constexpr const char* kVonMises = "von_mises";        // Pa
inline constexpr const char* kPrincipalStress = "principal_stress";  // Pa, kPrincipalComponents
// Pressure of pins in contact with a part's bores, on the bores' nodes (0 elsewhere).
inline constexpr const char* kContactPressure = "contact_pressure";  // Pa
// Prefix of a static field that holds a time-series field's value at the static pose
// ("static_" + kDisplacement), suffix of a vector field's magnitude (<field> + "_magnitude").
inline constexpr const char* kStaticPrefix = "static_";
inline constexpr const char* kMagnitudeSuffix = "_magnitude";
// A part welded from several solids (docs/meshes.md): its mesh's element sets "solid.<name>" and
// seam face/node sets "weld.<a>.<b>" (the prefixes of meshes/part_file.hpp, checked equal by the
// postproc tests), and the element field kSolid: each element's solid, the 0-based index into the
// body's solid names in alphabetical order (dimensionless; absent for a part of one solid).
inline constexpr const char* kSolid = "solid";
inline constexpr const char* kSolidSetPrefix = "solid.";
inline constexpr const char* kWeldSetPrefix = "weld.";
// The extreme an envelope holds (attribute of envelopes/<field>).
inline constexpr const char* kEnvelopeMax = "max";

// "block_<i>", the group of element block i (blocks keep their order).
std::string block_name(size_t index);
// "static_<field>": the static field that holds a series field at the static pose.
std::string static_name(const std::string& field);
// "<field>_magnitude": the magnitude of a vector field.
std::string magnitude_name(const std::string& field);
// "mode_<i>", i from 1: a mode shape's static field (and the mode's column name).
std::string mode_name(int i);
}  // namespace layout

}  // namespace kinetofem::post
