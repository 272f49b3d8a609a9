// The XDMF text of a results file, as ParaView's three readers need it (XDMF Reader
// = Xdmf2, Xdmf3ReaderS, Xdmf3ReaderT; postproc/src/xdmf_document.hpp explains the
// choices), and the sample file of the ParaView test.
//
// XdmfParaViewSample.WritesResultsAndExpectations writes "paraview_sample.h5/.xdmf"
// and "paraview_sample.expect.json" (what the readers must show: times, blocks,
// counts, arrays and sample values), and "paraview_empty.h5/.xdmf" (nothing). With KINETOFEM_XDMF_SAMPLE_DIR set it writes
// them there and keeps them: scripts/test-xdmf-paraview.sh (ctest label
// `paraview`) does so and runs scripts/check_xdmf_paraview.py on them.
// XdmfParaViewSample.MovingBodyMovesInAllThreeReaders runs only there (with the
// directory set and pvpython found): it opens a moving body (its geometry is a series
// field) with the three readers and checks where its points are at every step.
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::TemporaryDirectory;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// Tags open and close in order (enough to catch a broken writer; ParaView's readers
// are the real parser, in the `paraview` test).
bool tags_balance(const std::string& xml, std::string& why) {
  std::vector<std::string> open;
  const std::regex tag(R"(<(/?)([A-Za-z_][\w:.-]*)[^>]*?(/?)>)");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), tag); it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[2];
    if ((*it)[1] == "/") {
      if (open.empty() || open.back() != name) return why = "mismatched </" + name + ">", false;
      open.pop_back();
    } else if ((*it)[3] != "/") {
      open.push_back(name);
    }
  }
  if (!open.empty()) return why = "unclosed <" + open.back() + ">", false;
  return true;
}

Provenance provenance() {
  Provenance p;
  p.case_path = "synthetic";
  p.case_text = "[case]\nname = \"paraview sample\"\n";
  return p;
}

// Exactly representable values, different per body, field, node, component and step.
double value(double base, Eigen::Index row, int column, int step) {
  return base + 1000.0 * step + 10.0 * double(row) + double(column);
}

FieldMatrix field(Eigen::Index rows, int columns, double base, int step = 0) {
  FieldMatrix f(rows, columns);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (int c = 0; c < columns; ++c) f(i, c) = value(base, i, c, step);
  return f;
}

fem::Mesh mixed_mesh() {
  fem::Mesh mesh = testing::single_hex20();
  fem::ElementBlock tet;
  tet.type = fem::ElementType::Tet4;
  tet.connectivity = {0, 1, 3, 4};
  mesh.blocks.push_back(tet);
  return mesh;
}

// ---------------------------------------------------------------------------------------
// The sample file and what the readers must show.

// The tuples scripts/check_xdmf_paraview.py samples: 0, n/3, 2n/3, n-1.
std::vector<Eigen::Index> sampled(Eigen::Index n) {
  std::vector<Eigen::Index> rows = {0, n / 3, (2 * n) / 3, n - 1};
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

std::string json_row(const FieldMatrix& f, Eigen::Index row) {
  std::string out = "[";
  for (Eigen::Index c = 0; c < f.cols(); ++c) out += fmt::format("{}{}", c ? ", " : "", f(row, c));
  return out + "]";
}

std::string json_samples(const FieldMatrix& f) {
  std::string out = "{";
  bool first = true;
  for (Eigen::Index row : sampled(f.rows())) {
    out += fmt::format("{}\"{}\": {}", first ? "" : ", ", row, json_row(f, row));
    first = false;
  }
  return out + "}";
}

struct ExpectedArray {
  std::string name;
  FieldMatrix values;               // static
  std::vector<FieldMatrix> steps;   // or per time step
};

std::string json_array(const ExpectedArray& a) {
  const FieldMatrix& shape = a.steps.empty() ? a.values : a.steps.front();
  std::string out = fmt::format("\"{}\": {{\"components\": {}, \"tuples\": {}", a.name,
                                shape.cols(), shape.rows());
  if (a.steps.empty()) {
    out += ", \"samples\": " + json_samples(a.values);
  } else {
    out += ", \"steps\": {";
    for (size_t k = 0; k < a.steps.size(); ++k)
      out += fmt::format("{}\"{}\": {}", k ? ", " : "", k, json_samples(a.steps[k]));
    out += "}";
  }
  return out + "}";
}

struct ExpectedBlock {
  std::string name;
  fem::Index points = 0, cells = 0;
  std::vector<ExpectedArray> point, cell, field;
};

std::string json_block(const ExpectedBlock& b) {
  auto group = [](const std::vector<ExpectedArray>& arrays) {
    std::string out = "{";
    for (size_t i = 0; i < arrays.size(); ++i) out += (i ? ", " : "") + json_array(arrays[i]);
    return out + "}";
  };
  return fmt::format(
      "{{\"name\": \"{}\", \"points\": {}, \"cells\": {}, \"arrays\": {{\"point\": {}, \"cell\": "
      "{}, \"field\": {}}}}}",
      b.name, b.points, b.cells, group(b.point), group(b.cell), group(b.field));
}

// A body that moves: the TET10 "assembly.crank" whose series field `position` is its
// geometry (SeriesField::geometry): the mesh translated by kMovingOffset at step 0 and
// by kMovingStep more at every step, plus displacement, displacement_magnitude,
// von_mises and a von_mises envelope (what the pipeline writes for an assembly body).
constexpr double kMovingOffset[3] = {1.0, 2.0, 3.0};
constexpr double kMovingStep[3] = {0.5, -0.25, 0.125};

FieldMatrix moved(const fem::Mesh& mesh, int step) {
  FieldMatrix p = mesh.nodes;
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    for (int c = 0; c < 3; ++c) p(i, c) += kMovingOffset[c] + step * kMovingStep[c];
  return p;
}

ExpectedBlock add_moving_body(ResultsWriter& writer, const std::vector<double>& times) {
  const fem::Mesh mesh = testing::single_tet10();
  const fem::Index n = mesh.node_count();
  BodyWriter& body = writer.add_body("assembly.crank", mesh);
  body.begin_series({{"position", "m", 3, kVectorComponents, true},
                     {"displacement", "m", 3, kVectorComponents},
                     {"displacement_magnitude", "m", 1},
                     {"von_mises", "Pa", 1}});
  ExpectedArray position{"position", {}, {}}, u{"displacement", {}, {}},
      magnitude{"displacement_magnitude", {}, {}}, vm{"von_mises", {}, {}};
  for (int k = 0; k < int(times.size()); ++k) {
    position.steps.push_back(moved(mesh, k));
    u.steps.push_back(field(n, 3, 0.0625, k) / 1024.0);
    magnitude.steps.push_back(field(n, 1, 0.5, k) / 1024.0);
    vm.steps.push_back(field(n, 1, 1000000.5, k));
    body.write_step(times[size_t(k)],
                    {{"position", position.steps.back()}, {"displacement", u.steps.back()},
                     {"displacement_magnitude", magnitude.steps.back()},
                     {"von_mises", vm.steps.back()}});
  }
  const FieldMatrix vm_max = field(n, 1, 1100000.5);
  body.write_envelope("von_mises", "Pa", vm_max, IndexMatrix::Constant(n, 1, 2));
  return {"assembly.crank", n, 1,
          {{"von_mises_max", vm_max, {}},
           {"von_mises_max_step", FieldMatrix::Constant(n, 1, 2.0), {}},
           position, u, magnitude, vm},
          {}, {}};
}

// lever (TET10, series of 4 steps, static fields named like series fields, an
// element field, a 9-component tensor, an envelope), bracket (HEX20 + TET4:
// Mixed, series), assembly.crank (TET10 moving: its geometry is a series field),
// base (HEX20, no series: in every step), mechanism histories (1, 2 and 3
// components over 11 times). Returns the expectations as JSON.
std::string write_sample(const std::filesystem::path& h5) {
  const std::vector<double> times = {0.0, 0.25, 0.5, 0.75};
  const int steps = int(times.size());
  std::vector<ExpectedBlock> blocks;
  ResultsWriter writer(h5, provenance());

  const fem::Mesh tet = testing::single_tet10();
  const fem::Index nt = tet.node_count();
  BodyWriter& lever = writer.add_body("lever", tet);
  ExpectedBlock eb{"lever", nt, 1, {}, {}, {}};
  auto add_static = [&](const std::string& name, const std::string& shown, int c, double base) {
    const FieldMatrix f = field(nt, c, base);
    lever.write_static(name, "1", f);
    eb.point.push_back({shown, f, {}});
  };
  add_static("displacement", "displacement_static", 3, 0.5);
  add_static("stress", "stress_static", 6, 100000.5);
  add_static("von_mises", "von_mises_static", 1, 200000.5);
  add_static("orientation", "orientation", 9, 300000.5);
  const FieldMatrix sed = field(1, 1, 42.25);
  lever.write_element_field("strain_energy_density", "J/m^3", sed);
  eb.cell.push_back({"strain_energy_density", sed, {}});
  lever.begin_series({{"displacement", "m", 3, kVectorComponents},
                      {"von_mises", "Pa", 1},
                      {"stress", "Pa", 6, kVoigtComponents}});
  ExpectedArray su{"displacement", {}, {}}, svm{"von_mises", {}, {}}, ss{"stress", {}, {}};
  for (int k = 0; k < steps; ++k) {
    su.steps.push_back(field(nt, 3, 0.125, k));
    svm.steps.push_back(field(nt, 1, 500000.125, k));
    ss.steps.push_back(field(nt, 6, 600000.125, k));
    lever.write_step(times[size_t(k)],
                     {{"displacement", su.steps.back()}, {"von_mises", svm.steps.back()},
                      {"stress", ss.steps.back()}});
  }
  const FieldMatrix vm_max = field(nt, 1, 700000.5);
  lever.write_envelope("von_mises", "Pa", vm_max, IndexMatrix::Constant(nt, 1, 3));
  eb.point.push_back({"von_mises_max", vm_max, {}});
  eb.point.push_back({"von_mises_max_step", FieldMatrix::Constant(nt, 1, 3.0), {}});
  eb.point.push_back(su);
  eb.point.push_back(svm);
  eb.point.push_back(ss);
  blocks.push_back(eb);

  const fem::Mesh mixed = mixed_mesh();
  const fem::Index nm = mixed.node_count();
  BodyWriter& bracket = writer.add_body("bracket", mixed);
  ExpectedBlock bb{"bracket", nm, 2, {}, {}, {}};
  const FieldMatrix id = field(2, 1, 7.0);
  bracket.write_element_field("id", "1", id);
  bb.cell.push_back({"id", id, {}});
  bracket.begin_series({{"von_mises", "Pa", 1}});
  ExpectedArray bvm{"von_mises", {}, {}};
  for (int k = 0; k < steps; ++k) {
    bvm.steps.push_back(field(nm, 1, 800000.75, k));
    bracket.write_step(times[size_t(k)], {{"von_mises", bvm.steps.back()}});
  }
  bb.point.push_back(bvm);
  blocks.push_back(bb);

  blocks.push_back(add_moving_body(writer, times));

  const fem::Mesh hex = testing::single_hex20();
  BodyWriter& base = writer.add_body("base", hex);
  const FieldMatrix temperature = field(hex.node_count(), 1, 900000.25);
  base.write_static("temperature", "K", temperature);
  blocks.push_back({"base", hex.node_count(), 1, {{"temperature", temperature, {}}}, {}, {}});

  std::vector<double> t_m;
  for (int i = 0; i <= 10; ++i) t_m.push_back(0.1 * i);
  writer.set_mechanism_time(t_m);
  ExpectedBlock mb{"mechanism", 1, 1, {}, {}, {}};
  FieldMatrix t_col(Eigen::Index(t_m.size()), 1);
  for (size_t i = 0; i < t_m.size(); ++i) t_col(Eigen::Index(i), 0) = t_m[i];
  mb.field.push_back({"time", t_col, {}});
  const std::vector<std::pair<std::string, int>> histories = {
      {"drive.effort", 1}, {"point.H", 2}, {"joint.A.force", 3}};
  double hb = 0.5;
  for (const auto& [name, c] : histories) {
    const FieldMatrix h = field(Eigen::Index(t_m.size()), c, hb);
    hb += 100.0;
    writer.write_history(name, "1", h);
    mb.field.push_back({name, h, {}});
  }
  blocks.push_back(mb);
  writer.commit();

  fem::Index total = 0;
  std::string json = "{\n  \"times\": [";
  for (size_t k = 0; k < times.size(); ++k) json += fmt::format("{}{}", k ? ", " : "", times[k]);
  json += "],\n  \"blocks\": [\n";
  for (size_t b = 0; b < blocks.size(); ++b) {
    json += "    " + json_block(blocks[b]) + (b + 1 < blocks.size() ? ",\n" : "\n");
    total += blocks[b].points;
  }
  json += fmt::format("  ],\n  \"total_points\": {}\n}}\n", total);
  return json;
}

TEST(XdmfParaViewSample, WritesResultsAndExpectations) {
  TemporaryDirectory temporary;
  const char* keep = std::getenv("KINETOFEM_XDMF_SAMPLE_DIR");
  const std::filesystem::path dir = keep && *keep ? std::filesystem::path(keep) : temporary.path();
  std::filesystem::create_directories(dir);
  const std::string expect = write_sample(dir / "paraview_sample.h5");
  {
    std::ofstream out(dir / "paraview_sample.expect.json", std::ios::binary | std::ios::trunc);
    out << expect;
    ASSERT_TRUE(bool(out));
  }
  {
    // And a file with nothing in it (the Xdmf2 reader used to crash on its empty Domain).
    ResultsWriter empty(dir / "paraview_empty.h5", provenance());
    empty.commit();
  }
  const std::string xml = read_text(dir / "paraview_sample.xdmf");
  std::string why;
  ASSERT_TRUE(tags_balance(xml, why)) << why;
  // A temporal collection per grid (4 bodies + mechanism), 4 steps each.
  EXPECT_EQ(count_of(xml, R"(GridType="Collection" CollectionType="Temporal")"), 5u);
  EXPECT_EQ(count_of(xml, "<Time Value="), 20u);
  EXPECT_NE(xml.find(R"(<Grid Name="base" GridType="Collection" CollectionType="Temporal">)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<Attribute Name="von_mises_static" AttributeType="Scalar" Center="Node">)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<Attribute Name="orientation" AttributeType="Tensor" Center="Node">)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<Topology TopologyType="Mixed" NumberOfElements="2">)"), std::string::npos);
  EXPECT_NE(expect.find("\"total_points\": 61"), std::string::npos);  // 10 + 20 + 10 + 20 + 1
}

// ---------------------------------------------------------------------------------------
// The moving body in ParaView: every reader shows its points where the geometry field
// puts them at each step. Runs inside the `paraview` test (scripts/test-xdmf-paraview.sh
// sets KINETOFEM_XDMF_SAMPLE_DIR and runs XdmfParaViewSample.*); skipped elsewhere and
// where pvpython is missing. scripts/check_xdmf_paraview.py compares the readers'
// arrays on the sample file (which has the same body) but not their points.

// pvpython (PVPYTHON, else from PATH), or "" if there is none.
std::string find_pvpython() {
  if (const char* given = std::getenv("PVPYTHON"); given && *given) return given;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / "pvpython";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return "";
}

// Per time step of one reader: the number of points and the bounds of each leaf block,
// as "@@ <step> <points> <xmin> <xmax> <ymin> <ymax> <zmin> <zmax>" lines; anything
// else the reader prints (warnings, errors) is noise.
constexpr const char* kBoundsScript = R"py(
import sys
from paraview import simple
reader_name, path = sys.argv[1], sys.argv[2]
if reader_name == "XDMFReader":
    reader = simple.XDMFReader(FileNames=[path])
else:
    reader = getattr(simple, reader_name)(FileName=[path])
times = reader.TimestepValues
times = [float(t) for t in times] if isinstance(times, (list, tuple)) or hasattr(times, "__len__") else [float(times)]

def leaves(data):
    if data.IsA("vtkDataObjectTree"):
        pieces = data.IsA("vtkMultiPieceDataSet")
        for i in range(data.GetNumberOfPieces() if pieces else data.GetNumberOfBlocks()):
            child = data.GetPiece(i) if pieces else data.GetBlock(i)
            if child is not None:
                yield from leaves(child)
    else:
        yield data

for k, t in enumerate(times):
    reader.UpdatePipeline(t)
    for block in leaves(reader.GetClientSideObject().GetOutputDataObject(0)):
        b = block.GetBounds()
        print("@@ %d %d %s" % (k, block.GetNumberOfPoints(), " ".join("%.17g" % v for v in b)))
sys.stdout.flush()
)py";

struct ReaderRun {
  std::vector<std::string> noise;
  // Per step: points and bounds (xmin, xmax, ymin, ymax, zmin, zmax) of each block.
  std::map<int, std::vector<std::pair<long, std::array<double, 6>>>> steps;
  int status = -1;
};

ReaderRun run_reader(const std::string& pvpython, const std::filesystem::path& script,
                     const std::string& reader, const std::filesystem::path& xdmf) {
  // Without the sanitizer stage's LD_PRELOAD: only kinetofem's own programs run under it.
  const std::string command = fmt::format("env -u LD_PRELOAD '{}' '{}' {} '{}' 2>&1", pvpython,
                                          script.string(), reader, xdmf.string());
  ReaderRun run;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::string output;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
  run.status = ::pclose(pipe);
  std::stringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("@@ ", 0) == 0) {
      std::stringstream fields(line.substr(3));
      int step = 0;
      long points = 0;
      std::array<double, 6> bounds{};
      fields >> step >> points;
      for (double& b : bounds) fields >> b;
      run.steps[step].push_back({points, bounds});
    } else if (line.find_first_not_of(" \t\r") != std::string::npos) {
      run.noise.push_back(line);
    }
  }
  return run;
}

TEST(XdmfParaViewSample, MovingBodyMovesInAllThreeReaders) {
  const char* keep = std::getenv("KINETOFEM_XDMF_SAMPLE_DIR");
  if (!keep || !*keep)
    GTEST_SKIP() << "runs in the paraview test (ctest -L paraview), which sets KINETOFEM_XDMF_SAMPLE_DIR";
  const std::string pvpython = find_pvpython();
  if (pvpython.empty()) GTEST_SKIP() << "pvpython not found (set PVPYTHON)";
  // Absolute: the Xdmf3 readers cannot find the .h5 of an .xdmf given by a bare file name.
  const std::filesystem::path dir = std::filesystem::absolute(keep) / "moving";
  std::filesystem::create_directories(dir);
  const std::vector<double> times = {0.0, 0.25, 0.5, 0.75};
  {
    ResultsWriter writer(dir / "moving.h5", provenance());
    add_moving_body(writer, times);
    writer.commit();
  }
  const std::filesystem::path script = dir / "moving_bounds.py";
  {
    std::ofstream out(script, std::ios::binary | std::ios::trunc);
    out << kBoundsScript;
    ASSERT_TRUE(bool(out));
  }
  const fem::Mesh mesh = testing::single_tet10();
  for (const char* reader : {"XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT"}) {
    SCOPED_TRACE(reader);
    const ReaderRun run = run_reader(pvpython, script, reader, dir / "moving.xdmf");
    EXPECT_EQ(run.status, 0);
    std::string noise;
    for (const auto& line : run.noise) noise += line + "\n";
    EXPECT_TRUE(run.noise.empty()) << "the reader printed:\n" << noise;
    ASSERT_EQ(run.steps.size(), times.size());
    for (int k = 0; k < int(times.size()); ++k) {
      SCOPED_TRACE(fmt::format("step {}", k));
      ASSERT_EQ(run.steps.at(k).size(), 1u);  // one block
      const auto& [points, bounds] = run.steps.at(k).front();
      EXPECT_EQ(points, mesh.node_count());
      const FieldMatrix p = moved(mesh, k);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(bounds[size_t(2 * c)], p.col(c).minCoeff(), 1e-12);
        EXPECT_NEAR(bounds[size_t(2 * c + 1)], p.col(c).maxCoeff(), 1e-12);
      }
    }
    // The mechanism moves: the last step's box is the first one's moved by 3 steps.
    const auto& first = run.steps.at(0).front().second;
    const auto& last = run.steps.at(int(times.size()) - 1).front().second;
    for (int c = 0; c < 3; ++c)
      for (int side = 0; side < 2; ++side)
        EXPECT_NEAR(last[size_t(2 * c + side)] - first[size_t(2 * c + side)],
                    (double(times.size()) - 1.0) * kMovingStep[c], 1e-12);
  }
}

// ---------------------------------------------------------------------------------------
// The text, one choice at a time.

// The TET10 body "lever" with a 3-step series of displacement and von_mises.
std::string series_document(const TemporaryDirectory& dir, bool with_histories = false) {
  const fem::Mesh mesh = testing::single_tet10();
  {
    ResultsWriter writer(dir / "run.h5", provenance());
    BodyWriter& b = writer.add_body("lever", mesh);
    b.write_static("static_von_mises", "Pa", field(10, 1, 1.0));
    b.write_static("stress", "Pa", field(10, 6, 2.0));
    b.begin_series({{"displacement", "m", 3, kVectorComponents}, {"von_mises", "Pa", 1}});
    for (int k = 0; k < 3; ++k)
      b.write_step(0.25 * k, {{"displacement", field(10, 3, 3.0, k)}, {"von_mises", field(10, 1, 4.0, k)}});
    if (with_histories) {
      writer.set_mechanism_time({0.0, 0.5});
      writer.write_history("drive.effort", "N*m", field(2, 1, 5.0));
    }
    writer.commit();
  }
  return read_text(dir / "run.xdmf");
}

TEST(XdmfText, SeriesStepIsAHyperSlabForXdmf2AndAHeavyDataSelectionForXdmf3) {
  TemporaryDirectory dir;
  const std::string xml = series_document(dir);
  // Step 2 of (3, 10, 3): Xdmf3 reads the text (start:stride:count:dataspace), Xdmf2
  // the HyperSlab of the children.
  EXPECT_NE(xml.find(R"(<DataItem Type="HyperSlab" Dimensions="10 3" NumberType="Float" Precision="8" Format="HDF">run.h5:/bodies/lever/series/displacement|2 0 0:1 1 1:1 10 3:3 10 3)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<DataItem Dimensions="3 3" NumberType="Int" Format="XML">2 0 0 1 1 1 1 10 3</DataItem>)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<DataItem Dimensions="3 10 3" NumberType="Float" Precision="8" Format="HDF">run.h5:/bodies/lever/series/displacement</DataItem>)"),
            std::string::npos);
  // An ItemType="HyperSlab" is a reference in Xdmf3: vtkXdmf3 skips it ("[None]").
  EXPECT_EQ(xml.find("ItemType="), std::string::npos);
}

TEST(XdmfText, GeometrySeriesFieldIsTheGeometryOfEachStep) {
  TemporaryDirectory dir;
  {
    ResultsWriter writer(dir / "run.h5", provenance());
    add_moving_body(writer, {0.0, 0.5, 1.0});
    writer.commit();
  }
  const std::string xml = read_text(dir / "run.xdmf");
  std::string why;
  ASSERT_TRUE(tags_balance(xml, why)) << why;
  // Every step's Geometry is the slice of `position` at that step, in the series
  // attributes' DataItem (Xdmf3: the text; Xdmf2: the HyperSlab of the children).
  EXPECT_EQ(count_of(xml, "<Geometry "), 3u);
  EXPECT_EQ(xml.find("/mesh/nodes"), std::string::npos);
  for (int k = 0; k < 3; ++k) {
    const std::string geometry = fmt::format(
        "        <Geometry GeometryType=\"XYZ\">\n"
        "          <DataItem Type=\"HyperSlab\" Dimensions=\"10 3\" NumberType=\"Float\" Precision=\"8\" "
        "Format=\"HDF\">run.h5:/bodies/assembly.crank/series/position|{0} 0 0:1 1 1:1 10 3:3 10 3\n"
        "            <DataItem Dimensions=\"3 3\" NumberType=\"Int\" Format=\"XML\">{0} 0 0 1 1 1 1 10 3</DataItem>\n"
        "            <DataItem Dimensions=\"3 10 3\" NumberType=\"Float\" Precision=\"8\" "
        "Format=\"HDF\">run.h5:/bodies/assembly.crank/series/position</DataItem>\n"
        "          </DataItem>\n"
        "        </Geometry>\n",
        k);
    EXPECT_EQ(count_of(xml, geometry), 1u) << "step " << k;
  }
  // Steps 1 and 2 include the Topology (child 2 after the Time) and the two envelope
  // attributes (children 4, 5) from step 0, around their own Geometry.
  EXPECT_EQ(count_of(xml, "<Topology "), 1u);
  const std::string topology =
      R"x(<xi:include xpointer="xpointer(/Xdmf/Domain/Grid[@Name='assembly.crank']/Grid[1]/*[position() = 2])"/>)x";
  const std::string statics =
      R"x(<xi:include xpointer="xpointer(/Xdmf/Domain/Grid[@Name='assembly.crank']/Grid[1]/*[position() &gt; 3 and position() &lt;= 5])"/>)x";
  EXPECT_EQ(count_of(xml, topology), 2u);
  EXPECT_EQ(count_of(xml, statics), 2u);
  EXPECT_LT(xml.find(topology), xml.find("|1 0 0:1 1 1:1 10 3:3 10 3"));
  EXPECT_EQ(count_of(xml, R"(<Attribute Name="von_mises_max" AttributeType="Scalar" Center="Node">)"), 1u);
  // `position` is a point array too (a Vector in every step).
  EXPECT_EQ(count_of(xml, R"(<Attribute Name="position" AttributeType="Vector" Center="Node">)"), 3u);
}

TEST(XdmfText, GeometryFieldWithoutStepsLeavesTheMeshGeometry) {
  TemporaryDirectory dir;
  {
    ResultsWriter writer(dir / "run.h5", provenance());
    writer.add_body("crank", testing::single_tet10())
        .begin_series({{"position", "m", 3, kVectorComponents, true}});
    writer.commit();
  }
  const std::string xml = read_text(dir / "run.xdmf");
  EXPECT_NE(xml.find("run.h5:/bodies/crank/mesh/nodes</DataItem>"), std::string::npos);
  EXPECT_EQ(xml.find("HyperSlab"), std::string::npos);
}

TEST(XdmfText, SixComponentFieldsAreMatricesNotTensor6) {
  TemporaryDirectory dir;
  const std::string xml = series_document(dir);
  EXPECT_NE(xml.find(R"(<Attribute Name="stress" AttributeType="Matrix" Center="Node">)"),
            std::string::npos);
  EXPECT_EQ(xml.find("Tensor6"), std::string::npos);
}

TEST(XdmfText, OneTemporalCollectionPerBodyWithTheStaticFieldsInEveryStep) {
  TemporaryDirectory dir;
  const std::string xml = series_document(dir);
  std::string why;
  ASSERT_TRUE(tags_balance(xml, why)) << why;
  EXPECT_EQ(count_of(xml, R"(<Grid Name="lever" GridType="Collection" CollectionType="Temporal">)"), 1u);
  EXPECT_EQ(count_of(xml, "GridType=\"Uniform\""), 3u);  // one per step, no time-less grid
  EXPECT_EQ(count_of(xml, "<Time Value="), 3u);
  EXPECT_NE(xml.find(R"(<Time Value="0.25"/>)"), std::string::npos);
  // The mesh and the static fields once, in step 0; steps 1 and 2 include them
  // (Topology, Geometry and 2 static attributes: elements 2..5 after the Time).
  EXPECT_EQ(count_of(xml, "<Topology "), 1u);
  EXPECT_EQ(count_of(xml, R"(<Attribute Name="static_von_mises")"), 1u);
  EXPECT_EQ(count_of(xml, R"x(<xi:include xpointer="xpointer(/Xdmf/Domain/Grid[@Name='lever']/Grid[1]/*[position() &gt; 1 and position() &lt;= 5])"/>)x"),
            2u);
  // The series fields in every step.
  EXPECT_EQ(count_of(xml, R"(<Attribute Name="displacement" AttributeType="Vector" Center="Node">)"), 3u);
}

TEST(XdmfText, StaticFieldNamedLikeASeriesFieldGetsASuffix) {
  TemporaryDirectory dir;
  {
    ResultsWriter writer(dir / "run.h5", provenance());
    BodyWriter& b = writer.add_body("lever", testing::single_tet10());
    b.write_static("von_mises", "Pa", field(10, 1, 1.0));
    b.write_element_field("von_mises", "Pa", field(1, 1, 1.0));  // cell data: no clash
    b.begin_series({{"von_mises", "Pa", 1}});
    b.write_step(0.0, {{"von_mises", field(10, 1, 2.0)}});
    writer.commit();
  }
  const std::string xml = read_text(dir / "run.xdmf");
  EXPECT_EQ(count_of(xml, R"(<Attribute Name="von_mises_static" AttributeType="Scalar" Center="Node">)"), 1u);
  EXPECT_EQ(count_of(xml, R"(<Attribute Name="von_mises" AttributeType="Scalar" Center="Cell">)"), 1u);
  EXPECT_EQ(count_of(xml, R"(<Attribute Name="von_mises" AttributeType="Scalar" Center="Node">)"), 1u);
  // The HDF5 names stay as written.
  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  EXPECT_EQ(file.read_static("lever", "von_mises").values(0, 0), 1.0);
}

TEST(XdmfText, HistoriesAreFieldDataOfAMechanismGridInEveryStep) {
  TemporaryDirectory dir;
  const std::string xml = series_document(dir, true);
  EXPECT_NE(xml.find(R"(<Grid Name="mechanism" GridType="Collection" CollectionType="Temporal">)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<Attribute Name="drive.effort" AttributeType="Scalar" Center="Grid">)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<DataItem Dimensions="2 1" NumberType="Float" Precision="8" Format="HDF">run.h5:/mechanism/drive.effort</DataItem>)"),
            std::string::npos);
  // "time" inline as (T, 1): read from the (T) dataset Xdmf3 would make one tuple of T values.
  EXPECT_NE(xml.find(R"(<Attribute Name="time" AttributeType="Scalar" Center="Grid">)"), std::string::npos);
  EXPECT_NE(xml.find(R"(<DataItem Dimensions="2 1" NumberType="Float" Precision="8" Format="XML">)"),
            std::string::npos);
  EXPECT_EQ(count_of(xml, R"x(<xi:include xpointer="xpointer(/Xdmf/Domain/Grid[@Name='mechanism']/Grid[1]/*[position() &gt; 1])"/>)x"),
            2u);
}

TEST(XdmfText, HistoryOnlyFileHasAMechanismGridAndNoTime) {
  TemporaryDirectory dir;
  {
    ResultsWriter writer(dir / "linkage.h5", provenance());
    writer.set_mechanism_time({0.0, 0.005, 0.01});
    writer.write_history("point.H", "m", field(3, 2, 0.5), {"x", "y"});
    writer.commit();
  }
  const std::string xml = read_text(dir / "linkage.xdmf");
  std::string why;
  ASSERT_TRUE(tags_balance(xml, why)) << why;
  EXPECT_NE(xml.find(R"(<Grid Name="mechanism" GridType="Uniform">)"), std::string::npos);
  EXPECT_NE(xml.find(R"(<Topology TopologyType="Polyvertex" NumberOfElements="1" NodesPerElement="1">)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<Attribute Name="point.H" AttributeType="Matrix" Center="Grid">)"), std::string::npos);
  EXPECT_NE(xml.find("0 0.005 0.01\n"), std::string::npos);  // the time, shortest exact text
  EXPECT_EQ(xml.find("<Time"), std::string::npos);
}

TEST(XdmfText, EmptyResultsFileStillHasAGrid) {
  // Xdmf2 (ParaView's XDMF Reader) crashes on a Domain without grids.
  TemporaryDirectory dir;
  {
    ResultsWriter writer(dir / "empty.h5", provenance());
    writer.commit();
  }
  const std::string xml = read_text(dir / "empty.xdmf");
  EXPECT_NE(xml.find(R"(<Grid Name="results" GridType="Collection" CollectionType="Spatial"/>)"),
            std::string::npos);
}

TEST(XdmfText, BodyNamedMechanismKeepsItsNameAndTheHistoriesMove) {
  TemporaryDirectory dir;
  {
    ResultsWriter writer(dir / "run.h5", provenance());
    writer.add_body("mechanism", testing::single_tet10()).write_static("t", "K", field(10, 1, 1.0));
    writer.set_mechanism_time({0.0});
    writer.write_history("drive.effort", "N*m", field(1, 1, 5.0));
    writer.commit();
  }
  const std::string xml = read_text(dir / "run.xdmf");
  EXPECT_EQ(count_of(xml, R"(<Grid Name="mechanism" GridType="Uniform">)"), 1u);
  EXPECT_EQ(count_of(xml, R"(<Grid Name="mechanism_histories" GridType="Uniform">)"), 1u);
}

}  // namespace
}  // namespace kinetofem::post
