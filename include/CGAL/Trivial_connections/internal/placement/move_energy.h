// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H

#include <CGAL/Trivial_connections/internal/factorization/selected_inverse.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The energy change of moving index between vertices, the integers of loops and links kept. The minimised
  energy is E = b^T M^-1 b, and a vertex's b is 2 pi k_v - K_v. Moving d = 2 pi u / n of it from v to w
  changes b by d (e_w - e_v), so
    dE = 2 d (lambda_w - lambda_v) + d^2 (G_vv + G_ww - 2 G_vw),   lambda = M^-1 b, G = M^-1,
  the first term the energy gradient of the current solve. A free integer m_l of a loop or link changed by s
  adds 2 pi s / n on its row, and the same expansion, with the multiplier of that row, prices it. The entries of G between a vertex and its
  neighbours are on the pattern of the factor, so one selected inversion gives them all; a pair of distant
  vertices costs the back-substitution of a column (kept). Without a readable factor every entry comes from
  columns. A vertex without a row (boundary vertices, one pinned vertex per closed component) has G = 0.
*/
class Move_energy
{
public:
  using Column_solve = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

  // `row_of_vertex`: the row of each vertex (or -1); `position`: row -> position in the factored system
  Move_energy(std::vector<int> row_of_vertex, const int* position, Eigen::Index rows,
              std::unique_ptr<Selected_inverse> inverse, Column_solve solve)
    : m_row(std::move(row_of_vertex)), m_position(position), m_rows(rows), m_inverse(std::move(inverse)),
      m_solve(std::move(solve))
  {
  }

  bool selected() const { return bool(m_inverse); }
  std::size_t column_solves() const { return m_column_solves; }

  double diagonal(int v) { return entry(v, v); }

  double entry(int v, int w) { return row_entry(m_row[std::size_t(v)], m_row[std::size_t(w)]); }
  int row_of(int v) const { return m_row[std::size_t(v)]; }

  // (M^-1)_{rv rw} for rows (0 when one is -1); off the pattern, from the column of rv
  double row_entry(int rv, int rw)
  {
    if(rv < 0 || rw < 0)
      return 0;
    if(m_inverse) {
      const double z = m_inverse->entry(m_position[rv], m_position[rw]);
      if(!std::isnan(z))
        return z;
    }
    return column(rv)[rw];
  }

  // G_vv + G_ww - 2 G_vw: the energy of moving a unit of b from v to w (an effective resistance)
  double resistance(int v, int w) { return diagonal(v) + diagonal(w) - 2 * entry(v, w); }

  // a lower bound without a column: |G_vw| <= sqrt(G_vv G_ww) (M^-1 is positive definite)
  double resistance_lower_bound(int v, int w)
  {
    const double a = std::sqrt((std::max)(diagonal(v), 0.)), b = std::sqrt((std::max)(diagonal(w), 0.));
    return (a - b) * (a - b);
  }

private:
  const Eigen::VectorXd& column(int r)
  {
    auto c = m_columns.find(r);
    if(c != m_columns.end())
      return c->second;
    // the columns kept stay under about 256 MB
    if(double(m_columns.size() + 1) * double(m_rows) * sizeof(double) > 256e6)
      m_columns.clear();
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m_rows);
    e[r] = 1;
    ++m_column_solves;
    return m_columns.emplace(r, m_solve(e)).first->second;
  }

  std::vector<int> m_row;
  const int* m_position;
  Eigen::Index m_rows;
  std::unique_ptr<Selected_inverse> m_inverse;
  Column_solve m_solve;
  std::unordered_map<int, Eigen::VectorXd> m_columns;
  std::size_t m_column_solves = 0;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H
