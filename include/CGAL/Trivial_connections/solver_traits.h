// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H
#define CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H

#include <CGAL/assertions.h>
#include <CGAL/Eigen_solver_traits.h>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <new>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
The default sparse solver of `Trivial_connection_solver`: Eigen's header-only `SimplicialLDLT`, with the
natural ordering because the solver hands it a matrix that is already in a fill-reducing order (AMD) with
the rows of the loop integers last; the metric of the loop integers is then read from the factor. It reads
the upper triangle, which is what the solver stores: Eigen copies a lower one first.
*/
using Default_solver_traits =
  CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper,
                                                  Eigen::NaturalOrdering<int>>>;

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
/*!
\ingroup PkgTrivialConnectionsRef
SuiteSparse's supernodal CHOLMOD (through Eigen's `CholmodSupport`), set to keep the order of the matrix it
is given (the solver orders it). Available when `CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD` is defined and
CHOLMOD is linked (CMake option `TRIVIAL_CONNECTIONS_WITH_CHOLMOD`).
*/
class Cholmod_supernodal_factorization
  : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>
{
public:
  /// a supernodal factorization that keeps the given order (`nmethods = 1`, natural ordering)
  Cholmod_supernodal_factorization()
  {
    cholmod().nmethods = 1;
    cholmod().method[0].ordering = CHOLMOD_NATURAL;
    cholmod().postorder = 0;
  }
  /// the factor, or null before a successful factorization
  /// \returns CHOLMOD's factor of the last factorization (owned by this object), or `nullptr`
  const cholmod_factor* factor() const { return m_cholmodFactor; }
};

/// \ingroup PkgTrivialConnectionsRef
/// CGAL solver traits of `Cholmod_supernodal_factorization`
using Cholmod_solver_traits = CGAL::Eigen_solver_traits<Cholmod_supernodal_factorization>;
/// the solver the command-line program uses: CHOLMOD when it is available
using Recommended_solver_traits = Cholmod_solver_traits;
#else
/// the solver the command-line program uses: CHOLMOD when it is available
using Recommended_solver_traits = Default_solver_traits;
#endif

namespace internal {

/*
  A fill-reducing order of the rows of a symmetric matrix (order[position] = row), computed the way the
  backend would compute it on its own: the solver then moves the loop rows last and hands the backend
  the reordered matrix to factor as it is. Default: Eigen's AMD.
*/
template <class SolverTraits>
struct Fill_reducing_ordering
{
  // `column_start`, `rows`: a symmetric pattern, both triangles and the diagonal (compressed columns,
  // sorted); `order[position] = row`. Eigen's AMD (as AMDOrdering, without its copy into A + A^T).
  static void compute(int n, const std::vector<int>& column_start, const std::vector<int>& rows,
                      std::vector<int>& order)
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
};

/*
  The triangle of the symmetric system that the backend reads (Eigen::Lower or Eigen::Upper), so that the
  solver stores only that one; 0 (the default, for backends it does not know) means the whole matrix.
*/
template <class SolverTraits>
struct Stored_triangle
{
  static constexpr int value = 0;
};

template <class Scalar, int UpLo, class Index>
struct Stored_triangle<CGAL::Eigen_solver_traits<
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<Scalar>, UpLo, Eigen::NaturalOrdering<Index>>>>
{
  static constexpr int value = UpLo;
};

template <class Scalar, int UpLo, class Index>
struct Stored_triangle<CGAL::Eigen_solver_traits<
  Eigen::SimplicialLLT<Eigen::SparseMatrix<Scalar>, UpLo, Eigen::NaturalOrdering<Index>>>>
{
  static constexpr int value = UpLo;
};

/*
  Whether the backend's substitutions read its factor alone, so that the solver can release the matrix after
  the factorization (CGAL::Eigen_solver_traits keeps a pointer to it, which stays valid). False for backends
  it does not know: an iterative solver, for one, reads the matrix at every solve.
*/
template <class SolverTraits>
struct Substitutions_need_only_the_factor
{
  static constexpr bool value = false;
};

template <class Matrix, int UpLo, class Ordering>
struct Substitutions_need_only_the_factor<CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Matrix, UpLo, Ordering>>>
{
  static constexpr bool value = true;
};

template <class Matrix, int UpLo, class Ordering>
struct Substitutions_need_only_the_factor<CGAL::Eigen_solver_traits<Eigen::SimplicialLLT<Matrix, UpLo, Ordering>>>
{
  static constexpr bool value = true;
};

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
  template <class Traits>
  static void scale(Traits& traits, Eigen::VectorXd& v)
  {
    v = v.cwiseQuotient(traits.solver().vectorD());
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
struct Stored_triangle<CGAL::Eigen_solver_traits<Cholmod_supernodal_factorization>>
{
  static constexpr int value = Eigen::Lower;
};

template <>
struct Substitutions_need_only_the_factor<CGAL::Eigen_solver_traits<Cholmod_supernodal_factorization>>
{
  static constexpr bool value = true;
};

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
  static void backward(Traits& traits, Eigen::VectorXd& v) { solve(traits, CHOLMOD_Lt, v); }

private:
  // With a cholmod_common of its own: the solver's one holds scratch memory, and these substitutions may run
  // from several threads at once (they only read the factor).
  template <class Traits>
  static void solve(Traits& traits, int system, Eigen::VectorXd& v)
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
#endif

} // namespace internal

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H
