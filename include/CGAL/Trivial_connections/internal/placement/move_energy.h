// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H

#include <CGAL/Trivial_connections/internal/concurrency.h>
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
  // `factor`: the factor M = L D L^T in those positions when it could be read (n = 0 otherwise), for columns made
  // several at a time
  Move_energy(std::vector<int> row_of_vertex, const int* position, Eigen::Index rows,
              std::unique_ptr<Selected_inverse> inverse, Unit_lower_factor&& factor, Column_solve solve)
    : m_row(std::move(row_of_vertex)), m_position(position), m_rows(rows), m_inverse(std::move(inverse)),
      m_factor(std::move(factor)), m_solve(std::move(solve))
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

  // makes the columns of these vertices that are not kept yet, half on a second thread (the solves only read the
  // factor)
  void prefetch(const std::vector<int>& vertices)
  {
    std::vector<int> missing;
    for(int v : vertices) {
      const int r = m_row[std::size_t(v)];
      if(r >= 0 && !m_columns.count(r) && std::find(missing.begin(), missing.end(), r) == missing.end())
        missing.push_back(r);
    }
    if(missing.empty())
      return;
    if(double(m_columns.size() + missing.size()) * double(m_rows) * sizeof(double) > 256e6)
      m_columns.clear();
    auto solve_range = [&](std::size_t begin, std::size_t end) {
      std::vector<Eigen::VectorXd> out;
      if(m_factor.n == int(m_rows)) {
        std::vector<double> z; // one workspace per thread: fresh pages cost more than the substitutions here
        for(std::size_t i = begin; i < end; i += block)
          columns_of_factor(missing, i, (std::min)(end, i + block), z, out);
        return out;
      }
      for(std::size_t i = begin; i < end; ++i) {
        Eigen::VectorXd e = Eigen::VectorXd::Zero(m_rows);
        e[missing[i]] = 1;
        out.push_back(m_solve(e));
      }
      return out;
    };
    const std::size_t half = missing.size() / 2;
    auto second = concurrently([&] { return solve_range(half, missing.size()); });
    std::vector<Eigen::VectorXd> first = solve_range(0, half), rest = second.get();
    for(std::size_t i = 0; i < half; ++i)
      m_columns.emplace(missing[i], std::move(first[i]));
    for(std::size_t i = half; i < missing.size(); ++i)
      m_columns.emplace(missing[i], std::move(rest[i - half]));
    m_column_solves += missing.size();
  }

  // G e_v over the rows (kept; valid until the next column is made), or null for a vertex without a row
  const Eigen::VectorXd* column_of(int v)
  {
    const int r = m_row[std::size_t(v)];
    return r < 0 ? nullptr : &column(r);
  }

private:
  static constexpr std::size_t block = 8;

  // The columns of rows[begin, end) (at most `block`), appended to `out`: the substitutions through the factor
  // for all of them at once, which reads the factor once instead of once per column.
  void columns_of_factor(const std::vector<int>& rows, std::size_t begin, std::size_t end, std::vector<double>& z,
                         std::vector<Eigen::VectorXd>& out) const
  {
    const std::size_t b = end - begin, n = std::size_t(m_factor.n);
    const int* start = m_factor.start.data();
    const int* row = m_factor.row.data();
    const double* l = m_factor.value.data();
    z.assign(n * b, 0.); // position-major: z[p * b + c]
    int first = int(n);
    for(std::size_t c = 0; c < b; ++c) {
      const int p = m_position[rows[begin + c]];
      z[std::size_t(p) * b + c] = 1;
      first = (std::min)(first, p);
    }
    for(int j = first; j < int(n); ++j) { // L^-1, from the first unit on
      const double* zj = &z[std::size_t(j) * b];
      for(int p = start[j]; p < start[j + 1]; ++p) {
        double* zi = &z[std::size_t(row[p]) * b];
        for(std::size_t c = 0; c < b; ++c)
          zi[c] -= l[p] * zj[c];
      }
    }
    for(std::size_t j = 0; j < n; ++j) // D^-1
      for(std::size_t c = 0; c < b; ++c)
        z[j * b + c] /= m_factor.d[j];
    for(int j = int(n) - 1; j >= 0; --j) { // L^-T
      double* zj = &z[std::size_t(j) * b];
      for(int p = start[j]; p < start[j + 1]; ++p) {
        const double* zi = &z[std::size_t(row[p]) * b];
        for(std::size_t c = 0; c < b; ++c)
          zj[c] -= l[p] * zi[c];
      }
    }
    for(std::size_t c = 0; c < b; ++c) {
      Eigen::VectorXd column(m_rows);
      for(Eigen::Index r = 0; r < m_rows; ++r)
        column[r] = z[std::size_t(m_position[r]) * b + c];
      out.push_back(std::move(column));
    }
  }

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
  Unit_lower_factor m_factor;
  Column_solve m_solve;
  std::unordered_map<int, Eigen::VectorXd> m_columns;
  std::size_t m_column_solves = 0;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H
