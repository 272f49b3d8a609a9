#pragma once
// Load transfer: a link under a pure rigid-body acceleration balanced at its
// bores is a simply supported beam under a distributed load.
//
// The link (verification/geometry/beam_link.geo: 640 x 40 x 20 mm, pins
// 600 mm apart) translates with a = 100 m/s^2 along y; its d'Alembert body
// force -rho a is balanced by the two pin reactions m a / 2 (distributing
// couplings on the bores), the body held by a 3-2-1 support that carries
// nothing. Reference (beam theory, e.g. Gere & Timoshenko, Mechanics of
// Materials): span L = 0.6 m between the pins, overhangs e = 0.02 m, uniform
// load q = rho A a with A = h t (the bores lie on the supports, so removing
// their material changes reactions and load together and not the mid-span
// moment):
//   M_mid = R L / 2 - q (L/2 + e)^2 / 2,  R = q (L + 2e) / 2,
//   sigma_xx = M_mid (h/2) / I,  I = t h^3 / 12.
// Elasticity corrections at L/h = 15 are ~0.1 %; tolerance 2 % on
// the mean recovered nodal stress of the extreme fibres at mid-span. The
// body force points along -y and the pins push +y: the beam sags towards -y
// between them, so the +y fibre is in compression.
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::verification {

struct AcceleratedLink {
  double acceleration_mps2 = 100.0;
  double span_m = 0.6, overhang_m = 0.02, depth_m = 0.04, thickness_m = 0.02;

  // sigma_xx = M_mid (h/2) / I of the header for density rho (Pa).
  double beam_stress_pa(double density_kg_m3) const;
};

inline constexpr double kBeamTheoryTolerance = 0.02;  // relative: see above

// beam_link.geo meshed with TET10 of 6 mm.
fem::Mesh beam_link_mesh();

// Solved on `mesh` (beam_link_mesh(); default material): the beam-theory
// stress, and the mean nodal sigma_xx of the nodes within 4 mm of mid-span on
// the fibres y = +h/2 (top) and y = -h/2 (bottom).
struct AcceleratedLinkResult {
  double beam_stress_pa = 0.0;
  double top_pa = 0.0, bottom_pa = 0.0;
  int top_nodes = 0, bottom_nodes = 0;
};
AcceleratedLinkResult solve_accelerated_link(const fem::Mesh& mesh, const AcceleratedLink& link = {});

}  // namespace kinetofem::verification
