#pragma once
// from_planar — a planar MultibodyModel (multibody/model.hpp) lifted into the
// spatial core (spatial::Model), so that a planar linkage can run through
// either core and their results can be compared.
//
// The lift, SI units throughout:
//   plane       the planar world (x, y) is the spatial z = 0 plane; a body
//               frame at (x, y, theta) becomes the frame at (x, y, 0) turned
//               by theta about z; body points, centres of mass and point
//               masses get z = 0.
//   inertia     I_zz is the planar centroidal inertia; the out-of-plane
//               moments take the polar rule of a lamina, I_xx = I_yy = I_zz / 2,
//               no products (a stated choice: the planar model has none).
//               Why it does not change the planar reactions: in planar motion
//               w = (0, 0, w_z) and w' = (0, 0, w_z'), so I_xx and I_yy
//               multiply zeros; with no xz, yz products J w is along z and the
//               gyroscopic term w x J w vanishes, so the in-plane equations
//               are the planar ones whatever I_xx, I_yy > 0 are. (Point masses
//               at z = 0 add no xz, yz products either.) They only keep the
//               mass matrix positive definite.
//   joints      revolute: axis z on both bodies (5 rows); prismatic: axis_i in
//               the plane, h_j the same direction carried into body_j at the
//               held relative angle, f_i = f_j = z (5 rows); fixed: axes z
//               (6 rows); chain: the spatial chain row in the z = 0 plane,
//               same hinge, roller, radius, wrap and reference (1 row). The
//               reference directions f_i, f_j are the bodies' x axes (z for
//               the prismatic), so a relative angle about z is
//               theta_j - theta_i as in the planar core.
//   drives      Angle -> a Rotation drive on the revolute joint between the
//               same two bodies in the same order; Displacement -> a
//               Translation drive on the prismatic joint between the same
//               bodies with the same points and axis; the law and s_0 shared.
//               Force drives alike, with their laws (Constant, DcMotor,
//               PdServo -> EffortLaw) and parameters.
//   loads       gravity (g_x, g_y, 0); point forces (F_x, F_y, 0); springs
//               and dampers unchanged.
// Joints and drives keep their names and order, so Frame::joints and
// Frame::drives line up with the planar frames'.
//
// The out-of-plane rows (z of each point and the two axis rows of each
// revolute) are redundant in a closed planar loop (3 per loop, results.hpp
// takes the minimum-norm multipliers, which carry nothing under in-plane
// loads); the in-plane rows are the planar ones.
//
// Not lifted (an Error naming the feature and the model): transmissions, and
// a drive whose coordinate is not a joint's as described above. Why no
// transmission: the spatial core measures a relative angle as atan2 of body
// vectors, periodic in 2 pi, and s_out - i s_in is not periodic for a
// non-integer ratio i; the row would need the joints' winding counts (the
// SPEC §4 belt arm turns its output eight times), which the planar core's
// absolute angles carry and the stateless spatial System does not.
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"

namespace kinetofem::mech::spatial {

Model from_planar(const MultibodyModel& planar);

}  // namespace kinetofem::mech::spatial
