// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H

#include <CGAL/Trivial_connections/internal/concurrency.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_storage.h>
#include <CGAL/Trivial_connections/internal/factorization/selected_inverse.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
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
  adds 2 pi s / n on its row, and the same expansion, with the multiplier of that row, prices it.
  The entries of G between a vertex and its neighbours are on the pattern of the factor, so one selected inversion
  gives them all, at about the factorization's cost; with few singularities their paths in the
  elimination tree (see Path) give those wanted for far less. A pair of distant vertices costs the
  back-substitution of a column (kept), or with paths the product of their two paths (path_entry()). Without a
  readable factor every entry comes from columns. A vertex without a row (boundary vertices, one pinned vertex per
  closed component) has G = 0.
*/
class Move_energy
{
public:
  using Column_solve = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
  // the factor as read again from the backend, zeros included (n = 0: it cannot be)
  using Factor_reading = std::function<Unit_lower_factor()>;
  // where the entries near the singularities come from, with a readable factor (tests choose)
  enum class Entries { automatic, selected_inversion, paths };
  static constexpr double default_column_budget_bytes = 256e6; // see Column_store

  // `row_of_vertex`: the row of each vertex (or -1); `position`: row -> position in the factored system;
  // `factor`: the factor M = L D L^T in those positions when it could be read (n = 0 otherwise); `first`: the
  // vertices whose entries are wanted first (the singular ones and their neighbours), to choose between a
  // selected inversion and paths; `read_again`: reads the factor again, for a switch from paths to the inversion
  // when the factor had explicit zeros (dropped for the paths, needed by the inversion)
  Move_energy(std::vector<int> row_of_vertex, const int* position, Eigen::Index rows, Unit_lower_factor&& factor,
              const std::vector<int>& first, Column_solve solve, Entries choice = Entries::automatic,
              double column_budget_bytes = default_column_budget_bytes, Factor_reading read_again = Factor_reading())
    : m_row(std::move(row_of_vertex)), m_position(position), m_rows(rows), m_factor_storage(std::move(factor)),
      m_solve(std::move(solve)), m_read_again(std::move(read_again)), m_store(rows, column_budget_bytes)
  {
    if(m_factor_storage.n != int(m_rows) || m_factor_storage.n == 0)
      return;
    // The work of each: a selected inversion's from its supernodes (see selected_inversion_work()); a path that of
    // the columns along it, for each vertex wanted, and more as singularities move.
    const int n = m_factor_storage.n;
    const double inversion = selected_inversion_work(m_factor_storage.start, m_factor_storage.row);
    // The elimination tree of the factor as read: its rows of a column are ancestors of it, which the paths and
    // the columns rely on. A supernodal factor brings the zeros of its dense blocks along, and pins' fixed edges
    // put zeros in any factor: the inversion needs them (its pattern must stay chordal), the substitutions of
    // paths and columns do not (CHOLMOD, refined_elephant: 3.7 x faster), but the tree is read before they go
    // (without them, a column's first row may no longer be its parent: fandisk's pins left neither paths nor
    // columns but one back-substitution per entry).
    const bool tree = elimination_tree_pattern(m_factor_storage);
    m_parent = elimination_tree_parents(m_factor_storage.start, m_factor_storage.row);
    // the factor with its zeros, for the inversion (empty when it has none)
    Unit_lower_factor padded = without_zeros(m_factor_storage);
    std::vector<double> path(std::size_t(n), 0.);
    for(int j = n - 1; j >= 0; --j) {
      const int b = m_factor_storage.start[std::size_t(j)], e = m_factor_storage.start[std::size_t(j) + 1];
      path[std::size_t(j)] = double(e - b + 1) + (parent(j) >= 0 ? path[std::size_t(parent(j))] : 0.);
    }
    double paths = 0;
    for(int v : first)
      if(m_row[std::size_t(v)] >= 0)
        paths += path[std::size_t(m_position[m_row[std::size_t(v)]])];
    // measured break-even: paths / inversion about 2 (armadillo, N = 4); turbine_loop1 N = 1 at 0.13 is 3 x faster
    // with paths, femur N = 4 at 15 is 1.5 x slower
    const bool use_paths =
      tree && (choice == Entries::paths || (choice == Entries::automatic && 2 * paths < 3 * inversion));
    m_paths_usable = use_paths && std::all_of(m_factor_storage.d.begin(), m_factor_storage.d.end(), [](double d) { return d > 0; });
    // The paths made grow with the moves (the new neighbours of every singularity moved): chosen by the vertices
    // wanted first, they may cost more than the inversion in the end (cheese_loop3, N = 2: 616 singularities, 5,460
    // moves, half of the refinement in paths). Once the paths made have cost about what the inversion would, it
    // takes over (rent or buy: then about twice the better of the two at most, whatever the moves still to come), where
    // the factor as read is the one to invert, or, when it had explicit zeros to keep its pattern chordal (CHOLMOD's
    // supernodes), the factor read again (cheese_loop3, N = 2: paths to the end were 1.6 x the placement).
    m_zeros_dropped = padded.n > 0;
    if(m_paths_usable && choice == Entries::automatic && (!m_zeros_dropped || m_read_again)) {
      m_path_cost = std::move(path);
      m_inversion_cost = inversion;
    }
    m_covered.assign(std::size_t(n), tree ? 0 : 1);
    m_entry.assign(std::size_t(n), -1);
    if(m_covered.front())
      for(int j = n - 1; j >= 0; --j) {
        m_covered_positions.push_back(j);
        m_entry[std::size_t(j)] = m_entries++;
        m_covered_work += entries_of_column(j);
      }
    if(m_paths_usable)
      m_paths.resize(std::size_t(m_rows));
    else
      // the factor as read goes to the inversion, which keeps it for the columns (no copy); with its zeros, the
      // inversion gets that one, and the columns keep the factor without them
      m_inverse.reset(padded.n > 0 ? new Selected_inverse(std::move(padded))
                                   : new Selected_inverse(std::move(m_factor_storage), true));
  }

  bool selected() const { return bool(m_inverse); }
  // the factor read, without its explicit zeros (n = 0: none)
  const Unit_lower_factor& factor() const
  {
    return m_inverse && m_inverse->factor_kept() ? m_inverse->factor() : m_factor_storage;
  }
  std::size_t column_solves() const { return m_column_solves; }

  double diagonal(int v) { return entry(v, v); }

  double entry(int v, int w) { return row_entry(m_row[std::size_t(v)], m_row[std::size_t(w)]); }
  bool paths() const { return m_paths_usable; }
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
    if(m_paths_usable) {
      const Path& a = path_of(rv);
      const Path& b = path_of(rw);
      if(m_paths_usable)
        return path_product(a, b);
    }
    watch_rows({rv, rw});
    return column(rv)[entry_of_row(rw)];
  }

  // G_vv + G_ww - 2 G_vw: the energy of moving a unit of b from v to w (an effective resistance)
  double resistance(int v, int w) { return diagonal(v) + diagonal(w) - 2 * entry(v, w); }

  /*
    Entries of G between distant vertices from their paths, when both are made (prefetch_paths()), instead of the
    column of one of them: a sum over the part of the two paths common to both, the top of the elimination tree,
    where a column costs the factor's columns over all the covered positions. Only reads: safe on two threads.
  */
  bool path_made(int r) const { return r < 0 || (m_paths_usable && m_paths[std::size_t(r)].made); }
  double path_entry(int rv, int rw) const
  {
    CGAL_precondition(path_made(rv) && path_made(rw));
    return rv < 0 || rw < 0 ? 0. : path_product(m_paths[std::size_t(rv)], m_paths[std::size_t(rw)]);
  }
  // the length of a made path (0 for no row): a bound on the work of a product with it
  std::size_t path_length(int r) const { return r < 0 ? 0 : m_paths[std::size_t(r)].position.size(); }
  // the work of one more column now: its substitutions over the covered positions (twice the factor's entries
  // there), the path of its unit aside
  double column_work() const { return 2 * m_covered_work; }

  // makes the columns of these vertices that are not kept yet, half on a second thread (the solves only read the
  // factor); `make_room`: the columns kept and not asked for may be dropped first when they would exceed the budget
  // (false while columns read before are still in use)
  void prefetch(const std::vector<int>& vertices, bool make_room = true)
  {
    std::vector<int> missing;
    for(int v : vertices) {
      const int r = m_row[std::size_t(v)];
      if(r >= 0 && !m_columns.count(r) && std::find(missing.begin(), missing.end(), r) == missing.end())
        missing.push_back(r);
    }
    if(missing.empty())
      return;
    watch_rows(missing);
    if(make_room && m_store.would_exceed(missing.size())) {
      // drop the columns not asked for: those asked for are read next whatever the budget, and dropping them too
      // made each of them again alone (cheese_loop3, N = 4: the 81 columns of one side, 569k rows each, made
      // again every round, 3,065 back-substitutions in all)
      std::vector<char> asked(std::size_t(m_rows), 0);
      for(int v : vertices)
        if(m_row[std::size_t(v)] >= 0)
          asked[std::size_t(m_row[std::size_t(v)])] = 1;
      for(auto c = m_columns.begin(); c != m_columns.end();) {
        if(asked[std::size_t(c->first)]) {
          ++c;
        } else {
          m_store.release(c->second);
          c = m_columns.erase(c);
        }
      }
    }
    std::vector<double*> slots;
    for(int r : missing) {
      slots.push_back(m_store.slot());
      m_columns.emplace(r, slots.back());
    }
    auto solve_range = [&](std::size_t begin, std::size_t end) {
      if(factor().n == int(m_rows)) {
        // one workspace per half (the second ends the range), kept: megabytes, fresh pages each round otherwise
        Block_work& work = m_block_work[end == missing.size() ? 1 : 0];
        for(std::size_t i = begin; i < end; i += block)
          columns_of_factor(missing, slots, i, (std::min)(end, i + block), work.z, work.on_path);
        return;
      }
      for(std::size_t i = begin; i < end; ++i) {
        Eigen::VectorXd e = Eigen::VectorXd::Zero(m_rows);
        e[missing[i]] = 1;
        Eigen::Map<Eigen::VectorXd>(slots[i], m_rows) = m_solve(e);
      }
    };
    m_second_thread.on_two_halves(missing.size(), solve_range); // the halves write apart
    m_column_solves += missing.size();
  }

  // makes the paths of these vertices not made yet, half on a second thread
  void prefetch_paths(const std::vector<int>& vertices)
  {
    if(!m_paths_usable)
      return;
    std::vector<int> missing;
    double work = 0;
    for(int v : vertices) {
      const int r = m_row[std::size_t(v)];
      if(r >= 0 && !m_paths[std::size_t(r)].made) {
        missing.push_back(r);
        m_paths[std::size_t(r)].made = true; // listed once
        work += m_path_cost.empty() ? 0. : m_path_cost[std::size_t(m_position[r])];
      }
    }
    // Equal cost is at twice the inversion's predicted work: a unit of it took 1.5-3.4 times a unit of path
    // (timed on armadillo, turbine_loop1, holes, bunny00, refined_elephant, ldlt). At 1.5 times, as in the first
    // choice, the inversion came too early: turbine_loop1 refined 1.3-1.4 x slower, holes' aligned boundary 1.15 x.
    if(!m_path_cost.empty() && m_path_work + work >= 2 * m_inversion_cost) {
      if(!m_zeros_dropped) // the factor goes to the inversion, kept there for the columns
        m_inverse.reset(new Selected_inverse(std::move(m_factor_storage), true));
      else {
        Unit_lower_factor again = m_read_again();
        if(again.n == m_factor_storage.n)
          m_inverse.reset(new Selected_inverse(std::move(again)));
      }
      if(m_inverse) {
        m_paths_usable = false;
        std::vector<Path>().swap(m_paths);
        std::vector<double>().swap(m_path_cost);
        return;
      }
      std::vector<double>().swap(m_path_cost); // the factor could not be read again: the paths stay
    }
    m_path_work += work;
    auto make = [&](std::size_t begin, std::size_t end) {
      std::vector<double> work(std::size_t(factor().n), 0.);
      std::vector<int> stamp(std::size_t(factor().n), -1);
      bool tree = true;
      for(std::size_t i = begin; i < end && tree; ++i)
        tree = make_path(missing[i], work, stamp);
      return tree;
    };
    const std::pair<bool, bool> made = m_second_thread.on_two_halves(missing.size(), make);
    m_paths_usable = made.first && made.second;
  }

  /*
    The columns are kept on the positions of the factor that the entries read need only: the paths to the root
    of the vertices watched (the singular ones and their neighbours, as they move). An entry of G e_v at position
    j needs those above j in the elimination tree only (the backward substitution reads the rows of column j of L,
    its ancestors), so the kept columns grow onto newly watched paths exactly, each at the cost of those columns
    of L. refined_elephant, N = 4: the singular vertices and their neighbours reach a fifth of the tree.
    A kept column holds its entries in the order the positions were covered, so that it touches as much memory as
    there are covered positions (cheese_loop3, N = 4: 184k of 569k rows; its columns, kept at once by the hundred,
    were a peak of 5.5 GB and a fifth of the refinement in fresh pages): entry_of_row() tells where a row's is.
  */
  void watch(const std::vector<int>& vertices)
  {
    std::vector<int> rows;
    for(int v : vertices)
      if(m_row[std::size_t(v)] >= 0)
        rows.push_back(m_row[std::size_t(v)]);
    watch_rows(rows);
  }
  bool watched(int r) const { return m_covered.empty() || m_covered[std::size_t(m_position[r])]; }
  // where the entry of row r is in a column (r itself when columns are whole; -1: not watched)
  int entry_of_row(int r) const { return m_covered.empty() ? r : m_entry[std::size_t(m_position[r])]; }

  /*
    Whole columns of M^-1 at system rows `rows`, into out (system rows x rows.size(), row r of M^-1 e_rows[c] in
    out(r, c)): the substitutions through the factor for `block` columns at once and the blocks on two threads,
    rather than a back-substitution per column, which reads the factor once per column (the free integers' columns
    of Move_integers under guidance: 63 of them, bunny00_loop1 0.8 s). False without a readable factor.
  */
  template <class RowMajorMatrix>
  bool full_columns(const std::vector<int>& rows, RowMajorMatrix& out)
  {
    const Unit_lower_factor& f = factor();
    if(f.n == 0 || f.n != int(m_rows) || m_position == nullptr)
      return false;
    const std::size_t n = std::size_t(f.n);
    out.resize(Eigen::Index(n), Eigen::Index(rows.size()));
    const std::size_t blocks = (rows.size() + block - 1) / block;
    auto solve_blocks = [&](std::size_t first_block, std::size_t last_block) {
      const int* start = f.start.data();
      const int* row = f.row.data();
      const double* l = f.value.data();
      const double* d = f.d.data();
      std::vector<double> z;
      for(std::size_t k = first_block; k < last_block; ++k) {
        const std::size_t begin = k * block, b = (std::min)(block, rows.size() - begin);
        z.assign(n * b, 0.); // position-major: z[p * b + c]
        std::size_t first = n;
        for(std::size_t c = 0; c < b; ++c) {
          const std::size_t p = std::size_t(m_position[rows[begin + c]]);
          z[p * b + c] = 1;
          first = (std::min)(first, p);
        }
        // L^-1 from the first unit on, skipping the positions still zero (off the units' paths to the roots)
        for(std::size_t j = first; j < n; ++j) {
          double zj[block];
          bool zero = true;
          for(std::size_t c = 0; c < b; ++c) {
            zj[c] = z[j * b + c];
            zero = zero && zj[c] == 0;
          }
          if(zero)
            continue;
          for(int p = start[j]; p < start[j + 1]; ++p) {
            double* zi = &z[std::size_t(row[p]) * b];
            for(std::size_t c = 0; c < b; ++c)
              zi[c] -= l[p] * zj[c];
          }
        }
        // D^-1 and L^-T, every position, descending
        for(std::size_t j = n; j-- > 0;) {
          double sum[block];
          for(std::size_t c = 0; c < b; ++c)
            sum[c] = z[j * b + c] / d[j];
          for(int p = start[j]; p < start[j + 1]; ++p) {
            const double* zi = &z[std::size_t(row[p]) * b];
            for(std::size_t c = 0; c < b; ++c)
              sum[c] -= l[p] * zi[c];
          }
          std::copy(sum, sum + b, &z[j * b]);
        }
        for(std::size_t r = 0; r < n; ++r) {
          const double* zr = &z[std::size_t(m_position[r]) * b];
          for(std::size_t c = 0; c < b; ++c)
            out(Eigen::Index(r), Eigen::Index(begin + c)) = zr[c];
        }
      }
    };
    m_second_thread.on_two_halves(blocks, solve_blocks); // the blocks write apart
    return true;
  }

  // whether column_of(v) is made already (or null)
  bool has_column(int v) const
  {
    const int r = m_row[std::size_t(v)];
    return r < 0 || m_columns.count(r) != 0;
  }

  // G e_v on the rows watched, at entry_of_row() (kept until a prefetch() makes room), or null for a vertex
  // without a row
  const double* column_of(int v)
  {
    const int r = m_row[std::size_t(v)];
    return r < 0 ? nullptr : column(r);
  }

private:
  static constexpr std::size_t block = 8;

  // the factor's entries in column j, its diagonal included (the work of that column in a substitution)
  double entries_of_column(int j) const
  {
    return double(factor().start[std::size_t(j) + 1] - factor().start[std::size_t(j)] + 1);
  }

  // the parent of position j in the elimination tree: the first row below the diagonal of its column in the factor
  // as read, zeros included (-1: a root)
  int parent(int j) const { return m_parent[std::size_t(j)]; }

  // `f` without its explicit zeros; returns f as it was, or an empty factor (n = 0) when f had no zeros (no copy:
  // fresh memory costs its page faults, femur's supernodal factor a sixth of the refinement's set-up)
  static Unit_lower_factor without_zeros(Unit_lower_factor& f)
  {
    const std::size_t nonzeros =
      std::size_t(std::count_if(f.value.begin(), f.value.end(), [](double x) { return x != 0; }));
    if(nonzeros == f.value.size())
      return Unit_lower_factor();
    Unit_lower_factor compact;
    compact.n = f.n;
    compact.d = f.d;
    compact.start.resize(std::size_t(f.n) + 1);
    compact.row.resize(nonzeros);
    compact.value.resize(nonzeros);
    std::size_t q = 0;
    for(int j = 0; j < f.n; ++j) {
      compact.start[std::size_t(j)] = int(q);
      for(int p = f.start[std::size_t(j)]; p < f.start[std::size_t(j) + 1]; ++p)
        if(f.value[std::size_t(p)] != 0) {
          compact.row[q] = f.row[std::size_t(p)];
          compact.value[q++] = f.value[std::size_t(p)];
        }
    }
    compact.start[std::size_t(f.n)] = int(q);
    std::swap(f, compact);
    return compact;
  }

  /*
    With M = L D L^T, G_vw = y_v^T y_w where y_v = D^-1/2 L^-1 e_v. L^-1 e_v is nonzero only on the path from v
    to its root in the elimination tree (a column of L has its rows among the ancestors of its own), so y_v costs
    the columns of L along that path, and y_v^T y_w is a sum over the part common to both paths: from where they
    meet to the root. Far cheaper than a selected inversion of the whole factor when few vertices are wanted.
  */
  struct Path
  {
    bool made = false;
    std::vector<int> position; // from the vertex's position up to its root
    std::vector<double> value; // y there
  };

  const Path& path_of(int r)
  {
    Path& p = m_paths[std::size_t(r)];
    if(!p.made) {
      p.made = true;
      if(m_work.empty()) {
        m_work.assign(std::size_t(factor().n), 0.);
        m_stamp.assign(std::size_t(factor().n), -1);
      }
      m_paths_usable = make_path(r, m_work, m_stamp);
    }
    return p;
  }

  static double path_product(const Path& a, const Path& b)
  {
    double sum = 0;
    for(std::size_t i = a.position.size(), j = b.position.size();
        i > 0 && j > 0 && a.position[i - 1] == b.position[j - 1]; --i, --j)
      sum += a.value[i - 1] * b.value[j - 1];
    return sum;
  }

  // the path of row r; `work` is zero and `stamp` has no entry r on entry, and `work` is zero again on exit; false
  // when a row of L is off the path (not an elimination tree's pattern: paths are not used then)
  bool make_path(int r, std::vector<double>& work, std::vector<int>& stamp) const
  {
    Path& path = const_cast<Path&>(m_paths[std::size_t(r)]); // each row's path is made by one thread
    path.position.clear();
    const Unit_lower_factor& f = factor();
    const int* start = f.start.data();
    const int* row = f.row.data();
    for(int j = m_position[r]; j >= 0; j = parent(j)) {
      path.position.push_back(j);
      stamp[std::size_t(j)] = r;
    }
    work[std::size_t(m_position[r])] = 1;
    bool tree = true;
    path.value.resize(path.position.size());
    for(std::size_t i = 0; i < path.position.size(); ++i) {
      const int j = path.position[i];
      const double yj = work[std::size_t(j)];
      work[std::size_t(j)] = 0;
      path.value[i] = yj / std::sqrt(f.d[std::size_t(j)]);
      for(int p = start[j]; p < start[j + 1]; ++p) {
        tree = tree && stamp[std::size_t(row[p])] == r;
        work[std::size_t(row[p])] -= f.value[std::size_t(p)] * yj;
      }
    }
    if(!tree)
      std::fill(work.begin(), work.end(), 0.);
    return tree;
  }

  // whether every row of a column of f is an ancestor of it in the tree of first rows: its rows below the first
  // are among those of its parent's column, from the root down (a factor's symbolic pattern always is; checked)
  static bool elimination_tree_pattern(const Unit_lower_factor& f)
  {
    const int* start = f.start.data();
    const int* row = f.row.data();
    for(int j = 0; j < f.n; ++j) {
      const int b = start[j], e = start[j + 1];
      if(b == e)
        continue;
      const int p = row[b];
      int q = start[p];
      for(int a = b + 1; a < e; ++a) {
        while(q < start[p + 1] && row[q] < row[a])
          ++q;
        if(q == start[p + 1] || row[q] != row[a])
          return false;
      }
    }
    return true;
  }

  // covers the paths of these rows, extending the kept columns onto the new positions
  void watch_rows(const std::vector<int>& rows)
  {
    if(m_covered.empty())
      return;
    std::vector<int> fresh;
    for(int r : rows)
      if(r >= 0)
        for(int j = m_position[r]; j >= 0 && !m_covered[std::size_t(j)]; j = parent(j)) {
          m_covered[std::size_t(j)] = 1;
          m_entry[std::size_t(j)] = m_entries++;
          m_covered_work += entries_of_column(j);
          fresh.push_back(j);
        }
    if(fresh.empty())
      return;
    std::sort(fresh.begin(), fresh.end(), std::greater<int>());
    std::vector<int> merged(m_covered_positions.size() + fresh.size());
    std::merge(m_covered_positions.begin(), m_covered_positions.end(), fresh.begin(), fresh.end(), merged.begin(),
               std::greater<int>());
    m_covered_positions.swap(merged);
    // G e_v is D^-1 L^-1 e_v then L^-T: off the path of v (covered since its column was made), only L^-T
    std::vector<double*> kept;
    for(auto& c : m_columns)
      kept.push_back(c.second);
    auto extend = [&](std::size_t begin, std::size_t end) {
      const int* start = factor().start.data();
      const int* row = factor().row.data();
      const double* l = factor().value.data();
      for(std::size_t i = begin; i < end; ++i) {
        double* column = kept[i];
        for(int j : fresh) {
          double sum = 0;
          for(int p = start[j]; p < start[j + 1]; ++p)
            sum += l[p] * column[m_entry[std::size_t(row[p])]];
          column[m_entry[std::size_t(j)]] = -sum;
        }
      }
    };
    m_second_thread.on_two_halves(kept.size(), extend);
  }

  // The columns of rows[begin, end) (at most `block`), into out[begin, end): the substitutions through the factor
  // for all of them at once, which reads the factor once instead of once per column.
  void columns_of_factor(const std::vector<int>& rows, const std::vector<double*>& out, std::size_t begin,
                         std::size_t end, std::vector<double>& z, std::vector<char>& on_path) const
  {
    const Unit_lower_factor& f = factor();
    const std::size_t b = end - begin, n = std::size_t(f.n);
    const int* start = f.start.data();
    const int* row = f.row.data();
    const double* l = f.value.data();
    const double* d = f.d.data();
    z.assign(n * b, 0.); // position-major: z[p * b + c]
    // L^-1: nonzero only on the paths of the units to their roots in the elimination tree (their union, in
    // increasing order); the dense pass from the first unit on when the pattern is not a tree's
    std::vector<int> nodes;
    if(on_path.size() != n)
      on_path.assign(n, 0);
    int first = int(n);
    for(std::size_t c = 0; c < b; ++c) {
      const int p = m_position[rows[begin + c]];
      z[std::size_t(p) * b + c] = 1;
      first = (std::min)(first, p);
      for(int j = p; j >= 0 && !on_path[std::size_t(j)]; j = parent(j)) {
        on_path[std::size_t(j)] = 1;
        nodes.push_back(j);
      }
    }
    std::sort(nodes.begin(), nodes.end());
    // The b values of a position are copied to (or summed in) a local array: written through a pointer into z,
    // they could alias the rows read, and would be stored and loaded again at each entry of the factor. A full
    // block has its width known at compile time (cheese_loop1, N = 4: the refinement 0.89 -> 0.70-0.75 s).
    auto with_width = [b](const auto& kernel) {
      if(b == block)
        kernel(std::integral_constant<std::size_t, block>());
      else
        kernel(b);
    };
    auto eliminate = [&](int j) {
      with_width([&](auto width) {
        double zj[block];
        std::copy(&z[std::size_t(j) * b], &z[std::size_t(j) * b] + std::size_t(width), zj);
        for(int p = start[j]; p < start[j + 1]; ++p) {
          double* zi = &z[std::size_t(row[p]) * b];
          const double lp = l[p];
          for(std::size_t c = 0; c < std::size_t(width); ++c)
            zi[c] -= lp * zj[c];
        }
      });
    };
    bool tree = true;
    for(std::size_t q = 0; q < nodes.size() && tree; ++q) {
      const int j = nodes[q];
      for(int p = start[j]; p < start[j + 1]; ++p)
        tree = tree && on_path[std::size_t(row[p])];
      if(tree)
        eliminate(j);
    }
    for(int j : nodes)
      on_path[std::size_t(j)] = 0;
    if(!tree) {
      std::fill(z.begin(), z.end(), 0.);
      for(std::size_t c = 0; c < b; ++c)
        z[std::size_t(m_position[rows[begin + c]]) * b + c] = 1;
      for(int j = first; j < int(n); ++j)
        eliminate(j);
    }
    // D^-1 and L^-T on the covered positions (descending), which hold the paths of these rows
    with_width([&](auto width) {
      const std::size_t w = std::size_t(width);
      for(int j : m_covered_positions) {
        double* zj = &z[std::size_t(j) * b];
        double sum[block];
        for(std::size_t c = 0; c < w; ++c)
          sum[c] = zj[c] / d[j];
        for(int p = start[j]; p < start[j + 1]; ++p) {
          const double* zi = &z[std::size_t(row[p]) * b];
          const double lp = l[p];
          for(std::size_t c = 0; c < w; ++c)
            sum[c] -= lp * zi[c];
        }
        std::copy(sum, sum + w, zj);
      }
    });
    // out on the covered positions, all columns at once: the b values of a position share a cache line (by
    // columns, each entry was a miss per column)
    with_width([&](auto width) {
      const std::size_t w = std::size_t(width);
      double* column[block];
      for(std::size_t c = 0; c < w; ++c)
        column[c] = out[begin + c];
      for(int j : m_covered_positions) {
        const double* zj = &z[std::size_t(j) * b];
        const int e = m_entry[std::size_t(j)];
        for(std::size_t c = 0; c < w; ++c)
          column[c][e] = zj[c];
      }
    });
  }

  // (made here, the store may grow past its budget: columns in use stay valid until the next prefetch())
  const double* column(int r)
  {
    auto c = m_columns.find(r);
    if(c != m_columns.end())
      return c->second;
    ++m_column_solves;
    watch_rows({r});
    double* slot = m_store.slot();
    if(factor().n == int(m_rows)) {
      columns_of_factor({r}, {slot}, 0, 1, m_column_work, m_on_path);
    } else {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(m_rows);
      e[r] = 1;
      Eigen::Map<Eigen::VectorXd>(slot, m_rows) = m_solve(e);
    }
    return m_columns.emplace(r, slot).first->second;
  }

  /*
    The columns kept, in chunks of at least 2 MB that the kernel may back with huge pages where it offers them
    (advise_huge_page_blocks()): thousands of fresh 4 KB pages, each a fault, cost more than the substitutions
    that fill them (femur, N = 4: 326 columns of 3,897 rows). About the budget (256 MB by default) is kept, more
    when the columns asked for at once need it.
  */
  class Column_store
  {
  public:
    Column_store(Eigen::Index rows, double budget_bytes) : m_length(std::size_t(rows)), m_budget(budget_bytes)
    {
      const std::size_t bytes = (std::max)(m_length * sizeof(double), std::size_t(1));
      m_per_chunk = (std::max)(std::size_t(1), huge / bytes);
      m_chunk_bytes = (m_per_chunk * bytes + huge - 1) / huge * huge;
    }

    bool would_exceed(std::size_t more) const
    {
      return double(m_used - m_free.size() + more) * double(m_length) * sizeof(double) > m_budget;
    }

    double* slot()
    {
      if(!m_free.empty()) {
        double* reused = m_free.back();
        m_free.pop_back();
        return reused;
      }
      if(m_used == m_chunks.size() * m_per_chunk) {
        void* memory = ::operator new(m_chunk_bytes, std::align_val_t(huge));
        std::unique_ptr<double, Free> chunk(static_cast<double*>(memory));
        advise_huge_page_blocks(chunk.get(), m_chunk_bytes); // 4 KB pages when refused
        m_chunks.push_back(std::move(chunk));
      }
      const std::size_t i = m_used++;
      return m_chunks[i / m_per_chunk].get() + (i % m_per_chunk) * m_length;
    }

    // the chunks stay, to be written again: freed and allocated anew, their pages were zeroed by the kernel each
    // time (cheese_loop1, N = 4: 7 % of the refinement)
    void clear()
    {
      m_used = 0;
      m_free.clear();
    }
    // a slot to be written again by a later slot()
    void release(double* slot) { m_free.push_back(slot); }

  private:
    static constexpr std::size_t huge = std::size_t(2) << 20;
    struct Free
    {
      void operator()(double* p) const { ::operator delete(static_cast<void*>(p), std::align_val_t(huge)); }
    };
    std::size_t m_length, m_per_chunk = 1, m_chunk_bytes = huge, m_used = 0;
    double m_budget;
    std::vector<std::unique_ptr<double, Free>> m_chunks;
    std::vector<double*> m_free; // released slots among the m_used
  };

  std::vector<int> m_row;
  const int* m_position;
  Eigen::Index m_rows;
  std::unique_ptr<Selected_inverse> m_inverse;
  Unit_lower_factor m_factor_storage; // the factor read (without its zeros), unless the inversion keeps it
  Column_solve m_solve;
  Factor_reading m_read_again;
  bool m_zeros_dropped = false; // the factor read had explicit zeros, dropped
  std::unordered_map<int, double*> m_columns; // into m_store, on the covered positions
  std::vector<char> m_covered;           // per position: watched (empty: no factor, columns whole)
  std::vector<int> m_covered_positions;  // those, descending
  std::vector<int> m_entry;              // per position: where a kept column has its entry (-1: not covered)
  int m_entries = 0;                     // the entries of a kept column
  double m_covered_work = 0;             // the factor's entries in the covered columns, diagonals included
  std::vector<int> m_parent;             // position -> its parent in the elimination tree (-1: a root)
  Column_store m_store;
  std::size_t m_column_solves = 0;
  bool m_paths_usable = false;
  std::vector<Path> m_paths; // by row
  std::vector<double> m_path_cost; // by position: the work of its path (empty: no switch to the inversion)
  double m_inversion_cost = 0, m_path_work = 0; // the inversion's work, and that of the paths made
  std::vector<double> m_work; // zero between paths
  std::vector<int> m_stamp;
  std::vector<double> m_column_work; // for a column made alone
  struct Block_work
  {
    std::vector<double> z;
    std::vector<char> on_path;
  };
  Block_work m_block_work[2]; // for the columns made by prefetch(), one per half
  std::vector<char> m_on_path;
  Second_thread m_second_thread; // the second halves of the columns, paths and watched rows made
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_ENERGY_H
