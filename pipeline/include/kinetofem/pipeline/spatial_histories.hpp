#pragma once
// Stage "write the spatial mechanism": a run of the spatial multibody core
// (mechanisms/spatial/results.hpp) into a results file, as histories over the
// output times and as a skeleton of every rigid body that ParaView shows moving.
// Names: postproc/results_layout.hpp; the whole layout: docs/results.md.
//
// Units SI, world axes (z as the model has it) unless a name says body.
//
// Histories (/mechanism/<name>, one row per frame of the run, at the frames' times):
//   body.<b>.origin                       (3) m        the body frame's origin
//   body.<b>.euler_parameters             (4) 1        e0..e3 of R, the rotation body axes -> world
//   body.<b>.rotation                     (9) 1        R row by row (xx, xy, xz, yx, ...):
//                                                      x_world = origin + R x_body
//   body.<b>.velocity, acceleration       (3) m/s, m/s^2     of the origin
//   body.<b>.angular_velocity, angular_acceleration (3) rad/s, rad/s^2
//   body.<b>.com_position, com_velocity, com_acceleration (3) the centre of mass with point masses
//   joint.<j>.on_<b>.force_world          (3) N        the joint's load on body b, for both bodies
//   joint.<j>.on_<b>.moment_world         (3) N*m      about the joint point on b
//   joint.<j>.on_<b>.point                (3) m        that point
//   drive.<d>.s, s_dot, s_ddot            (1) rad, rad/s, rad/s^2 (rotation) or m, m/s, m/s^2 (translation)
//   drive.<d>.effort                      (1) N*m or N on body_j, reacted on body_i
//   drive.<d>.power                       (1) W        effort * s_dot
//   drive.<d>.on_<b>.force_world, moment_world, point   the drive's load on each of its bodies
//   energy.kinetic, energy.potential      (1) J        (potential: gravity and springs)
//   check.drift_position (m), check.drift_velocity (m/s), check.equilibrium_residual (1),
//   check.redundant_rows (1)
// A force drive (a motor: a load, not a constraint row, so not in the frames)
// gets drive.<d>.effort alone, from spatial::System::force_drive_effort at each
// frame. These are the planar histories' names (pipeline/histories.hpp) where
// the quantity is the same, so the mechanism loads picture (joint force
// magnitudes, drive efforts) and the CSV export read a spatial run as they read
// a planar one. Names keep letters, digits, '_', '-' and '.'; any other
// character becomes '_'.
//
// Skeleton: a body "skeleton.<b>" per rigid body (the ground too), a TET4 mesh
// in the body frame:
//   nodes     the body origin (node 0), then every named point in name order
//             (a point within kSkeletonMergeFraction of the characteristic
//             length of an earlier node is that node), then 4 per bone;
//             node sets "origin" and one per named point hold its node;
//   bones     the edges of the shortest tree through those nodes (Prim's,
//             from the origin: a point's bone comes from the nearest node
//             already in the tree, so points on a line make a chain), each an
//             octahedron of 4 TET4 with its two nodes as tips and a square
//             section at kSkeletonRingFraction of the way from the tree's
//             side, half-diagonal min(kSkeletonWidthPerLength * bone length,
//             kSkeletonWidthPerModel * characteristic length);
//   a body with one node: an octahedron of half-size kSkeletonWidthPerModel *
//             characteristic length about it, tips on the body's z axis.
// Fields: the series position (N x 3, m, world: origin + R x_body; the
// geometry of each output time, so the body moves in ParaView), velocity
// (N x 3, m/s, world: the rigid-body velocity of each node) and
// velocity_magnitude (N x 1, m/s: a scalar to colour by, and for
// `kinetofem post --field`), and the static body_position (N x 3, m, body
// axes: the node's coordinates in its body frame, which do not change).
//
// Sets the mechanism time grid to the frames' times (ResultsWriter::set_mechanism_time,
// once per file): a caller with histories of its own on the same times writes them after.
#include <vector>

#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::pipeline {

// Skeleton sizes (see above), as fractions.
inline constexpr double kSkeletonRingFraction = 0.2;
inline constexpr double kSkeletonWidthPerLength = 0.1;
inline constexpr double kSkeletonWidthPerModel = 0.02;
inline constexpr double kSkeletonMergeFraction = 1e-9;

// Throws Error if the run has no frames, or a frame does not match the model
// (body count, joint count).
void write_spatial_mechanism_histories(post::ResultsWriter& writer, const mech::spatial::Model& model,
                                       const mech::spatial::Results& results);

// The skeleton mesh of body `body` of the model (body frame, m), as above.
fem::Mesh spatial_skeleton_mesh(const mech::spatial::Model& model, std::size_t body);

}  // namespace kinetofem::pipeline
