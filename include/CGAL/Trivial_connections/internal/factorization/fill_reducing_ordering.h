// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FILL_REDUCING_ORDERING_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FILL_REDUCING_ORDERING_H

// The fill-reducing order the solver gives its system, per solver traits (AMD, METIS, CHOLMOD's own).

#include <CGAL/Trivial_connections/solver_traits.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_cost.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// Eigen's AMD of a symmetric pattern (both triangles and the diagonal, compressed columns, sorted), as
// AMDOrdering without its copy into A + A^T; `order[position] = row`
inline void amd_order(int n, const std::vector<int>& column_start, const std::vector<int>& rows, std::vector<int>& order)
{
  const Eigen::Index nnz = Eigen::Index(rows.size());
  Eigen::SparseMatrix<double> pattern(n, n);
  // the workspace minimum_degree_ordering resizes the matrix to, reserved so that nothing is copied
  pattern.resizeNonZeros(nnz + nnz / 5 + 2 * Eigen::Index(n));
  pattern.resizeNonZeros(nnz);
  std::copy(column_start.begin(), column_start.end(), pattern.outerIndexPtr());
  std::copy(rows.begin(), rows.end(), pattern.innerIndexPtr());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  if(n > 0)
    Eigen::internal::minimum_degree_ordering(pattern, amd);
  order.resize(std::size_t(n));
  for(int i = 0; i < n; ++i)
    order[std::size_t(i)] = amd.size() > 0 ? amd.indices()[i] : i;
}

/*
  A fill-reducing order of the rows of a symmetric matrix (order[position] = row), computed the way the
  backend would compute it on its own: the solver then moves the loop rows last and hands the backend
  the reordered matrix to factor as it is. Default: Eigen's AMD, or METIS where it pays (with METIS).
*/
template <class SolverTraits>
struct Fill_reducing_ordering
{
  // `column_start`, `rows`: a symmetric pattern, both triangles and the diagonal (compressed columns,
  // sorted); `order[position] = row`. Eigen's AMD, or METIS's nested dissection where it pays (below).
  static void compute(int n, const std::vector<int>& column_start, const std::vector<int>& rows,
                      std::vector<int>& order)
  {
    amd_order(n, column_start, rows, order);
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_METIS
    // METIS costs about 5 us per row, ten times AMD: it is tried when half of the predicted simplicial
    // factorization with AMD would repay it (meshes of about 300k vertices and more), and its order is kept
    // when its factor has fewer flops
    const Factor_cost with_amd = elimination_cost(n, column_start, rows, order);
    if(predicted_simplicial_seconds(with_amd) / 2 > 5e-6 * n) {
      std::vector<int> nested;
      if(metis_order(n, column_start, rows, nested) &&
         elimination_cost(n, column_start, rows, nested).flops < with_amd.flops)
        order.swap(nested);
    }
#endif
  }
};

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
// CHOLMOD's own choice (AMD, or METIS nested dissection when AMD fills too much), from its analysis.
template <>
struct Fill_reducing_ordering<CGAL::Eigen_solver_traits<Cholmod_supernodal_factorization>>
{
  static void compute(int rows_and_columns, const std::vector<int>& column_start, const std::vector<int>& rows,
                      std::vector<int>& order)
  {
    const std::size_t n = std::size_t(rows_and_columns);
    order.resize(n);
    for(std::size_t i = 0; i < n; ++i)
      order[i] = int(i);
    if(n == 0)
      return;
    cholmod_common common;
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SIMPLICIAL; // only the ordering is wanted
    cholmod_sparse pattern;
    pattern.nrow = pattern.ncol = n;
    pattern.nzmax = rows.size();
    pattern.p = const_cast<int*>(column_start.data());
    pattern.i = const_cast<int*>(rows.data());
    pattern.nz = nullptr;
    pattern.x = pattern.z = nullptr;
    pattern.stype = -1; // symmetric: the lower triangle is read, the upper one ignored
    pattern.itype = CHOLMOD_INT;
    pattern.xtype = CHOLMOD_PATTERN;
    pattern.dtype = CHOLMOD_DOUBLE;
    pattern.sorted = 1;
    pattern.packed = 1;
    cholmod_factor* symbolic = cholmod_analyze(&pattern, &common);
    if(symbolic != nullptr && symbolic->Perm != nullptr) {
      const int* perm = static_cast<const int*>(symbolic->Perm);
      for(std::size_t i = 0; i < n; ++i)
        order[i] = perm[i];
    }
    if(symbolic != nullptr)
      cholmod_free_factor(&symbolic, &common);
    cholmod_finish(&common);
  }
};

/*
  AMD for both backends. METIS's nested dissection (postordered along its elimination tree, so that CHOLMOD finds its
  supernodes in the order it keeps) was measured and lost: CHOLMOD's supernodes are smaller on it, so fewer flops
  do not pay. On the 2 cores of benchmark/RESULTS.md, a 1.2M-face mesh (600k rows): dissection 2.4 s (on two
  threads) against 0.8 s for AMD, factorization 3.1 s (5 GFlop) against 3.5 s (16 GFlop); a 4.8M-face mesh, the
  program as a whole: 35.1 s against 30.6 s with AMD (13.9 s factoring 42 GFlop against 18.3 s factoring 175, but
  about 13 s more of ordering), for a peak memory of 2.9 GB against 3.7 GB. Where the dissection pays for the
  simplicial backend (above), the supernodal one is faster still.
*/
template <class Crossover>
struct Fill_reducing_ordering<Cost_based_solver_traits<Crossover>>
{
  static void compute(int n, const std::vector<int>& column_start, const std::vector<int>& rows,
                      std::vector<int>& order)
  {
    amd_order(n, column_start, rows, order);
  }
};
#endif

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FILL_REDUCING_ORDERING_H
