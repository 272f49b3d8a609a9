#include "kinetofem/structure/calculix_assembly_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include <Eigen/Eigenvalues>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/calculix_export.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/structure/rigid_motion.hpp"

namespace kinetofem::structure {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Dof = long long;  // 3 (node - 1) + component (0, 1, 2): one ccx DoF
using Terms = std::map<Dof, double>;

Dof dof_of(long long node, int component) { return 3 * (node - 1) + component; }
long long node_of(Dof d) { return d / 3 + 1; }
int component_of(Dof d) { return int(d % 3) + 1; }

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// Linear relations kept in reduced row echelon form: each row solved for its
// own pivot DoF (coefficient 1), which no other row contains. ccx then takes
// every row as it stands: the pivot is the dependent DoF and appears nowhere
// else, so ccx has nothing to cascade.
class Eliminator {
 public:
  explicit Eliminator(double drop_tolerance) : drop_(drop_tolerance) {}

  // Adds `row` (sum a_d u_d = 0), the earlier pivots substituted, solved for
  // `preferred` if it is still in the row, else for its largest coefficient.
  void add(Terms row, Dof preferred, const std::string& owner) {
    std::vector<std::pair<Dof, double>> hits;
    for (const auto& [d, a] : row)
      if (pivot_row_.count(d)) hits.emplace_back(d, a);
    for (const auto& [d, a] : hits)
      for (const auto& [e, b] : rows_[pivot_row_.at(d)].terms) row[e] -= a * b;
    clean(row);
    require(!row.empty(), "CalculiX deck: {} is implied by the other relations (dependent constraints)", owner);
    Dof pivot = preferred;
    if (!row.count(pivot)) {
      double largest = -1.0;
      for (const auto& [d, a] : row)
        if (std::abs(a) > largest) largest = std::abs(a), pivot = d;
    }
    const double scale = row.at(pivot);
    for (auto& [d, a] : row) a /= scale;
    row[pivot] = 1.0;
    for (Row& other : rows_) {
      const auto it = other.terms.find(pivot);
      if (it == other.terms.end()) continue;
      const double c = it->second;
      for (const auto& [e, b] : row) other.terms[e] -= c * b;
      other.terms.erase(pivot);
      clean(other.terms);
    }
    pivot_row_[pivot] = rows_.size();
    rows_.push_back({std::move(row), pivot});
  }

  struct Row {
    Terms terms;
    Dof pivot = -1;
  };
  const std::vector<Row>& rows() const { return rows_; }
  // The row that makes d dependent, or nullptr.
  const Row* row_of(Dof d) const {
    const auto it = pivot_row_.find(d);
    return it == pivot_row_.end() ? nullptr : &rows_[it->second];
  }
  double largest_dropped() const { return largest_dropped_; }

 private:
  void clean(Terms& row) {
    double largest = 0.0;
    for (const auto& [d, a] : row) largest = std::max(largest, std::abs(a));
    for (auto it = row.begin(); it != row.end();) {
      const double a = std::abs(it->second);
      if (a <= drop_ * largest) {
        if (largest > 0) largest_dropped_ = std::max(largest_dropped_, a / largest);
        it = row.erase(it);
      } else {
        ++it;
      }
    }
  }

  double drop_;
  std::vector<Row> rows_;
  std::map<Dof, size_t> pivot_row_;
  double largest_dropped_ = 0.0;
};

void write_terms(std::FILE* out, const Terms& terms, Dof pivot) {
  std::fprintf(out, "*EQUATION\n%zu\n", terms.size());
  int on_line = 0;
  auto put = [&](Dof d, double a) {
    std::fprintf(out, "%s%lld, %d, %.12e", on_line == 0 ? "" : ", ", node_of(d), component_of(d), a);
    if (++on_line == 4) {  // ccx: at most 12 entries (4 terms) a line
      std::fputc('\n', out);
      on_line = 0;
    }
  };
  put(pivot, terms.at(pivot));
  for (const auto& [d, a] : terms)
    if (d != pivot) put(d, a);
  if (on_line != 0) std::fputc('\n', out);
}

}  // namespace

AssemblyDeck write_calculix_pose_deck(const PoseDeckStructure& pose, const std::filesystem::path& path,
                                      const AssemblyDeckOptions& options) {
  const std::vector<PoseDeckPart>& parts = pose.parts;
  const std::vector<PoseDeckInterface>& interfaces = pose.interfaces;
  const size_t M = interfaces.size();
  for (const PoseDeckPart& part : parts)
    require(part.model != nullptr, "CalculiX deck {}: {} has no model", path.string(), part.name);
  require(pose.constraints.rows() == 0 || pose.constraints.cols() == Eigen::Index(6 * M),
          "CalculiX deck {}: {} constraint columns for {} interfaces", path.string(), pose.constraints.cols(), M);
  require(size_t(pose.constraints.rows()) == pose.constraint_owner.size(),
          "CalculiX deck {}: {} constraint rows, {} owners", path.string(), pose.constraints.rows(),
          pose.constraint_owner.size());
  const Eigen::Index n6 = Eigen::Index(6 * M);
  require(pose.springs.size() == 0 || (pose.springs.rows() == n6 && pose.springs.cols() == n6),
          "CalculiX deck {}: a springs' matrix of {} x {} for {} interfaces", path.string(), pose.springs.rows(),
          pose.springs.cols(), M);

  AssemblyDeck deck;
  Eliminator relations(options.drop_tolerance);
  std::set<Dof> fixed;
  std::map<Dof, double> load;

  // Numbering: the parts' nodes, then per interface a translation and a
  // rotation node, then per moving rigid body with interfaces its pair.
  long long next_node = 1, next_element = 1;
  for (const PoseDeckPart& part : parts) {
    AssemblyDeckPart p;
    p.body = part.body;
    p.rotation = part.rotation;
    p.origin_m = part.origin_m;
    p.first_node = next_node;
    p.nodes = part.model->mesh.node_count();
    p.first_element = next_element;
    p.elements = part.model->mesh.element_count();
    next_node += p.nodes;
    next_element += p.elements;
    deck.parts.push_back(p);
  }
  deck.solid_elements = next_element - 1;
  for (size_t k = 0; k < M; ++k) {
    deck.translation_node.push_back(next_node++);
    deck.rotation_node.push_back(next_node++);
  }
  // Interface component c (0-2 translation, 3-5 rotation) as a ccx DoF.
  auto interface_dof = [&](size_t k, int c) {
    return c < 3 ? dof_of(deck.translation_node[k], c) : dof_of(deck.rotation_node[k], c - 3);
  };
  std::vector<long long> body_node(pose.rigid_bodies.size(), 0);  // translation node; rotation = +1
  for (const PoseDeckInterface& i : interfaces) {
    if (i.part >= 0) {
      require(size_t(i.part) < parts.size() && i.column >= 0, "CalculiX deck {}: {}: no part {} (of {}), column {}",
              path.string(), i.tie_owner, i.part, parts.size(), i.column);
      continue;
    }
    require(i.rigid_body >= 0 && size_t(i.rigid_body) < pose.rigid_bodies.size(),
            "CalculiX deck {}: {}: neither on a part nor on a rigid body", path.string(), i.tie_owner);
    if (body_node[size_t(i.rigid_body)] == 0) {
      body_node[size_t(i.rigid_body)] = next_node;
      next_node += 2;
    }
  }

  // The parts: foundations held, loads rotated to world axes, and the ties of
  // their interfaces.
  for (size_t p = 0; p < parts.size(); ++p) {
    const PoseDeckPart& part = parts[p];
    const AssemblyDeckPart& dp = deck.parts[p];
    for (fem::Index n : part.held_nodes)
      for (int c = 0; c < 3; ++c) fixed.insert(dof_of(dp.first_node + n, c));
    const Eigen::VectorXd& f = part.nodal_loads_n;
    require(f.size() == 3 * dp.nodes,
            "CalculiX deck {}: {} is not the part the assembly was built with ({} nodes, its loads {})", path.string(),
            part.name, dp.nodes, f.size() / 3);
    for (fem::Index n = 0; n < dp.nodes; ++n) {
      const Vector3d fw = dp.rotation * f.segment<3>(3 * n);
      for (int c = 0; c < 3; ++c)
        if (fw(c) != 0.0) load[dof_of(dp.first_node + n, c)] += fw(c);
    }
  }
  for (size_t k = 0; k < M; ++k) {
    const PoseDeckInterface& i = interfaces[k];
    const std::string& owner = i.tie_owner;
    if (i.part < 0) {
      const long long node = body_node[size_t(i.rigid_body)];
      const detail::Matrix6d T = detail::transfer(i.arm_m);
      for (int c = 0; c < 6; ++c) {
        Terms row;
        row[interface_dof(k, c)] = 1.0;
        for (int a = 0; a < 6; ++a)
          if (T(c, a) != 0.0) row[a < 3 ? dof_of(node, a) : dof_of(node + 1, a - 3)] -= T(c, a);
        relations.add(std::move(row), interface_dof(k, c), owner);
      }
      continue;
    }
    const PoseDeckPart& part = parts[size_t(i.part)];
    const AssemblyDeckPart& dp = deck.parts[size_t(i.part)];
    require(part.interface_columns != nullptr, "CalculiX deck {}: {}: {} has no interface columns", path.string(),
            owner, part.name);
    const Eigen::MatrixXd& G = *part.interface_columns;
    require(G.rows() == 3 * dp.nodes, "CalculiX deck {}: {} is not the part the assembly was built with", path.string(),
            part.name);
    require(G.cols() >= 6 * Eigen::Index(i.column + 1), "CalculiX deck {}: {}: column {} of {} interfaces on {}",
            path.string(), owner, i.column, G.cols() / 6, part.name);
    const int local = i.column;
    const Matrix3d& R = dp.rotation;
    for (int c = 0; c < 6; ++c) {
      // Row c of Q6 G_k^T Q^T: per node row c of R g_t R^T (translation) or R g_r R^T (rotation).
      Terms row;
      row[interface_dof(k, c)] = -1.0;
      for (fem::Index n = 0; n < dp.nodes; ++n) {
        Eigen::Matrix<double, 6, 3> g = G.block(3 * n, 6 * local, 3, 6).transpose();  // 6 x 3, body axes
        if (g.isZero(0.0)) continue;
        const Eigen::Matrix<double, 1, 3> w =
            (c < 3 ? Eigen::Matrix<double, 1, 3>(R.row(c) * g.topRows<3>() * R.transpose())
                   : Eigen::Matrix<double, 1, 3>(R.row(c - 3) * g.bottomRows<3>() * R.transpose()));
        for (int a = 0; a < 3; ++a) {
          const Dof d = dof_of(dp.first_node + n, a);
          if (w(a) != 0.0 && !fixed.count(d)) row[d] += w(a);
        }
      }
      relations.add(std::move(row), interface_dof(k, c), owner);
    }
  }

  // The joints and rigid drives: C u = 0 over the interfaces' motions.
  const Eigen::MatrixXd& C = pose.constraints;
  for (Eigen::Index r = 0; r < C.rows(); ++r) {
    Terms row;
    for (size_t k = 0; k < M; ++k)
      for (int c = 0; c < 6; ++c)
        if (C(r, Eigen::Index(6 * k + c)) != 0.0) row[interface_dof(k, c)] += C(r, Eigen::Index(6 * k + c));
    relations.add(std::move(row), -1, pose.constraint_owner[size_t(r)]);
  }

  // The springs: S = sum lambda v v^T, one SPRING1 per term on its own node.
  struct Spring {
    long long node = 0;
    double stiffness = 0.0;
  };
  std::vector<Spring> springs;
  if (pose.springs.size() > 0 && !pose.springs.isZero(0.0)) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(pose.springs);
    require(eigen.info() == Eigen::Success, "CalculiX deck {}: the springs' eigenvalues failed", path.string());
    const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
    for (Eigen::Index e = 0; e < eigen.eigenvalues().size(); ++e) {
      const double lambda = eigen.eigenvalues()(e);
      if (std::abs(lambda) <= 1e-12 * largest) continue;  // round-off of a rank-deficient S
      require(lambda > 0, "CalculiX deck {}: the springs' matrix has a negative eigenvalue {:.6g}", path.string(),
              lambda);
      Spring s{next_node++, lambda};
      Terms row;
      row[dof_of(s.node, 0)] = 1.0;
      for (size_t k = 0; k < M; ++k)
        for (int c = 0; c < 6; ++c) {
          const double v = eigen.eigenvectors()(Eigen::Index(6 * k + c), e);
          if (std::abs(v) > 1e-15) row[interface_dof(k, c)] -= v;
        }
      relations.add(std::move(row), dof_of(s.node, 0), fmt::format("spring {}", springs.size() + 1));
      springs.push_back(s);
    }
  }

  // Moving rigid bodies' loads at their node pair.
  for (size_t b = 0; b < pose.rigid_bodies.size(); ++b) {
    const Vector6d& l = pose.rigid_bodies[b].load;
    if (body_node[b] == 0) continue;
    for (int c = 0; c < 6; ++c)
      if (l(c) != 0.0) load[c < 3 ? dof_of(body_node[b], c) : dof_of(body_node[b] + 1, c - 3)] += l(c);
  }
  // Loads on dependent DoFs moved onto their equation's independent DoFs
  // (pivot = -sum a_e u_e: a force F on it does the work of -a_e F on each u_e).
  std::map<Dof, double> applied;
  for (const auto& [d, F] : load) {
    if (fixed.count(d)) continue;  // the foundation takes it
    if (const Eliminator::Row* row = relations.row_of(d)) {
      for (const auto& [e, a] : row->terms)
        if (e != d && !fixed.count(e)) applied[e] -= a * F;
    } else {
      applied[d] += F;
    }
  }

  File file(std::fopen(path.c_str(), "w"));
  require(file != nullptr, "cannot write CalculiX deck {}", path.string());
  std::FILE* out = file.get();
  std::setvbuf(out, nullptr, _IOFBF, 1 << 20);
  std::fprintf(out, "*HEADING\n%s\n*NODE, NSET=NALL\n", options.heading.c_str());
  auto put_node = [&](long long id, const Vector3d& x) {
    std::fprintf(out, "%lld, %.12e, %.12e, %.12e\n", id, x.x(), x.y(), x.z());
  };
  for (size_t p = 0; p < parts.size(); ++p) {
    const AssemblyDeckPart& dp = deck.parts[p];
    const fem::Mesh& mesh = parts[p].model->mesh;
    for (fem::Index n = 0; n < dp.nodes; ++n)
      put_node(dp.first_node + n, dp.origin_m + dp.rotation * mesh.nodes.row(n).transpose());
  }
  for (size_t k = 0; k < M; ++k) {
    put_node(deck.translation_node[k], interfaces[k].position_m);
    put_node(deck.rotation_node[k], interfaces[k].position_m);
  }
  for (size_t b = 0; b < pose.rigid_bodies.size(); ++b)
    if (body_node[b] != 0) {
      put_node(body_node[b], pose.rigid_bodies[b].origin_m);
      put_node(body_node[b] + 1, pose.rigid_bodies[b].origin_m);
    }
  for (const Spring& s : springs) put_node(s.node, Vector3d::Zero());
  deck.node_count = next_node - 1;

  // Elements (ccx node order) and their materials.
  std::vector<std::string> sections;  // "ELSET, MATERIAL" pairs
  for (size_t p = 0; p < parts.size(); ++p) {
    const fem::FeModel& fe = *parts[p].model;
    fem::ElementMaterials materials = fem::IsotropicMaterial{};
    try {
      materials = fem::element_materials(fe);
    } catch (const Error& e) {
      fail("CalculiX deck {}: {}: {}", path.string(), parts[p].name, e.what());
    }
    long long element_id = deck.parts[p].first_element;
    fem::Index global = 0;
    std::set<int> used;
    for (size_t b = 0; b < fe.mesh.blocks.size(); ++b) {
      const fem::ElementBlock& block = fe.mesh.blocks[b];
      const std::vector<int> order = fem::calculix_node_order(block.type);
      for (size_t k = 0; k < materials.materials().size(); ++k) {
        bool header = false;
        for (fem::Index e = 0; e < block.size(); ++e) {
          if (materials.index_of(global + e) != int(k)) continue;
          if (!header) {
            std::fprintf(out, "*ELEMENT, TYPE=%s, ELSET=P%zuB%zuM%zu\n", fem::calculix_element_name(block.type), p + 1,
                         b + 1, k);
            sections.push_back(fmt::format("P{}B{}M{}, MATERIAL=P{}M{}", p + 1, b + 1, k, p + 1, k));
            used.insert(int(k));
            header = true;
          }
          const auto nodes = block.element(e);
          std::fprintf(out, "%lld", element_id + global + e);
          for (size_t i = 0; i < order.size(); ++i)
            std::fprintf(out, ",%s%lld", (i + 1) % 15 == 0 ? "\n" : " ",
                         static_cast<long long>(deck.parts[p].first_node + nodes[size_t(order[i])]));
          std::fputc('\n', out);
        }
      }
      global += block.size();
    }
    for (int k : used) {
      const fem::IsotropicMaterial& m = materials.materials()[size_t(k)];
      const std::string whose = k == 0 ? std::string("its elements in no listed set")
                                       : "element set '" + materials.element_set(size_t(k)) + "'";
      std::fprintf(out, "** %s: material '%s' of %s\n*MATERIAL, NAME=P%zuM%d\n*ELASTIC\n%.12e, %.12e\n",
                   parts[p].name.c_str(), m.name.c_str(), whose.c_str(), p + 1, k, m.youngs_modulus_pa,
                   m.poisson_ratio);
    }
  }
  for (const std::string& s : sections) std::fprintf(out, "*SOLID SECTION, ELSET=%s\n", s.c_str());
  std::fprintf(out, "*ELSET, ELSET=ESOLID, GENERATE\n1, %lld, 1\n", deck.solid_elements);
  for (size_t s = 0; s < springs.size(); ++s) {
    std::fprintf(out, "*ELEMENT, TYPE=SPRING1, ELSET=SPRING%zu\n%lld, %lld\n", s + 1,
                 deck.solid_elements + 1 + (long long)s, springs[s].node);
    std::fprintf(out, "*SPRING, ELSET=SPRING%zu\n1\n%.12e\n", s + 1, springs[s].stiffness);
  }
  deck.springs = int(springs.size());

  // Equations; a row left with its pivot alone holds that DoF.
  std::vector<Dof> held(fixed.begin(), fixed.end());
  // A spring node's DoFs 2 and 3 (the element activates all three) carry nothing.
  for (const Spring& s : springs) held.push_back(dof_of(s.node, 1)), held.push_back(dof_of(s.node, 2));
  for (const Eliminator::Row& row : relations.rows()) {
    if (row.terms.size() == 1) {
      held.push_back(row.pivot);
      continue;
    }
    write_terms(out, row.terms, row.pivot);
    ++deck.equations;
    deck.equation_terms += (long long)row.terms.size();
  }
  deck.largest_dropped = relations.largest_dropped();
  if (!held.empty()) {
    std::fputs("*BOUNDARY\n", out);
    for (Dof d : held) std::fprintf(out, "%lld, %d, %d\n", node_of(d), component_of(d), component_of(d));
  }
  deck.boundaries = int(held.size());

  std::fputs("*NSET, NSET=NPRINT\n", out);
  {
    std::vector<long long> ids;
    if (options.print_part_displacements)
      for (const AssemblyDeckPart& dp : deck.parts)
        for (fem::Index n = 0; n < dp.nodes; ++n) ids.push_back(dp.first_node + n);
    for (size_t k = 0; k < M; ++k) ids.push_back(deck.translation_node[k]), ids.push_back(deck.rotation_node[k]);
    for (size_t i = 0; i < ids.size(); ++i)
      std::fprintf(out, "%lld%s", ids[i], i + 1 == ids.size() ? "\n" : (i % 16 == 15 ? ",\n" : ", "));
  }

  std::fprintf(out, "*STEP\n*STATIC%s%s\n*CLOAD\n", options.solver.empty() ? "" : ", SOLVER=",
               options.solver.c_str());
  for (const auto& [d, F] : applied)
    if (F != 0.0) {
      std::fprintf(out, "%lld, %d, %.12e\n", node_of(d), component_of(d), F);
      ++deck.loads;
    }
  if (deck.loads == 0) std::fprintf(out, "%lld, 1, 0.0\n", deck.parts.empty() ? 1LL : deck.parts[0].first_node);
  std::fputs("*NODE PRINT, NSET=NPRINT\nU\n", out);
  if (options.print_gauss_stresses) std::fputs("*EL PRINT, ELSET=ESOLID\nS\n", out);
  if (options.file_stresses) std::fputs("*EL FILE\nS\n", out);
  std::fputs("*END STEP\n", out);
  require(std::ferror(out) == 0, "error writing CalculiX deck {}", path.string());
  require(std::fclose(file.release()) == 0, "error closing CalculiX deck {}", path.string());
  return deck;
}

namespace {

// The moving bodies in `is_rigid` order (model order) as the deck's rigid
// bodies: their index per model body (-1: none).
template <class IsRigid>
std::vector<int> rigid_body_indices(size_t bodies, IsRigid is_rigid) {
  std::vector<int> index(bodies, -1);
  int next = 0;
  for (size_t b = 0; b < bodies; ++b)
    if (is_rigid(b)) index[b] = next++;
  return index;
}

}  // namespace

AssemblyDeck write_calculix_assembly_deck(const ElasticAssembly& assembly, const std::vector<Part>& parts,
                                          const mech::MultibodyModel& model, const mech::Frame& frame,
                                          const std::filesystem::path& path, const AssemblyDeckOptions& options) {
  const std::vector<InterfaceInfo> interfaces = assembly.interfaces();
  InterfaceStructure structure = assembly.interface_structure(frame);
  auto body_index = [&](const std::string& name) {
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == name) return b;
    fail("CalculiX deck {}: the mechanism '{}' has no body '{}'", path.string(), model.name, name);
  };
  require(frame.bodies.size() == model.bodies.size(), "CalculiX deck {}: the frame has {} bodies, the mechanism {}",
          path.string(), frame.bodies.size(), model.bodies.size());
  auto origin_of = [&](size_t b) { return Vector3d(frame.bodies[b].q.x(), frame.bodies[b].q.y(), 0.0); };
  const auto part_of = [&](const std::string& body) -> int {
    for (size_t p = 0; p < parts.size(); ++p)
      if (parts[p].body() == body) return int(p);
    return -1;
  };

  PoseDeckStructure pose;
  for (const Part& part : parts) {
    const size_t b = body_index(part.body());
    PoseDeckPart p;
    p.name = part.name();
    p.body = part.body();
    p.model = &part.model;
    p.rotation = structure.body_rotation[b];
    p.origin_m = origin_of(b);
    if (model.bodies[b].fixed)
      for (const fem::DisplacementSupport& s : foundation_support(part))
        p.held_nodes.insert(p.held_nodes.end(), s.nodes.begin(), s.nodes.end());
    p.nodal_loads_n = assembly.part_loads(part.body()).loads_at(frame).forces;
    pose.parts.push_back(std::move(p));
  }
  // Rigid bodies: the moving bodies whose interfaces are not on a part.
  std::vector<bool> rigid(model.bodies.size(), false);
  for (const InterfaceInfo& i : interfaces)
    if (!i.elastic) {
      const size_t b = body_index(i.body);
      require(!model.bodies[b].fixed, "CalculiX deck {}: interface '{}' on the rigid ground", path.string(), i.name);
      rigid[b] = true;
    }
  const std::vector<int> rigid_index = rigid_body_indices(model.bodies.size(), [&](size_t b) { return rigid[b]; });
  {
    const std::vector<Vector6d> body_loads = assembly.body_loads(frame);
    size_t moving = 0;
    for (size_t b = 0; b < model.bodies.size(); ++b) {
      if (model.bodies[b].fixed) continue;
      const Vector6d& l = body_loads.at(moving++);
      if (rigid_index[b] >= 0) pose.rigid_bodies.push_back({model.bodies[b].name, origin_of(b), l});
    }
  }
  std::map<std::string, int> local_count;
  for (size_t k = 0; k < interfaces.size(); ++k) {
    const InterfaceInfo& i = interfaces[k];
    const size_t b = body_index(i.body);
    PoseDeckInterface d;
    d.tie_owner = "the tie of " + i.kind + " '" + i.name + "' on '" + i.body + "'";
    d.arm_m = structure.interface_arm_m[k];
    d.position_m = origin_of(b) + structure.interface_arm_m[k];
    if (!i.elastic) {
      d.rigid_body = rigid_index[b];
    } else {
      d.part = part_of(i.body);
      require(d.part >= 0, "CalculiX deck {}: interface '{}' is on body '{}', whose part was not given", path.string(),
              i.name, i.body);
      d.column = local_count[i.body]++;
      PoseDeckPart& p = pose.parts[size_t(d.part)];
      if (p.interface_columns == nullptr) {
        try {
          p.interface_columns = &assembly.interface_columns(i.body);
        } catch (const Error& e) {
          fail("CalculiX deck {} (written with the distributing couplings' equations only): {}", path.string(),
               e.what());
        }
      }
    }
    pose.interfaces.push_back(std::move(d));
  }
  pose.constraints = std::move(structure.constraints);
  pose.constraint_owner = std::move(structure.constraint_owner);
  pose.springs = std::move(structure.springs);
  return write_calculix_pose_deck(pose, path, options);
}

AssemblyDeck write_calculix_assembly_deck(const SpatialElasticAssembly& assembly, const mech::spatial::Model& model,
                                          const mech::spatial::Frame& frame, const std::filesystem::path& path,
                                          const AssemblyDeckOptions& options) {
  require(frame.bodies.size() == model.bodies.size(), "CalculiX deck {}: the frame has {} bodies, the mechanism {}",
          path.string(), frame.bodies.size(), model.bodies.size());
  for (size_t b = 0; b < model.bodies.size(); ++b)
    require(frame.bodies[b].name == model.bodies[b].name,
            "CalculiX deck {}: the frame is of another mechanism (body '{}', the mechanism's '{}')", path.string(),
            frame.bodies[b].name, model.bodies[b].name);
  const std::vector<SpatialInterfaceInfo> interfaces = assembly.interfaces();
  InterfaceStructure structure = assembly.interface_structure(frame);
  auto body_index = [&](const std::string& name) {
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == name) return b;
    fail("CalculiX deck {}: the mechanism '{}' has no body '{}'", path.string(), model.name, name);
  };

  PoseDeckStructure pose;
  std::vector<int> part_of_body(model.bodies.size(), -1);
  for (const SpatialPart& part : assembly.parts()) {
    const size_t b = body_index(part.body());
    part_of_body[b] = int(pose.parts.size());
    PoseDeckPart p;
    p.name = part.label.empty() ? "part '" + part.body() + "'" : part.label;
    p.body = part.body();
    p.model = &assembly.supported_model(part.body());
    p.rotation = frame.bodies[b].rotation;
    p.origin_m = frame.bodies[b].origin;
    p.nodal_loads_n = assembly.part_loads(part.body(), frame);
    p.interface_columns = &assembly.interface_columns(part.body());
    pose.parts.push_back(std::move(p));
  }
  const std::vector<int> rigid_index =
      rigid_body_indices(model.bodies.size(), [&](size_t b) { return !model.bodies[b].fixed && part_of_body[b] < 0; });
  {
    const std::vector<Vector6d> body_loads = assembly.body_loads(frame);
    size_t moving = 0;
    for (size_t b = 0; b < model.bodies.size(); ++b) {
      if (model.bodies[b].fixed) continue;
      const Vector6d& l = body_loads.at(moving++);
      if (rigid_index[b] >= 0) pose.rigid_bodies.push_back({model.bodies[b].name, frame.bodies[b].origin, l});
    }
  }
  std::vector<int> local_count(model.bodies.size(), 0);
  for (size_t k = 0; k < interfaces.size(); ++k) {
    const SpatialInterfaceInfo& i = interfaces[k];
    const size_t b = body_index(i.body);
    require(!model.bodies[b].fixed, "CalculiX deck {}: {} on the ground", path.string(), i.name);
    PoseDeckInterface d;
    d.tie_owner = "the tie of " + i.name + " on '" + i.body + "'";
    d.arm_m = structure.interface_arm_m[k];
    d.position_m = frame.bodies[b].origin + structure.interface_arm_m[k];
    if (part_of_body[b] >= 0) {
      d.part = part_of_body[b];
      d.column = local_count[b]++;
    } else {
      d.rigid_body = rigid_index[b];
    }
    pose.interfaces.push_back(std::move(d));
  }
  pose.constraints = std::move(structure.constraints);
  pose.constraint_owner = std::move(structure.constraint_owner);
  pose.springs = std::move(structure.springs);
  return write_calculix_pose_deck(pose, path, options);
}

AssemblyDeckResults read_calculix_assembly_results(const AssemblyDeck& deck, const std::filesystem::path& job) {
  std::filesystem::path dat = job, frd = job;
  dat += ".dat";
  frd += ".frd";
  const std::vector<fem::DisplacementField> steps = fem::read_calculix_dat_displacements(dat, deck.node_count);
  require(!steps.empty(), "CalculiX results {}: no displacements", dat.string());
  const fem::DisplacementField& u = steps.back();
  AssemblyDeckResults out;
  for (size_t k = 0; k < deck.translation_node.size(); ++k) {
    Vector6d m;
    m << u.row(deck.translation_node[k] - 1).transpose(), u.row(deck.rotation_node[k] - 1).transpose();
    require(!m.hasNaN(), "CalculiX results {}: interface {} was not printed", dat.string(), k + 1);
    out.interface_motion.push_back(m);
  }
  for (const AssemblyDeckPart& p : deck.parts) out.displacement_m.push_back(u.middleRows(p.first_node - 1, p.nodes));

  // Integration-point stresses: "elem ip sxx syy szz sxy sxz syz" after a
  // "stresses (elem, integ.pnt.,...)" header.
  out.peak_gauss_von_mises_pa.assign(deck.parts.size(), 0.0);
  {
    std::ifstream in(dat);
    std::string line;
    bool in_block = false;
    while (std::getline(in, line)) {
      if (line.find("stresses (elem, integ.pnt.") != std::string::npos) {
        in_block = true;
        continue;
      }
      if (!in_block) continue;
      long long element = 0, point = 0;
      double s[6];
      if (std::sscanf(line.c_str(), "%lld %lld %lf %lf %lf %lf %lf %lf", &element, &point, &s[0], &s[1], &s[2],
                      &s[3], &s[5], &s[4]) == 8) {
        for (size_t p = 0; p < deck.parts.size(); ++p)
          if (element >= deck.parts[p].first_element && element < deck.parts[p].first_element + deck.parts[p].elements) {
            const fem::Vector6d stress = Eigen::Map<const fem::Vector6d>(s);
            out.peak_gauss_von_mises_pa[p] = std::max(out.peak_gauss_von_mises_pa[p], fem::von_mises(stress));
          }
      } else if (line.find_first_not_of(" \t\r") != std::string::npos) {
        in_block = false;
      }
    }
  }
  if (std::filesystem::exists(frd)) {
    const std::vector<fem::StressField> stress = fem::read_calculix_frd_stresses(frd, deck.node_count);
    if (!stress.empty())
      for (const AssemblyDeckPart& p : deck.parts) {
        Eigen::VectorXd vm(p.nodes);
        for (fem::Index n = 0; n < p.nodes; ++n)
          vm(n) = fem::von_mises(stress.back().row(p.first_node - 1 + n).transpose());
        out.nodal_von_mises_pa.push_back(vm);
      }
  }
  return out;
}

}  // namespace kinetofem::structure
