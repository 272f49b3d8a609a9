#pragma once
// An elastic round pin in a bore: its flexibility on the bore's contact
// pressure basis (derivation and error: docs/contact.md, "The elastic pin").
//
// BoreContactSurface takes the pin as rigid: its gap is
//     clearance + n . u_bore - E q.
// An elastic pin adds its own surface's radial displacement under the
// opposite pressure, gap = clearance + n . u_bore - n . u_pin - E q, with
// u_pin the pin's deformation (its rigid motion is q). On the pressure basis
// p(x) = sum_c p_c L_c(x) of the bore's corners this is the pin's condensed
// compliance, added to the bore's:
//     A_pin = Q^T N^T Pi^T G Pi N Q   (corners x corners, m^3/Pa, symmetric, >= 0)
// with
//   Q   the mortar map of the bore's corner functions onto the pin's surface
//       nodes, Q_ac = integral over the bore of N_a(pin)(theta, z) L_c dA: the
//       bore's point at angle theta about the axis and z along it meets the
//       pin's point at the same theta and z (the pin is concentric; its
//       radius is the bore's less the clearance);
//   N   the pin surface nodes' radial unit vectors (the pressure on the pin
//       pushes inwards, -n);
//   Pi  = I - W (R^T W)^-1 R^T, which balances the pressure's resultant (force
//       and moment, all six components) by a uniform body force of the pin's
//       rigid accelerations (W = M R, M the pin's consistent mass, R its six
//       rigid modes): the pin carries the joint's force in from elsewhere
//       along its span, spread like its own mass. Pi^T removes the rigid
//       motion from a displacement (M-orthogonally), so that the pin's
//       translation and tilt are exactly the multipliers q of E;
//   G   the pin's flexibility under a statically determinate (3-2-1)
//       support (its reactions vanish under Pi's self-equilibrated loads).
//
// The pin is meshed here (pin_mesh): a cylinder of HEX20 elements, an O-grid
// (a square core and four curved blocks), its axis the bore's axis, its span
// the bore's extent along the axis. Its model is factorized once, solved for
// the m corner pressures in blocks, and freed; only A_pin is kept.
#include <string>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/bore_contact.hpp"
#include "kinetofem/solver/material.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem {

// A solid round pin of HEX20 elements along z from z = 0 to span_m, its
// axis the z axis (m): an O-grid of a square core (half-side 0.4 of the
// radius) and four curved blocks, `circumferential_elements` around (a
// multiple of 4, >= 8), `radial_elements` across each curved block and
// `axial_elements` along the span. Every node of the lateral surface lies on
// the circle; the lateral faces (QUAD8, outward) are the face set "surface".
// Throws Error for a non-positive size or a bad count.
Mesh pin_mesh(double radius_m, double span_m, int circumferential_elements, int radial_elements,
              int axial_elements);

struct ElasticPinOptions {
  // Elements around the pin; 0: from the bore, about its corner spacing
  // (4 * ceil(2 pi r / (4 h)) with h = sqrt(bore area / corners)), at least 16.
  int circumferential_elements = 0;
  int radial_elements = 0;  // across the O-grid's curved blocks; 0: a quarter of the above, at least 2
  int axial_elements = 0;   // 0: span / h, at least 1
  // Each face of the bore split into this many parts per edge for Q's
  // quadrature (the pin's shape functions are smooth only within the pin's
  // faces, which the bore's faces cross).
  int quadrature_subdivisions = 4;
};

// The flexibility of one elastic pin on a bore's pressure basis.
class ElasticPin {
 public:
  // The pin fills the bore (a surface of `part_mesh`) less `clearance_m`
  // (radius = bore.radius_m() - clearance_m), spans the bore along its axis,
  // and is of `material` (its density only weights the balancing body force;
  // 0 is taken as uniform). Throws Error for a bad material or a clearance not
  // below the bore's radius.
  ElasticPin(const Mesh& part_mesh, const BoreContactSurface& bore, const IsotropicMaterial& material,
             double clearance_m, const Log& log, const ElasticPinOptions& options = {});

  // A_pin, corners x corners of the bore (m^3/Pa): add it to the bore's A.
  const Eigen::MatrixXd& compliance() const { return compliance_; }

  double radius_m() const { return radius_; }
  double span_m() const { return span_; }
  Index node_count() const { return nodes_; }
  int circumferential_elements() const { return circumferential_; }
  // The mortar map's quadrature error: |sum_c Q_ac - integral of N_a over the
  // pin's surface (scaled to the bore's radius)|, summed over the pin's
  // surface nodes, over the bore's area (0 when Q integrates exactly).
  double mapping_error() const { return mapping_error_; }
  double set_up_seconds() const { return seconds_; }

 private:
  Eigen::MatrixXd compliance_;
  double radius_ = 0.0, span_ = 0.0, mapping_error_ = 0.0, seconds_ = 0.0;
  Index nodes_ = 0;
  int circumferential_ = 0;
};

}  // namespace kinetofem::fem
