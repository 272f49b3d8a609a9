#include "kinetofem/loads/link_contact.hpp"

#include <algorithm>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/bore_contact_pin.hpp"

namespace kinetofem::loads {

void LinkContactHistory::add_forces(const Eigen::Ref<const Eigen::MatrixXd>& pressure,
                                    Eigen::Ref<Eigen::MatrixXd> forces) const {
  Eigen::Index offset = 0;
  for (const auto& b : bores) {
    b.surface.add_forces(pressure.middleRows(offset, b.surface.size()), forces);
    offset += b.surface.size();
  }
}

namespace {

// The coupling components a round pin carries: F and M normal to the axis.
// Indices into the coupling's six patterns (F_x, F_y, F_z, M_x, M_y, M_z).
constexpr int kCarried[4] = {0, 1, 3, 4};

std::string joints_of(const LinkLoads& loads) {
  std::string names;
  for (const auto& c : loads.contact_bores()) names += (names.empty() ? "'" : ", '") + c.joint + "'";
  return names;
}

}  // namespace

LinkContactHistory solve_contact_over_motion(fem::LinearStaticAnalysis& analysis, const LinkLoads& loads,
                                             const std::vector<mech::Frame>& frames, const Log& log,
                                             const fem::ContactSolverOptions& options) {
  const fem::Mesh& mesh = analysis.model().mesh;
  const std::vector<ContactBore>& contact = loads.contact_bores();
  require(!contact.empty(), "link '{}': no pin is in contact with a bore", loads.body());
  require(!frames.empty(), "link '{}': no output times for the contact", loads.body());
  Stopwatch clock;
  LinkContactHistory h;
  for (const auto& c : contact) {
    require(c.bore.axis_direction.isApprox(Eigen::Vector3d::UnitZ()),
            "link '{}': joint '{}': the pin's axis must be the body's z axis", loads.body(), c.joint);
    h.bores.push_back({c.joint, fem::BoreContactSurface(mesh, c.bore.face_set, c.bore.axis_point_m, c.bore.axis_direction),
                       c.clearance_m, {}, {}, {}});
  }
  // The support must leave the contact nodes free (a held node has no
  // compliance: A would be singular).
  std::vector<char> held(size_t(mesh.node_count()), 0);
  for (const auto& s : analysis.model().supports)
    for (const fem::Index n : s.nodes) held[size_t(n)] = 1;
  Eigen::Index m = 0;
  std::vector<Eigen::Index> offset;
  for (const auto& b : h.bores) {
    for (const fem::Index n : b.surface.nodes())
      require(!held[size_t(n)], "link '{}': node {} of bore '{}' (joint '{}') is held by the part's support; a "
              "contact node must be free", loads.body(), n, b.surface.face_set(), b.joint);
    offset.push_back(m);
    m += b.surface.size();
  }

  // The condensed operators, m solves in blocks: A = F^T K^-1 F, D = F^T K^-1 P;
  // an elastic pin adds its own compliance on its bore's block of A.
  const Eigen::MatrixXd P = loads.pattern_forces();
  std::vector<const fem::BoreContactSurface*> surfaces;
  for (const auto& b : h.bores) surfaces.push_back(&b.surface);
  fem::CondensedContact condensed = fem::condense_contact(analysis, surfaces, P);
  Eigen::MatrixXd& A = condensed.compliance;
  const Eigen::MatrixXd& D = condensed.pattern_gaps;
  for (size_t b = 0; b < h.bores.size(); ++b) {
    if (!contact[b].pin_material) continue;
    const fem::ElasticPin pin(mesh, h.bores[b].surface, *contact[b].pin_material, h.bores[b].clearance_m, log);
    A.block(offset[b], offset[b], pin.compliance().rows(), pin.compliance().cols()) += pin.compliance();
  }
  h.condensed_bytes = 8.0 * double(A.size() + D.size());
  h.set_up_seconds = clock.seconds();
  log.detail("  link '{}': contact of {} pin(s) on {} bore corner nodes: condensed operators in {:.2f} s ({:.1f} MB)",
             loads.body(), h.bores.size(), m, h.set_up_seconds, h.condensed_bytes / 1e6);

  // The rigid-pin map, block diagonal over the bores; the clearances.
  const Eigen::Index k = 4 * Eigen::Index(h.bores.size());
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(m, k);
  Eigen::VectorXd clearance(m), area(m);  // weighted clearance (m^3), corner areas (m^2)
  for (size_t b = 0; b < h.bores.size(); ++b) {
    const auto& s = h.bores[b].surface;
    E.block(offset[b], 4 * Eigen::Index(b), s.size(), 4) = s.rigid_pin_map();
    area.segment(offset[b], s.size()) = s.corner_area_m2();
    clearance.segment(offset[b], s.size()) = h.bores[b].clearance_m * s.corner_area_m2();
  }

  clock.restart();
  const Eigen::Index steps = Eigen::Index(frames.size());
  h.pressure_pa.resize(m, steps);
  h.remaining_coefficients.resize(P.cols(), steps);
  for (auto& b : h.bores) {
    b.pressure_pa.resize(b.surface.size(), steps);
    b.states.reserve(size_t(steps));
    b.carried.reserve(size_t(steps));
  }
  std::vector<char> in_contact;
  for (Eigen::Index t = 0; t < steps; ++t) {
    const mech::Frame& frame = frames[size_t(t)];
    Eigen::VectorXd c = loads.coefficients_at(frame).coefficients;
    Eigen::VectorXd r(k);
    for (size_t b = 0; b < h.bores.size(); ++b) {
      const int first = contact[b].first_pattern;
      for (int j = 0; j < 4; ++j) {
        r[4 * Eigen::Index(b) + j] = c[first + kCarried[j]];
        c[first + kCarried[j]] = 0.0;
      }
    }
    const Eigen::VectorXd free_gap = clearance + D * c;
    fem::ContactSolution s;
    try {
      s = fem::solve_contact(A, free_gap, E, r, in_contact, options);
    } catch (const Error& e) {
      fail("link '{}', pin(s) {} at t = {:.6g} s: {}", loads.body(), joints_of(loads), frame.t, e.what());
    }
    in_contact = s.in_contact;
    h.pressure_pa.col(t) = s.pressure;
    h.remaining_coefficients.col(t) = c;
    h.worst_penetration_m = std::max(h.worst_penetration_m, -(s.gap.cwiseQuotient(area)).minCoeff());
    h.worst_resultant_error = std::max(h.worst_resultant_error, s.resultant_error);
    h.most_active_set_steps = std::max(h.most_active_set_steps, s.active_set_steps);
    h.interior_point_poses += s.interior_point_steps > 0 ? 1 : 0;
    for (size_t b = 0; b < h.bores.size(); ++b) {
      auto& bore = h.bores[b];
      const auto pressure = s.pressure.segment(offset[b], bore.surface.size());
      bore.pressure_pa.col(t) = pressure;
      bore.states.push_back(fem::contact_state(bore.surface, pressure));
      bore.carried.push_back(r.segment<4>(4 * Eigen::Index(b)));
    }
  }
  h.solve_seconds = clock.seconds();
  log.detail("  link '{}': contact solved at {} output times in {:.3f} s ({:.3g} ms per pose; at most {} active-set "
             "steps{})",
             loads.body(), steps, h.solve_seconds, 1e3 * h.solve_seconds / double(steps), h.most_active_set_steps,
             h.interior_point_poses > 0 ? fmt::format(", {} poses by the interior-point fallback", h.interior_point_poses)
                                         : std::string());
  return h;
}

}  // namespace kinetofem::loads
