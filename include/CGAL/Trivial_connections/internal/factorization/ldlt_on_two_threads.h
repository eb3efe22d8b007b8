// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_LDLT_ON_TWO_THREADS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_LDLT_ON_TWO_THREADS_H

#include <CGAL/Trivial_connections/internal/concurrency.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_storage.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <future>
#include <memory>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The numeric factorization of an Eigen SimplicialLDLT (natural ordering, after its analyzePattern()) on two
  threads, for the factors of meshes, where a second core otherwise idles during the longest phase of the set-up.

  Row k of Eigen's up-looking factorization reads only the columns of its descendants in the elimination tree,
  so the rows of disjoint subtrees are independent. The subtree holding more than half of the predicted work
  (sum of squared column counts) is split, its root going to the "top", until none does; the two threads take
  the subtrees from a shared queue, heaviest first. For a mesh the top is then the chain of separators at the
  root, which holds about 40 % of the work, as much in its rows' entries in subtree columns as in the chain.
  So the top rows go in three steps: (1) each top row's entries in subtree columns, which read only subtree
  rows: the rows are independent; (2) each top row's right-hand side in the top columns, A(t,k) minus the sum
  over subtree columns j of L(t,j) D(j) L(k,j), kept in the entries of row k; (3) the top columns: when the top
  rows are the last ones and their block is full (a mesh's root separator), a blocked dense LDL^T there; else
  the up-looking step in the top columns only, one row after the other. The first thread finds where the entries of top rows go in each column
  (after the subtree rows, in row order: two passes over their patterns, writing straight into the factor's
  index array, already written once) while the second starts the subtrees. In steps (1) and (2) one thread goes
  up from the first top row and the other down from the last, so that neighbouring entries of a column are
  written by the same thread.

  Every row is computed by the same operations whichever thread computes it: the factor does not depend on the
  timing. It equals Eigen's factorize() up to rounding (the terms of a top row are summed in another order;
  relative differences about 1e-15). Measured on the 2-core VM of benchmark/RESULTS.md, warm heap, factor pages
  written beforehand: 75k faces 33-38 -> 26-27 ms, 302k faces 386-423 -> 283-298 ms.
*/
template <class Simplicial>
class Ldlt_on_two_threads
{
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  using Members = Simplicial_members<Simplicial>;
  // below this many flops (sum of the squared column counts, about 3 ms), one thread: not worth a thread
  static constexpr double kMinimumFlops = 1e7;

public:
  // After s.analyzePattern(a) succeeded: the numeric factorization of `a` (the matrix given to the analysis,
  // with the triangle `Simplicial` reads), on two threads when a second one can run, else the same steps on this
  // one. Returns false when it did not run (too small to pay): the caller then calls s.factorize(a).
  // `full_top_block`, when given, tells which way step (3) went (for the tests).
  static bool factorize(Simplicial& s, const Sparse& a, bool* full_top_block = nullptr)
  {
    Ldlt_on_two_threads worker(s);
    const bool ran = worker.run(a);
    if(full_top_block != nullptr)
      *full_top_block = ran && worker.m_full_top_block;
    return ran;
  }

private:
  explicit Ldlt_on_two_threads(Simplicial& s)
    : m_s(s),
      m_parent(Members::parent(s).data()),
      m_nz(Members::column_counts(s).data()),
      m_shift_offset(Members::shift_offset(s)),
      m_shift_scale(Members::shift_scale(s))
  {
  }

  struct Workspace
  {
    std::vector<double> y;
    std::vector<int> pattern, tags;
    std::vector<int> cursor; // per column, the entry of the next top row this thread visits there
    int step = 1;            // +1: this thread goes through the top rows upwards, -1: downwards
    explicit Workspace(int n)
      : y(std::size_t(n), 0.), pattern(std::size_t(n)), tags(std::size_t(n), -1), cursor(std::size_t(n), 0)
    {
    }
  };

  bool run(const Sparse& a)
  {
    const int n = int(a.rows());
    if(!Members::analysed(m_s) || Members::permutation(m_s).size() != 0 || n == 0)
      return false;
    const int* count = m_nz; // the column counts of the analysis
    double flops = 0;
    for(int j = 0; j < n; ++j)
      flops += double(count[j]) * double(count[j]);
    if(flops < kMinimumFlops)
      return false;

    // the upper triangle, as the sequential factorization reads it
    Sparse copy;
    const Sparse* upper = &a;
    if((int(Simplicial::UpLo) & int(Eigen::Upper)) != int(Eigen::Upper)) {
      copy.resize(n, n);
      copy.template selfadjointView<Eigen::Upper>() = a.template selfadjointView<Simplicial::UpLo>();
      upper = &copy;
    }
    m_counts.assign(count, count + n);
    auto& L = Members::factor(m_s);
    m_Lp = L.outerIndexPtr();
    m_Li = L.innerIndexPtr();
    m_Lx = L.valuePtr();
    Members::diagonal(m_s).resize(n);
    m_D = Members::diagonal(m_s).data();
    partition(n);

    std::atomic<int> next_subtree{0};
    auto subtrees = [this, upper, &next_subtree](Workspace& w) {
      for(int t; (t = next_subtree.fetch_add(1)) < m_subtrees;)
        for(int r = m_subtree_start[t]; r < m_subtree_start[t + 1]; ++r)
          subtree_row(*upper, m_rows[r], w);
    };
    std::unique_ptr<Workspace> second_workspace(new Workspace(0));
    std::future<int> second = concurrently([&, n] {
      *second_workspace = Workspace(n);
      subtrees(*second_workspace);
      return 0;
    });
    // Without a second thread (one usable core) the same steps run on this one, the deferred task when its
    // result is asked for: the factor, to the last bit, does not depend on the cores (a batch pins its workers'
    // programs to a core each, and a run on the user's machine gives the same bytes).
    Workspace first_workspace(n);
    top_symbolic(*upper, first_workspace);
    subtrees(first_workspace);
    second.get();

    // the top rows: the entries in subtree columns, their updates of the entries in top columns (each row on
    // its own), then the entries in top columns (one row after the other)
    auto on_two_threads = [&](auto step) {
      // the first thread from the first row up, the second from the last one down: neighbouring entries of a
      // column are written by the same thread
      std::atomic<int> taken{0};
      const int m = int(m_top_rows.size());
      start_top_rows(first_workspace, +1);
      start_top_rows(*second_workspace, -1);
      second = concurrently([&] {
        for(int q = m - 1; taken.fetch_add(1) < m; --q)
          step(q, *second_workspace);
        return 0;
      });
      for(int q = 0; taken.fetch_add(1) < m; ++q)
        step(q, first_workspace);
      second.get();
    };
    on_two_threads([this, upper](int q, Workspace& w) { top_row_in_subtree_columns(*upper, q, w); });
    on_two_threads([this, upper](int q, Workspace& w) { top_row_updates_of_top_columns(*upper, q, w); });
    m_full_top_block = top_block_is_full(n);
    if(m_full_top_block)
      factorize_full_top_block(n);
    else {
      start_top_rows(first_workspace, +1);
      for(int q = 0; q < int(m_top_rows.size()); ++q)
        top_row_in_top_columns(*upper, q, first_workspace);
    }

    std::copy(m_counts.begin(), m_counts.end(), m_nz);
    Members::set_factorized(m_s, m_pivot_zero.load() ? Eigen::NumericalIssue : Eigen::Success);
    return true;
  }

  // The subtrees and the top rows, from the elimination tree and predicted work per column (count^2).
  void partition(int n)
  {
    const int* parent = m_parent;
    std::vector<double> work(static_cast<std::size_t>(n));
    for(int j = 0; j < n; ++j)
      work[j] = double(m_counts[j]) * m_counts[j] + 4. * m_counts[j] + 8.;
    for(int j = 0; j < n; ++j) // a parent comes after its children
      if(parent[j] >= 0)
        work[parent[j]] += work[j];
    std::vector<int> child_start(std::size_t(n) + 2, 0), child(static_cast<std::size_t>(n));
    for(int j = 0; j < n; ++j)
      ++child_start[std::size_t(parent[j] < 0 ? n : parent[j]) + 1];
    for(int j = 0; j <= n; ++j)
      child_start[j + 1] += child_start[j];
    {
      std::vector<int> next(child_start.begin(), child_start.end() - 1);
      for(int j = 0; j < n; ++j)
        child[next[parent[j] < 0 ? n : parent[j]]++] = j;
    }
    double total = 0;
    for(int r = child_start[n]; r < child_start[n + 1]; ++r)
      total += work[child[r]];
    std::vector<int> roots(child.begin() + child_start[n], child.begin() + child_start[n + 1]);
    auto lighter = [&work](int x, int y) { return work[x] < work[y]; };
    std::make_heap(roots.begin(), roots.end(), lighter);
    std::vector<int> tree(std::size_t(n), -1); // subtree of a row; -2: a top row
    while(!roots.empty() && work[roots.front()] > total / 2) { // a subtree with more than half of the work
      std::pop_heap(roots.begin(), roots.end(), lighter);
      const int r = roots.back();
      roots.pop_back();
      tree[r] = -2;
      for(int c = child_start[r]; c < child_start[r + 1]; ++c) {
        roots.push_back(child[c]);
        std::push_heap(roots.begin(), roots.end(), lighter);
      }
    }
    std::sort(roots.begin(), roots.end(), [&work](int x, int y) { return work[x] > work[y]; });
    m_subtrees = int(roots.size());
    for(int t = 0; t < m_subtrees; ++t)
      tree[roots[t]] = t;
    for(int j = n - 1; j >= 0; --j)
      if(tree[j] == -1)
        tree[j] = tree[parent[j]]; // every row that is neither a top row nor a root has a parent
    // rows by subtree, increasing within each (children first)
    m_subtree_start.assign(std::size_t(m_subtrees) + 1, 0);
    m_top_rows.clear();
    m_is_top.assign(std::size_t(n), 0);
    for(int j = 0; j < n; ++j)
      if(tree[j] >= 0)
        ++m_subtree_start[tree[j] + 1];
      else {
        m_is_top[j] = 1;
        m_top_rows.push_back(j);
      }
    for(int t = 0; t < m_subtrees; ++t)
      m_subtree_start[t + 1] += m_subtree_start[t];
    m_rows.resize(std::size_t(m_subtree_start[m_subtrees]));
    std::vector<int> next(m_subtree_start.begin(), m_subtree_start.end() - 1);
    for(int j = 0; j < n; ++j)
      if(tree[j] >= 0)
        m_rows[next[tree[j]]++] = j;
  }

  // Eigen's row k: the pattern of row k of L (the reach of column k of the upper triangle in the elimination
  // tree), in topological order, in w.pattern[top, n); returns top. Scatters column k into w.y when `scatter`.
  int row_pattern(const Sparse& upper, int k, Workspace& w, bool scatter) const
  {
    const int n = int(upper.rows());
    const int* parent = m_parent;
    int* pattern = w.pattern.data();
    int* tags = w.tags.data();
    int top = n;
    tags[k] = k;
    for(typename Sparse::InnerIterator it(upper, k); it; ++it) {
      int i = int(it.index());
      if(i <= k) {
        if(scatter)
          w.y[i] += it.value();
        int len = 0;
        for(; tags[i] != k; i = parent[i]) {
          pattern[len++] = i;
          tags[i] = k;
        }
        while(len > 0)
          pattern[--top] = pattern[--len];
      }
    }
    return top;
  }

  // Eigen's up-looking step for row k of a subtree: every column it reads or extends is in the same subtree.
  void subtree_row(const Sparse& upper, int k, Workspace& w)
  {
    const int n = int(upper.rows());
    const int* Lp = m_Lp;
    int* Li = m_Li;
    double* Lx = m_Lx;
    int* nz = m_nz;
    double* D = m_D;
    double* y = w.y.data();
    y[k] = 0;
    nz[k] = 0;
    int top = row_pattern(upper, k, w, true);
    double d = y[k] * m_shift_scale + m_shift_offset;
    y[k] = 0;
    for(; top < n; ++top) {
      const int i = w.pattern[top];
      const double yi = y[i];
      y[i] = 0;
      const double l_ki = yi / D[i];
      const int end = Lp[i] + nz[i];
      int p = Lp[i];
      for(; p < end; ++p)
        y[Li[p]] -= Lx[p] * yi;
      d -= l_ki * yi;
      Li[p] = k;
      Lx[p] = l_ki;
      ++nz[i];
    }
    D[k] = d;
    if(d == 0)
      m_pivot_zero.store(true);
  }

  // Where the entries of the top rows go: in each column, after the entries of subtree rows (which are all
  // smaller), in increasing row order. Writes their row indices into the factor, in two passes over the
  // patterns of the top rows (one counts the entries per column, one writes them), so that nothing but the
  // factor, which is already written once, grows with their number.
  void top_symbolic(const Sparse& upper, Workspace& w)
  {
    const int n = int(upper.rows());
    std::vector<int> next(std::size_t(n), 0);
    for(int k : m_top_rows)
      for(int top = row_pattern(upper, k, w, false); top < n; ++top)
        ++next[w.pattern[top]];
    m_first_top_entry.resize(std::size_t(n));
    for(int i = 0; i < n; ++i) {
      m_first_top_entry[i] = m_Lp[i] + m_counts[i] - next[i];
      next[i] = m_first_top_entry[i];
    }
    std::fill(w.tags.begin(), w.tags.end(), -1);
    for(int k : m_top_rows)
      for(int top = row_pattern(upper, k, w, false); top < n; ++top)
        m_Li[next[w.pattern[top]]++] = k;
    std::fill(w.tags.begin(), w.tags.end(), -1);
  }

  bool is_top(int i) const { return m_is_top[i] != 0; }

  // Before a pass over the top rows, upwards (+1) or downwards (-1) from one end: row_pattern() marks with k.
  void start_top_rows(Workspace& w, int step) const
  {
    const int n = int(w.tags.size());
    std::fill(w.tags.begin(), w.tags.end(), -1);
    w.step = step;
    for(int i = 0; i < n; ++i)
      w.cursor[i] = step > 0 ? m_first_top_entry[i] : m_Lp[i] + m_counts[i] - 1;
  }

  // the entry of the current top row in column i (of its pattern; each column once per row)
  static int entry_of(int i, Workspace& w)
  {
    const int p = w.cursor[i];
    w.cursor[i] += w.step;
    return p;
  }

  // Row k of L in the subtree columns, and D(k) without the terms of top columns: only subtree rows are read.
  void top_row_in_subtree_columns(const Sparse& upper, int q, Workspace& w)
  {
    const int n = int(upper.rows());
    const int k = m_top_rows[q];
    double* y = w.y.data();
    int top = row_pattern(upper, k, w, true);
    double d = y[k] * m_shift_scale + m_shift_offset;
    y[k] = 0;
    for(; top < n; ++top) {
      const int i = w.pattern[top];
      const double yi = y[i];
      y[i] = 0;
      if(is_top(i))
        continue;
      const double l_ki = yi / m_D[i];
      const int first_top = m_first_top_entry[i];
      for(int p = m_Lp[i]; p < first_top; ++p)
        y[m_Li[p]] -= m_Lx[p] * yi;
      d -= l_ki * yi;
      m_Lx[entry_of(i, w)] = l_ki;
    }
    m_D[k] = d;
  }

  // The right-hand side of row k in the top columns: A(t, k) minus the terms of the subtree columns, kept in the
  // entries of row k until top_row_in_top_columns().
  void top_row_updates_of_top_columns(const Sparse& upper, int q, Workspace& w)
  {
    const int n = int(upper.rows());
    const int k = m_top_rows[q];
    double* y = w.y.data();
    const int first = row_pattern(upper, k, w, true);
    y[k] = 0;
    for(int top = first; top < n; ++top) {
      const int i = w.pattern[top];
      if(is_top(i))
        continue;
      y[i] = 0;
      const int own = entry_of(i, w);
      const double yi = m_Lx[own] * m_D[i];
      for(int p = m_first_top_entry[i]; p < own; ++p)
        y[m_Li[p]] -= m_Lx[p] * yi;
    }
    for(int top = first; top < n; ++top) {
      const int i = w.pattern[top];
      if(is_top(i)) {
        m_Lx[entry_of(i, w)] = y[i];
        y[i] = 0;
      }
    }
  }

  // Row k of L in the top columns, and D(k): the up-looking step on what the two steps above left.
  void top_row_in_top_columns(const Sparse& upper, int q, Workspace& w)
  {
    const int n = int(upper.rows());
    const int k = m_top_rows[q];
    double* y = w.y.data();
    const int first = row_pattern(upper, k, w, false);
    for(int top = first; top < n; ++top) {
      const int i = w.pattern[top];
      if(is_top(i))
        y[i] = m_Lx[entry_of(i, w)];
    }
    double d = m_D[k];
    for(int top = first; top < n; ++top) {
      const int i = w.pattern[top];
      if(!is_top(i))
        continue;
      const double yi = y[i];
      y[i] = 0;
      const double l_ki = yi / m_D[i];
      int p = m_Lp[i];
      for(; m_Li[p] != k; ++p)
        y[m_Li[p]] -= m_Lx[p] * yi;
      d -= l_ki * yi;
      m_Lx[p] = l_ki;
    }
    m_D[k] = d;
    if(d == 0)
      m_pivot_zero.store(true);
  }

  // True when the top rows are the last rows and their block of L is full, as for the separator at the root of a
  // mesh: its columns are then the columns of a packed lower triangle, without gaps.
  bool top_block_is_full(int n) const
  {
    const int m = int(m_top_rows.size());
    if(m == 0 || m_top_rows.front() != n - m)
      return false;
    for(int i = n - m; i < n; ++i)
      if(m_counts[i] != n - 1 - i || m_first_top_entry[i] != m_Lp[i])
        return false;
    return true;
  }

  // Step (3) on a full top block: a blocked right-looking LDL^T of what steps (1) and (2) left there (the Schur
  // complement, its diagonal in D), in place. The updates of the columns right of a panel are matrix products:
  // about four times the speed of the up-looking rows (75k faces: 4.2 -> 1.1 ms; 302k faces: 52 -> 13 ms).
  void factorize_full_top_block(int n)
  {
    constexpr int width = 32;
    // column j of the block: column(j)[r] is L(r, j), r > j
    auto column = [this](int j) { return m_Lx + m_Lp[j] - (j + 1); };
    Eigen::MatrixXd panel, scaled_panel, product;
    for(int j0 = n - int(m_top_rows.size()); j0 < n; j0 += width) {
      const int j1 = std::min(j0 + width, n);
      for(int j = j0; j < j1; ++j) { // the panel's columns, right-looking inside it
        const double d = m_D[j];
        if(d == 0) {
          m_pivot_zero.store(true);
          return;
        }
        double* l = column(j);
        for(int r = j + 1; r < n; ++r)
          l[r] /= d;
        for(int c = j + 1; c < j1; ++c) {
          const double f = l[c] * d;
          m_D[c] -= l[c] * f;
          double* lc = column(c);
          for(int r = c + 1; r < n; ++r)
            lc[r] -= l[r] * f;
        }
      }
      if(j1 == n)
        break;
      // the columns right of the panel, `width` at a time: minus P diag(D) P^T, P the panel below it
      panel.resize(n - j1, j1 - j0);
      scaled_panel.resize(n - j1, j1 - j0);
      for(int j = j0; j < j1; ++j) {
        const double* l = column(j);
        for(int r = j1; r < n; ++r) {
          panel(r - j1, j - j0) = l[r];
          scaled_panel(r - j1, j - j0) = l[r] * m_D[j];
        }
      }
      for(int c0 = j1; c0 < n; c0 += width) {
        const int c1 = std::min(c0 + width, n);
        product.noalias() = panel.bottomRows(n - c0) * scaled_panel.middleRows(c0 - j1, c1 - c0).transpose();
        for(int c = c0; c < c1; ++c) {
          m_D[c] -= product(c - c0, c - c0);
          double* lc = column(c);
          for(int r = c + 1; r < n; ++r)
            lc[r] -= product(r - c0, c - c0);
        }
      }
    }
  }

  Simplicial& m_s;
  const int* m_parent; // the elimination tree
  int* m_nz;           // the column counts: of the analysis, then Eigen's running counts in subtree columns
  double m_shift_offset, m_shift_scale;
  const int* m_Lp = nullptr;
  int* m_Li = nullptr;
  double* m_Lx = nullptr;
  double* m_D = nullptr;
  std::vector<int> m_counts;                       // column counts of the analysis
  int m_subtrees = 0;
  std::vector<int> m_rows, m_subtree_start;        // subtree rows, by subtree
  std::vector<int> m_top_rows;                     // increasing
  std::vector<char> m_is_top;                      // per row
  std::vector<int> m_first_top_entry;              // per column: its first entry in a top row
  std::atomic<bool> m_pivot_zero{false};
  bool m_full_top_block = false;
};

// After analyzePattern() of an Eigen SimplicialLDLT with the natural ordering: its numeric factorization of M, on
// two threads where that pays; otherwise Eigen's, after the factor's pages are written on two threads
// (factor_storage.h). On two threads the pages of the factor are first written by both threads anyway; a large
// factor is offered huge pages either way.
template <class Simplicial>
void factorize_analysed_ldlt(Simplicial& s, const Eigen::SparseMatrix<double>& M)
{
  advise_huge_pages_for_simplicial_factor(s);
  if(!Ldlt_on_two_threads<Simplicial>::factorize(s, M)) {
    touch_simplicial_factor_storage(s);
    s.factorize(M);
  }
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_LDLT_ON_TWO_THREADS_H
