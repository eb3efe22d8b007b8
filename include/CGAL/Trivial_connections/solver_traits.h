// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H
#define CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H

#include <CGAL/assertions.h>
#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_cost.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_storage.h>
#include <CGAL/Trivial_connections/internal/factorization/ldlt_on_two_threads.h>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <memory>
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

  /// the numeric factorization, after `analyzePattern()`. The first one allocates the numeric factor itself
  /// first and writes each page of it once, half on a second thread, before CHOLMOD fills it (the first write
  /// of new memory costs a page fault; see the user manual's section on performance).
  /// \param matrix the matrix analysed (its lower triangle is read)
  void factorize(const Eigen::SparseMatrix<double>& matrix)
  {
    prepare_factor_storage();
    Base::factorize(matrix);
  }
  /// `analyzePattern()` then `factorize()`
  /// \param matrix the matrix to factor (its lower triangle is read)
  /// \returns this factorization
  Cholmod_supernodal_factorization& compute(const Eigen::SparseMatrix<double>& matrix)
  {
    Base::analyzePattern(matrix);
    factorize(matrix);
    return *this;
  }

private:
  using Base = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;

  // the conversion cholmod_super_numeric() would make (symbolic supernodal -> real supernodal L L^T), with the
  // new storage written; nothing without an analysis or once the factor is numeric (a refactorization)
  void prepare_factor_storage()
  {
    cholmod_factor* L = m_cholmodFactor;
    if(L == nullptr || !L->is_super || L->xtype != CHOLMOD_PATTERN)
      return;
    if(!cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, L, &cholmod()) || L->x == nullptr)
      return; // out of memory: the numeric factorization reports it
    internal::write_every_page_on_two_threads(static_cast<double*>(L->x), std::ptrdiff_t(L->xsize));
  }
};

/// \ingroup PkgTrivialConnectionsRef
/// CGAL solver traits of `Cholmod_supernodal_factorization`
using Cholmod_solver_traits = CGAL::Eigen_solver_traits<Cholmod_supernodal_factorization>;

/// \ingroup PkgTrivialConnectionsRef
/// the backend of a factorization of `Cost_based_solver_traits`
enum class Factorization_backend
{
  none,              ///< no factorization yet (or it failed)
  simplicial_ldlt,   ///< Eigen's `SimplicialLDLT`
  cholmod_supernodal ///< `Cholmod_supernodal_factorization`
};

/*!
\ingroup PkgTrivialConnectionsRef
Chooses its backend per factorization by predicted cost: Eigen's `SimplicialLDLT` or
`Cholmod_supernodal_factorization`. The symbolic analysis of the simplicial factorization (which it reuses
when it keeps that backend) gives the nonzeros `nnz` and the flops `sum c_j^2` of the factor, c_j its column
counts; a supernodal factorization (CHOLMOD with OpenBLAS) costs nearly the same per nonzero whatever the flops
per column, a simplicial one grows with the flops. The factorization is supernodal when
`flops > flops_per_nonzero * nnz + fixed_flops`, by default 110 flops per nonzero and 9e8 flops (the crossover
measured on the machine of benchmark/RESULTS.md with the simplicial factorization on two threads, see
`Measured_crossover`: meshes with long columns, or of about 350k faces and more). Available with CHOLMOD (`CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD`); the command-line
program uses it, with `Measured_crossover`.
\tparam Crossover a class with `static constexpr double` members `flops_per_nonzero` and `fixed_flops`
*/
template <class Crossover>
class Cost_based_solver_traits
{
public:
  /// the number type
  using NT = double;
  /// the vector type
  using Vector = CGAL::Eigen_vector<double>;
  /// the matrix type (its lower triangle is read)
  using Matrix = CGAL::Eigen_sparse_matrix<double>;
  /// the index type
  using Index = Eigen::Index;
  /// the simplicial backend
  using Simplicial = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>;
  /// the backend of the last factorization
  using Backend = Factorization_backend;

  /// factors `A` with the backend of lower predicted cost
  /// \param A the matrix (its lower triangle is read)
  /// \param D set to 1
  /// \returns whether the factorization succeeded
  bool factor(const Matrix& A, NT& D)
  {
    D = 1;
    const Eigen::SparseMatrix<double>& M = A.eigen_object();
    m_backend = Backend::none;
    m_cholmod.reset();
    m_simplicial = std::make_shared<Analysed_simplicial>();
    m_simplicial->analyzePattern(M);
    if(m_simplicial->info() != Eigen::Success)
      return false;
    const internal::Factor_cost cost = m_simplicial->cost();
    m_nonzeros = cost.nonzeros;
    m_flops = cost.flops;
    if(m_flops <= Crossover::flops_per_nonzero * m_nonzeros + Crossover::fixed_flops) {
      internal::factorize_analysed_ldlt(static_cast<Simplicial&>(*m_simplicial), M);
      m_backend = Backend::simplicial_ldlt;
      return m_simplicial->info() == Eigen::Success;
    }
    m_simplicial.reset();
    m_cholmod = std::make_shared<Cholmod_supernodal_factorization>();
    m_cholmod->compute(M);
    m_backend = Backend::cholmod_supernodal;
    return m_cholmod->info() == Eigen::Success;
  }

  /// `X = A^-1 B` with the last factorization
  /// \param B the right-hand side
  /// \param X the solution
  /// \returns whether the solve succeeded
  bool linear_solver(const Vector& B, Vector& X)
  {
    CGAL_precondition(m_backend != Backend::none);
    if(m_backend == Backend::simplicial_ldlt) {
      X = m_simplicial->solve(B);
      return m_simplicial->info() == Eigen::Success;
    }
    X = m_cholmod->solve(B);
    return m_cholmod->info() == Eigen::Success;
  }

  /// the backend of the last factorization
  /// \returns `none` before a successful factorization
  Backend backend() const { return m_backend; }
  /// the nonzeros below the diagonal of the last factor, from the symbolic analysis
  /// \returns the sum of the column counts
  double factor_nonzeros() const { return m_nonzeros; }
  /// the flops `sum c_j^2` of the last factor, from the symbolic analysis
  /// \returns the sum of the squared column counts
  double factor_flops() const { return m_flops; }

  /// the simplicial factorization
  /// \returns it, when `backend()` is `simplicial_ldlt`
  Simplicial& simplicial() { return *m_simplicial; }
  /// the supernodal factorization
  /// \returns it, when `backend()` is `cholmod_supernodal`
  Cholmod_supernodal_factorization& cholmod() { return *m_cholmod; }

private:
  // the column counts of Eigen's analysis are protected
  struct Analysed_simplicial : Simplicial
  {
    internal::Factor_cost cost() const
    {
      return internal::factor_cost_of_counts(this->m_nonZerosPerCol, std::size_t(this->m_nonZerosPerCol.size()));
    }
  };

  double m_nonzeros = 0, m_flops = 0;
  Backend m_backend = Backend::none;
  std::shared_ptr<Analysed_simplicial> m_simplicial;
  std::shared_ptr<Cholmod_supernodal_factorization> m_cholmod;
};

/*!
\ingroup PkgTrivialConnectionsRef
The crossover of `Cost_based_solver_traits` measured on the machine of benchmark/RESULTS.md (2 cores, OpenBLAS),
factorization phase of the solver, simplicial on two threads against supernodal (2026-12-03): 302k faces
(1.43 GFlop, 6.3M nonzeros) 0.43-0.54 s against 0.52-0.62 s; 1.2M faces, genus 0 (4.8 GFlop, 23.6M nonzeros)
5.9-6.0 s against 2.7 s; 1.1M faces, genus 133 (6.9 GFlop, 25M nonzeros) 2.9 s against 2.5 s. On one thread the
simplicial factorization is about a quarter slower (the crossover measured before was 110 per nonzero + 6.6e7).
*/
struct Measured_crossover
{
  static constexpr double flops_per_nonzero = 110; ///< flops per nonzero of the factor
  static constexpr double fixed_flops = 9e8;       ///< flops of the supernodal factorization's fixed cost
};

/// \ingroup PkgTrivialConnectionsRef
/// the backend chosen by predicted cost, with the measured crossover
using Automatic_solver_traits = Cost_based_solver_traits<Measured_crossover>;

/// the solver the command-line program uses: the choice by predicted cost when CHOLMOD is available
using Recommended_solver_traits = Automatic_solver_traits;
#else
/// the solver the command-line program uses: CHOLMOD when it is available
using Recommended_solver_traits = Default_solver_traits;
#endif

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

// Automatic_solver_traits: what its backend of the moment does
template <class Crossover>
struct Stored_triangle<Cost_based_solver_traits<Crossover>>
{
  static constexpr int value = Eigen::Lower;
};

template <class Crossover>
struct Substitutions_need_only_the_factor<Cost_based_solver_traits<Crossover>>
{
  static constexpr bool value = true;
};

// the views of one backend of Automatic_solver_traits that the specializations above read (solver())
template <class Backend>
struct Backend_view
{
  Backend& backend;
  Backend& solver() { return backend; }
  const Backend& solver() const { return backend; }
};

using Automatic_simplicial_traits = CGAL::Eigen_solver_traits<Automatic_solver_traits::Simplicial>;
using Automatic_simplicial_view = Backend_view<Automatic_solver_traits::Simplicial>;
using Automatic_cholmod_view = Backend_view<Cholmod_supernodal_factorization>;
using Automatic_backend = Factorization_backend;

// `on_simplicial(view)` or `on_supernodal(view)` for the backend of the last factorization, `none` without one
template <class Traits, class OnSimplicial, class OnSupernodal, class Result>
Result on_backend(Traits& traits, OnSimplicial on_simplicial, OnSupernodal on_supernodal, Result none)
{
  switch(traits.backend()) {
  case Automatic_backend::simplicial_ldlt: {
    Automatic_simplicial_view view{traits.simplicial()};
    return on_simplicial(view);
  }
  case Automatic_backend::cholmod_supernodal: {
    Automatic_cholmod_view view{traits.cholmod()};
    return on_supernodal(view);
  }
  default:
    return none;
  }
}

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
  static void backward(Traits& traits, Eigen::VectorXd& v)
  {
    on_backend(
      traits, [&](auto& view) { Simplicial::backward(view, v, v.size()); return true; },
      [&](auto& view) { Supernodal::backward(view, v); return true; }, false);
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

#endif // CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H
