#include "kinetofem/verification/persson_pin.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kinetofem/solver/bore_contact.hpp"
#include "kinetofem/solver/bore_contact_pin.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::verification {

namespace {

using namespace kinetofem::fem;
constexpr double kPi = std::numbers::pi;

constexpr double kHoleRadius = 0.010, kOuterRadius = 0.200, kThickness = 0.001;
constexpr int kAround = 192, kAcross = 38;

// The annular plate, HEX20, graded from the hole (first element as long
// radially as around) to the outer radius; face set "hole"; held in x and y
// on the outer rim, in z on its mid-plane nodes.
FeModel annular_plate() {
  FeModel fe;
  const double first = kHoleRadius * 2 * kPi / kAround;
  // Geometric growth g with first * (g^n - 1) / (g - 1) = outer - hole.
  double lo = 1.0001, hi = 2.0;
  for (int k = 0; k < 200; ++k) {
    const double g = 0.5 * (lo + hi);
    (first * (std::pow(g, kAcross) - 1) / (g - 1) > kOuterRadius - kHoleRadius ? hi : lo) = g;
  }
  const double growth = 0.5 * (lo + hi);
  std::vector<double> radius = {kHoleRadius};  // at double resolution: corners and mid-sides
  for (int i = 0; i < kAcross; ++i) {
    const double h = first * std::pow(growth, i);
    radius.push_back(radius.back() + h / 2);
    radius.push_back(radius.back() + h / 2);
  }
  radius.back() = kOuterRadius;
  const int around = 2 * kAround, across = int(radius.size()), levels = 3;
  auto node = [&](int i, int j, int l) { return Index((l * across + j) * around + (i % around)); };
  fe.mesh.nodes.resize(Index(around * across * levels), 3);
  for (int l = 0; l < levels; ++l)
    for (int j = 0; j < across; ++j)
      for (int i = 0; i < around; ++i) {
        const double phi = 2 * kPi * i / around;
        fe.mesh.nodes.row(node(i, j, l)) << radius[size_t(j)] * std::cos(phi), radius[size_t(j)] * std::sin(phi),
            kThickness * l / 2;
      }
  // HEX20 (mesh.hpp numbering) of lattice cells: xi around, eta outwards, zeta up.
  constexpr int offsets[20][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2},
                                  {0, 2, 2}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0},
                                  {2, 2, 1}, {0, 2, 1}, {1, 0, 2}, {0, 1, 2}, {2, 1, 2}, {1, 2, 2}};
  ElementBlock hexes{ElementType::Hex20, {}};
  FaceBlock hole{FaceType::Quad8, {}};
  for (int i = 0; i < kAround; ++i)
    for (int j = 0; j < kAcross; ++j) {
      // xi around and eta outwards is left-handed with z up: take eta
      // outwards as the first axis.
      for (const auto& o : offsets) hexes.connectivity.push_back(node(2 * i + o[1], 2 * j + o[0], o[2]));
    }
  // The hole's faces (eta = 0 side), outward from the plate (towards the axis).
  for (Index e = 0; e < Index(kAround * kAcross); e += kAcross) {
    const auto nodes = hexes.element(e);
    for (int f = 0; f < faces_per_element(ElementType::Hex20); ++f) {
      const auto local = element_face_nodes(ElementType::Hex20, f);
      bool on_hole = true;
      for (const int a : local)
        on_hole = on_hole && std::abs(fe.mesh.nodes.row(nodes[size_t(a)]).head<2>().norm() - kHoleRadius) < 1e-12;
      if (on_hole)
        for (const int a : local) hole.connectivity.push_back(nodes[size_t(a)]);
    }
  }
  DisplacementSupport rim{"outer rim", {}, {true, true, false}};
  DisplacementSupport mid{"outer rim, mid-plane", {}, {false, false, true}};
  for (int l = 0; l < levels; ++l)
    for (int i = 0; i < around; ++i)
      if (l != 1 || i % 2 == 0) rim.nodes.push_back(node(i, across - 1, l));
  for (int i = 0; i < around; i += 2) mid.nodes.push_back(node(i, across - 1, 1));
  // Only the lattice points that are element nodes (not the faces' and
  // cells' centres), renumbered in order.
  std::vector<Index> number(size_t(fe.mesh.nodes.rows()), -1);
  for (const Index n : hexes.connectivity) number[size_t(n)] = 0;
  Index used = 0;
  for (auto& n : number)
    if (n == 0) n = used++;
  NodeCoordinates nodes(used, 3);
  for (size_t n = 0; n < number.size(); ++n)
    if (number[n] >= 0) nodes.row(number[n]) = fe.mesh.nodes.row(Index(n));
  fe.mesh.nodes = nodes;
  for (auto* list : {&hexes.connectivity, &hole.connectivity, &rim.nodes, &mid.nodes})
    for (Index& n : *list) n = number[size_t(n)];
  std::sort(rim.nodes.begin(), rim.nodes.end());
  fe.mesh.blocks.push_back(std::move(hexes));
  fe.mesh.face_sets["hole"] = {std::move(hole)};
  fe.mesh.validate();
  fe.supports = {rim, mid};
  return fe;
}

}  // namespace

double persson_clearance_ratio(double eps) {
  const double s = std::sin(eps / 2), c = std::cos(eps / 2);
  return 2 / kPi * (std::pow(c, 4) / (s * s) * (1 + std::log(c)) - s * s);
}

double persson_peak_ratio(double eps) {
  const double s = std::sin(eps / 2), c = std::cos(eps / 2);
  return (2 * s + std::pow(c, 4) / (2 * s * s) * std::log((1 + s) / (1 - s))) / kPi;
}

double persson_half_angle(double clearance_ratio) {
  double lo = 1e-6, hi = 2 * kPi / 3;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (persson_clearance_ratio(mid) > clearance_ratio ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct PerssonPlate::Impl {
  const Log& log;
  FeModel fe = annular_plate();
  LinearStaticAnalysis analysis{fe, log};
  BoreContactSurface hole{fe.mesh, "hole", Eigen::Vector3d(0, 0, kThickness / 2), Eigen::Vector3d::UnitZ()};
  Eigen::MatrixXd compliance = condense_contact(analysis, {&hole}, Eigen::MatrixXd::Zero(3 * fe.mesh.node_count(), 0))
                                   .compliance;
  explicit Impl(const Log& l) : log(l) {}

  // The contact of a pin (elastic or rigid) of that clearance: peak,
  // half-angle, the corners at the arc's edge.
  void contact(double clearance_m, double force_n, bool elastic, PerssonPinResult& r) const {
    Eigen::MatrixXd A = compliance;
    if (elastic) {
      ElasticPinOptions options;
      options.circumferential_elements = 100;
      options.radial_elements = 6;
      options.axial_elements = 1;
      const ElasticPin pin(fe.mesh, hole, fe.material, clearance_m, log, options);
      A += pin.compliance();
      r.pin_mapping_error = pin.mapping_error();
    }
    const Eigen::VectorXd b = clearance_m * hole.corner_area_m2();
    const ContactSolution s = solve_contact(A, b, hole.rigid_pin_map(), Eigen::Vector4d(force_n, 0, 0, 0), {});
    r.resultant_error = std::max(r.resultant_error, s.resultant_error);
    double peak = 0.0, last_in = 0.0, first_out = kPi;
    for (Index k = 0; k < hole.size(); ++k)
      if (s.pressure[k] > 0) {
        peak = std::max(peak, s.pressure[k]);
        last_in = std::max(last_in, std::abs(hole.angle_rad()[k]));
      }
    for (Index k = 0; k < hole.size(); ++k) {
      const double angle = std::abs(hole.angle_rad()[k]);
      if (!(s.pressure[k] > 0) && angle > last_in) first_out = std::min(first_out, angle);
    }
    // The edge lies between the last corner in contact and the first open
    // one: their midpoint, within half a corner spacing.
    if (elastic) {
      r.peak_pa = peak;
      r.last_in_rad = last_in;
      r.first_out_rad = first_out;
      r.half_angle_rad = 0.5 * (last_in + first_out);
    } else {
      r.rigid_peak_pa = peak;
      r.rigid_half_angle_rad = 0.5 * (last_in + first_out);
    }
  }
};

PerssonPlate::PerssonPlate(const Log& log) : impl_(std::make_unique<Impl>(log)) {}
PerssonPlate::~PerssonPlate() = default;

double PerssonPlate::hole_radius_m() { return kHoleRadius; }
double PerssonPlate::thickness_m() { return kThickness; }

PerssonPinResult PerssonPlate::solve(double clearance_m, double force_n) const {
  PerssonPinResult r;
  r.clearance_m = clearance_m;
  r.force_n = force_n;
  const double E = impl_->fe.material.youngs_modulus_pa;  // plane stress: E* = E
  const double P = force_n / kThickness;
  r.reference_half_angle_rad = persson_half_angle(E * clearance_m / P);
  r.reference_peak_pa = persson_peak_ratio(r.reference_half_angle_rad) * P / kHoleRadius;
  impl_->contact(clearance_m, force_n, true, r);
  impl_->contact(clearance_m, force_n, false, r);
  return r;
}

}  // namespace kinetofem::verification
