// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_MATRIX_STORAGE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_MATRIX_STORAGE_H

// What a backend reads of the system matrix: the triangle the solver stores, and whether the solver can
// release the matrix after the factorization.

#include <CGAL/Trivial_connections/solver_traits.h>

#include <Eigen/SparseCore>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

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
#endif

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_MATRIX_STORAGE_H
