// A part welded from two solids behaves as the same part made of one solid.
//
// Reference: the one-solid model of the same geometry at the same element
// size (TET10). A weld of two solids along a whole interface is a conformal
// mesh with shared nodes, so the only difference between the two models is
// where Gmsh puts the nodes (the seam is a surface the welded mesh must
// follow): discretisation only.
//
// 1. A cantilever bar 200 x 20 x 20 mm cut at mid-length into two solids
//    welded end to end, against the uncut bar: tip deflection and peak von
//    Mises stress (in the middle half, away from the clamp and the load)
//    within 1e-3.
// 2. A T-section cantilever of two plates (a flange 60 x 10 mm and a web
//    10 x 40 mm standing on it, 200 mm long) welded along the web's foot,
//    against the same T fused into one solid: within 1 % (the seam lies where
//    the web meets the flange; the meshes differ more).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

#include <gmsh.h>
#include <gtest/gtest.h>

#include "kinetofem/core/log.hpp"
#include "kinetofem/meshes/gmsh_session.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::meshes {
namespace {

using fem::Index;

struct BoxMm {
  double x, y, z, dx, dy, dz;
};

class TempFolder {
 public:
  TempFolder() {
    path_ = std::filesystem::temp_directory_path() /
            ("kinetofem_welded_verification_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Writes the boxes (mm) into a .brep: as separate solids, or fused into one.
void write_boxes(const std::filesystem::path& file, const std::vector<BoxMm>& boxes, bool fused) {
  GmshSession session;
  session.call(file.string(), "writing the test geometry", [&] {
    gmsh::model::add("boxes");
    gmsh::vectorpair solids;
    for (const auto& b : boxes) solids.emplace_back(3, gmsh::model::occ::addBox(b.x, b.y, b.z, b.dx, b.dy, b.dz));
    if (fused && solids.size() > 1) {
      gmsh::vectorpair out;
      std::vector<gmsh::vectorpair> map;
      gmsh::model::occ::fuse({solids.front()}, {solids.begin() + 1, solids.end()}, out, map);
    }
    gmsh::model::occ::synchronize();
    gmsh::write(file.string());
  });
}

struct Result {
  double tip_deflection_m = 0;  // mean -u_y over the tip face's nodes
  double peak_von_mises_pa = 0;  // over the nodes with 50 <= x <= 150 mm
  Index nodes = 0;
};

// Cantilever along x, length 200 mm: clamped at x = 0, a shear force of 1 kN
// in -y spread over the end face x = 200 mm (`tip_area_m2`).
Result solve_cantilever(const std::filesystem::path& file, double tip_area_m2) {
  PartFileOptions part;
  part.length_unit_m = 1e-3;
  part.face_sets = {{"tip", {0.1999, -1, -1}, {0.2001, 1, 1}}};
  MeshOptions options;
  options.element_size_m = 0.005;
  options.order = 2;
  fem::FeModel model;
  model.mesh = mesh_part_file(file, part, options);
  std::vector<Index> root;
  for (Index n = 0; n < model.mesh.node_count(); ++n)
    if (std::abs(model.mesh.nodes(n, 0)) < 1e-9) root.push_back(n);
  model.supports.push_back({"root", root, {true, true, true}, Eigen::Vector3d::Zero()});
  fem::LoadCase load;
  load.tractions.push_back({"tip", Eigen::Vector3d(0, -1000.0 / tip_area_m2, 0)});
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(model, log);
  const auto u = analysis.solve({load}).front();
  const auto stress = fem::recover_nodal_stress(model.mesh, fem::element_materials(model), u);
  Result r;
  r.nodes = model.mesh.node_count();
  const auto& tip = model.mesh.node_set("tip");
  for (Index n : tip) r.tip_deflection_m -= u(n, 1);
  r.tip_deflection_m /= double(tip.size());
  for (Index n = 0; n < model.mesh.node_count(); ++n)
    if (model.mesh.nodes(n, 0) >= 0.050 && model.mesh.nodes(n, 0) <= 0.150)
      r.peak_von_mises_pa = std::max(r.peak_von_mises_pa, stress.von_mises_pa(n));
  return r;
}

void print(const char* what, const Result& r) {
  std::printf("%s: %lld nodes, tip deflection %.6e m, peak von Mises %.6e Pa\n", what,
              static_cast<long long>(r.nodes), r.tip_deflection_m, r.peak_von_mises_pa);
}

TEST(WeldedPartVerification, BarCutInTwoEqualsTheOneSolidBar) {
  TempFolder dir;
  write_boxes(dir / "bar.brep", {{0, 0, 0, 200, 20, 20}}, false);
  write_boxes(dir / "bar_two.brep", {{0, 0, 0, 100, 20, 20}, {100, 0, 0, 100, 20, 20}}, false);
  const Result one = solve_cantilever(dir / "bar.brep", 400e-6);
  const Result two = solve_cantilever(dir / "bar_two.brep", 400e-6);
  print("one solid", one);
  print("two welded solids", two);
  // Reference: the one-solid bar at the same mesh size (discretisation
  // only); 1e-3.
  EXPECT_NEAR(two.tip_deflection_m / one.tip_deflection_m, 1.0, 1e-3);
  EXPECT_NEAR(two.peak_von_mises_pa / one.peak_von_mises_pa, 1.0, 1e-3);
  // Sanity against beam theory (Euler-Bernoulli P L^3 / 3EI plus shear; the
  // clamp adds a little): within 5 %, so a wrong load or support fails here.
  const double E = 210e9, I = 0.020 * std::pow(0.020, 3) / 12, L = 0.2, P = 1000;
  const double G = E / 2.6, kappa = 5.0 / 6.0;
  const double beam = P * L * L * L / (3 * E * I) + P * L / (kappa * G * 400e-6);
  EXPECT_NEAR(one.tip_deflection_m / beam, 1.0, 0.05);
}

TEST(WeldedPartVerification, TJointOfTwoPlatesEqualsTheOneSolidT) {
  TempFolder dir;
  const std::vector<BoxMm> plates = {{0, 0, -30, 200, 10, 60}, {0, 10, -5, 200, 40, 10}};
  write_boxes(dir / "t_one.brep", plates, true);
  write_boxes(dir / "t_two.brep", plates, false);
  const double tip_area = 60e-6 * 10 + 10e-6 * 40;
  const Result one = solve_cantilever(dir / "t_one.brep", tip_area);
  const Result two = solve_cantilever(dir / "t_two.brep", tip_area);
  print("T one solid", one);
  print("T two welded plates", two);
  // Reference: the T as one solid at the same mesh size; 1 %.
  EXPECT_NEAR(two.tip_deflection_m / one.tip_deflection_m, 1.0, 0.01);
  EXPECT_NEAR(two.peak_von_mises_pa / one.peak_von_mises_pa, 1.0, 0.01);
}

}  // namespace
}  // namespace kinetofem::meshes
