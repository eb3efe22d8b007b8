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
/*
  METIS's nested dissection (METIS_NodeND, default options) of a symmetric pattern (both triangles; the
  diagonal is skipped), order[position] = row. It takes about 5 microseconds per row here, ten times Eigen's AMD,
  and gives factors with 1.5 to 3 times fewer flops on meshes of 150k vertices and more.
*/
inline bool metis_order(int n, const std::vector<int>& column_start, const std::vector<int>& rows,
                        std::vector<int>& order)
{
  std::vector<idx_t> xadj(std::size_t(n) + 1, 0), adjncy;
  adjncy.reserve(rows.size());
  for(int c = 0; c < n; ++c) {
    for(int p = column_start[std::size_t(c)]; p < column_start[std::size_t(c) + 1]; ++p)
      if(rows[std::size_t(p)] != c)
        adjncy.push_back(idx_t(rows[std::size_t(p)]));
    xadj[std::size_t(c) + 1] = idx_t(adjncy.size());
  }
  idx_t nodes = idx_t(n);
  const std::size_t size = std::size_t(n);
  std::vector<idx_t> perm(size), iperm(size);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  const int status = METIS_NodeND(&nodes, xadj.data(), adjncy.data(), nullptr, options, perm.data(), iperm.data());
  if(status == METIS_ERROR_MEMORY)
    throw std::bad_alloc();
  if(status != METIS_OK)
    return false;
  order.resize(std::size_t(n));
  for(int k = 0; k < n; ++k)
    order[std::size_t(k)] = int(perm[std::size_t(k)]); // perm[new] = old
  return true;
}
#endif

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_COST_H
