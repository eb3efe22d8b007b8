// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_KEPT_FACTOR_FIXING_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_KEPT_FACTOR_FIXING_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/quad/seamless_parametrization.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The minimiser of the seamless parametrisation's energy as its unknowns are fixed one at a time, on one kept
  factorization (issue 43: the greedy rounding paid one sparse factorization per integer).

  After a factor() of the parametrisation, the energy is |M y - r|^2 over the reduced unknowns y, with normal
  matrix N (factored) and kept unknowns z = B y + o. Fixing z_j = c is the linear constraint b_j^T y = c - o_j
  (b_j the row j of B). Fixing unknowns one after the other is conditioning: with u_j the column N^-1 b_j made
  N-orthogonal to the earlier ones (u_j = N^-1 b_j - U U^T b_j, U the earlier u scaled by 1 / sqrt(pivot)), the
  minimiser moves by u_j (c - z_j) / (b_j^T u_j). So a fix costs one back-substitution with the kept factor and a
  dense update of size (watched unknowns) x (fixes since the factorization): the bordering of the factor by the
  fixed rows, kept as the columns V = B U (a Cholesky factor of the bordered block, in the watched unknowns' rows).
  Only the watched unknowns' values are kept up to date (the rounding reads nothing else), unless asked for the
  whole solution (tests: then U is kept too, n x fixes).

  The dense block grows by one column per fix. After `max_block` fixes since the last factorization the next
  values() factors again with every fixed unknown eliminated (the parametrisation's own solve), and the block
  starts empty: 0 is the plain scheme (a factorization per batch of fixes, as before this class). A pivot below
  1e-10 of its unconditioned value (an unknown the fixed ones nearly determine) is not trusted to the update:
  the values are refactored from scratch as well, where the parametrisation checks the fixed values against its
  constraints exactly as without the kept factor.
*/
class Kept_factor_fixing
{
public:
  // param: factored (solve() or factor()) with its fixed values of now; watched: z indices, not eliminated
  Kept_factor_fixing(Seamless_parametrization& param, std::vector<int> watched, int max_block,
                     bool keep_solution = false)
    : m_param(param), m_watched(std::move(watched)), m_max_block(max_block), m_keep_solution(keep_solution)
  {
    CGAL_precondition(max_block >= 0);
    for(int z : m_watched)
      CGAL_precondition(!param.is_eliminated(z));
    adopt_factor();
  }

  // Fixes watched unknown i (an index into `watched`) to `value`, in the parametrisation as well.
  void fix(int i, double value)
  {
    const int z = m_watched[std::size_t(i)];
    m_param.fix(z, value);
    ++m_pending;
    if(m_stale || m_block >= m_max_block) {
      m_stale = true;
      return;
    }
    // b: row i of the watched rows of B
    Eigen::VectorXd b = Eigen::VectorXd::Zero(m_rows.cols());
    for(Row_sparse::InnerIterator it(m_rows, i); it; ++it)
      b[it.col()] = it.value();
    const Eigen::VectorXd w = m_param.solve_normal(b);
    ++m_back_substitutions;
    const double unconditioned = b.dot(w);
    Eigen::VectorXd a = m_rows * w; // the watched rows of N^-1 b
    if(m_block > 0)
      a.noalias() -= m_V.leftCols(m_block) * m_V.row(i).head(m_block).transpose();
    const double pivot = a[i];
    if(!(unconditioned > 0) || !(pivot > 1e-10 * unconditioned)) {
      m_stale = true; // (nearly) determined by the fixed ones: the parametrisation's solve decides
      return;
    }
    const double step = (value - m_values[i]) / pivot;
    m_values += a * step;
    m_values[i] = value;
    if(m_V.cols() < m_block + 1)
      m_V.conservativeResize(Eigen::NoChange, std::max<Eigen::Index>(2 * m_V.cols(), 16));
    m_V.col(m_block) = a / std::sqrt(pivot);
    if(m_keep_solution) {
      Eigen::VectorXd u = w;
      if(m_block > 0)
        u.noalias() -= m_U.leftCols(m_block) * m_V.row(i).head(m_block).transpose();
      m_y += u * step;
      if(m_U.cols() < m_block + 1)
        m_U.conservativeResize(Eigen::NoChange, std::max<Eigen::Index>(2 * m_U.cols(), 16));
      m_U.col(m_block) = u / std::sqrt(pivot);
    }
    ++m_block;
  }

  // The watched unknowns' values at the minimiser with every value fixed so far (factors again when due).
  const Eigen::VectorXd& values()
  {
    if(m_stale) {
      m_param.factor();
      ++m_factorizations;
      adopt_factor();
    }
    return m_values;
  }

  // With keep_solution: the map of the minimiser (corner values from the reduced unknowns of the last factor()).
  Seamless_parametrization::Map map()
  {
    CGAL_precondition(m_keep_solution);
    values();
    return m_param.map_of(m_y);
  }

  // fixes not yet in the parametrisation's last factorization
  int fixes_since_factorization() const { return m_pending; }
  int factorizations() const { return m_factorizations; } // made here, not the one adopted at construction
  int back_substitutions() const { return m_back_substitutions; }
  int largest_block() const { return std::max(m_largest_block, m_block); } // the most fixes on one factor

private:
  using Row_sparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

  void adopt_factor()
  {
    const Seamless_parametrization::Sparse& B = m_param.variable_basis();
    const Eigen::VectorXd& y = m_param.reduced_solution();
    const Row_sparse rows_of_B(B);
    std::vector<Eigen::Triplet<double>> t;
    m_values.resize(Eigen::Index(m_watched.size()));
    for(std::size_t i = 0; i < m_watched.size(); ++i) {
      double value = m_param.variable_offset()[m_watched[i]];
      for(Row_sparse::InnerIterator it(rows_of_B, m_watched[i]); it; ++it) {
        t.emplace_back(int(i), int(it.col()), it.value());
        value += it.value() * y[it.col()];
      }
      m_values[Eigen::Index(i)] = value;
    }
    m_rows = Row_sparse(Eigen::Index(m_watched.size()), B.cols());
    m_rows.setFromTriplets(t.begin(), t.end());
    if(m_V.rows() != m_values.size())
      m_V.resize(m_values.size(), 0);
    m_largest_block = std::max(m_largest_block, m_block);
    m_block = 0;
    m_pending = 0;
    m_stale = false;
    if(m_keep_solution) {
      m_y = y;
      if(m_U.rows() != y.size()) // the reduced unknowns change with the factorization
        m_U.resize(y.size(), 0);
    }
  }

  Seamless_parametrization& m_param;
  std::vector<int> m_watched;
  int m_max_block;
  bool m_keep_solution;
  Row_sparse m_rows;        // the watched rows of B
  Eigen::VectorXd m_values; // of the watched unknowns
  Eigen::MatrixXd m_V;      // watched rows of the scaled conditioned columns, m_block of them in use
  Eigen::MatrixXd m_U;      // with keep_solution: the columns themselves
  Eigen::VectorXd m_y;      // with keep_solution: the reduced solution
  int m_block = 0, m_pending = 0;
  bool m_stale = false;
  int m_factorizations = 0, m_back_substitutions = 0, m_largest_block = 0;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_KEPT_FACTOR_FIXING_H
