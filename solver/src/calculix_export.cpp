#include "kinetofem/solver/calculix_export.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/element_library.hpp"

namespace kinetofem::fem {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// Comma-separated integers, at most 16 entries per line (the Abaqus/ccx
// limit), a trailing comma on each line that continues.
void write_id_list(std::FILE* file, const std::vector<long long>& ids, size_t first_line) {
  size_t on_line = 0, line_limit = first_line;
  for (size_t k = 0; k < ids.size(); ++k) {
    std::fprintf(file, "%s%lld", on_line == 0 ? "" : ", ", ids[k]);
    if (++on_line == line_limit && k + 1 < ids.size()) {
      std::fputs(",\n", file);
      on_line = 0;
      line_limit = 16;
    }
  }
  std::fputc('\n', file);
}

}  // namespace

const char* calculix_element_name(ElementType type) { return element_facts(type).calculix_name; }

std::vector<int> calculix_node_order(ElementType type) {
  const auto order = element_facts(type).calculix_from_gmsh;
  return {order.begin(), order.end()};
}

void write_calculix_deck(const FeModel& model, const Eigen::MatrixXd& external_forces,
                         const std::filesystem::path& path, const CalculixDeckOptions& options) {
  const Mesh& mesh = model.mesh;
  mesh.validate();
  const ElementMaterials materials = element_materials(model);
  const DofMap dofs(mesh.node_count(), model.supports);
  require(external_forces.rows() == dofs.dof_count(),
          "CalculiX deck {}: force vectors have {} rows, the model {} DoFs", path.string(),
          external_forces.rows(), dofs.dof_count());
  require(external_forces.cols() > 0, "CalculiX deck {}: no load case", path.string());

  File file(std::fopen(path.c_str(), "w"));
  require(file != nullptr, "cannot write CalculiX deck {}", path.string());
  std::FILE* out = file.get();
  std::setvbuf(out, nullptr, _IOFBF, 1 << 20);

  // Reals as %.12e: ccx reads at most 20 characters per field (13
  // significant digits, sign and a three-digit exponent included).
  std::fprintf(out, "*HEADING\n%s\n", options.heading.c_str());
  std::fputs("*NODE, NSET=NALL\n", out);
  for (Index n = 0; n < mesh.node_count(); ++n)
    std::fprintf(out, "%lld, %.12e, %.12e, %.12e\n", static_cast<long long>(n + 1),
                 mesh.nodes(n, 0), mesh.nodes(n, 1), mesh.nodes(n, 2));

  Index element_id = 1;
  std::vector<long long> ids;
  for (size_t b = 0; b < mesh.blocks.size(); ++b) {
    const ElementBlock& block = mesh.blocks[b];
    const std::vector<int> order = calculix_node_order(block.type);
    std::fprintf(out, "*ELEMENT, TYPE=%s, ELSET=E%zu\n", calculix_element_name(block.type), b + 1);
    for (Index e = 0; e < block.size(); ++e, ++element_id) {
      const auto nodes = block.element(e);
      ids.assign(1, static_cast<long long>(element_id));
      for (int local : order) ids.push_back(static_cast<long long>(nodes[size_t(local)] + 1));
      write_id_list(out, ids, 16);
    }
  }

  if (materials.uniform()) {
    std::fprintf(out, "*MATERIAL, NAME=MAT1\n*ELASTIC\n%.12e, %.12e\n",
                 model.material.youngs_modulus_pa, model.material.poisson_ratio);
    for (size_t b = 0; b < mesh.blocks.size(); ++b)
      std::fprintf(out, "*SOLID SECTION, ELSET=E%zu, MATERIAL=MAT1\n", b + 1);
  } else {
    // One section per material over the elements that take it; a material
    // that no element takes gets none.
    std::vector<std::vector<long long>> members(materials.materials().size());
    for (Index e = 0; e < mesh.element_count(); ++e)
      members[size_t(materials.index_of(e))].push_back(static_cast<long long>(e + 1));
    for (size_t k = 0; k < members.size(); ++k) {
      if (members[k].empty()) continue;
      const IsotropicMaterial& m = materials.materials()[k];
      const std::string whose = k == 0 ? std::string("the elements in no listed set")
                                       : "element set '" + materials.element_set(k) + "'";
      std::fprintf(out, "** material '%s' of %s\n", m.name.c_str(), whose.c_str());
      std::fprintf(out, "*ELSET, ELSET=M%zu\n", k + 1);
      write_id_list(out, members[k], 16);
      std::fprintf(out, "*MATERIAL, NAME=MAT%zu\n*ELASTIC\n%.12e, %.12e\n", k + 1,
                   m.youngs_modulus_pa, m.poisson_ratio);
      std::fprintf(out, "*SOLID SECTION, ELSET=M%zu, MATERIAL=MAT%zu\n", k + 1, k + 1);
    }
  }

  // ccx accepts only homogeneous conditions in the model data; nonzero
  // values go into the first step (and stay in the later ones: OP=MOD).
  bool any_nonzero = false, any_zero = false;
  for (Index d = 0; d < dofs.dof_count(); ++d)
    if (dofs.equation(d) < 0) (dofs.prescribed_values()[d] != 0.0 ? any_nonzero : any_zero) = true;
  if (any_zero) {
    std::fputs("*BOUNDARY\n", out);
    for (Index d = 0; d < dofs.dof_count(); ++d) {
      if (dofs.equation(d) >= 0 || dofs.prescribed_values()[d] != 0.0) continue;
      std::fprintf(out, "%lld, %d, %d\n", static_cast<long long>(d / 3 + 1), int(d % 3) + 1,
                   int(d % 3) + 1);
    }
  }

  const bool print_some = options.print_displacements &&
                          (options.print_all_displacements || !options.printed_nodes.empty());
  if (print_some && !options.print_all_displacements) {
    std::fputs("*NSET, NSET=NPRINT\n", out);
    ids.clear();
    for (Index n : options.printed_nodes) {
      require(n >= 0 && n < mesh.node_count(), "CalculiX deck: printed node {} out of range (0..{})",
              n, mesh.node_count() - 1);
      ids.push_back(static_cast<long long>(n + 1));
    }
    write_id_list(out, ids, 16);
  }

  for (Index k = 0; k < external_forces.cols(); ++k) {
    std::fprintf(out, "*STEP\n*STATIC%s%s\n", options.solver.empty() ? "" : ", SOLVER=",
                 options.solver.c_str());
    if (k == 0 && any_nonzero) {
      std::fputs("*BOUNDARY\n", out);
      for (Index d = 0; d < dofs.dof_count(); ++d)
        if (dofs.equation(d) < 0 && dofs.prescribed_values()[d] != 0.0)
          std::fprintf(out, "%lld, %d, %d, %.12e\n", static_cast<long long>(d / 3 + 1),
                       int(d % 3) + 1, int(d % 3) + 1, dofs.prescribed_values()[d]);
    }
    // OP=NEW: the previous step's forces are removed, not kept.
    std::fputs("*CLOAD, OP=NEW\n", out);
    bool any = false;
    for (Index d = 0; d < dofs.dof_count(); ++d) {
      const double value = external_forces(d, k);
      if (value == 0.0 || dofs.equation(d) < 0) continue;  // forces on supports do nothing
      std::fprintf(out, "%lld, %d, %.12e\n", static_cast<long long>(d / 3 + 1), int(d % 3) + 1,
                   value);
      any = true;
    }
    // ccx wants at least one data line; a zero force changes nothing.
    if (!any) std::fputs("1, 1, 0.0\n", out);
    if (print_some)
      std::fprintf(out, "*NODE PRINT, NSET=%s\nU\n",
                   options.print_all_displacements ? "NALL" : "NPRINT");
    if (options.file_displacements) std::fputs("*NODE FILE\nU\n", out);
    if (options.file_stresses) std::fputs("*EL FILE\nS\n", out);
    std::fputs("*END STEP\n", out);
  }
  require(std::ferror(out) == 0, "error writing CalculiX deck {}", path.string());
  require(std::fclose(file.release()) == 0, "error closing CalculiX deck {}", path.string());
}

void write_calculix_deck(const FeModel& model, const std::vector<LoadCase>& load_cases,
                         const std::filesystem::path& path, const CalculixDeckOptions& options) {
  write_calculix_deck(model, assemble_external_forces(model.mesh, element_materials(model), load_cases),
                      path, options);
}

std::vector<DisplacementField> read_calculix_dat_displacements(const std::filesystem::path& path,
                                                               Index node_count) {
  std::ifstream in(path);
  require(bool(in), "cannot read CalculiX results {}", path.string());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<DisplacementField> steps;
  bool in_block = false;
  std::string line;
  long long line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      // ccx prints one block per set and step; a new block at a later time
      // starts a new step (blocks of several sets in one step would not).
      steps.emplace_back(DisplacementField::Constant(node_count, 3, nan));
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    long long node = 0;
    double u[3];
    if (std::sscanf(line.c_str(), "%lld %lf %lf %lf", &node, &u[0], &u[1], &u[2]) == 4) {
      require(node >= 1 && node <= node_count, "{}:{}: node {} out of range (1..{})",
              path.string(), line_number, node, node_count);
      steps.back().row(node - 1) << u[0], u[1], u[2];
    } else if (line.find_first_not_of(" \t\r") != std::string::npos) {
      in_block = false;  // another kind of output
    }
  }
  return steps;
}

std::vector<StressField> read_calculix_frd_stresses(const std::filesystem::path& path,
                                                    Index node_count) {
  std::ifstream in(path);
  require(bool(in), "cannot read CalculiX results {}", path.string());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<StressField> steps;
  bool in_stress = false;
  std::string line;
  long long line_number = 0;
  // ASCII .frd: a result block starts with " -4  NAME", its node records are
  // " -1" + node (I10) + values (E12.5 each, fixed width, no separators),
  // " -3" ends it.
  while (std::getline(in, line)) {
    ++line_number;
    if (line.rfind(" -4", 0) == 0) {
      in_stress = line.find("STRESS") != std::string::npos;
      if (in_stress) steps.emplace_back(StressField::Constant(node_count, 6, nan));
      continue;
    }
    if (!in_stress) continue;
    if (line.rfind(" -3", 0) == 0) {
      in_stress = false;
      continue;
    }
    if (line.rfind(" -1", 0) != 0) continue;
    require(line.size() >= 13 + 6 * 12, "{}:{}: short stress record", path.string(), line_number);
    const long long node = std::stoll(line.substr(3, 10));
    require(node >= 1 && node <= node_count, "{}:{}: node {} out of range (1..{})", path.string(),
            line_number, node, node_count);
    for (int c = 0; c < 6; ++c)
      steps.back()(node - 1, c) = std::stod(line.substr(13 + 12 * size_t(c), 12));
  }
  return steps;
}

}  // namespace kinetofem::fem
