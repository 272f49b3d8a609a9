// ResultsWriter / ResultsFile: round trip, units, XDMF, atomic commit, errors.
//
// Round-trip values are compared exactly: HDF5 stores IEEE doubles and int64
// unchanged, so anything but bit-equality is a bug.
#include <sys/stat.h>

#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <hdf5.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/version.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "post_test_calls.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::TemporaryDirectory;

Provenance test_provenance() {
  Provenance p;
  p.case_path = "cases/lever/case.toml";
  p.case_text = "# lever case\n[mechanism]\nlength_m = 0.45\n";
  const char* argv[] = {"kinetofem", "run", "cases/lever/case.toml", "--out", "my dir"};
  p.command_line = command_line_of(5, argv);
  return p;
}

// Deterministic nodal values: a smooth function of the coordinates and the step.
FieldMatrix field_of(const fem::Mesh& mesh, int components, double scale) {
  FieldMatrix f(mesh.node_count(), components);
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    for (int c = 0; c < components; ++c)
      f(i, c) = scale * (1.0 + c) * (mesh.nodes(i, 0) + 2.0 * mesh.nodes(i, 1) - mesh.nodes(i, 2)) +
                1e-3 * double(i);
  return f;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Well-formed XML, checked minimally: tags nest and close in order, attribute
// values are quoted, there is one root element, text holds no stray '<' or '&'.
bool well_formed_xml(const std::string& xml, std::string& why) {
  std::vector<std::string> open;
  int roots = 0;
  size_t pos = 0;
  while (pos < xml.size()) {
    const size_t lt = xml.find('<', pos);
    const std::string text = xml.substr(pos, lt == std::string::npos ? std::string::npos : lt - pos);
    for (size_t amp = text.find('&'); amp != std::string::npos; amp = text.find('&', amp + 1))
      if (!std::regex_search(text.substr(amp), std::regex("^&(amp|lt|gt|quot|apos);"))) {
        why = "bare '&' in text";
        return false;
      }
    if (lt == std::string::npos) break;
    if (xml.compare(lt, 2, "<?") == 0) {
      pos = xml.find("?>", lt);
      if (pos == std::string::npos) return why = "unclosed <?", false;
      pos += 2;
      continue;
    }
    size_t gt = lt + 1;
    bool in_quote = false;
    for (; gt < xml.size() && (in_quote || xml[gt] != '>'); ++gt)
      if (xml[gt] == '"') in_quote = !in_quote;
    if (gt >= xml.size()) return why = "unclosed tag", false;
    const std::string tag = xml.substr(lt + 1, gt - lt - 1);
    pos = gt + 1;
    if (tag.starts_with("/")) {
      if (open.empty() || open.back() != tag.substr(1)) return why = "mismatched </" + tag.substr(1) + ">", false;
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
    if (!std::regex_match(tag, std::regex(R"([A-Za-z_][\w:.-]*(\s+[\w:.-]+="[^"<]*")*\s*/?)")))
      return why = "malformed tag <" + tag + ">", false;
    if (open.empty()) ++roots;
    if (!tag.ends_with("/")) open.push_back(name);
  }
  if (!open.empty()) return why = "unclosed <" + open.back() + ">", false;
  if (roots != 1) return why = "expected one root element", false;
  return true;
}

struct HdfItem {
  std::string dimensions, file, dataset;
};

// Every HDF-format DataItem: its Dimensions and the file:dataset it names.
std::vector<HdfItem> hdf_items(const std::string& xml) {
  std::vector<HdfItem> items;
  const std::regex item(R"(<DataItem ([^>]*)Format="HDF"[^>]*>([^<:]+):([^<]+)</DataItem>)");
  const std::regex dims(R"(Dimensions="([^"]*)\")");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), item); it != std::sregex_iterator(); ++it) {
    std::smatch d;
    const std::string attributes = (*it)[1];
    std::regex_search(attributes, d, dims);
    items.push_back({d[1], (*it)[2], (*it)[3]});
  }
  return items;
}

// Dimensions of a dataset read with the HDF5 C API directly (independent of the reader).
std::string raw_dims(const std::filesystem::path& file, const std::string& dataset) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  const hid_t s = H5Dget_space(d);
  hsize_t dims[8] = {};
  const int rank = H5Sget_simple_extent_dims(s, dims, nullptr);
  H5Sclose(s);
  H5Dclose(d);
  H5Fclose(f);
  std::string text;
  for (int k = 0; k < rank; ++k) {
    if (k > 0) text += ' ';
    text += std::to_string(dims[k]);
  }
  return rank < 0 ? "missing" : text;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// A complete results file: a TET10 body and a HEX20 body with static fields,
// an element field, a 3-step series, an envelope; mechanism histories.
struct WrittenRun {
  fem::Mesh tet = testing::single_tet10();
  fem::Mesh hex = testing::single_hex20();
  std::vector<double> times_s = {0.0, 0.25, 0.5};
  std::vector<FieldMatrix> tet_u, tet_vm;

  void write(const std::filesystem::path& path) {
    ResultsWriter writer(path, test_provenance());
    BodyWriter& t = writer.add_body("lever", tet);
    t.write_static("displacement", "m", field_of(tet, 3, 1e-3), kVectorComponents);
    t.write_static("stress", "Pa", field_of(tet, 6, 1e8), kVoigtComponents);
    t.write_static("von_mises", "Pa", field_of(tet, 1, 2e8));
    t.write_element_field("strain_energy_density", "J/m^3", FieldMatrix::Constant(1, 1, 42.0));
    t.begin_series({{"displacement", "m", 3, kVectorComponents}, {"von_mises", "Pa", 1}});
    for (size_t k = 0; k < times_s.size(); ++k) {
      tet_u.push_back(field_of(tet, 3, 1e-3 * double(k + 1)));
      tet_vm.push_back(field_of(tet, 1, 1e8 * double(k + 1)));
      EXPECT_EQ(t.write_step(times_s[k], {{"displacement", tet_u[k]}, {"von_mises", tet_vm[k]}}),
                fem::Index(k));
    }
    IndexMatrix last = IndexMatrix::Constant(tet.node_count(), 1, 2);
    t.write_envelope("von_mises", "Pa", tet_vm.back(), last);

    BodyWriter& h = writer.add_body("link2", hex);
    h.write_static("displacement", "m", field_of(hex, 3, 2e-3), kVectorComponents);
    h.begin_series({{"stress", "Pa", 6, kVoigtComponents}});
    for (size_t k = 0; k < times_s.size(); ++k)
      h.write_step(times_s[k], {{"stress", field_of(hex, 6, 1e7 * double(k + 1))}});

    writer.set_mechanism_time({0.0, 0.1, 0.2, 0.3});
    FieldMatrix torque(4, 1);
    torque << 10.0, 12.5, 15.0, 11.0;
    writer.write_history("drive_torque", "N*m", torque);
    FieldMatrix reaction(4, 3);
    for (int k = 0; k < 12; ++k) reaction(k / 3, k % 3) = -5.0 + k;
    writer.write_history("joint_A_reaction", "N", reaction, kVectorComponents);
    writer.commit();
  }
};

TEST(ResultsFile, RoundTripOfTet10AndHex20MeshesAndFields) {
  TemporaryDirectory dir;
  WrittenRun run;
  run.write(dir / "run.h5");
  ASSERT_TRUE(std::filesystem::exists(dir / "run.h5"));
  ASSERT_TRUE(std::filesystem::exists(dir / "run.xdmf"));

  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  EXPECT_EQ(file.bodies(), (std::vector<std::string>{"lever", "link2"}));
  for (const auto& [body, mesh] : {std::pair{"lever", &run.tet}, std::pair{"link2", &run.hex}}) {
    const fem::Mesh back = file.read_mesh(body);
    EXPECT_EQ(back.nodes, mesh->nodes) << body;
    ASSERT_EQ(back.blocks.size(), 1u);
    EXPECT_EQ(back.blocks[0].type, mesh->blocks[0].type);
    EXPECT_EQ(back.blocks[0].connectivity, mesh->blocks[0].connectivity);
    EXPECT_EQ(back.node_sets, mesh->node_sets);
    EXPECT_EQ(back.element_sets, mesh->element_sets);
    ASSERT_EQ(back.face_sets.size(), mesh->face_sets.size());
    for (const auto& [name, blocks] : mesh->face_sets) {
      ASSERT_EQ(back.face_sets.at(name).size(), blocks.size());
      EXPECT_EQ(back.face_sets.at(name)[0].type, blocks[0].type);
      EXPECT_EQ(back.face_sets.at(name)[0].connectivity, blocks[0].connectivity);
    }
  }

  EXPECT_EQ(file.static_fields("lever"),
            (std::vector<std::string>{"displacement", "stress", "von_mises"}));
  const FieldData stress = file.read_static("lever", "stress");
  EXPECT_EQ(stress.values, field_of(run.tet, 6, 1e8));
  EXPECT_EQ(stress.units, "Pa");
  EXPECT_EQ(stress.component_names, kVoigtComponents);
  EXPECT_TRUE(file.read_static("lever", "von_mises").component_names.empty());
  EXPECT_EQ(file.read_element_field("lever", "strain_energy_density").values(0, 0), 42.0);

  EXPECT_EQ(file.series_fields("lever"), (std::vector<std::string>{"displacement", "von_mises"}));
  EXPECT_EQ(file.series_times("lever"), run.times_s);
  for (size_t k = 0; k < run.times_s.size(); ++k) {
    EXPECT_EQ(file.read_step("lever", "displacement", fem::Index(k)).values, run.tet_u[k]);
    EXPECT_EQ(file.read_step("lever", "von_mises", fem::Index(k)).values, run.tet_vm[k]);
  }
  EXPECT_EQ(file.read_step("link2", "stress", 1).values, field_of(run.hex, 6, 2e7));
  EXPECT_EQ(file.read_step("link2", "stress", 1).units, "Pa");

  const EnvelopeData envelope = file.read_envelope("lever", "von_mises");
  EXPECT_EQ(envelope.values, run.tet_vm.back());
  EXPECT_EQ(envelope.step, IndexMatrix::Constant(10, 1, 2));
  EXPECT_EQ(envelope.operation, "max");

  EXPECT_EQ(file.mechanism_time(), (std::vector<double>{0.0, 0.1, 0.2, 0.3}));
  EXPECT_EQ(file.histories(), (std::vector<std::string>{"drive_torque", "joint_A_reaction"}));
  const FieldData torque = file.read_history("drive_torque");
  EXPECT_EQ(torque.units, "N*m");
  EXPECT_EQ(torque.values(2, 0), 15.0);
  EXPECT_EQ(file.read_history("joint_A_reaction").values.cols(), 3);

  const Provenance p = file.provenance();
  EXPECT_EQ(p.kinetofem_version, kVersion);
  EXPECT_EQ(p.git_commit, kGitCommit);
  EXPECT_EQ(p.case_text, test_provenance().case_text);
  EXPECT_EQ(p.case_path, "cases/lever/case.toml");
  EXPECT_EQ(p.command_line, "kinetofem run cases/lever/case.toml --out 'my dir'");
  EXPECT_TRUE(std::regex_match(p.created_utc, std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
      << p.created_utc;
  EXPECT_FALSE(p.units_note.empty());
}

TEST(ResultsFile, EveryDatasetHasAUnitsAttribute) {
  TemporaryDirectory dir;
  WrittenRun().write(dir / "run.h5");
  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  const auto datasets = file.datasets();
  // provenance 1; lever: mesh 6 (nodes, 2 connectivities, 3 sets), static 3, element 1,
  // series 3 (time + 2), envelope 2; link2: mesh 6, static 1, series 2; mechanism 3.
  EXPECT_EQ(datasets.size(), 28u);
  for (const auto& d : datasets) EXPECT_TRUE(file.has_units(d)) << d;
  EXPECT_EQ(file.units_of("/bodies/lever/mesh/nodes"), "m");
  EXPECT_EQ(file.units_of("/bodies/lever/series/time"), "s");
  EXPECT_EQ(file.units_of("/bodies/lever/series/displacement"), "m");
  EXPECT_EQ(file.units_of("/mechanism/time"), "s");
  EXPECT_EQ(file.units_of("/bodies/lever/envelopes/von_mises/step"), "1");
}

TEST(ResultsFile, WrittenVtkConnectivityPutsMidEdgeNodesAtVtkEdgeMidpoints) {
  // VTK edges (vtkQuadraticTetra / vtkQuadraticHexahedron), as in vtk_node_order_test.cpp.
  const std::vector<std::pair<int, int>> tet = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  const std::vector<std::pair<int, int>> hex = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                                {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  TemporaryDirectory dir;
  WrittenRun run;
  run.write(dir / "run.h5");
  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  for (const auto& [body, edges, corners] :
       {std::tuple{"lever", &tet, 4}, std::tuple{"link2", &hex, 8}}) {
    const fem::Mesh mesh = file.read_mesh(body);
    const IndexMatrix vtk =
        file.read_indices(std::string("/bodies/") + body + "/mesh/blocks/block_0/connectivity_vtk");
    ASSERT_EQ(vtk.rows(), 1);
    ASSERT_EQ(vtk.cols(), corners + Eigen::Index(edges->size()));
    for (size_t k = 0; k < edges->size(); ++k) {
      const Eigen::RowVector3d mid = mesh.nodes.row(vtk(0, corners + Eigen::Index(k)));
      const Eigen::RowVector3d expected = 0.5 * (mesh.nodes.row(vtk(0, (*edges)[k].first)) +
                                                 mesh.nodes.row(vtk(0, (*edges)[k].second)));
      EXPECT_LT((mid - expected).norm(), 1e-15) << body << " VTK edge " << k;
    }
  }
}

TEST(ResultsFile, XdmfIsWellFormedAndReferencesTheDatasetsWithTheirShapes) {
  TemporaryDirectory dir;
  WrittenRun().write(dir / "run.h5");
  const std::string xml = read_text(dir / "run.xdmf");
  std::string why;
  ASSERT_TRUE(well_formed_xml(xml, why)) << why;

  EXPECT_NE(xml.find(R"(<Xdmf Version="3.0")"), std::string::npos);
  EXPECT_NE(xml.find(R"(TopologyType="Tetrahedron_10" NumberOfElements="1")"), std::string::npos);
  EXPECT_NE(xml.find(R"(TopologyType="Hexahedron_20" NumberOfElements="1")"), std::string::npos);
  // One temporal collection per body and one for the mechanism histories
  // (read by ParaView's XDMF Reader and both Xdmf3 readers alike).
  EXPECT_EQ(count_of(xml, R"(GridType="Collection" CollectionType="Temporal")"), 3u);
  EXPECT_EQ(count_of(xml, "<Time Value="), 9u);  // 3 steps x (2 bodies + mechanism)
  EXPECT_NE(xml.find(R"(<Time Value="0.25"/>)"), std::string::npos);
  // Matrix, not Tensor6: the Xdmf2 and Xdmf3 libraries order Tensor6 differently.
  EXPECT_NE(xml.find(R"(Name="stress" AttributeType="Matrix" Center="Node")"), std::string::npos);
  EXPECT_NE(xml.find(R"(Name="strain_energy_density" AttributeType="Scalar" Center="Cell")"),
            std::string::npos);
  // The hyperslab of step 2 of the lever's displacement: start (2,0,0), count (1,10,3).
  EXPECT_NE(xml.find(R"(<DataItem Dimensions="3 3" NumberType="Int" Format="XML">2 0 0 1 1 1 1 10 3</DataItem>)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<DataItem Type="HyperSlab" Dimensions="10 3" NumberType="Float" Precision="8" Format="HDF">run.h5:/bodies/lever/series/displacement|2 0 0:1 1 1:1 10 3:3 10 3)"),
            std::string::npos);

  // Every HDF reference names the .h5 beside it (relative) and a dataset of exactly that shape.
  const auto items = hdf_items(xml);
  EXPECT_GT(items.size(), 20u);
  for (const auto& item : items) {
    EXPECT_EQ(item.file, "run.h5");
    EXPECT_EQ(item.dimensions, raw_dims(dir / "run.h5", item.dataset)) << item.dataset;
  }
  EXPECT_NE(xml.find("run.h5:/bodies/lever/mesh/blocks/block_0/connectivity_vtk"), std::string::npos);
}

TEST(ResultsFile, BodyWithSeveralBlocksGetsAMixedTopology) {
  TemporaryDirectory dir;
  fem::Mesh mesh = testing::single_hex20();
  fem::ElementBlock tet;
  tet.type = fem::ElementType::Tet4;
  tet.connectivity = {0, 1, 3, 4};
  mesh.blocks.push_back(tet);
  {
    ResultsWriter writer(dir / "mixed.h5", test_provenance());
    writer.add_body("bracket", mesh).write_element_field("id", "1", FieldMatrix::Constant(2, 1, 1.0));
    writer.commit();
  }
  const std::string xml = read_text(dir / "mixed.xdmf");
  std::string why;
  ASSERT_TRUE(well_formed_xml(xml, why)) << why;
  EXPECT_NE(xml.find(R"(<Topology TopologyType="Mixed" NumberOfElements="2">)"), std::string::npos);
  // Per element: type code, then its nodes: (1 + 20) + (1 + 4).
  EXPECT_NE(xml.find(R"(Dimensions="26" NumberType="Int")"), std::string::npos);
  const ResultsFile file = ResultsFile::open(dir / "mixed.h5");
  const IndexMatrix mixed = file.read_indices("/bodies/bracket/mesh/xdmf_mixed_topology");
  ASSERT_EQ(mixed.rows(), 26);
  EXPECT_EQ(mixed(0, 0), 48);   // Hexahedron_20
  EXPECT_EQ(mixed(21, 0), 6);   // Tetrahedron
  EXPECT_EQ(mixed(22, 0), 0);
  EXPECT_EQ(file.read_mesh("bracket").blocks.size(), 2u);
}

TEST(ResultsFile, AcceptsColumnVectorsAndStridedBlocksOfLargerMatrices) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  const FieldMatrix both = field_of(mesh, 6, 1.0);  // rows of 6: leftCols(3) has stride 6
  Eigen::VectorXd vm(mesh.node_count());             // column-major N x 1
  for (Eigen::Index i = 0; i < vm.size(); ++i) vm(i) = 100.0 + double(i);
  {
    ResultsWriter writer(dir / "run.h5", test_provenance());
    BodyWriter& body = writer.add_body("lever", mesh);
    body.write_static("left", "m", both.leftCols(3));
    body.write_static("vm", "Pa", vm);
    body.begin_series({{"right", "m", 3}, {"vm", "Pa", 1}});
    body.write_step(1.0, {{"right", both.rightCols(3)}, {"vm", vm}});
    writer.commit();
  }
  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  EXPECT_EQ(file.read_static("lever", "left").values, FieldMatrix(both.leftCols(3)));
  EXPECT_EQ(file.read_static("lever", "vm").values, FieldMatrix(vm));
  EXPECT_EQ(file.read_step("lever", "right", 0).values, FieldMatrix(both.rightCols(3)));
  EXPECT_EQ(file.read_step("lever", "vm", 0).values, FieldMatrix(vm));
}

TEST(ResultsFile, SeriesIsChunkedPerTimeStepAndGrowsStepByStep) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_hex20();
  ResultsWriter writer(dir / "s.h5", test_provenance());
  BodyWriter& body = writer.add_body("b", mesh);
  body.begin_series({{"u", "m", 3}});
  for (int k = 0; k < 5; ++k) {
    // The file grows one step per call: the series is never held in memory.
    body.write_step(0.1 * k, {{"u", field_of(mesh, 3, k)}});
    EXPECT_EQ(body.steps_written(), k + 1);
  }
  writer.commit();
  const hid_t f = H5Fopen((dir / "s.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, "/bodies/b/series/u", H5P_DEFAULT);
  const hid_t plist = H5Dget_create_plist(d);
  hsize_t chunk[3] = {};
  EXPECT_EQ(H5Pget_layout(plist), H5D_CHUNKED);
  EXPECT_EQ(H5Pget_chunk(plist, 3, chunk), 3);
  EXPECT_EQ(chunk[0], 1u);
  EXPECT_EQ(chunk[1], 20u);
  EXPECT_EQ(chunk[2], 3u);
  H5Pclose(plist);
  H5Dclose(d);
  H5Fclose(f);
  EXPECT_EQ(raw_dims(dir / "s.h5", "/bodies/b/series/u"), "5 20 3");
}

TEST(ResultsFile, WriterThatThrowsMidwayLeavesNoFileAndKeepsTheOlderOne) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  const FieldMatrix old_u = field_of(mesh, 3, 1.0);
  {
    ResultsWriter writer(dir / "run.h5", test_provenance());
    writer.add_body("lever", mesh).write_static("displacement", "m", old_u);
    writer.commit();
  }
  const std::string old_xdmf = read_text(dir / "run.xdmf");

  // A run that fails part-way (here: a wrong field shape) and unwinds.
  EXPECT_THROW(
      {
        ResultsWriter writer(dir / "run.h5", test_provenance());
        BodyWriter& body = writer.add_body("lever", mesh);
        body.write_static("displacement", "m", field_of(mesh, 3, 2.0));
        EXPECT_TRUE(std::filesystem::exists(dir / "run.h5.tmp"));
        body.write_static("stress", "Pa", FieldMatrix::Zero(3, 6));  // 3 rows, mesh has 10 nodes
        writer.commit();
      },
      Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "run.h5.tmp"));
  EXPECT_FALSE(std::filesystem::exists(dir / "run.xdmf.tmp"));
  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  EXPECT_EQ(file.read_static("lever", "displacement").values, old_u);
  EXPECT_EQ(file.static_fields("lever"), std::vector<std::string>{"displacement"});
  EXPECT_EQ(read_text(dir / "run.xdmf"), old_xdmf);

  // A first run that fails leaves nothing under the final name.
  try {
    ResultsWriter writer(dir / "fresh.h5", test_provenance());
    writer.add_body("lever", mesh);
    throw std::runtime_error("solver diverged");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "fresh.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "fresh.h5.tmp"));
  EXPECT_FALSE(std::filesystem::exists(dir / "fresh.xdmf"));
}

TEST(ResultsFile, UnwritableDirectoryIsAnErrorNamingIt) {
  TemporaryDirectory dir;
  const auto missing = dir / "no_such_dir";
  try {
    ResultsWriter writer(missing / "run.h5", test_provenance());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  // A regular file where the directory should be (fails even for root).
  std::ofstream(dir / "plain_file") << "x";
  try {
    ResultsWriter writer(dir / "plain_file" / "run.h5", test_provenance());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "plain_file").string()), std::string::npos)
        << e.what();
  }
}

TEST(ResultsFile, ReadOnlyDirectoryIsAnErrorNamingIt) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  TemporaryDirectory dir;
  const auto locked = dir / "locked";
  std::filesystem::create_directory(locked);
  std::filesystem::permissions(locked, std::filesystem::perms::owner_read |
                                           std::filesystem::perms::owner_exec);
  try {
    ResultsWriter writer(locked / "run.h5", test_provenance());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(locked.string()), std::string::npos) << e.what();
  }
}

TEST(ResultsFile, BadSeriesCallsAreErrorsNamingTheFieldAndStep) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  ResultsWriter writer(dir / "run.h5", test_provenance());
  BodyWriter& body = writer.add_body("lever", mesh);
  body.begin_series({{"u", "m", 3}, {"von_mises", "Pa", 1}});
  const FieldMatrix u = field_of(mesh, 3, 1.0), vm = field_of(mesh, 1, 1.0);
  try {
    body.write_step(0.0, {{"u", u}});
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'von_mises' missing"), std::string::npos) << e.what();
  }
  body.write_step(0.0, {{"u", u}, {"von_mises", vm}});
  EXPECT_THROW(body.write_step(0.0, {{"u", u}, {"von_mises", vm}}), Error);  // time must increase
  EXPECT_THROW(body.write_step(0.1, {{"u", vm}, {"von_mises", vm}}), Error);  // wrong shape
  EXPECT_THROW(body.write_step(0.1, {{"u", u}, {"p", vm}}), Error);           // undeclared
  EXPECT_THROW(writer.add_body("lever", mesh), Error);                        // duplicate body
  EXPECT_THROW(writer.add_body("bad/name", mesh), Error);
  // The rejected calls did not touch the file: it still commits with one step.
  writer.commit();
  EXPECT_EQ(ResultsFile::open(dir / "run.h5").series_times("lever"), std::vector<double>{0.0});
  EXPECT_THROW(writer.commit(), Error);
}

TEST(ResultsFile, GeometrySeriesFieldIsMarkedInTheFileAndReadBack) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  const FieldMatrix position = field_of(mesh, 3, 1.0), vm = field_of(mesh, 1, 1e6);
  {
    ResultsWriter writer(dir / "run.h5", test_provenance());
    BodyWriter& moving = writer.add_body("assembly.lever", mesh);
    moving.begin_series({{"displacement", "m", 3, kVectorComponents},
                         {"position", "m", 3, kVectorComponents, /*geometry=*/true},
                         {"von_mises", "Pa", 1}});
    moving.write_step(0.0, {{"displacement", position}, {"position", position}, {"von_mises", vm}});
    BodyWriter& still = writer.add_body("lever", mesh);
    still.begin_series({{"position", "m", 3, kVectorComponents}});
    still.write_step(0.0, {{"position", position}});
    writer.add_body("base", mesh);
    writer.commit();
  }
  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  EXPECT_EQ(file.format_version(), 1);  // an added attribute: the layout is unchanged
  EXPECT_EQ(file.geometry_field("assembly.lever"), "position");
  EXPECT_EQ(file.geometry_field("lever"), "");
  EXPECT_EQ(file.geometry_field("base"), "");  // no series at all
  EXPECT_THROW(file.geometry_field("crank"), Error);
  EXPECT_EQ(file.read_step("assembly.lever", "position", 0).values, position);
  EXPECT_EQ(file.read_step("assembly.lever", "position", 0).units, "m");

  // The flag is the int64 attribute xdmf_geometry = 1 on the series dataset itself.
  const hid_t h5 = H5Fopen((dir / "run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(h5, 0);
  const hid_t dataset = H5Dopen2(h5, "/bodies/assembly.lever/series/position", H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  ASSERT_GT(H5Aexists(dataset, layout::kXdmfGeometry), 0);
  const hid_t attribute = H5Aopen(dataset, layout::kXdmfGeometry, H5P_DEFAULT);
  std::int64_t flag = 0;
  EXPECT_GE(H5Aread(attribute, H5T_NATIVE_INT64, &flag), 0);
  EXPECT_EQ(flag, 1);
  H5Aclose(attribute);
  const hid_t other = H5Dopen2(h5, "/bodies/assembly.lever/series/displacement", H5P_DEFAULT);
  EXPECT_EQ(H5Aexists(other, layout::kXdmfGeometry), 0);
  H5Dclose(other);
  H5Dclose(dataset);
  H5Fclose(h5);
}

TEST(ResultsFile, GeometryIsAtMostOneThreeComponentSeriesField) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  ResultsWriter writer(dir / "run.h5", test_provenance());
  BodyWriter& body = writer.add_body("assembly.lever", mesh);
  auto message_of = [&](const std::vector<SeriesField>& fields) {
    try {
      body.begin_series(fields);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no Error");
  };
  const std::string one = message_of({{"von_mises", "Pa", 1, {}, true}});
  EXPECT_NE(one.find("'assembly.lever'"), std::string::npos) << one;
  EXPECT_NE(one.find("'von_mises'"), std::string::npos) << one;
  EXPECT_NE(one.find("1 components"), std::string::npos) << one;
  const std::string two = message_of({{"position", "m", 3, kVectorComponents, true},
                                      {"deformed", "m", 3, kVectorComponents, true}});
  EXPECT_NE(two.find("'assembly.lever'"), std::string::npos) << two;
  EXPECT_NE(two.find("'position'"), std::string::npos) << two;
  EXPECT_NE(two.find("'deformed'"), std::string::npos) << two;
  // The refused declarations left nothing behind: a correct one still works.
  body.begin_series({{"position", "m", 3, kVectorComponents, true}});
  body.write_step(0.0, {{"position", mesh.nodes}});
  writer.commit();
  EXPECT_EQ(ResultsFile::open(dir / "run.h5").geometry_field("assembly.lever"), "position");
}

TEST(ResultsFile, ReaderErrorsNameWhatIsMissing) {
  TemporaryDirectory dir;
  WrittenRun().write(dir / "run.h5");
  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  try {
    file.read_mesh("crank");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'crank'"), std::string::npos) << m;
    EXPECT_NE(m.find("lever, link2"), std::string::npos) << m;
  }
  EXPECT_THROW(file.read_static("lever", "temperature"), Error);
  EXPECT_THROW(file.read_step("lever", "displacement", 3), Error);
  // A failing HDF5 call names the function and the file.
  try {
    file.units_of("/bodies/lever/nothing");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("H5Dopen2"), std::string::npos) << m;
    EXPECT_NE(m.find((dir / "run.h5").string()), std::string::npos) << m;
  }
  std::ofstream(dir / "not_hdf5.h5") << "plain text";
  EXPECT_THROW(ResultsFile::open(dir / "not_hdf5.h5"), Error);
  EXPECT_THROW(ResultsFile::open(dir / "absent.h5"), Error);
}


// Tables (/tables/<name>): any size, not tied to the mechanism time grid, not in the XDMF file.
TEST(ResultsFile, TablesOfAnySizeRoundTripWithUnitsAndComponents) {
  TemporaryDirectory dir;
  {
    ResultsWriter writer(dir / "tables.h5", test_provenance());
    writer.set_mechanism_time({0.0, 0.5, 1.0});  // tables need no grid; this one is 3 long
    FieldMatrix time(7, 1), displacement(7, 3), scalar(1, 1);
    for (int k = 0; k < 7; ++k) {
      time(k, 0) = 0.25 * k;
      displacement.row(k) << 1e-3 * k, -2e-3 * k, 0.5e-3;
    }
    scalar(0, 0) = std::numeric_limits<double>::infinity();  // e.g. a settling time that never comes
    writer.write_table("response.time", "s", time);
    writer.write_table("response.point.H.displacement", "m", displacement, kVectorComponents);
    writer.write_table("point.H.settling_time", "s", scalar);
    writer.write_table("empty", "m", FieldMatrix(0, 2));
    writer.commit();
  }
  const ResultsFile file = ResultsFile::open(dir / "tables.h5");
  EXPECT_EQ(file.format_version(), kFormatVersion);
  EXPECT_EQ(file.tables(), (std::vector<std::string>{"empty", "point.H.settling_time", "response.point.H.displacement",
                                                     "response.time"}));
  const FieldData time = file.read_table("response.time");
  EXPECT_EQ(time.values.rows(), 7);
  EXPECT_EQ(time.values(6, 0), 1.5);
  EXPECT_EQ(time.units, "s");
  EXPECT_TRUE(time.component_names.empty());
  const FieldData u = file.read_table("response.point.H.displacement");
  EXPECT_EQ(u.values.rows(), 7);
  EXPECT_EQ(u.values(3, 1), -6e-3);
  EXPECT_EQ(u.component_names, kVectorComponents);
  EXPECT_EQ(file.read_table("point.H.settling_time").values(0, 0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(file.read_table("empty").values.rows(), 0);
  EXPECT_EQ(file.units_of("/tables/response.time"), "s");
  EXPECT_EQ(file.histories(), std::vector<std::string>{});  // tables are not histories
  EXPECT_EQ(read_text(dir / "tables.xdmf").find("/tables/"), std::string::npos);
}

TEST(ResultsFile, FileWithoutTablesListsNone) {
  TemporaryDirectory dir;
  WrittenRun().write(dir / "run.h5");
  EXPECT_TRUE(ResultsFile::open(dir / "run.h5").tables().empty());
}

using testing::error_text;

TEST(ResultsFile, BadTableCallsAreErrorsNamingTheTable) {
  TemporaryDirectory dir;
  ResultsWriter writer(dir / "bad.h5", test_provenance());
  const FieldMatrix one = FieldMatrix::Constant(1, 1, 2.0);
  writer.write_table("stop_time", "s", one);
  std::string m = error_text([&] { writer.write_table("stop_time", "s", one); });
  EXPECT_NE(m.find("table 'stop_time' is already written"), std::string::npos) << m;
  m = error_text([&] { writer.write_table("a/b", "s", one); });
  EXPECT_NE(m.find("table name 'a/b' is not allowed"), std::string::npos) << m;
  m = error_text([&] { writer.write_table("u", "m", FieldMatrix(FieldMatrix::Zero(4, 3)), {"x", "y"}); });
  EXPECT_NE(m.find("'u' has 3 columns but 2 component names"), std::string::npos) << m;
  m = error_text([&] { writer.write_table("nothing", "m", FieldMatrix(4, 0)); });
  EXPECT_NE(m.find("table 'nothing' has no columns"), std::string::npos) << m;
  writer.commit();  // the refused calls left the file usable

  const ResultsFile file = ResultsFile::open(dir / "bad.h5");
  EXPECT_EQ(file.tables(), std::vector<std::string>{"stop_time"});
  m = error_text([&] { file.read_table("settling_time"); });
  EXPECT_NE(m.find((dir / "bad.h5").string()), std::string::npos) << m;
  EXPECT_NE(m.find("no table 'settling_time'"), std::string::npos) << m;
  EXPECT_NE(m.find("present: stop_time"), std::string::npos) << m;
}

}  // namespace
}  // namespace kinetofem::post
