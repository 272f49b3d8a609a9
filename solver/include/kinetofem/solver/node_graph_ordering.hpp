#pragma once
// Fill-reducing ordering of K_ff from the mesh's node graph: METIS nested
// dissection (METIS_NodeND) of the graph whose vertices are the nodes with at
// least one free DoF and whose edges join two nodes that share an element,
// expanded to the free equations (nodes in METIS order, each node's free DoFs
// consecutive, x before y before z). CHOLMOD takes it as a given ordering
// (CholmodSolver::analyze(matrix, ordering), cholmod_l_analyze_p); this is
// CholmodOptions::Ordering::NodeGraphMetis, the default of LinearStaticAnalysis.
//
// Why: CHOLMOD's own METIS ordering builds the pattern of A + A^T of the DoF
// matrix (3 DoFs per node, so about 9x the entries of the node graph) and
// METIS compresses the identical DoF rows back to nodes before it dissects
// (then with two trial separators per level, METIS's rule for a compressed
// graph); here the node graph is built from the connectivity at once.
// Measured on the manipulator's lever (TET10, 2 shared cores, bench/README.md
// "node_graph_ordering"): the analysis (ordering + symbolic factorization)
// 1.6-1.7x faster at 8 mm (79k equations, 0.45-0.62 s instead of 0.76-1.02 s) and
// 1.6-2.0x at 4 mm (473k equations, 3.7-4.1 s instead of 5.9-8.2 s), for
// 1.7 % more nnz(L) and 3-4 % more flops: a different dissection of the same
// graph (other METIS seeds: +0.5 ... +3.7 % nnz(L) at 8 mm). The solutions agree
// to round-off (1e-13 on the test models; 1.4e-11 and 1.3e-10 on the lever,
// where AMD against METIS differs by 5.5e-12 and 9.3e-11).
//
// Not cached with the mesh (yet): METIS_NodeND is about half of the new
// analysis (0.26 s at 8 mm, 2.0 s at 4 mm), but 4.5-13 % of analysis +
// factorization, computed once per part and run (the factorization is
// shared by every load case). A cache beside the mesh cache would store the
// order of the whole node graph (all nodes, so that it does not depend on
// the supports: measured +2.2 % nnz(L) instead of +1.7 % at 8 mm).
#include <vector>

#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem {

// Undirected graph in compressed sparse row form: the neighbours of vertex v
// are adjacency[offset[v] .. offset[v + 1]), sorted, without v itself (no
// self loops), each edge stored in both directions.
struct NodeGraph {
  std::vector<Index> node;       // mesh node of each vertex, ascending
  std::vector<Index> offset;     // vertex_count() + 1 entries
  std::vector<Index> adjacency;  // 2 x edge_count() entries: vertex indices

  Index vertex_count() const { return Index(node.size()); }
  Index edge_count() const { return Index(adjacency.size()) / 2; }
};

// Node graph of the mesh restricted to the nodes with a free DoF (a node all
// of whose DoFs are prescribed has no equation and is left out, with its
// edges). Throws Error if the DoF map does not belong to the mesh.
NodeGraph build_node_graph(const Mesh& mesh, const DofMap& dofs);

// METIS_NodeND of the graph with METIS's default options (those CHOLMOD uses):
// order[k] = vertex eliminated k-th, a permutation of 0..vertex_count()-1.
// Throws Error naming the METIS function and its status if METIS fails, or
// if the graph is too large for METIS's 32-bit indices.
std::vector<Index> metis_nested_dissection(const NodeGraph& graph);

// Free equations in the order of the vertices: for each vertex order[k], its
// node's free equations (x, y, z, prescribed ones skipped), consecutive.
// A permutation of 0..dofs.free_count()-1 (permutation[k] = equation
// eliminated k-th), as cholmod_l_analyze_p takes it.
std::vector<Index> expand_to_equations(const NodeGraph& graph, const std::vector<Index>& order,
                                       const DofMap& dofs);

// Time of each step, s.
struct NodeGraphOrderingTimes {
  double graph_seconds = 0.0;  // build_node_graph
  double metis_seconds = 0.0;  // metis_nested_dissection
  double expand_seconds = 0.0; // expand_to_equations
};

// The three steps above: the ordering for CholmodSolver::analyze, named
// "METIS (node graph)", its `seconds` the total time of the three steps.
GivenOrdering node_graph_ordering(const Mesh& mesh, const DofMap& dofs,
                                  NodeGraphOrderingTimes* times = nullptr);

}  // namespace kinetofem::fem
