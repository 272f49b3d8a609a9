// kinetofem post RESULT.h5 — post-processing of a results file: a summary
// (bodies, fields, envelope maxima with time and place, hot spots), time
// histories at a node or of the mechanism, CSV files and PNG pictures.
// docs/postproc.md describes the options and the files written.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/commands.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/manipulator_names.hpp"
#include "kinetofem/postproc/csv_export.hpp"
#include "kinetofem/postproc/fatigue_nodes.hpp"
#include "kinetofem/postproc/hot_spots.hpp"
#include "kinetofem/postproc/png_plots.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/postproc/time_history.hpp"
#include "kinetofem/postproc/vibration_results.hpp"

namespace kinetofem::app {

namespace {

namespace fs = std::filesystem;

struct PostOptions {
  fs::path results;
  int hot_spots = 5;
  double separation_mm = 10.0;
  std::string history;  // NODE, x,y,z (mm) or a mechanism history name
  std::string body;
  std::string field = post::layout::kVonMises;
  fs::path csv_dir, png_dir;
  bool all = false;
  double deformation_scale = 0.0;  // 0: automatic
  std::string image_size = "1400x900";
  std::optional<double> at_time_s;  // --at: reconstruct this output time's fields from the load patterns
};

// What --history names: a node, a point (m) or a mechanism history.
struct HistorySpec {
  std::optional<fem::Index> node;
  std::optional<Eigen::Vector3d> point_m;
  std::string mechanism;
};

HistorySpec parse_history(const std::string& text) {
  HistorySpec spec;
  if (!text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    spec.node = std::stoll(text);
    return spec;
  }
  if (text.find(',') != std::string::npos) {
    std::vector<double> xyz;
    size_t start = 0;
    while (start <= text.size()) {
      const size_t end = std::min(text.find(',', start), text.size());
      const std::string item = text.substr(start, end - start);
      size_t used = 0;
      double v = 0;
      try {
        v = std::stod(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      require(used > 0 && used == item.size() && std::isfinite(v),
              "--history '{}': '{}' is not a number; expected NODE or x,y,z in mm", text, item);
      xyz.push_back(v);
      start = end + 1;
    }
    require(xyz.size() == 3, "--history '{}': {} coordinates; expected NODE or x,y,z in mm", text, xyz.size());
    spec.point_m = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]) * 1e-3;
    return spec;
  }
  spec.mechanism = text;
  return spec;
}

std::string listed(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

std::string where(const fem::NodeCoordinates& nodes, fem::Index n) {
  return fmt::format("node {} ({:.1f}, {:.1f}, {:.1f}) mm", n, nodes(n, 0) * 1e3, nodes(n, 1) * 1e3,
                     nodes(n, 2) * 1e3);
}

std::string when(double t) { return std::isnan(t) ? "static" : fmt::format("t = {:.4f} s", t); }

void print_summary(const post::ResultsFile& r, const std::vector<post::HotSpot>& spots, const std::string& units,
                   const PostOptions& o) {
  const post::Provenance p = r.provenance();
  fmt::print("kinetofem post: {}\n", r.path().string());
  fmt::print("  case {}, written {} by kinetofem {} ({})\n", p.case_path.empty() ? "?" : p.case_path,
             p.created_utc, p.kinetofem_version, p.git_commit);
  fmt::print("  bodies:\n");
  for (const auto& body : r.bodies()) {
    const fem::Mesh mesh = r.read_mesh(body);
    fmt::print("    {}: {} nodes, {} elements\n", body, mesh.node_count(), mesh.element_count());
    const auto times = r.series_times(body);
    if (post::is_vibration_body(body))  // mode shapes: static fields mode_<i>, mode_<i>_magnitude
      fmt::print("      mode shapes (world coordinates at the pose, max |u| = 1): {}\n", listed(r.static_fields(body)));
    else if (!times.empty())
      fmt::print("      series: {} output times, {:.4g} .. {:.4g} s: {}\n", times.size(), times.front(),
                 times.back(), listed(r.series_fields(body)));
    if (!post::is_vibration_body(body))
      fmt::print("      static fields: {}\n", listed(r.static_fields(body)));
    if (!r.element_fields(body).empty()) fmt::print("      element fields: {}\n", listed(r.element_fields(body)));
    fmt::print("      envelopes: {}\n", listed(r.envelopes(body)));
  }

  fmt::print("  maxima (envelopes over the motion; static fields of static load cases):\n");
  for (const auto& body : r.bodies()) {
    if (post::is_vibration_body(body)) continue;  // mode shapes, normalized to 1: nothing to rank
    std::vector<std::string> fields = r.envelopes(body);
    for (const auto& f : r.series_fields(body))
      if (std::find(fields.begin(), fields.end(), f) == fields.end() && r.read_step(body, f, 0).values.cols() == 1)
        fields.push_back(f);
    for (const auto& f : r.static_fields(body))
      if (r.read_static(body, f).values.cols() == 1 && std::find(fields.begin(), fields.end(), f) == fields.end())
        fields.push_back(f);
    for (const auto& f : fields) {
      post::BodyEnvelope env;
      try {
        env = post::max_envelope(r, body, f);
      } catch (const Error&) {
        continue;  // a multi-component or non-"max" field: nothing to rank
      }
      const post::DisplayUnit u = post::display_unit(env.units);
      const fem::Index n = env.peak_node();
      fmt::print("    {:<8} {:<24} {:>11.4f} {:<4} {:<16} {}  [{}]\n", body, f, env.peak_value() * u.factor, u.label,
                 when(env.time_of(n)), where(env.nodes_m, n), env.source_name());
    }
  }

  const auto histories = r.histories();
  if (!histories.empty()) {
    const auto t = r.mechanism_time();
    fmt::print("  mechanism histories ({} times, {:.4g} .. {:.4g} s), range over the motion:\n", t.size(),
               t.empty() ? 0.0 : t.front(), t.empty() ? 0.0 : t.back());
    for (const auto& name : histories) {
      const post::TimeHistory h = post::mechanism_history(r, name);
      const post::DisplayUnit u = post::display_unit(h.units);
      for (long c = 0; c < h.values.cols(); ++c) {
        const std::string label =
            h.values.cols() == 1 ? name
                                 : name + "_" + (size_t(c) < h.component_names.size() ? h.component_names[size_t(c)] : std::to_string(c));
        fmt::print("    {:<34} {:>12.4f} .. {:>12.4f} {}\n", label, h.values.col(c).minCoeff() * u.factor,
                   h.values.col(c).maxCoeff() * u.factor, u.label);
      }
    }
  }

  fmt::print("  top {} hot spots of {} (nodes within {:g} mm of a listed one on the same body skipped):\n",
             o.hot_spots, o.field, o.separation_mm);
  const post::DisplayUnit u = post::display_unit(units);
  fmt::print("    {:>2}  {:<8} {:>7} {:>9} {:>9} {:>9}  {:<16} {:>10}\n", "#", "body", "node", "x [mm]", "y [mm]",
             "z [mm]", "time", "[" + u.label + "]");
  for (size_t i = 0; i < spots.size(); ++i) {
    const auto& s = spots[i];
    // On a welded part: the solid, and the seam when the node lies on one.
    const std::string place = s.solid.empty() ? std::string()
                              : s.seam.empty() ? "  solid " + s.solid
                                               : fmt::format("  solid {}, seam {}", s.solid, s.seam);
    fmt::print("    {:>2}  {:<8} {:>7} {:>9.1f} {:>9.1f} {:>9.1f}  {:<16} {:>10.3f}{}\n", i + 1, s.body, s.node,
               s.position_m.x() * 1e3, s.position_m.y() * 1e3, s.position_m.z() * 1e3, when(s.time_s),
               s.value * u.factor, place);
  }
}

// The fatigue check's ten worst nodes over all bodies (damage per cycle, then
// utilization), when the run had fatigue.enabled.
void print_fatigue(const post::ResultsFile& r) {
  if (!post::has_fatigue(r)) return;
  const std::vector<post::FatigueNode> worst = post::worst_fatigue_nodes(r, 10);
  fmt::print("  fatigue: the {} worst nodes (damage per work cycle, then utilization u; life infinite where every "
             "range is below the cut-off limit):\n", worst.size());
  fmt::print("    {:>2}  {:<8} {:>7} {:>9} {:>9} {:>9} {:>8} {:>12} {:>12} {:>12} {:>8} {:>12}\n", "#", "body", "node",
             "x [mm]", "y [mm]", "z [mm]", "cat MPa", "D/cycle", "life cycles", "life [h]", "u", "range [MPa]");
  for (size_t i = 0; i < worst.size(); ++i) {
    const post::FatigueNode& n = worst[i];
    fmt::print("    {:>2}  {:<8} {:>7} {:>9.1f} {:>9.1f} {:>9.1f} {:>8g} {:>12.4e} {:>12.4e} {:>12.4e} {:>8.4f} {:>12.4f}\n",
               i + 1, n.body, n.node, n.position_m.x() * 1e3, n.position_m.y() * 1e3, n.position_m.z() * 1e3,
               n.detail_category_pa * 1e-6, n.damage_per_cycle, n.life_cycles, n.life_h, n.utilization,
               n.max_range_pa * 1e-6);
  }
}

// The vibration over the motion, when the run had it: the first natural frequency's range over
// the motion and in the static pose, and per tracked point its dynamic amplification and
// settling after the stop.
void print_vibration(const post::ResultsFile& r) {
  const post::VibrationContents v = post::vibration_contents(r);
  if (!v.frequencies) return;
  const post::NaturalFrequencies f = post::read_natural_frequencies(r);
  fmt::print("  vibration ({} lowest modes of the elastic assembly in each pose):\n", f.modes());
  fmt::print("    first natural frequency over the motion {:.3f} .. {:.3f} Hz (lowest at t = {:.4f} s){}\n",
             f.lowest_first_hz, f.highest_first_hz, f.lowest_first_time_s,
             f.static_hz.empty() ? std::string("") : fmt::format("; static pose {:.3f} Hz", f.static_hz.front()));
  for (const auto& point : v.points) {
    const post::PointVibrationData p = post::read_point_vibration(r, point);
    fmt::print("    point {}: dynamic amplification {:.3f} (peak |u| {:.4f} mm with vibration, {:.4f} mm quasi-static), "
               "rings up to {:.3g} mm after the stop, {}\n",
               point, p.dynamic_amplification, p.peak_dynamic_m * 1e3, p.peak_quasi_static_m * 1e3,
               p.amplitude_at_stop_m * 1e3,
               std::isfinite(p.settling_time_s)
                   ? fmt::format("settles within {:.4f} mm {:.3f} s after the stop", p.settling_tolerance_m * 1e3,
                                 p.settling_time_s)
                   : fmt::format("does not settle within {:.4f} mm", p.settling_tolerance_m * 1e3));
  }
}

post::TimeHistory history_of(const post::ResultsFile& r, const PostOptions& o) {
  const HistorySpec spec = parse_history(o.history);
  if (!spec.mechanism.empty()) return post::mechanism_history(r, spec.mechanism);
  require(!o.body.empty(), "--history {}: a node history needs --body (bodies: {})", o.history, listed(r.bodies()));
  const auto bodies = r.bodies();
  require(std::find(bodies.begin(), bodies.end(), o.body) != bodies.end(), "--body '{}': '{}' has no such body (bodies: {})",
          o.body, r.path().string(), listed(bodies));
  fem::Index node = 0;
  if (spec.node) {
    node = *spec.node;
  } else {
    const fem::NodeCoordinates nodes = r.read_mesh(o.body).nodes;
    node = post::nearest_node(nodes, *spec.point_m);
    fmt::print("  nearest node to ({}) mm on '{}': {}, {:.2f} mm away\n", o.history, o.body, where(nodes, node),
               (nodes.row(node).transpose() - *spec.point_m).norm() * 1e3);
  }
  return post::node_history(r, o.body, o.field, node);
}

void print_history(const post::TimeHistory& h) {
  const post::DisplayUnit u = post::display_unit(h.units);
  fmt::print("  time history: {} [{}]\n", h.description, u.label);
  for (size_t k = 0; k < h.time_s.size(); ++k) {
    std::string row = fmt::format("    {:>10.5f}", h.time_s[k]);
    for (long c = 0; c < h.values.cols(); ++c) row += fmt::format(" {:>14.6g}", h.values(long(k), c) * u.factor);
    fmt::print("{}\n", row);
  }
}

fs::path make_directory(const fs::path& dir, const char* option) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  require(!ec && fs::is_directory(dir), "{} {}: cannot create the directory: {}", option, dir.string(),
          ec ? ec.message() : "not a directory");
  return dir;
}

std::string file_safe(std::string s) {
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
  return s;
}

// --at T: every body with load patterns (a superposition run) at the output
// time nearest T, its fields reconstructed exactly from the patterns
// (post::superpose): printed peak, and with --csv a file per body.
void print_fields_at(const post::ResultsFile& r, double at_s, const fs::path& csv_dir, std::vector<std::string>& written) {
  bool any = false;
  for (const auto& body : r.bodies()) {
    if (!r.has_load_patterns(body)) continue;
    const post::LoadPatternData patterns = r.read_load_patterns(body);
    const std::vector<double>& t = patterns.time_s;
    require(!t.empty() && at_s >= t.front() - 1e-12 && at_s <= t.back() + 1e-12,
            "--at {} s: outside the motion of body '{}' ([{}, {}] s)", at_s, body, t.front(), t.back());
    const auto nearest = std::min_element(t.begin(), t.end(), [&](double a, double b) {
      return std::abs(a - at_s) < std::abs(b - at_s);
    });
    const Eigen::Index step = Eigen::Index(nearest - t.begin());
    const post::SuperposedFields f = post::superpose(patterns, step);
    const fem::Mesh mesh = r.read_mesh(body);
    fem::Index node = 0;
    const double peak = f.von_mises_pa.maxCoeff(&node);
    const Eigen::VectorXd magnitude = f.elastic_displacement_m.rowwise().norm();
    fmt::print("  {} at t = {:.6g} s (output time {} of {}, from {} load patterns): peak von Mises {:.4f} MPa at node {} "
               "({:.1f}, {:.1f}, {:.1f}) mm; max |u| {:.5f} mm\n",
               body, t[size_t(step)], step, t.size(), patterns.names.size(), peak * 1e-6, node,
               mesh.nodes(node, 0) * 1e3, mesh.nodes(node, 1) * 1e3, mesh.nodes(node, 2) * 1e3, magnitude.maxCoeff() * 1e3);
    any = true;
    if (csv_dir.empty()) continue;
    make_directory(csv_dir, "--csv");
    const fs::path p = csv_dir / fmt::format("{}_at_{:.6g}s.csv", file_safe(body), t[size_t(step)]);
    std::FILE* out = std::fopen(p.string().c_str(), "w");
    require(out != nullptr, "{}: cannot be written", p.string());
    std::fprintf(out, "node,x_mm,y_mm,z_mm,u_x_mm,u_y_mm,u_z_mm,von_mises_MPa,s_xx_MPa,s_yy_MPa,s_zz_MPa,s_xy_MPa,s_yz_MPa,s_zx_MPa\n");
    for (fem::Index i = 0; i < mesh.node_count(); ++i) {
      std::fprintf(out, "%ld,%.6g,%.6g,%.6g,%.9g,%.9g,%.9g,%.9g", long(i), mesh.nodes(i, 0) * 1e3, mesh.nodes(i, 1) * 1e3,
                   mesh.nodes(i, 2) * 1e3, f.elastic_displacement_m(i, 0) * 1e3, f.elastic_displacement_m(i, 1) * 1e3,
                   f.elastic_displacement_m(i, 2) * 1e3, f.von_mises_pa[i] * 1e-6);
      for (int c = 0; c < 6; ++c) std::fprintf(out, ",%.9g", f.stress_pa(i, c) * 1e-6);
      std::fprintf(out, "\n");
    }
    require(std::fclose(out) == 0, "{}: write failed", p.string());
    written.push_back(p.string());
  }
  require(any, "--at: no body of '{}' has load patterns (a run with solver.load_path = \"step_by_step\", or an older "
          "file); its written steps are in the series", r.path().string());
}

// "WIDTHxHEIGHT" in px.
std::pair<int, int> parse_image_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, rest = 0;
  require(std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &rest) == 3 && (x == 'x' || x == 'X'),
          "--image-size '{}': expected WIDTHxHEIGHT in px, e.g. 1400x900", text);
  require(w >= 400 && h >= 300 && w <= 8000 && h <= 8000, "--image-size '{}': from 400x300 to 8000x8000 px", text);
  return {w, h};
}


// The pictures of the vibration over the motion: the natural frequencies, and each tracked
// point's vibration over the motion and after the stop.
void write_vibration_pictures(const post::ResultsFile& r, const post::VibrationContents& vibration,
                              const fs::path& png_dir, const post::PictureOptions& po, std::vector<std::string>& written) {
  if (vibration.frequencies) {
    const fs::path p = png_dir / "vibration_frequencies.png";
    const post::FrequencyPictureInfo info = post::write_frequency_picture(r, p, po);
    written.push_back(fmt::format("{}  ({} modes; mode 1 {:.2f} .. {:.2f} Hz, lowest at {})", p.string(), info.modes,
                                  info.lowest_first_hz, info.highest_first_hz, when(info.lowest_first_time_s)));
  }
  for (const auto& point : vibration.points) {
    const fs::path p = png_dir / ("vibration_point_" + file_safe(point) + ".png");
    const post::PointVibrationPictureInfo info = post::write_point_vibration_picture(r, p, point, po);
    written.push_back(fmt::format("{}  (amplification {:.3f}, {})", p.string(), info.dynamic_amplification,
                                  std::isfinite(info.settling_time_s)
                                      ? fmt::format("settles {:.3f} s after the stop", info.settling_time_s)
                                      : std::string("does not settle")));
  }
}

// The pictures of the elastic assembly: the static pose study, the step of the
// largest deflection of the gripper point H, and each tracked point's deflection.
void write_assembly_pictures(const post::ResultsFile& r, const post::AssemblyContents& assembly, const fs::path& png_dir,
                             const post::PictureOptions& po, std::vector<std::string>& written) {
  post::AssemblyPictureOptions ao{po};
  auto draw = [&](const std::string& file) {
    const fs::path p = png_dir / file;
    const post::AssemblyPictureInfo info = post::write_assembly_picture(r, p, ao);
    written.push_back(fmt::format("{}  ({}, deformation x{:g})", p.string(),
                                  info.step < 0 ? info.chosen_by : when(info.time_s) + ", " + info.chosen_by,
                                  info.deformation_scale));
  };
  if (assembly.has_static) {
    ao.pose = post::AssemblyPictureOptions::Pose::Static;
    draw("assembly_static.png");
  }
  ao.pose = post::AssemblyPictureOptions::Pose::LargestDeflection;
  ao.point = mech::manipulator::kPointH;  // the gripper point, when the assembly tracked it
  const bool has_h = std::find(assembly.points.begin(), assembly.points.end(), ao.point) != assembly.points.end();
  draw(has_h ? "assembly_max_H.png" : "assembly_max.png");
  for (const auto& point : assembly.points) {
    const fs::path p = png_dir / ("deflection_" + file_safe(point) + ".png");
    const post::PointDeflectionInfo info = post::write_point_deflection_picture(r, p, point, po);
    written.push_back(fmt::format("{}  (max |u| {:.3f} mm at {})", p.string(), info.max_m * 1e3, when(info.time_s)));
  }
}

int run_post(const PostOptions& o) {
  if (const std::string problem = input_file_problem(o.results); !problem.empty())
    fail("{}: {}, expected a results file (RESULT.h5)", o.results.string(),
         problem == "no such file" ? "no such results file" : problem);
  require(o.hot_spots >= 0, "--hot-spots {}: must be 0 or more", o.hot_spots);
  require(o.separation_mm >= 0, "--separation-mm {}: must be 0 or more", o.separation_mm);
  const auto [width_px, height_px] = parse_image_size(o.image_size);
  const post::ResultsFile r = post::ResultsFile::open(o.results);

  // Check the history request before any output, so a typo fails fast.
  std::optional<post::TimeHistory> history;
  if (!o.history.empty()) history = history_of(r, o);
  else require(o.body.empty(), "--body '{}' given without --history", o.body);

  const std::vector<post::BodyEnvelope> envelopes = post::max_envelopes(r, o.field);
  // A spatial mechanism's moving skeletons (results_layout.hpp) carry no
  // stress: a file of skeletons only has nothing for --field to miss.
  const std::vector<std::string> bodies = r.bodies();
  const bool parts = std::any_of(bodies.begin(), bodies.end(), [](const std::string& b) {
    return !b.starts_with(post::layout::kSkeletonBodyPrefix);
  });
  if (envelopes.empty() && parts)
    fail("--field '{}': no body of '{}' has this field (bodies: {}; fields of '{}': static {}, series {})", o.field,
         r.path().string(), listed(r.bodies()), r.bodies().front(), listed(r.static_fields(r.bodies().front())),
         listed(r.series_fields(r.bodies().front())));
  const std::vector<post::HotSpot> spots =
      post::find_hot_spots(envelopes, {.count = o.hot_spots, .separation_m = o.separation_mm * 1e-3});
  print_summary(r, spots, envelopes.empty() ? std::string("Pa") : envelopes.front().units, o);
  print_fatigue(r);
  print_vibration(r);
  if (history) print_history(*history);

  fs::path csv_dir = o.csv_dir, png_dir = o.png_dir;
  if (o.all) {
    const fs::path dir = o.results.parent_path() / (o.results.stem().string() + "_post");
    if (csv_dir.empty()) csv_dir = dir;
    if (png_dir.empty()) png_dir = dir;
  }
  std::vector<std::string> written;
  if (o.at_time_s) print_fields_at(r, *o.at_time_s, csv_dir, written);
  if (!csv_dir.empty()) {
    make_directory(csv_dir, "--csv");
    if (!envelopes.empty()) {
      post::write_hot_spots_csv(csv_dir / "hot_spots.csv", spots, o.field, envelopes.front().units);
      written.push_back((csv_dir / "hot_spots.csv").string());
    }
    for (const auto& body : r.bodies()) {
      const fs::path p = csv_dir / (file_safe(body) + "_nodes.csv");
      post::write_body_fields_csv(p, r, body);
      written.push_back(p.string());
    }
    if (!r.histories().empty()) {
      post::write_mechanism_csv(csv_dir / "mechanism.csv", r);
      written.push_back((csv_dir / "mechanism.csv").string());
    }
    if (history) {
      const std::string name = o.body.empty() ? history->quantity : o.body + "_" + o.field + "_" + o.history;
      const fs::path p = csv_dir / ("history_" + file_safe(name) + ".csv");
      post::write_history_csv(p, *history);
      written.push_back(p.string());
    }
  }
  if (!png_dir.empty()) {
    make_directory(png_dir, "--png");
    const post::AssemblyContents assembly = post::assembly_contents(r);
    const bool links_have_field = std::any_of(envelopes.begin(), envelopes.end(), [&](const post::BodyEnvelope& e) {
      return std::find(assembly.bodies.begin(), assembly.bodies.end(), e.body) == assembly.bodies.end() &&
             !post::is_vibration_body(e.body);
    });
    if (links_have_field) {  // the stress picture leaves the assembly's and the vibration's bodies out
      post::StressPictureOptions so;
      so.field = o.field;
      so.deformation_scale = o.deformation_scale;
      so.width_px = width_px;
      so.height_px = height_px;
      const fs::path p = png_dir / (file_safe(o.field) + "_critical.png");
      const post::StressPictureInfo info = post::write_stress_picture(r, p, so);
      written.push_back(fmt::format("{}  ({}, deformation x{:g})", p.string(), when(info.time_s), info.deformation_scale));
    }
    if (post::has_fatigue(r))  // the fatigue fields on each part (static fields: the undeformed shape)
      for (const char* field : {post::layout::kFatigueDamage, post::layout::kFatigueUtilization}) {
        const std::vector<post::FatigueNode> worst = post::worst_fatigue_nodes(r, 1);
        if (field == std::string(post::layout::kFatigueDamage) && (worst.empty() || worst.front().damage_per_cycle <= 0)) {
          written.push_back(fmt::format("{}: not drawn, the damage is 0 at every node (every range below the cut-off "
                                        "limit; see the utilization)", file_safe(field) + ".png"));
          continue;
        }
        post::StressPictureOptions fo;
        fo.caption = "over the work cycle (EN 1993-1-9)";
        fo.field = field;
        fo.displacement_field = "";  // drawn undeformed
        fo.width_px = width_px;
        fo.height_px = height_px;
        const fs::path p = png_dir / (file_safe(field) + ".png");
        const post::StressPictureInfo info = post::write_stress_picture(r, p, fo);
        written.push_back(fmt::format("{}  (max {:.4g} on {}, node {})", p.string(), info.max_value, info.peak_body,
                                      info.peak_node));
      }
    bool has_loads = false;
    for (const auto& name : r.histories()) {
      const std::string units = r.read_history(name).units;
      has_loads = has_loads || units == "N" || units == "N*m";
    }
    const post::PictureOptions po{.title_name = "", .width_px = width_px, .height_px = height_px};
    if (has_loads) {
      post::write_mechanism_loads_picture(r, png_dir / "mechanism_loads.png", po);
      written.push_back((png_dir / "mechanism_loads.png").string());
    }
    if (!post::contact_tables(r).empty()) {
      const fs::path p = png_dir / "pin_contact.png";
      const post::ContactPictureInfo info = post::write_contact_picture(r, p, po);
      written.push_back(fmt::format("{}  ({} pins; peak {:.3f} MPa on {} at {})", p.string(), info.pins.size(),
                                    info.peak_pressure_pa * 1e-6, info.peak_pin, when(info.peak_time_s)));
    }
    if (!post::contact_tables(r, post::ContactTables::Assembly).empty()) {
      const fs::path p = png_dir / "assembly_pin_contact.png";
      const post::ContactPictureInfo info = post::write_contact_picture(r, p, po, post::ContactTables::Assembly);
      written.push_back(fmt::format("{}  ({} pins in the elastic assembly; peak {:.3f} MPa on {} at {})", p.string(),
                                    info.pins.size(), info.peak_pressure_pa * 1e-6, info.peak_pin,
                                    when(info.peak_time_s)));
    }
    for (const auto& name : r.histories())
      if (name.rfind("gripper_point_", 0) == 0 || name.rfind("point.", 0) == 0) {
        const std::string point = name.rfind("point.", 0) == 0 ? name.substr(6) : name.substr(14);
        const fs::path p = png_dir / ("path_" + file_safe(point) + ".png");
        post::write_path_picture(r, p, name, po);
        written.push_back(p.string());
      }
    if (!assembly.bodies.empty()) write_assembly_pictures(r, assembly, png_dir, po, written);
    write_vibration_pictures(r, post::vibration_contents(r), png_dir, po, written);
  }
  if (!written.empty()) {
    fmt::print("  written:\n");
    for (const auto& w : written) fmt::print("    {}\n", w);
  }
  return 0;
}

}  // namespace

void add_post_command(CLI::App& app, CommandContext& context) {
  auto o = std::make_shared<PostOptions>();
  auto* post = app.add_subcommand("post", "Post-process a results file: summary, hot spots, histories, CSV, PNG");
  post->add_option("results", o->results, "Results file (RESULT.h5) written by `kinetofem run`")->required();
  post->add_option("--hot-spots", o->hot_spots, "Number of hot spots to list")->capture_default_str();
  post->add_option("--separation-mm", o->separation_mm, "Hot spots: skip nodes this close to a listed one (mm)")
      ->capture_default_str();
  post->add_option("--history", o->history,
                   "Time history: NODE (index) or x,y,z (mm, nearest node) with --body, or a mechanism history name");
  post->add_option("--body", o->body, "Body of a node history");
  post->add_option("--field", o->field, "Field for hot spots, pictures and node histories")->capture_default_str();
  post->add_option("--csv", o->csv_dir, "Write CSV files into this directory");
  post->add_option("--png", o->png_dir, "Write PNG pictures into this directory");
  post->add_option("--deformation-scale", o->deformation_scale, "Deformation scale of the stress picture (0: automatic)")
      ->capture_default_str();
  post->add_option("--image-size", o->image_size, "Size of the PNG pictures, WIDTHxHEIGHT in px")
      ->capture_default_str();
  post->add_option("--at", o->at_time_s,
                   "Reconstruct the fields at the output time nearest this time (s) from the stored load patterns "
                   "(exact; also times whose fields were not written); with --csv, a CSV per body");
  post->add_flag("--all", o->all, "Write every CSV and PNG into <result dir>/<name>_post/");
  post->callback([o, &context] { context.exit_code = run_post(*o); });
}

}  // namespace kinetofem::app
