// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H
#define CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H

#include <CGAL/assertions.h>
#include <CGAL/Eigen_solver_traits.h>
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
// only the bodies of the CHOLMOD classes below: the cost that chooses the backend, the factor's storage written
// on two threads, and the simplicial factorization on two threads
#include <CGAL/Trivial_connections/internal/factorization/factor_cost.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_storage.h>
#include <CGAL/Trivial_connections/internal/factorization/ldlt_on_two_threads.h>
#endif

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <cstddef>
#include <memory>

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

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H
