// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_COST_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_COST_H

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_METIS
#include <CGAL/Trivial_connections/internal/concurrency.h>

#include <metis.h>
#endif

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The size and the work of a Cholesky factor, from its column counts c_j (below the diagonal): nonzeros
  sum c_j, and flops sum c_j^2 (the multiply-adds of a left-looking factorization, up to lower-order terms).
  This is what the symbolic analysis of a backend would report, and it predicts the numeric factorization:
  a simplicial one runs at a rate of flops, a supernodal one (dense blocks, BLAS) closer to a rate of nonzeros.
*/
struct Factor_cost
{
  double nonzeros = 0;
  double flops = 0;
};

// Factor_cost from column counts (a Factor_cost of Eigen's SimplicialLDLT analysis, for one)
template <class Counts>
Factor_cost factor_cost_of_counts(const Counts& counts, std::size_t n)
{
  Factor_cost cost;
  for(std::size_t j = 0; j < n; ++j) {
    const double c = double(counts[j]);
    cost.nonzeros += c;
    cost.flops += c * c;
  }
  return cost;
}

/*
  Factor_cost of a symmetric pattern (compressed columns, both triangles, sorted or not; the diagonal is
  ignored) in the order `order` (order[position] = row), by the elimination tree (Liu's algorithm, as in
  Eigen's SimplicialCholesky analysis): O(nonzeros of L) time, O(n) memory.
*/
inline Factor_cost elimination_cost(int n, const std::vector<int>& column_start, const std::vector<int>& rows,
                                    const std::vector<int>& order)
{
  const std::size_t size = std::size_t(n);
  std::vector<int> position(size), parent(size), tag(size);
  std::vector<std::int64_t> count(size, 0);
  for(int k = 0; k < n; ++k)
    position[std::size_t(order[std::size_t(k)])] = k;
  for(int k = 0; k < n; ++k) {
    parent[std::size_t(k)] = -1;
    tag[std::size_t(k)] = k;
    const int column = order[std::size_t(k)];
    for(int p = column_start[std::size_t(column)]; p < column_start[std::size_t(column) + 1]; ++p) {
      int i = position[std::size_t(rows[std::size_t(p)])];
      if(i >= k)
        continue;
      // row k of L: the etree path from i up to the first node already marked for k
      for(; tag[std::size_t(i)] != k; i = parent[std::size_t(i)]) {
        if(parent[std::size_t(i)] == -1)
          parent[std::size_t(i)] = k;
        ++count[std::size_t(i)];
        tag[std::size_t(i)] = k;
      }
    }
  }
  return factor_cost_of_counts(count, std::size_t(n));
}

/*
  Eigen's SimplicialLDLT runs at about 2.2 GFlop/s on the 2-core machine of benchmark/RESULTS.md (1.8 to 2.6
  from 40 MFlop to 16 GFlop factors of mesh Laplacians): its predicted time in seconds.
*/
inline double predicted_simplicial_seconds(const Factor_cost& c) { return c.flops / 2.2e9; }

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_METIS
// The graph METIS reads (xadj, adjncy) of a symmetric pattern (both triangles; the diagonal is skipped), or of its
// subgraph induced by `vertices` (numbered by their positions there) when `vertices` is not null
inline void metis_graph(const std::vector<int>& column_start, const std::vector<int>& rows,
                        const std::vector<int>* vertices, std::vector<idx_t>& xadj, std::vector<idx_t>& adjncy)
{
  const std::size_t n = column_start.empty() ? 0 : column_start.size() - 1;
  const std::size_t size = vertices != nullptr ? vertices->size() : n;
  std::vector<idx_t> local;
  if(vertices != nullptr) {
    local.assign(n, -1);
    for(std::size_t i = 0; i < size; ++i)
      local[std::size_t((*vertices)[i])] = idx_t(i);
  }
  xadj.assign(size + 1, 0);
  adjncy.clear();
  adjncy.reserve(vertices != nullptr ? 7 * size : rows.size());
  for(std::size_t i = 0; i < size; ++i) {
    const int c = vertices != nullptr ? (*vertices)[i] : int(i);
    for(int p = column_start[std::size_t(c)]; p < column_start[std::size_t(c) + 1]; ++p) {
      const int r = rows[std::size_t(p)];
      const idx_t j = vertices != nullptr ? local[std::size_t(r)] : idx_t(r);
      if(r != c && j >= 0)
        adjncy.push_back(j);
    }
    xadj[i + 1] = idx_t(adjncy.size());
  }
}

// METIS_NodeND (default options) of the graph of metis_graph(); `order` gets its rows in elimination order
inline bool metis_order_of(const std::vector<int>& column_start, const std::vector<int>& rows,
                           const std::vector<int>* vertices, std::vector<int>& order)
{
  std::vector<idx_t> xadj, adjncy;
  metis_graph(column_start, rows, vertices, xadj, adjncy);
  const std::size_t size = xadj.size() - 1;
  order.resize(size);
  if(size == 0)
    return true;
  idx_t nodes = idx_t(size);
  std::vector<idx_t> perm(size), iperm(size);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  const int status = METIS_NodeND(&nodes, xadj.data(), adjncy.data(), nullptr, options, perm.data(), iperm.data());
  if(status == METIS_ERROR_MEMORY)
    throw std::bad_alloc();
  if(status != METIS_OK)
    return false;
  for(std::size_t k = 0; k < size; ++k) // perm[new] = old
    order[k] = vertices != nullptr ? (*vertices)[std::size_t(perm[k])] : int(perm[k]);
  return true;
}

/*
  METIS's nested dissection of a symmetric pattern (both triangles; the diagonal is skipped), order[position] =
  row. METIS takes about 6 microseconds per row here, ten times Eigen's AMD, and gives factors with 1.5 to 4 times
  fewer flops on meshes of 150k vertices and more. From `parallel_rows` rows on, the first separator is computed
  first (METIS_ComputeVertexSeparator, as the first step of METIS_NodeND) and the two halves are dissected at the
  same time on two threads, then the separator is eliminated last: 2.4 s instead of 4.2 s for the 600k vertices of
  a 1.2M-face mesh on the 2 cores of benchmark/RESULTS.md, for a factor of 2 % more flops.
*/
inline bool metis_order(int n, const std::vector<int>& column_start, const std::vector<int>& rows,
                        std::vector<int>& order, int parallel_rows = 100000)
{
  if(n < parallel_rows)
    return metis_order_of(column_start, rows, nullptr, order);
  const std::size_t size = std::size_t(n);
  std::vector<idx_t> xadj, adjncy;
  metis_graph(column_start, rows, nullptr, xadj, adjncy);
  idx_t nodes = idx_t(n), separator_size = 0;
  std::vector<idx_t> part(size);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  const int status =
    METIS_ComputeVertexSeparator(&nodes, xadj.data(), adjncy.data(), nullptr, options, &separator_size, part.data());
  if(status == METIS_ERROR_MEMORY)
    throw std::bad_alloc();
  if(status != METIS_OK)
    return false;
  std::vector<idx_t>().swap(xadj);
  std::vector<idx_t>().swap(adjncy);
  std::vector<int> halves[2], separator;
  for(int v = 0; v < n; ++v)
    (part[std::size_t(v)] == 2 ? separator : halves[part[std::size_t(v)]]).push_back(v);
  std::vector<int> second;
  std::future<bool> second_half =
    concurrently([&] { return metis_order_of(column_start, rows, &halves[1], second); });
  const bool first_ok = metis_order_of(column_start, rows, &halves[0], order);
  const bool second_ok = second_half.get();
  if(!first_ok || !second_ok)
    return false;
  order.insert(order.end(), second.begin(), second.end());
  order.insert(order.end(), separator.begin(), separator.end());
  return true;
}
#endif

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_COST_H
