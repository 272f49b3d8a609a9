#include "kinetofem/app/fe_static_job.hpp"

#include <filesystem>

#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/meshes/lever.hpp"
#include "kinetofem/meshes/geo_file_scan.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/meshes/msh_io.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kMm;
using units::kMpa;
}  // namespace

const std::vector<KeySpec>& fe_static_schema() {
  static const meshes::LeverDimensions lever;
  static const fem::IsotropicMaterial steel;
  static const std::vector<KeySpec> schema = with_common_keys({
      case_name_key(),
      {.path = "case.type", .type = Type::String, .allowed = {"fe_static"}, .doc = "kind of analysis", .required = true},
      {.path = "case.description", .type = Type::String, .doc = "free text, copied into the results"},
      {.path = "geometry.kind", .type = Type::String, .default_text = "lever", .allowed = {"lever", "file"},
       .doc = "'lever': the parametric lever 1 of SPEC §1 (meshes/geometry/lever.geo); 'file': geometry.file"},
      {.path = "geometry.file", .type = Type::String,
       .doc = "geometry (.geo, .step, .brep) or mesh (.msh 4.1) file, relative to the case file (geometry.kind = 'file')"},
      {.path = "geometry.length_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = lever.length_m / kMm,
       .min = 0, .max = kMaxPartDimensionMm, .min_exclusive = true, .doc = "lever length a = |A0 A| between the bore centres",
       .range_note = kPartDimensionNote},
      {.path = "geometry.width_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = lever.width_m / kMm,
       .min = 0, .max = kMaxPartDimensionMm, .min_exclusive = true, .doc = "lever plate width",
       .range_note = kPartDimensionNote},
      {.path = "geometry.thickness_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = lever.thickness_m / kMm,
       .min = 0, .max = kMaxPartDimensionMm, .min_exclusive = true, .doc = "lever plate thickness",
       .range_note = kPartDimensionNote},
      {.path = "geometry.bore_diameter_mm", .type = Type::Number, .unit = "mm", .to_si = kMm,
       .default_number = lever.bore_diameter_m / kMm, .min = 0, .max = kMaxPartDimensionMm, .min_exclusive = true, .doc = "pin bore diameter",
       .range_note = kPartDimensionNote},
      {.path = "geometry.boss_diameter_mm", .type = Type::Number, .unit = "mm", .to_si = kMm,
       .default_number = lever.boss_diameter_m / kMm, .min = 0, .max = kMaxPartDimensionMm, .min_exclusive = true, .doc = "boss outer diameter",
       .range_note = kPartDimensionNote},
      {.path = "geometry.boss_length_mm", .type = Type::Number, .unit = "mm", .to_si = kMm,
       .default_number = lever.boss_length_m / kMm, .min = 0, .max = kMaxPartDimensionMm, .min_exclusive = true, .doc = "boss length along the pin axis",
       .range_note = kPartDimensionNote},
      {.path = "mesh.element_size_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 8.0,
       .min = 0, .min_exclusive = true, .doc = "target element edge length"},
      {.path = "mesh.order", .type = Type::Integer, .default_number = 2, .min = 1, .max = 2,
       .doc = "element order: 1 (TET4/HEX8) or 2 (TET10/HEX20)"},
      {.path = "mesh.family", .type = Type::String, .default_text = "tet", .allowed = {"tet", "hex"},
       .doc = "'tet': tetrahedra; 'hex': all-hexahedral by splitting tetrahedra"},
      {.path = "mesh.optimize", .type = Type::Boolean, .default_number = 1, .doc = "optimize element shapes after meshing"},
      mesh_time_limit_key(),
      {.path = "support", .type = Type::TableArray, .doc = "displacement supports"},
      {.path = "support[].set", .type = Type::String, .doc = "node set (physical group) of the mesh", .required = true},
      {.path = "support[].fixed", .type = Type::StringList, .default_text = "x,y,z", .allowed = {"x", "y", "z"},
       .doc = "prescribed displacement components"},
      {.path = "support[].displacement_mm", .type = Type::Vector3, .unit = "mm", .to_si = kMm, .default_number = 0.0,
       .doc = "prescribed displacement of the fixed components"},
      {.path = "force", .type = Type::TableArray, .doc = "resultant forces spread over face sets"},
      {.path = "force[].set", .type = Type::String, .doc = "face set (physical surface) loaded", .required = true},
      {.path = "force[].total_n", .type = Type::Vector3, .unit = "N",
       .doc = "resultant force, applied as a uniform traction (resultant / area) over the face set", .required = true},
      {.path = "pressure", .type = Type::TableArray, .doc = "pressures on face sets"},
      {.path = "pressure[].set", .type = Type::String, .doc = "face set (physical surface) loaded", .required = true},
      {.path = "pressure[].pressure_mpa", .type = Type::Number, .unit = "MPa", .to_si = kMpa,
       .doc = "pressure, positive pushing into the body", .required = true},
      {.path = "gravity.acceleration_m_s2", .type = Type::Vector3, .unit = "m/s^2", .default_number = 0.0,
       .doc = "gravitational acceleration vector (e.g. [0, 0, -9.81])"},
  });
  return schema;
}

namespace {

fem::Mesh build_mesh(const CaseFile& c, const Log& log, bool trust_geometry_file) {
  meshes::MeshOptions options;
  options.element_size_m = c.number("mesh.element_size_mm");
  options.order = int(c.integer("mesh.order"));
  options.family = c.text_value("mesh.family") == "hex" ? meshes::ElementFamily::Hexahedra
                                                        : meshes::ElementFamily::Tetrahedra;
  options.optimize = c.boolean("mesh.optimize");
  options.time_limit_s = c.number("mesh.time_limit_s");
  Stopwatch clock;
  fem::Mesh mesh;
  if (c.text_value("geometry.kind") == "lever") {
    meshes::LeverDimensions d;
    d.length_m = c.number("geometry.length_mm");
    d.width_m = c.number("geometry.width_mm");
    d.thickness_m = c.number("geometry.thickness_mm");
    d.bore_diameter_m = c.number("geometry.bore_diameter_mm");
    d.boss_diameter_m = c.number("geometry.boss_diameter_mm");
    d.boss_length_m = c.number("geometry.boss_length_mm");
    try {
      d.validate();
    } catch (const Error& e) {
      fail("{}: [geometry]: {}", c.path().string(), e.what());
    }
    log.info("meshing lever: a = {:.1f} mm, element size {:.1f} mm, order {}", d.length_m / kMm,
             options.element_size_m / kMm, options.order);
    mesh = meshes::mesh_lever(d, options);
  } else {
    require(c.has("geometry.file"), "{} is required when geometry.kind = \"file\"",
            c.where("geometry.file"));
    const auto file = c.path().parent_path() / c.text_value("geometry.file");
    // A missing file is the mesh reader's error; a FIFO would block it forever.
    if (const std::string problem = input_file_problem(file); !problem.empty() && problem != "no such file")
      fail("{} = \"{}\": {} ({})", c.where("geometry.file"), c.text_value("geometry.file"), problem, file.string());
    if (file.extension() == ".msh") {
      log.info("reading mesh {}", file.string());
      mesh = meshes::read_msh(file);
    } else {
      log.info("meshing {} (element size {:.1f} mm, order {})", file.string(),
               options.element_size_m / kMm, options.order);
      if (file.extension() == ".geo") {
        // Before Gmsh reads the script: what it may do besides geometry.
        meshes::GeoScanPolicy policy;
        policy.read_roots = {c.path().parent_path().empty() ? "." : c.path().parent_path()};
        policy.trusted = trust_geometry_file;
        meshes::scan_geo_file(file, policy);
      }
      mesh = meshes::mesh_geometry(file, options);
    }
  }
  log.info("  mesh: {} nodes, {} elements ({}), {:.2f} s", mesh.node_count(),
           mesh.element_count(), fem::name_of(mesh.blocks.front().type), clock.seconds());
  return mesh;
}

template <typename Map>
void require_set(const Map& sets, const std::string& name, const CaseFile& c,
                 const std::string& key, std::size_t element, const char* kind) {
  if (sets.count(name)) return;
  std::string present;
  for (const auto& [n, v] : sets) present += (present.empty() ? "" : ", ") + n;
  fail("{} = \"{}\": the mesh has no {} of that name (present: {})", c.where(key, element), name,
       kind, present.empty() ? "none" : present);
}

}  // namespace

FeStaticSummary run_fe_static(const CaseFile& c, const RunOptions& options) {
  Stopwatch total;
  const std::string name = case_name(c);
  const Log log = start_case_log(c, options, name, "type fe_static");

  // Fail before the long steps if the results cannot be written.
  std::error_code ec;
  std::filesystem::create_directories(options.output_dir, ec);
  if (ec) fail("{}: cannot create the output directory: {}", options.output_dir.string(), ec.message());

  fem::FeModel model;
  model.mesh = build_mesh(c, log, options.trust_part_files);
  model.material = read_material(c);

  require(c.count("support") > 0, "{}: no [[support]]: a static model needs supports",
          c.path().string());
  for (std::size_t k = 0; k < c.count("support"); ++k) {
    const std::string set = c.text_value("support[].set", k);
    require_set(model.mesh.node_sets, set, c, "support[].set", k, "node set");
    fem::DisplacementSupport support;
    support.label = set;
    support.nodes = model.mesh.node_sets.at(set);
    support.fixed = {false, false, false};
    for (const auto& axis : c.strings("support[].fixed", k)) support.fixed[size_t(axis[0] - 'x')] = true;
    support.value_m = c.vector3("support[].displacement_mm", k);
    model.supports.push_back(support);
  }

  fem::LoadCase load;
  load.name = name;
  load.gravity_m_s2 = c.vector3("gravity.acceleration_m_s2");
  Eigen::Vector3d applied = model.material.density_kg_m3 * load.gravity_m_s2;  // per volume, scaled below
  applied *= fem::mesh_volume(model.mesh);
  for (std::size_t k = 0; k < c.count("force"); ++k) {
    const std::string set = c.text_value("force[].set", k);
    require_set(model.mesh.face_sets, set, c, "force[].set", k, "face set");
    const double area = fem::surface_area(model.mesh, model.mesh.face_sets.at(set));
    require(area > 0, "{}: face set '{}' has zero area", c.where("force[].set", k), set);
    const Eigen::Vector3d force = c.vector3("force[].total_n", k);
    load.tractions.push_back({set, force / area});
    applied += force;
    log.info("  load: {:.4g} N on '{}' ({:.1f} mm^2), as traction {:.4g} MPa", force.norm(), set,
             area * 1e6, force.norm() / area / kMpa);
  }
  for (std::size_t k = 0; k < c.count("pressure"); ++k) {
    const std::string set = c.text_value("pressure[].set", k);
    require_set(model.mesh.face_sets, set, c, "pressure[].set", k, "face set");
    load.pressures.push_back({set, c.number("pressure[].pressure_mpa", k)});
  }

  const fem::StaticSolverOptions solver_options = read_solver_options(c);

  log.info("solving");
  fem::LinearStaticAnalysis analysis(model, log, solver_options);
  const Eigen::MatrixXd F = fem::assemble_external_forces(model.mesh, analysis.materials(), {load});
  const fem::DisplacementField u = analysis.solve_forces(F).front();
  Stopwatch clock;
  const fem::NodalStress stress = fem::recover_nodal_stress(model.mesh, analysis.materials(), u);
  const Eigen::VectorXd magnitude = fem::displacement_magnitude(u);
  log.info("  stress recovery: {:.2f} s", clock.seconds());

  // Equilibrium: support reactions must balance the applied loads.
  const Eigen::VectorXd reactions = analysis.reactions(u, F.col(0));
  Eigen::Vector3d reaction_sum = Eigen::Vector3d::Zero(), load_sum = Eigen::Vector3d::Zero();
  for (fem::Index i = 0; i < model.mesh.node_count(); ++i) {
    reaction_sum += reactions.segment<3>(3 * i);
    load_sum += F.col(0).segment<3>(3 * i);
  }

  FeStaticSummary summary;
  summary.node_count = model.mesh.node_count();
  summary.element_count = model.mesh.element_count();
  summary.dof_count = 3 * model.mesh.node_count();
  fem::Index vm_node = 0, u_node = 0;
  summary.max_von_mises_pa = stress.von_mises_pa.maxCoeff(&vm_node);
  summary.max_displacement_m = magnitude.maxCoeff(&u_node);
  summary.reaction_balance =
      load_sum.norm() > 0 ? (reaction_sum + load_sum).norm() / load_sum.norm() : reaction_sum.norm();

  // Results: written to a temporary file, renamed when complete.
  summary.results_file = options.output_dir / (name + ".h5");
  post::Provenance provenance;
  provenance.case_path = c.path().string();
  provenance.case_text = c.text();
  provenance.command_line = options.command_line;
  post::ResultsWriter writer(summary.results_file, provenance);
  auto& body = writer.add_body("part", model.mesh);
  body.write_static(post::layout::kDisplacement, "m", u, post::kVectorComponents);
  body.write_static(post::layout::kDisplacementMagnitude, "m", magnitude);
  body.write_static(post::layout::kStress, "Pa", stress.stress_pa, post::kVoigtComponents);
  body.write_static(post::layout::kVonMises, "Pa", stress.von_mises_pa);
  body.write_static(post::layout::kPrincipalStress, "Pa", stress.principal_pa, post::kPrincipalComponents);
  writer.commit();

  const auto vm_at = model.mesh.nodes.row(vm_node) / kMm;
  const auto u_at = model.mesh.nodes.row(u_node) / kMm;
  std::printf(
      "\nSummary of '%s'\n"
      "  mesh                 %ld nodes, %ld elements, %ld DoFs\n"
      "  solver               %s\n"
      "  max von Mises        %.3f MPa at node %ld (%.1f, %.1f, %.1f) mm\n"
      "  max displacement     %.5f mm at node %ld (%.1f, %.1f, %.1f) mm\n"
      "  applied load         (%.4g, %.4g, %.4g) N; reactions balance it to %.1e (relative)\n"
      "  results              %s (+ .xdmf for ParaView)\n"
      "  wall time            %.2f s\n",
      name.c_str(), summary.node_count, summary.element_count, summary.dof_count,
      analysis.solver_summary().c_str(),
      summary.max_von_mises_pa / kMpa, long(vm_node), vm_at[0], vm_at[1], vm_at[2],
      summary.max_displacement_m / kMm, long(u_node), u_at[0], u_at[1], u_at[2], load_sum[0],
      load_sum[1], load_sum[2], summary.reaction_balance, summary.results_file.string().c_str(),
      total.seconds());
  require(summary.reaction_balance < 1e-6,
          "equilibrium check failed: support reactions balance the loads only to {:.2e}",
          summary.reaction_balance);
  return summary;
}

}  // namespace kinetofem::app
