// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_SYSTEM_ASSEMBLY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_SYSTEM_ASSEMBLY_H

#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

using Row_permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

/*
  M = A W^-1 A^T, both triangles, in the order of the rows (where mesh files usually have locality),
  without forming A. The node rows are the weighted Laplacian of the node graph: its pattern is
  `node_start`/`node_rows` (from Mesh_topology::node_adjacency(), which the fill-reducing order may read
  meanwhile on another thread) and every interior edge adds its 1/w_e to four entries. The generator and
  link rows (last) gather their crossings, Gustavson-style, and the links the couplings C C^T / mu of the
  guided faces they share. Needs no fill-reducing order, so it can be formed while that order is computed.
  An edge fixed by a decided link adds its 0 (Constraint_rows::inverse_weight): the pattern stays the mesh's.
*/
template <class TriangleMesh>
Eigen::SparseMatrix<double> system_in_row_order(const Mesh_arrays<TriangleMesh>& m, const Constraint_rows& system,
                                                const std::vector<int>& node_start, const std::vector<int>& node_rows)
{
  using Sparse = Eigen::SparseMatrix<double>;
  const Mesh_topology& t = system.topology();
  const Mesh_geometry& geometry = system.geometry();
  const std::vector<int>& row_of_node = system.row_of_node;
  const std::vector<int>& row_of_slot = system.row_of_slot;
  const int rows = int(system.rows), ne = geometry.number_of_interior_edges();
  int node_row_count = 0;
  for(int node = 0; node < t.number_of_nodes; ++node)
    if(row_of_node[node] >= 0)
      ++node_row_count;
  auto nodes_of_edge = [&](int e) { return system.nodes_of_edge(m, e); };

  // generator (and link) crossings per edge (CSR): (its row, +-1)
  const std::size_t slots = row_of_slot.size();
  std::vector<int> crossing_start(std::size_t(ne) + 1, 0);
  for(std::size_t l = 0; l < slots; ++l)
    if(system.is_crossing_row(l))
      for(int p = system.slot_edge_start[l]; p < system.slot_edge_start[l + 1]; ++p)
        ++crossing_start[std::size_t(index_of_code(system.slot_edges[p])) + 1];
  for(int e = 0; e < ne; ++e)
    crossing_start[e + 1] += crossing_start[e];
  std::vector<std::pair<int, double>> crossings((std::size_t(crossing_start[ne]))); // not a declaration (clang)
  {
    std::vector<int> next(crossing_start.begin(), crossing_start.end() - 1);
    for(std::size_t l = 0; l < slots; ++l)
      if(system.is_crossing_row(l))
        for(int p = system.slot_edge_start[l]; p < system.slot_edge_start[l + 1]; ++p) {
          const int code = system.slot_edges[p];
          crossings[next[index_of_code(code)]++] = {row_of_slot[l], sign_of_code(code)};
        }
  }

  // the generator rows (all their entries, sorted), which are also the generator entries of the node columns
  std::vector<int> generator_start(1, 0), generator_row;
  std::vector<double> generator_value;
  {
    std::vector<int> pattern, mark(std::size_t(rows), -1);
    std::vector<double> sum(std::size_t(rows), 0.);
    auto add = [&](int r, double v, int g) {
      if(mark[r] != g) {
        mark[r] = g;
        sum[r] = 0;
        pattern.push_back(r);
      }
      sum[r] += v;
    };
    for(std::size_t l = 0; l < slots; ++l) {
      if(!system.is_crossing_row(l))
        continue;
      const int g = row_of_slot[l];
      pattern.clear();
      for(int p = system.slot_edge_start[l]; p < system.slot_edge_start[l + 1]; ++p) {
        const int code = system.slot_edges[p], e = index_of_code(code);
        const double v = sign_of_code(code) * system.inverse_weight[std::size_t(e)];
        const std::array<int, 2> ends = nodes_of_edge(e);
        const int a = ends[0], b = ends[1];
        if(a != b) {
          if(row_of_node[b] >= 0) add(row_of_node[b], v, g);
          if(row_of_node[a] >= 0) add(row_of_node[a], -v, g);
        }
        for(int q = crossing_start[e]; q < crossing_start[e + 1]; ++q)
          add(crossings[q].first, v * crossings[q].second, g);
      }
      if(l >= t.loops.size()) // a link: its guided ends' slacks couple it with the other links there (C C^T / mu)
        system.links().for_each_slack_coupling(int(l - t.loops.size()), [&](int other, double value) {
          add(row_of_slot[t.loops.size() + std::size_t(other)], value, g);
        });
      std::sort(pattern.begin(), pattern.end());
      for(int r : pattern) {
        generator_row.push_back(r);
        generator_value.push_back(sum[r]);
      }
      generator_start.push_back(int(generator_row.size()));
    }
  }
  CGAL_assertion(int(generator_start.size()) - 1 == rows - node_row_count);

  // column sizes: the non-pinned nodes of the pattern, then the generator rows coupled to the column
  Sparse M(rows, rows);
  int* outer = M.outerIndexPtr();
  std::fill(outer, outer + rows + 1, 0);
  for(int node = 0; node < t.number_of_nodes; ++node) {
    const int c = row_of_node[node];
    if(c < 0)
      continue;
    for(int p = node_start[node]; p < node_start[node + 1]; ++p)
      if(row_of_node[node_rows[p]] >= 0)
        ++outer[c + 1];
  }
  for(int g = node_row_count; g < rows; ++g) {
    const int first = generator_start[g - node_row_count], last = generator_start[g - node_row_count + 1];
    outer[g + 1] = last - first;
    for(int p = first; p < last; ++p)
      if(generator_row[p] < node_row_count)
        ++outer[generator_row[p] + 1];
  }
  for(int c = 0; c < rows; ++c)
    outer[c + 1] += outer[c];
  M.resizeNonZeros(outer[rows]);
  int* inner = M.innerIndexPtr();
  double* value = M.valuePtr();
  std::fill(value, value + outer[rows], 0.);
  // the node part of a node column, in row order (rows grow with nodes); then its generator rows
  std::vector<int> next(outer, outer + rows);
  for(int node = 0; node < t.number_of_nodes; ++node) {
    const int c = row_of_node[node];
    if(c < 0)
      continue;
    for(int p = node_start[node]; p < node_start[node + 1]; ++p) {
      const int r = row_of_node[node_rows[p]];
      if(r >= 0)
        inner[next[c]++] = r;
    }
  }
  const std::vector<int> node_part_end(next); // end of each node column's node part
  for(int g = node_row_count; g < rows; ++g)
    for(int p = generator_start[g - node_row_count]; p < generator_start[g - node_row_count + 1]; ++p) {
      const int r = generator_row[p];
      if(r < node_row_count) { // (g, r) and its mirror (r, g), generator rows in increasing order
        inner[next[r]] = g;
        value[next[r]++] = generator_value[p];
      }
      inner[next[g]] = r;
      value[next[g]++] = generator_value[p];
    }
  // the weighted Laplacian of the node graph: a few entries per column, found by a short scan
  auto entry = [&](int c, int r) -> double& {
    int p = outer[c];
    while(inner[p] != r)
      ++p;
    CGAL_assertion(p < node_part_end[c]);
    return value[p];
  };
  for(int e = 0; e < ne; ++e) {
    const std::array<int, 2> ends = nodes_of_edge(e);
    const int a = ends[0], b = ends[1];
    if(a == b)
      continue;
    const double v = system.inverse_weight[std::size_t(e)];
    const int ra = row_of_node[a], rb = row_of_node[b];
    if(ra >= 0) entry(ra, ra) += v;
    if(rb >= 0) entry(rb, rb) += v;
    if(ra >= 0 && rb >= 0) {
      entry(ra, rb) -= v;
      entry(rb, ra) -= v;
    }
  }
  return M;
}

// The positions of the rows in the factor: the node rows in the fill-reducing order `node_order` (nodes), each
// decided fan row right after the last of its nodes that are not free rows, then the free rows (loops and links),
// so that the metric of the integers is the trailing block of the factor. A boundary loop's node is a free row,
// last whatever its rank: anchored at that rank, every decided fan of an aligned boundary went to the top of the
// elimination tree (holes: a vertex's path to the root 490 positions long instead of 280, four times the work).
inline Row_permutation loop_rows_last(const Constraint_rows& system, const std::vector<int>& node_order)
{
  const Eigen::Index rows = system.rows;
  std::vector<char> is_loop_row(std::size_t(rows), 0);
  for(int r : system.free_rows)
    is_loop_row[r] = 1;
  // each decided row after the last of its nodes in the order (its rank there); rows touching only pinned nodes,
  // which have no row, or free rows, which come last, come first
  std::vector<int> rank(system.row_of_node.size(), -1), first_rows;
  for(std::size_t k = 0; k < node_order.size(); ++k)
    rank[std::size_t(node_order[k])] = int(k);
  std::vector<std::pair<int, int>> anchored; // (rank of the last node, row)
  {
    std::size_t d = 0;
    for(int l : system.decided_slots) {
      const int r = system.row_of_slot[std::size_t(l)];
      if(r < 0)
        continue;
      int last = -1;
      for(int p = system.decided_row_node_start[d]; p < system.decided_row_node_start[d + 1]; ++p) {
        const int node = system.decided_row_nodes[std::size_t(p)];
        const int node_row = system.row_of_node[std::size_t(node)];
        if(node_row >= 0 && !is_loop_row[std::size_t(node_row)])
          last = (std::max)(last, rank[std::size_t(node)]);
      }
      ++d;
      if(last < 0)
        first_rows.push_back(r);
      else
        anchored.push_back({last, r});
    }
    std::sort(anchored.begin(), anchored.end());
  }
  Row_permutation permutation(rows); // row -> position
  int position = 0;
  for(int r : first_rows)
    permutation.indices()[r] = position++;
  std::size_t next_anchored = 0;
  for(std::size_t k = 0; k < node_order.size(); ++k) {
    const int r = system.row_of_node[std::size_t(node_order[k])];
    if(r >= 0 && !is_loop_row[r])
      permutation.indices()[r] = position++;
    for(; next_anchored < anchored.size() && anchored[next_anchored].first == int(k); ++next_anchored)
      permutation.indices()[anchored[next_anchored].second] = position++;
  }
  for(int r : system.free_rows)
    permutation.indices()[r] = position++;
  CGAL_assertion(position == rows);
  return permutation;
}

// The triangle `stored_triangle` (Eigen::Lower, Eigen::Upper, or 0 for the whole matrix) of M (from
// system_in_row_order()) with its rows and columns at their positions, columns sorted (short: insertion sort).
inline Eigen::SparseMatrix<double> ordered_system(const Eigen::SparseMatrix<double>& M, const Row_permutation& permutation,
                                                  int stored_triangle)
{
  const int rows = int(M.rows());
  const int* position = permutation.indices().data();
  std::vector<int> row_at(std::size_t(rows), 0);
  for(int r = 0; r < rows; ++r)
    row_at[position[r]] = r;
  Eigen::SparseMatrix<double> S(rows, rows);
  S.resizeNonZeros(stored_triangle == 0 ? M.nonZeros() : (M.nonZeros() + rows) / 2);
  int* outer = S.outerIndexPtr();
  int* inner = S.innerIndexPtr();
  double* value = S.valuePtr();
  const int* m_outer = M.outerIndexPtr();
  const int* m_inner = M.innerIndexPtr();
  const double* m_value = M.valuePtr();
  int nnz = 0;
  for(int c = 0; c < rows; ++c) {
    outer[c] = nnz;
    const int begin = nnz;
    const int row = row_at[c];
    for(int p = m_outer[row]; p < m_outer[row + 1]; ++p) {
      const int r = position[m_inner[p]];
      if((stored_triangle == Eigen::Lower && r < c) || (stored_triangle == Eigen::Upper && r > c))
        continue;
      int q = nnz++;
      for(; q > begin && inner[q - 1] > r; --q) {
        inner[q] = inner[q - 1];
        value[q] = value[q - 1];
      }
      inner[q] = r;
      value[q] = m_value[p];
    }
  }
  outer[rows] = nnz;
  S.resizeNonZeros(nnz);
  return S;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_SYSTEM_ASSEMBLY_H
