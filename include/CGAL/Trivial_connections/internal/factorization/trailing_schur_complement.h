// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_TRAILING_SCHUR_COMPLEMENT_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_TRAILING_SCHUR_COMPLEMENT_H

// The metric of the loop integers read from the factor (see Trailing_schur_complement).

#include <CGAL/Trivial_connections/solver_traits.h>
#include <CGAL/Trivial_connections/internal/factorization/backend_view.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cstddef>
#include <type_traits>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  Reading the Schur complement S = M_LL - M_LN M_NN^-1 M_NL of the trailing rows L of a factored
  M = [M_NN M_NL; M_LN M_LL] from the factor: with M = L D L^T and the rows L last, S = L_LL D_L L_LL^T.
  `read` gives the lower triangular L_LL and the diagonal D_L (ones for an LL^T factorization).
  The inverse of S is (M^-1)_LL, the metric of the loop integers, at the cost of a dense k x k block
  instead of k back-substitutions. `read` returns false when the backend does not expose its factor or
  did not keep the given order; the caller then falls back to back-substitutions.
*/
template <class SolverTraits>
struct Trailing_schur_complement
{
  static bool read(SolverTraits&, Eigen::Index, Eigen::MatrixXd&, Eigen::VectorXd&) { return false; }
};

template <int UpLo, class Index>
struct Trailing_schur_complement<CGAL::Eigen_solver_traits<
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, UpLo, Eigen::NaturalOrdering<Index>>>>
{
  template <class Traits>
  static bool read(Traits& traits, Eigen::Index k, Eigen::MatrixXd& Lt, Eigen::VectorXd& d)
  {
    const auto& solver = traits.solver();
    if(solver.permutationP().size() != 0)
      return false;
    const auto& L = solver.matrixL().nestedExpression(); // strictly lower part, column major
    const Eigen::Index n = L.rows(), first = n - k;
    Lt = Eigen::MatrixXd::Identity(k, k);
    for(Eigen::Index j = first; j < n; ++j)
      for(typename std::decay<decltype(L)>::type::InnerIterator it(L, j); it; ++it)
        if(it.row() > j)
          Lt(it.row() - first, j - first) = it.value();
    d = solver.vectorD().tail(k);
    return true;
  }
};

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
template <>
struct Trailing_schur_complement<CGAL::Eigen_solver_traits<Cholmod_supernodal_factorization>>
{
  template <class Traits>
  static bool read(Traits& traits, Eigen::Index k, Eigen::MatrixXd& Lt, Eigen::VectorXd& d)
  {
    const cholmod_factor* F = traits.solver().factor();
    if(F == nullptr || !F->is_super || !F->is_ll || F->itype != CHOLMOD_INT)
      return false;
    const Eigen::Index n = Eigen::Index(F->n), first = n - k;
    const int* perm = static_cast<const int*>(F->Perm);
    if(perm != nullptr)
      for(Eigen::Index i = 0; i < n; ++i)
        if(perm[i] != i)
          return false;
    const int* super = static_cast<const int*>(F->super);
    const int* pi = static_cast<const int*>(F->pi);
    const int* px = static_cast<const int*>(F->px);
    const int* rows = static_cast<const int*>(F->s);
    const double* x = static_cast<const double*>(F->x);
    Lt = Eigen::MatrixXd::Zero(k, k);
    for(std::size_t s = 0; s < F->nsuper; ++s) {
      const int c0 = super[s], c1 = super[s + 1];
      if(c1 <= first)
        continue;
      const int nrows = pi[s + 1] - pi[s];
      // supernode s: a dense column-major nrows x (c1 - c0) block, rows listed from rows[pi[s]]
      for(int c = (std::max)(c0, int(first)); c < c1; ++c)
        for(int r = c - c0; r < nrows; ++r) {
          const int row = rows[pi[s] + r];
          if(row >= first)
            Lt(row - first, c - first) = x[px[s] + std::size_t(c - c0) * std::size_t(nrows) + std::size_t(r)];
        }
    }
    d = Eigen::VectorXd::Ones(k);
    return true;
  }
};

template <class Crossover>
struct Trailing_schur_complement<Cost_based_solver_traits<Crossover>>
{
  static bool read(Cost_based_solver_traits<Crossover>& traits, Eigen::Index k, Eigen::MatrixXd& L, Eigen::VectorXd& d)
  {
    return on_backend(
      traits, [&](auto& view) { return Trailing_schur_complement<Automatic_simplicial_traits>::read(view, k, L, d); },
      [&](auto& view) { return Trailing_schur_complement<Cholmod_solver_traits>::read(view, k, L, d); }, false);
  }
};
#endif

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_TRAILING_SCHUR_COMPLEMENT_H
