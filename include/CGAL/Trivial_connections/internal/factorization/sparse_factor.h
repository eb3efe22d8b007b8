// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_SPARSE_FACTOR_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_SPARSE_FACTOR_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_storage.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_substitutions.h>
#include <CGAL/Trivial_connections/internal/factorization/ldlt_on_two_threads.h>
#include <CGAL/Trivial_connections/internal/factorization/matrix_storage.h>
#include <CGAL/Trivial_connections/internal/factorization/selected_inverse.h>
#include <CGAL/Trivial_connections/internal/factorization/trailing_schur_complement.h>
#include <CGAL/Trivial_connections/internal/system/system_assembly.h>
#include <CGAL/Trivial_connections/solver_traits.h>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include <memory>
#include <mutex>
#include <type_traits>
#include <utility>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  Backends whose analysis allocates the factor and whose numeric factorization first writes it (on one thread):
  Sparse_factor calls the two apart, and factorize() here does the numeric step so that the factor's new pages
  are written on two threads: LDL^T on two threads where it pays (ldlt_on_two_threads.h), otherwise every page
  written once beforehand, half on a second thread (factor_storage.h). Eigen's simplicial factorizations in the
  order given (the package's CHOLMOD one does it in its own factorize()); their solves go through
  Factor_substitutions, never through Eigen_solver_traits::linear_solver(), which needs its factor() called.
*/
template <class SolverTraits>
struct Factorization_in_two_steps : std::false_type
{
};

template <class Matrix, int UpLo, class Index>
struct Factorization_in_two_steps<
  CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Matrix, UpLo, Eigen::NaturalOrdering<Index>>>> : std::true_type
{
  template <class Simplicial>
  static void factorize(Simplicial& s, const Eigen::SparseMatrix<double>& M) { factorize_analysed_ldlt(s, M); }
};

template <class Matrix, int UpLo, class Index>
struct Factorization_in_two_steps<
  CGAL::Eigen_solver_traits<Eigen::SimplicialLLT<Matrix, UpLo, Eigen::NaturalOrdering<Index>>>> : std::true_type
{
  template <class Simplicial>
  static void factorize(Simplicial& s, const Eigen::SparseMatrix<double>& M)
  {
    touch_simplicial_factor_storage(s);
    s.factorize(M);
  }
};

/*
  The backend's factorization M = L D L^T of the constraint system, in the order the system was assembled in
  (a fill-reducing order of the node rows, then the rows with a free integer), and the substitutions through
  it. Solves may run from several threads at once: the substitutions of the package's backends read the
  factor only; another backend's solve may use scratch memory of its own, so it runs under a lock.
*/
template <class SolverTraits>
class Sparse_factor
{
  using Substitutions = Factor_substitutions<SolverTraits>;

public:
  // whether forward() and backward() can stop at the trailing block (see Factor_substitutions)
  static constexpr bool leading_columns = Substitutions::leading_columns;
  // the triangle of the ordered system that the backend reads (0: the whole matrix)
  static constexpr int stored_triangle = Stored_triangle<SolverTraits>::value;

  Sparse_factor() = default;
  Sparse_factor(const Sparse_factor&) = delete;
  Sparse_factor& operator=(const Sparse_factor&) = delete;

  // `ordered`: the system from ordered_system() with `permutation`; taken without a copy
  void load(Eigen::SparseMatrix<double>& ordered, const Row_permutation& permutation)
  {
    m_permutation = permutation;
    m_system.reset(new typename SolverTraits::Matrix(Eigen::SparseMatrix<double>()));
    m_system->eigen_object().swap(ordered);
  }

  // an empty system (no rows) is not factored
  void factor(Eigen::Index rows)
  {
    m_substitutions_available = false;
    if(rows == 0)
      return;
    bool factored = false;
    if constexpr(Factorization_in_two_steps<SolverTraits>::value) {
      auto& backend = m_solver.solver();
      backend.analyzePattern(m_system->eigen_object());
      if(backend.info() == Eigen::Success)
        Factorization_in_two_steps<SolverTraits>::factorize(backend, m_system->eigen_object());
      factored = backend.info() == Eigen::Success;
    } else {
      double d = 1;
      factored = m_solver.factor(*m_system, d);
    }
    if(!factored)
      throw Invalid_input(Error_code::solver_failure, "the sparse factorization of the constraint system failed");
    m_substitutions_available = Substitutions::available(m_solver);
    if(Substitutions_need_only_the_factor<SolverTraits>::value)
      Eigen::SparseMatrix<double>().swap(m_system->eigen_object()); // released: the solves read the factor alone
  }

  const Row_permutation& permutation() const { return m_permutation; }
  const SolverTraits& solver_traits() const { return m_solver; }
  bool substitutions_available() const { return m_substitutions_available; }

  // The trailing k x k block of the factor, L_FF (unit lower triangular) and D_F, when the backend exposes it.
  bool read_trailing_block(Eigen::Index k, Eigen::MatrixXd& L, Eigen::VectorXd& d)
  {
    return Trailing_schur_complement<SolverTraits>::read(m_solver, k, L, d);
  }
  bool substitutions_exposed() { return Substitutions::available(m_solver); }
  // the factor as L D L^T (see Factor_reading)
  bool read_factor(Unit_lower_factor& f) { return Factor_reading<SolverTraits>::read(m_solver, f); }

  // z <- L^-1 z, through the first `columns` columns when the backend has leading_columns, else all of them
  void forward(Eigen::VectorXd& z, Eigen::Index columns)
  {
    if constexpr(leading_columns)
      Substitutions::forward(m_solver, z, columns);
    else
      Substitutions::forward(m_solver, z);
  }
  // z <- D^-1 z
  void scale(Eigen::VectorXd& z) { Substitutions::scale(m_solver, z); }
  // the sum of z_i^2 / d_i over the first `count` rows
  double scaled_square_norm(const Eigen::VectorXd& z, Eigen::Index count)
  {
    return Substitutions::scaled_square_norm(m_solver, z, count);
  }
  // z <- L^-T z, likewise
  void backward(Eigen::VectorXd& z, Eigen::Index columns)
  {
    if constexpr(leading_columns)
      Substitutions::backward(m_solver, z, columns);
    else
      Substitutions::backward(m_solver, z);
  }

  // M^-1 b, rows in their own order (b not empty)
  Eigen::VectorXd solve(const Eigen::VectorXd& b)
  {
    if(m_substitutions_available) {
      Eigen::VectorXd z = m_permutation * b;
      forward(z, z.size());
      scale(z);
      backward(z, z.size());
      z = m_permutation.transpose() * z; // in place: one vector per solve, not two
      return z;
    }
    typename SolverTraits::Vector rhs(b.size()), sol(b.size());
    rhs = m_permutation * b;
    {
      std::lock_guard<std::mutex> lock(m_backend_mutex);
      if(!m_solver.linear_solver(rhs, sol))
        throw Invalid_input(Error_code::solver_failure, "a back-substitution failed");
    }
    return m_permutation.transpose() * Eigen::VectorXd(sol);
  }

private:
  // the backend keeps a pointer to it; empty after the factorization when the backend needs only its factor
  std::unique_ptr<typename SolverTraits::Matrix> m_system;
  SolverTraits m_solver;
  Row_permutation m_permutation; // row -> position in m_system
  bool m_substitutions_available = false;
  std::mutex m_backend_mutex; // serialises the solves of backends without Factor_substitutions
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_SPARSE_FACTOR_H
