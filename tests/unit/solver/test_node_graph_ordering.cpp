// The node graph of a mesh and the METIS ordering expanded to the free
// equations (node_graph_ordering.hpp): graph structure, a valid permutation,
// every node's free DoFs consecutive, supported DoFs left out, and the
// errors of a bad ordering.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <span>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/solver/node_graph_ordering.hpp"
#include "kinetofem/verification/box_mesh.hpp"

namespace kinetofem::fem {
namespace {

namespace kv = kinetofem::verification;

Mesh box(ElementType type, std::array<int, 3> divisions) {
  kv::BoxMeshOptions options;
  options.length_m = {0.3, 0.1, 0.1};
  options.divisions = divisions;
  options.type = type;
  return kv::box_mesh(options);
}

// Reference: the neighbours of every node straight from the definition (two
// nodes are adjacent when one element holds both), by brute force.
std::vector<std::set<Index>> neighbours_by_definition(const Mesh& mesh) {
  std::vector<std::set<Index>> out(size_t(mesh.node_count()));
  for (const auto& block : mesh.blocks)
    for (Index e = 0; e < block.size(); ++e)
      for (Index a : block.element(e))
        for (Index b : block.element(e))
          if (a != b) out[size_t(a)].insert(b);
  return out;
}

TEST(NodeGraph, TwoHex8ElementsWithoutSupports) {
  const Mesh mesh = box(ElementType::Hex8, {2, 1, 1});  // 12 nodes
  const DofMap dofs(mesh.node_count(), {});
  const NodeGraph g = build_node_graph(mesh, dofs);
  ASSERT_EQ(g.vertex_count(), 12);
  // Reference: 8 end nodes see the 7 others of their element, the 4 nodes
  // of the shared face all 11: (8 * 7 + 4 * 11) / 2 = 50 edges.
  EXPECT_EQ(g.edge_count(), 50);
  const auto reference = neighbours_by_definition(mesh);
  for (Index v = 0; v < g.vertex_count(); ++v) {
    EXPECT_EQ(g.node[size_t(v)], v);
    const std::vector<Index> row(g.adjacency.begin() + g.offset[size_t(v)],
                                 g.adjacency.begin() + g.offset[size_t(v + 1)]);
    EXPECT_TRUE(std::is_sorted(row.begin(), row.end()));
    EXPECT_EQ(std::set<Index>(row.begin(), row.end()), reference[size_t(v)]) << "vertex " << v;
    EXPECT_EQ(std::count(row.begin(), row.end(), v), 0) << "self loop at " << v;
  }
}

TEST(NodeGraph, FullySupportedNodesAreLeftOutPartlySupportedKept) {
  const Mesh mesh = box(ElementType::Tet10, {3, 2, 2});
  const std::vector<Index>& x0 = mesh.node_set("x0");
  const std::vector<Index>& z0 = mesh.node_set("z0");
  const std::vector<DisplacementSupport> supports = {
      {"clamp", x0, {true, true, true}, Eigen::Vector3d::Zero()},
      {"roller", z0, {false, false, true}, Eigen::Vector3d::Zero()}};
  const DofMap dofs(mesh.node_count(), supports);
  const NodeGraph g = build_node_graph(mesh, dofs);
  EXPECT_EQ(g.vertex_count(), mesh.node_count() - Index(x0.size()));
  for (Index node : g.node)
    EXPECT_FALSE(std::binary_search(x0.begin(), x0.end(), node)) << "clamped node " << node;
  // Edges only between kept vertices, symmetric.
  const auto reference = neighbours_by_definition(mesh);
  for (Index v = 0; v < g.vertex_count(); ++v)
    for (Index k = g.offset[size_t(v)]; k < g.offset[size_t(v + 1)]; ++k) {
      const Index w = g.adjacency[size_t(k)];
      ASSERT_GE(w, 0);
      ASSERT_LT(w, g.vertex_count());
      EXPECT_TRUE(reference[size_t(g.node[size_t(v)])].count(g.node[size_t(w)]));
      const auto row_w = std::span(g.adjacency).subspan(size_t(g.offset[size_t(w)]),
                                                       size_t(g.offset[size_t(w + 1)] - g.offset[size_t(w)]));
      EXPECT_TRUE(std::binary_search(row_w.begin(), row_w.end(), v)) << v << " - " << w;
    }
}

TEST(NodeGraphOrdering, PermutationOfTheFreeEquationsNodeByNode) {
  const Mesh mesh = box(ElementType::Tet10, {6, 3, 3});  // > 120 vertices: METIS dissects
  const std::vector<DisplacementSupport> supports = {
      {"clamp", mesh.node_set("x0"), {true, true, true}, Eigen::Vector3d::Zero()},
      {"roller", mesh.node_set("z0"), {false, false, true}, Eigen::Vector3d::Zero()}};
  const DofMap dofs(mesh.node_count(), supports);
  NodeGraphOrderingTimes times;
  const GivenOrdering ordering = node_graph_ordering(mesh, dofs, &times);
  EXPECT_EQ(ordering.name, "METIS (node graph)");
  EXPECT_GE(times.metis_seconds, 0.0);
  EXPECT_NEAR(ordering.seconds, times.graph_seconds + times.metis_seconds + times.expand_seconds,
              1e-12);

  // A permutation of 0..free_count-1 (so no prescribed DoF appears).
  const std::vector<Index>& p = ordering.permutation;
  ASSERT_EQ(Index(p.size()), dofs.free_count());
  std::vector<Index> sorted = p;
  std::sort(sorted.begin(), sorted.end());
  for (Index k = 0; k < dofs.free_count(); ++k) ASSERT_EQ(sorted[size_t(k)], k);

  // Equation -> (node, component) from the DoF map.
  std::vector<Index> node_of(size_t(dofs.free_count())), component_of(size_t(dofs.free_count()));
  for (Index d = 0; d < dofs.dof_count(); ++d)
    if (dofs.equation(d) >= 0) {
      node_of[size_t(dofs.equation(d))] = d / 3;
      component_of[size_t(dofs.equation(d))] = d % 3;
    }
  // Every node's free DoFs consecutive, x before y before z, each node once,
  // and as many as it has free DoFs (2 on the roller, 3 inside).
  std::set<Index> seen;
  for (size_t k = 0; k < p.size();) {
    const Index node = node_of[size_t(p[k])];
    EXPECT_TRUE(seen.insert(node).second) << "node " << node << " appears twice";
    size_t end = k + 1;
    while (end < p.size() && node_of[size_t(p[end])] == node) {
      EXPECT_LT(component_of[size_t(p[end - 1])], component_of[size_t(p[end])]);
      ++end;
    }
    int free = 0;
    for (int c = 0; c < 3; ++c) free += dofs.equation(3 * node + c) >= 0;
    EXPECT_EQ(Index(end - k), free) << "node " << node;
    k = end;
  }
  // Not the natural order: METIS reordered the nodes.
  EXPECT_FALSE(std::is_sorted(p.begin(), p.end()));
}

TEST(NodeGraphOrdering, GraphWithoutEdgesKeepsTheNaturalOrder) {
  // One HEX8 with all nodes but node 6 clamped: one vertex, no edges.
  const Mesh mesh = box(ElementType::Hex8, {1, 1, 1});
  std::vector<Index> clamped;
  for (Index n = 0; n < mesh.node_count(); ++n)
    if (n != 6) clamped.push_back(n);
  const DofMap dofs(mesh.node_count(), {{"all but one", clamped, {true, true, true}, Eigen::Vector3d::Zero()}});
  const GivenOrdering ordering = node_graph_ordering(mesh, dofs);
  EXPECT_EQ(ordering.permutation, (std::vector<Index>{0, 1, 2}));
}

TEST(NodeGraphOrdering, InconsistentInputIsAnError) {
  const Mesh mesh = box(ElementType::Hex8, {2, 1, 1});
  const DofMap dofs(mesh.node_count(), {});
  const DofMap other(mesh.node_count() + 1, {});
  EXPECT_THROW(build_node_graph(mesh, other), Error);
  const NodeGraph g = build_node_graph(mesh, dofs);
  std::vector<Index> order(size_t(g.vertex_count()));
  for (Index v = 0; v < g.vertex_count(); ++v) order[size_t(v)] = v;
  order[1] = 0;  // vertex 0 twice
  EXPECT_THROW(expand_to_equations(g, order, dofs), Error);
  NodeGraph broken = g;
  broken.offset.pop_back();
  EXPECT_THROW(metis_nested_dissection(broken), Error);
}

TEST(CholmodGivenOrdering, NotAPermutationIsAnError) {
  const Mesh mesh = box(ElementType::Hex8, {2, 1, 1});
  const DofMap dofs(mesh.node_count(), {{"clamp", mesh.node_set("x0"), {true, true, true},
                                         Eigen::Vector3d::Zero()}});
  const AssembledStiffness K = assemble_stiffness(mesh, IsotropicMaterial{}, dofs);
  CholmodSolver solver;
  GivenOrdering bad = node_graph_ordering(mesh, dofs);
  bad.permutation[0] = bad.permutation[1];
  try {
    solver.analyze(K.free_free, bad);
    ADD_FAILURE() << "a repeated equation was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("not a permutation"), std::string::npos) << error.what();
  }
  bad.permutation.pop_back();
  EXPECT_THROW(solver.analyze(K.free_free, bad), Error);
  // The good one analyses, names itself and counts its time.
  GivenOrdering good = node_graph_ordering(mesh, dofs);
  good.seconds = 0.5;
  solver.analyze(K.free_free, good);
  EXPECT_EQ(solver.statistics().ordering, "METIS (node graph)");
  EXPECT_DOUBLE_EQ(solver.statistics().ordering_seconds, 0.5);
  EXPECT_GE(solver.statistics().analyze_seconds, 0.5);
}

}  // namespace
}  // namespace kinetofem::fem
