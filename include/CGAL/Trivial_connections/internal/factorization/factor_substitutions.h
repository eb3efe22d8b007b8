// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_SUBSTITUTIONS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_SUBSTITUTIONS_H

// The substitutions of a factor in place, without the backend's own solve (see Factor_substitutions).

#include <CGAL/Trivial_connections/solver_traits.h>
#include <CGAL/Trivial_connections/internal/factorization/backend_view.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_storage.h>

#include <CGAL/assertions.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cstddef>
#include <new>
#include <type_traits>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The substitutions of a factorization M = L D L^T in the order given to the backend (no permutation of its
  own): forward (v <- L^-1 v), scale (v <- D^-1 v), backward (v <- L^-T v). With the loop rows last, a solve
  that must choose the loop integers first needs one forward and one backward substitution instead of two
  solves. `available` is false for backends that do not expose them.
  Backends with `leading_columns` substitute through the first `columns` columns of L only instead:
  forward(v, columns) leaves on the trailing rows their right-hand side for the trailing block of L, and
  backward(v, columns) expects the trailing rows solved already. The solver does the trailing block with
  its dense copy (the Schur complement of the loop rows), faster than a sparse substitution.
*/
template <class SolverTraits>
struct Factor_substitutions
{
  static constexpr bool leading_columns = false;
  static bool available(const SolverTraits&) { return false; }
  static void forward(SolverTraits&, Eigen::VectorXd&) { CGAL_error(); }
  static void scale(SolverTraits&, Eigen::VectorXd&) { CGAL_error(); }
  static double scaled_square_norm(SolverTraits&, const Eigen::VectorXd&, Eigen::Index)
  {
    CGAL_error();
    return 0;
  }
  static void backward(SolverTraits&, Eigen::VectorXd&) { CGAL_error(); }
};

template <int UpLo, class Index>
struct Factor_substitutions<CGAL::Eigen_solver_traits<
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, UpLo, Eigen::NaturalOrdering<Index>>>>
{
  // the steps of SimplicialCholeskyBase::_solve_impl without its permutations (empty with the natural ordering)
  static constexpr bool leading_columns = true;
  template <class Traits>
  static bool available(Traits& traits)
  {
    return traits.solver().info() == Eigen::Success && traits.solver().permutationP().size() == 0;
  }
  // D read in place: vectorD() returns a copy (a fresh vector per solve, each of its pages a fault)
  template <class Traits>
  static void scale(Traits& traits, Eigen::VectorXd& v)
  {
    auto& solver = traits.solver();
    v.array() /= Simplicial_members<std::remove_reference_t<decltype(solver)>>::diagonal(solver).array();
  }
  // sum of v_i^2 / d_i over the first `count` rows (what scale() then a dot product with v give, without a copy)
  template <class Traits>
  static double scaled_square_norm(Traits& traits, const Eigen::VectorXd& v, Eigen::Index count)
  {
    auto& solver = traits.solver();
    const auto& d = Simplicial_members<std::remove_reference_t<decltype(solver)>>::diagonal(solver);
    return (v.head(count).array().square() / d.head(count).array()).sum();
  }
  // L is stored strictly lower (unit diagonal), column major
  template <class Traits>
  static void forward(Traits& traits, Eigen::VectorXd& v, Eigen::Index columns)
  {
    const auto& L = traits.solver().matrixL().nestedExpression();
    CGAL_precondition(L.isCompressed() && columns <= L.cols());
    const int* start = L.outerIndexPtr();
    const int* row = L.innerIndexPtr();
    const double* value = L.valuePtr();
    for(Eigen::Index j = 0; j < columns; ++j) {
      const double vj = v[j];
      if(vj != 0)
        for(int p = start[j]; p < start[j + 1]; ++p)
          v[row[p]] -= value[p] * vj;
    }
  }
  template <class Traits>
  static void backward(Traits& traits, Eigen::VectorXd& v, Eigen::Index columns)
  {
    const auto& L = traits.solver().matrixL().nestedExpression();
    CGAL_precondition(L.isCompressed() && columns <= L.cols());
    const int* start = L.outerIndexPtr();
    const int* row = L.innerIndexPtr();
    const double* value = L.valuePtr();
    for(Eigen::Index j = columns - 1; j >= 0; --j) {
      // four partial sums: one would wait for each product in turn
      double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
      int p = start[j];
      const int end = start[j + 1];
      for(; p + 3 < end; p += 4) {
        s0 += value[p] * v[row[p]];
        s1 += value[p + 1] * v[row[p + 1]];
        s2 += value[p + 2] * v[row[p + 2]];
        s3 += value[p + 3] * v[row[p + 3]];
      }
      for(; p < end; ++p)
        s0 += value[p] * v[row[p]];
      v[j] -= (s0 + s1) + (s2 + s3);
    }
  }
};

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
template <>
struct Factor_substitutions<CGAL::Eigen_solver_traits<Cholmod_supernodal_factorization>>
{
  template <class Traits>
  static bool available(Traits& traits)
  {
    const cholmod_factor* F = traits.solver().factor();
    if(F == nullptr || !F->is_ll || F->itype != CHOLMOD_INT || F->xtype != CHOLMOD_REAL)
      return false;
    const int* perm = static_cast<const int*>(F->Perm);
    if(perm != nullptr)
      for(std::size_t i = 0; i < F->n; ++i)
        if(perm[i] != int(i))
          return false;
    return true;
  }
  static constexpr bool leading_columns = false; // cholmod_solve runs through all columns
  template <class Traits>
  static void forward(Traits& traits, Eigen::VectorXd& v) { solve(traits, CHOLMOD_L, v); }

  template <class Traits>
  static void scale(Traits&, Eigen::VectorXd&) {} // L L^T: D = I
  template <class Traits>
  static double scaled_square_norm(Traits&, const Eigen::VectorXd& v, Eigen::Index count)
  {
    return v.head(count).squaredNorm();
  }
  template <class Traits>
  static void backward(Traits& traits, Eigen::VectorXd& v) { solve(traits, CHOLMOD_Lt, v); }

private:
  // L L^T with dense supernodes, read in place: cholmod_solve would start a cholmod_common and allocate its
  // workspace at each call, and go through BLAS per supernode (most supernodes of a surface are a few columns)
  template <class Traits>
  static void solve(Traits& traits, int system, Eigen::VectorXd& v)
  {
    const cholmod_factor* F = traits.solver().factor();
    if(!F->is_super) {
      solve_through_cholmod(traits, system, v);
      return;
    }
    const int* super = static_cast<const int*>(F->super);
    const int* pi = static_cast<const int*>(F->pi);
    const int* px = static_cast<const int*>(F->px);
    const int* all_rows = static_cast<const int*>(F->s);
    const double* x = static_cast<const double*>(F->x);
    double* w = v.data();
    if(system == CHOLMOD_L) {
      for(std::size_t s = 0; s < F->nsuper; ++s) {
        const int c0 = super[s], columns = super[s + 1] - c0, nrows = pi[s + 1] - pi[s];
        const int* rows = all_rows + pi[s];
        for(int k = 0; k < columns; ++k) {
          const double* block = x + px[s] + std::size_t(k) * std::size_t(nrows);
          const double wk = (w[c0 + k] /= block[k]);
          if(wk != 0)
            for(int r = k + 1; r < nrows; ++r)
              w[rows[r]] -= block[r] * wk;
        }
      }
      return;
    }
    for(std::size_t s = F->nsuper; s-- > 0;) {
      const int c0 = super[s], columns = super[s + 1] - c0, nrows = pi[s + 1] - pi[s];
      const int* rows = all_rows + pi[s];
      for(int k = columns - 1; k >= 0; --k) {
        const double* block = x + px[s] + std::size_t(k) * std::size_t(nrows);
        // four partial sums: one would wait for each product in turn
        double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
        int r = k + 1;
        for(; r + 3 < nrows; r += 4) {
          s0 += block[r] * w[rows[r]];
          s1 += block[r + 1] * w[rows[r + 1]];
          s2 += block[r + 2] * w[rows[r + 2]];
          s3 += block[r + 3] * w[rows[r + 3]];
        }
        for(; r < nrows; ++r)
          s0 += block[r] * w[rows[r]];
        w[c0 + k] = (w[c0 + k] - ((s0 + s1) + (s2 + s3))) / block[k];
      }
    }
  }

  // A simplicial factor: through cholmod_solve, with a cholmod_common of its own (the solver's one holds scratch
  // memory, and these substitutions may run from several threads at once: they only read the factor).
  template <class Traits>
  static void solve_through_cholmod(Traits& traits, int system, Eigen::VectorXd& v)
  {
    Cholmod_supernodal_factorization& solver = traits.solver();
    struct Common
    {
      cholmod_common c;
      Common() { cholmod_start(&c); }
      ~Common() { cholmod_finish(&c); }
    } common;
    cholmod_dense b;
    b.nrow = std::size_t(v.size());
    b.ncol = 1;
    b.nzmax = b.d = b.nrow;
    b.x = v.data();
    b.z = nullptr;
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* x = cholmod_solve(system, const_cast<cholmod_factor*>(solver.factor()), &b, &common.c);
    if(x == nullptr)
      throw std::bad_alloc();
    std::copy(static_cast<const double*>(x->x), static_cast<const double*>(x->x) + v.size(), v.data());
    cholmod_free_dense(&x, &common.c);
  }
};

// Through every column whichever the backend (CHOLMOD's substitutions cannot stop at the trailing block). The
// substitutions run only after available(): without a factor they do nothing.
template <class Crossover>
struct Factor_substitutions<Cost_based_solver_traits<Crossover>>
{
  using Traits = Cost_based_solver_traits<Crossover>;
  using Simplicial = Factor_substitutions<Automatic_simplicial_traits>;
  using Supernodal = Factor_substitutions<Cholmod_solver_traits>;
  static constexpr bool leading_columns = false;
  static bool available(Traits& traits)
  {
    return on_backend(
      traits, [](auto& view) { return Simplicial::available(view); },
      [](auto& view) { return Supernodal::available(view); }, false);
  }
  static void forward(Traits& traits, Eigen::VectorXd& v)
  {
    on_backend(
      traits, [&](auto& view) { Simplicial::forward(view, v, v.size()); return true; },
      [&](auto& view) { Supernodal::forward(view, v); return true; }, false);
  }
  static void scale(Traits& traits, Eigen::VectorXd& v)
  {
    // L L^T for CHOLMOD: D = I
    on_backend(
      traits, [&](auto& view) { Simplicial::scale(view, v); return true; }, [](auto&) { return true; }, false);
  }
  static double scaled_square_norm(Traits& traits, const Eigen::VectorXd& v, Eigen::Index count)
  {
    return on_backend(
      traits, [&](auto& view) { return Simplicial::scaled_square_norm(view, v, count); },
      [&](auto& view) { return Supernodal::scaled_square_norm(view, v, count); }, 0.);
  }
  static void backward(Traits& traits, Eigen::VectorXd& v)
  {
    on_backend(
      traits, [&](auto& view) { Simplicial::backward(view, v, v.size()); return true; },
      [&](auto& view) { Supernodal::backward(view, v); return true; }, false);
  }
};
#endif

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_SUBSTITUTIONS_H
