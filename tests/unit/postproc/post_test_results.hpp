#pragma once
// Synthetic results files for the post-processing tests, written with
// ResultsWriter, whose maxima are placed by hand so every expected hot spot,
// envelope and CSV value is known exactly.
//
// "motion.h5": two bodies with a 5-step series (t = 0, 0.1, ..., 0.4 s),
//   beam  (HEX8 grid 200 x 20 x 10 mm, 10 mm spacing): background below 50 MPa,
//         300 MPa at (50, 0, 0) mm at step 2, 290 MPa at its neighbour
//         (60, 0, 0) mm at step 2, 200 MPa at (150, 20, 10) mm at step 4;
//         its von_mises envelope is stored in the file;
//   plate (HEX8 grid 40 x 40 x 10 mm): 250 MPa at (20, 20, 10) mm at step 1;
//         no stored envelope (post-processing recomputes it);
//   mechanism histories over 21 times: drive_torque (N*m), chain_tension (N),
//   reaction_A0_on_lever (N, x y), gripper_point_H (m, x y: a quarter circle
//   of radius 0.5 m).
// "static.h5": body "bar" with static von_mises (Pa) and displacement (m) only.
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post::testing {

// A box of HEX8 elements with nodes every `spacing_m`, node index i + nx (j + ny k).
inline fem::Mesh hex_grid(int nx, int ny, int nz, double spacing_m) {
  fem::Mesh mesh;
  mesh.nodes.resize(nx * ny * nz, 3);
  auto id = [&](int i, int j, int k) { return fem::Index(i + nx * (j + ny * k)); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) mesh.nodes.row(id(i, j, k)) << i * spacing_m, j * spacing_m, k * spacing_m;
  fem::ElementBlock block;
  block.type = fem::ElementType::Hex8;
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        for (auto n : {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                       id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)})
          block.connectivity.push_back(n);
  mesh.blocks.push_back(block);
  return mesh;
}

struct SyntheticMotion {
  static constexpr int kSteps = 5;
  static constexpr double kDt = 0.1;
  // beam grid 21 x 3 x 2 nodes, plate 5 x 5 x 2
  static constexpr fem::Index kBeamPeak = 5;                  // (50, 0, 0) mm
  static constexpr fem::Index kBeamNeighbour = 6;             // (60, 0, 0) mm
  static fem::Index beam_second() { return 15 + 21 * (2 + 3 * 1); }  // (150, 20, 10) mm
  static fem::Index plate_peak() { return 2 + 5 * (2 + 5 * 1); }     // (20, 20, 10) mm
};

// von Mises of the synthetic beam/plate at step k (Pa).
inline Eigen::VectorXd synthetic_von_mises(const std::string& body, fem::Index nodes, int k) {
  Eigen::VectorXd vm(nodes);
  for (fem::Index n = 0; n < nodes; ++n) vm(n) = 1e6 * (10.0 + 0.1 * double(n % 97) + 5.0 * k);  // < 50 MPa
  if (body == "beam") {
    if (k == 2) vm(SyntheticMotion::kBeamPeak) = 300e6, vm(SyntheticMotion::kBeamNeighbour) = 290e6;
    if (k == 4) vm(SyntheticMotion::beam_second()) = 200e6;
  } else if (k == 1) {
    vm(SyntheticMotion::plate_peak()) = 250e6;
  }
  return vm;
}

inline std::filesystem::path write_synthetic_motion(const std::filesystem::path& dir) {
  const std::filesystem::path path = dir / "motion.h5";
  Provenance prov;
  prov.case_path = "synthetic";
  prov.case_text = "[case]\nname = \"synthetic\"\n";
  ResultsWriter writer(path, prov);
  for (const std::string body : {"beam", "plate"}) {
    const fem::Mesh mesh = body == "beam" ? hex_grid(21, 3, 2, 0.01) : hex_grid(5, 5, 2, 0.01);
    BodyWriter& w = writer.add_body(body, mesh);
    w.begin_series({{"displacement", "m", 3, kVectorComponents}, {"von_mises", "Pa", 1}});
    const fem::Index n = mesh.node_count();
    FieldMatrix max = FieldMatrix::Constant(n, 1, -1.0);
    IndexMatrix step = IndexMatrix::Zero(n, 1);
    for (int k = 0; k < SyntheticMotion::kSteps; ++k) {
      const Eigen::VectorXd vm = synthetic_von_mises(body, n, k);
      FieldMatrix u(n, 3);  // a bending-like deflection growing in time
      for (fem::Index i = 0; i < n; ++i)
        u.row(i) << 0.0, -1e-5 * (k + 1) * std::pow(mesh.nodes(i, 0) / 0.2, 2), 0.0;
      FieldMatrix vm_m = vm;
      w.write_step(k * SyntheticMotion::kDt, {{"displacement", u}, {"von_mises", vm_m}});
      for (fem::Index i = 0; i < n; ++i)
        if (vm(i) > max(i, 0)) max(i, 0) = vm(i), step(i, 0) = k;
    }
    if (body == "beam") w.write_envelope("von_mises", "Pa", max, step, "max");
    w.write_static("static_von_mises", "Pa", FieldMatrix::Constant(n, 1, 1e6));
  }
  const int T = 21;
  std::vector<double> t(T);
  FieldMatrix torque(T, 1), tension(T, 1), reaction(T, 2), h(T, 2);
  for (int k = 0; k < T; ++k) {
    t[size_t(k)] = 0.02 * k;
    const double s = std::sin(std::numbers::pi * t[size_t(k)] / 0.4);
    torque(k, 0) = 100.0 * s;
    tension(k, 0) = 500.0 + 300.0 * s;
    reaction.row(k) << 300.0 * s, 400.0 * s;  // |R| = 500 s
    const double angle = 0.5 * std::numbers::pi * t[size_t(k)] / 0.4;
    h.row(k) << 0.5 * std::cos(angle), 0.5 * std::sin(angle);
  }
  writer.set_mechanism_time(t);
  writer.write_history("drive_torque", "N*m", torque);
  writer.write_history("chain_tension", "N", tension);
  writer.write_history("reaction_A0_on_lever", "N", reaction, {"x", "y"});
  writer.write_history("gripper_point_H", "m", h, {"x", "y"});
  writer.commit();
  return path;
}

inline std::filesystem::path write_synthetic_static(const std::filesystem::path& dir) {
  const std::filesystem::path path = dir / "static.h5";
  Provenance prov;
  prov.case_path = "synthetic_static";
  ResultsWriter writer(path, prov);
  const fem::Mesh mesh = hex_grid(11, 3, 3, 0.01);
  BodyWriter& w = writer.add_body("bar", mesh);
  const fem::Index n = mesh.node_count();
  FieldMatrix vm(n, 1), u(n, 3);
  for (fem::Index i = 0; i < n; ++i) {
    vm(i, 0) = 25e6 * (1.0 + mesh.nodes(i, 0));  // largest at x = 100 mm
    u.row(i) << 1e-5 * mesh.nodes(i, 0) / 0.1, 0.0, 0.0;
  }
  w.write_static("von_mises", "Pa", vm);
  w.write_static("displacement", "m", u, kVectorComponents);
  writer.commit();
  return path;
}

}  // namespace kinetofem::post::testing
