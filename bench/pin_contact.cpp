// pin_contact — cost of pins in contact with their bores (docs/contact.md)
// against the distributing coupling, and the per-pose contact cost against
// the mesh size.
//
// Model: the SPEC §1 lever (500 mm between bores of 40 mm, the parametric
// lever of meshes/lever.hpp, TET10) turned once about its pin A0 in 2 s
// (cycloidal law) under gravity, a 40 kg mass at A; the pin A0 in contact
// with its bore (radial clearance 15 um), the mass on bore A by a coupling.
// For each element size it prints:
//   * the stress over 101 output times, couplings vs contact, each with its
//     own factorization: wall seconds and their ratio (target: at most 2);
//   * the contact alone at 10 000 output times: the set-up (m solves, m the
//     bore's corner nodes) and the cost per pose, which depends on m, not
//     on the mesh.
// Usage: pin_contact [ELEMENT_SIZE_MM ...]   (default 16 8)
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_contact.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/meshes/lever.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/testing/pendulum_links.hpp"

namespace {

using namespace kinetofem;

fem::FeModel lever_model(double element_size_m) {
  meshes::MeshOptions options;
  options.element_size_m = element_size_m;
  options.order = 2;
  fem::FeModel model;
  model.mesh = meshes::mesh_lever(meshes::LeverDimensions{}, options);
  // A 3-2-1 support on nodes of neither bore.
  std::vector<char> on_bore(size_t(model.mesh.node_count()), 0);
  for (const char* bore : {"bore_A0", "bore_A"})
    for (const fem::Index n : fem::nodes_of_faces(model.mesh.face_set(bore))) on_bore[size_t(n)] = 1;
  std::vector<fem::Index> free;
  for (fem::Index i = 0; i < model.mesh.node_count(); ++i)
    if (!on_bore[size_t(i)]) free.push_back(i);
  model.supports = fem::three_two_one_support(model.mesh, free);
  return model;
}

std::vector<mech::Frame> frames(const mech::MultibodyModel& model, int count) {
  std::vector<double> t;
  for (int k = 0; k < count; ++k) t.push_back(2.0 * k / (count - 1));
  return mech::run_kinematics(mech::MultibodySystem(model), t).frames;
}

double stress_over_motion_seconds(const fem::FeModel& model, const mech::MultibodyModel& mechanism,
                                  const std::vector<mech::Frame>& motion, loads::BoreLoad load, const Log& log) {
  Stopwatch clock;
  loads::LinkDefinition link{"link", &model, {{"J1", "bore_A0", load, 15e-6}}, {{"mass", "bore_A"}},
                             {{"D1", "bore_A0"}}};
  const loads::LinkLoads link_loads(link, mechanism);
  fem::LinearStaticAnalysis analysis(model, log);
  const loads::LinkEnvelope env = loads::analyse_link_over_motion(analysis, link_loads, motion, log);
  const double seconds = clock.seconds();
  std::printf("    %-9s peak von Mises %8.3f MPa, %2ld right-hand sides, %6.2f s\n",
              load == loads::BoreLoad::Contact ? "contact" : "coupling", env.peak_von_mises_pa * 1e-6,
              env.solved_right_hand_sides, seconds);
  return seconds;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes_mm;
  for (int k = 1; k < argc; ++k) sizes_mm.push_back(std::atof(argv[k]));
  if (sizes_mm.empty()) sizes_mm = {16.0, 8.0};
  const Log log = Log::quiet();
  std::printf("pin_contact: the SPEC §1 lever turned about its pin A0 (in contact, 15 um), TET10\n");
  std::printf("%8s %8s %8s %12s %12s %8s %12s %14s\n", "h [mm]", "nodes", "corners", "coupling [s]", "contact [s]",
              "ratio", "set-up [s]", "per pose [ms]");
  for (const double h : sizes_mm) {
    const fem::FeModel model = lever_model(h * 1e-3);
    const mech::MultibodyModel mechanism = testing::turning_link(model, {0.5, 0.0}, 40.0, 2.0);
    std::printf("  element size %.0f mm: 101 output times\n", h);
    const auto motion = frames(mechanism, 101);
    const double coupling = stress_over_motion_seconds(model, mechanism, motion, loads::BoreLoad::DistributingCoupling, log);
    const double contact = stress_over_motion_seconds(model, mechanism, motion, loads::BoreLoad::Contact, log);
    // The contact alone at 10 000 output times.
    const auto many = frames(mechanism, 10000);
    loads::LinkDefinition link{"link", &model, {{"J1", "bore_A0", loads::BoreLoad::Contact, 15e-6}},
                               {{"mass", "bore_A"}}, {{"D1", "bore_A0"}}};
    const loads::LinkLoads link_loads(link, mechanism);
    fem::LinearStaticAnalysis analysis(model, log);
    const loads::LinkContactHistory history = loads::solve_contact_over_motion(analysis, link_loads, many, log);
    std::printf("%8.0f %8ld %8ld %12.2f %12.2f %8.2f %12.2f %14.3f   (10 000 poses: %d by the fallback, at most %d "
                "active-set steps)\n",
                h, long(model.mesh.node_count()), long(history.contact_corners()), coupling, contact, contact / coupling,
                history.set_up_seconds, 1e3 * history.solve_seconds / double(many.size()), history.interior_point_poses,
                history.most_active_set_steps);
  }
  return 0;
}
