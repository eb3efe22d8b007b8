// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_PLACEMENT_AND_INTEGERS_H
#define CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_PLACEMENT_AND_INTEGERS_H

// Test support: singularity placement helpers; the brute-force check of the energy-optimal integers.

#include "solver_checks.h"

namespace tc_test {

// =====================================================================================================
// Singularity placement
// =====================================================================================================

/// the interior vertex nearest to point q (among the vertices of our component `comp`, or all when -1)
template <class Mesh>
int nearest_interior_vertex(const Mesh_view<Mesh>& view, const V3& q, int comp = -1)
{
  int best = -1; double bd = std::numeric_limits<double>::infinity();
  for(int v = 0; v < view.nv(); ++v)
    if(view.interior_vertex(v) && (comp < 0 || view.comp_of_vertex[v] == comp)) {
      const double d = norm(view.P[v] - q);
      if(d < bd) { bd = d; best = v; }
    }
  return best;
}

/// `count` interior vertices of our component `comp`, spread by farthest-point sampling (Euclidean);
/// fewer when the component has fewer interior vertices
template <class Mesh>
std::vector<int> spread_interior_vertices(const Mesh_view<Mesh>& view, int comp, int count)
{
  std::vector<int> candidates;
  for(int v = 0; v < view.nv(); ++v)
    if(view.interior_vertex(v) && view.comp_of_vertex[v] == comp) candidates.push_back(v);
  std::vector<int> chosen;
  if(candidates.empty() || count <= 0) return chosen;
  std::vector<double> d(candidates.size(), std::numeric_limits<double>::infinity());
  // start from the candidate farthest from the first one
  int next = 0;
  for(std::size_t i = 0; i < candidates.size(); ++i)
    if(norm(view.P[candidates[i]] - view.P[candidates[0]]) > norm(view.P[candidates[next]] - view.P[candidates[0]]))
      next = int(i);
  while(int(chosen.size()) < count && int(chosen.size()) < int(candidates.size())) {
    chosen.push_back(candidates[next]);
    const V3 p = view.P[candidates[next]];
    int far = -1;
    for(std::size_t i = 0; i < candidates.size(); ++i) {
      d[i] = std::min(d[i], norm(view.P[candidates[i]] - p));
      if(far < 0 || d[i] > d[far]) far = int(i);
    }
    next = far;
  }
  return chosen;
}

/*
  Singularities that satisfy Poincaré–Hopf on every component, for an n-direction field:
  closed chi > 0: n chi vertices of index +1/n; closed chi < 0: n |chi| vertices of index -1/n (with
  `unit_indices`, |chi| vertices of index ±1 instead); closed chi = 0: +1/n and -1/n; bordered: +1/n and
  -2/n (any indices are fine there: the boundary loops take the rest). Vertices spread by farthest-point
  sampling. A closed component with fewer interior vertices than that gets the same total spread over
  all its vertices (e.g. four +1/2 on a tetrahedron for n = 4).
*/
template <class Mesh>
Singularities plan_singularities(const Mesh_view<Mesh>& view, int n, bool unit_indices = false)
{
  Singularities s;
  for(int c = 0; c < view.ncomp; ++c) {
    const long long chi = view.chi[c];
    int available = 0;
    for(int v = 0; v < view.nv(); ++v)
      if(view.interior_vertex(v) && view.comp_of_vertex[v] == c) ++available;
    std::vector<Index> want;
    if(view.boundary_count[c] > 0) {
      if(available >= 2) want = {Index(1, n), Index(-2, n)};
    } else if(chi == 0) {
      want = {Index(1, n), Index(-1, n)};
    } else {
      const long long step = unit_indices ? n : 1;       // in units of 1/n
      const long long units = n * std::abs(chi) / step;  // number of singularities wanted
      const long long count = std::min<long long>(units, available);
      const long long sign = chi > 0 ? 1 : -1;
      for(long long i = 0; i < count; ++i)
        want.push_back(Index(sign * step * (units / count + (i < units % count ? 1 : 0)), n));
    }
    const std::vector<int> at = spread_interior_vertices(view, c, int(want.size()));
    EXPECT_EQ(at.size(), want.size()) << "test set-up: component " << c << " has too few interior vertices";
    for(std::size_t i = 0; i < want.size() && i < at.size(); ++i) s.emplace_back(at[i], want[i]);
  }
  return s;
}

// =====================================================================================================
// Brute-force check of the energy-optimal integers
// =====================================================================================================

/// The free integer coordinates of solver.loops(): every generator, and every boundary loop but the last of
/// its component, whose partner (the last one) moves the other way (Poincaré–Hopf fixes their sum).
template <class Solver>
void free_coordinates(const Solver& solver, std::vector<int>& free, std::vector<int>& partner)
{
  const auto& loops = solver.loops();
  std::map<std::size_t, int> last_boundary;
  for(std::size_t l = 0; l < loops.size(); ++l)
    if(loops[l].kind == TC::Loop_kind::boundary) last_boundary[loops[l].component] = int(l);
  free.clear(); partner.clear();
  for(std::size_t l = 0; l < loops.size(); ++l) {
    if(loops[l].kind == TC::Loop_kind::generator) { free.push_back(int(l)); partner.push_back(-1); }
    else if(last_boundary[loops[l].component] != int(l)) {
      free.push_back(int(l)); partner.push_back(last_boundary[loops[l].component]);
    }
  }
}

/*
  Around the integers the solver chose (report.loops[l].period), tries every combination within
  ±radius: each generator freely, and the boundary loops of a component in pairs with the component's
  last boundary loop (their sum is fixed by Poincaré–Hopf). Every prescribed solve is checked to keep
  the holonomy (residuals) and none may have a lower energy (recomputed by us from x) than the default.
  Returns the number of combinations tried.
*/
template <class Mesh, class Solver>
long long check_integers_by_enumeration(const Mesh_view<Mesh>& view, Solver& solver, const Singularities& sing,
                                        int n, const TC::Solve_report& best, int radius = 2,
                                        int* dimension = nullptr)
{
  const auto& loops = solver.loops();
  std::vector<std::int64_t> base;
  for(const auto& r : best.loops) base.push_back(r.period);
  std::vector<int> free, partner;
  free_coordinates(solver, free, partner);
  const double E_best = best.energy;
  if(dimension) *dimension = int(free.size());
  std::vector<int> offset(free.size(), -radius);
  long long tried = 0;
  double lowest = std::numeric_limits<double>::infinity();
  std::vector<int> lowest_at;
  for(;;) {
    std::vector<std::int64_t> periods = base;
    for(std::size_t i = 0; i < free.size(); ++i) {
      periods[free[i]] += offset[i];
      if(partner[i] >= 0) periods[partner[i]] -= offset[i];
    }
    std::vector<double> x;
    const TC::Solve_report r = solver.solve(descriptors(view, sing), view.halfedge_map(x),
                                            TC::parameters::loop_periods(periods, TC::parameters::symmetry_order(n)));
    EXPECT_LT(r.max_vertex_residual, 1e-9);
    EXPECT_LT(r.max_loop_residual, 1e-9);
    for(std::size_t l = 0; l < loops.size(); ++l) {
      EXPECT_EQ(r.loops[l].period, periods[l]);
      EXPECT_TRUE(r.loops[l].prescribed);
    }
    const double E = energy(view, x, solver.weighting());
    ++tried;
    if(E < lowest) { lowest = E; lowest_at = offset; }
    bool all_zero = std::all_of(offset.begin(), offset.end(), [](int o) { return o == 0; });
    if(all_zero)
      EXPECT_NEAR(E, E_best, 1e-9 * std::max(1., E_best)) << "the chosen integers, prescribed, give another energy";
    std::size_t i = 0;
    for(; i < offset.size(); ++i) {
      if(++offset[i] <= radius) break;
      offset[i] = -radius;
    }
    if(i == offset.size()) break;
  }
  std::ostringstream where;
  for(int o : lowest_at) where << o << " ";
  EXPECT_GE(lowest, E_best - 1e-9 * std::max(1., E_best))
    << "brute force found lower energy " << lowest << " < " << E_best << " at offsets ( " << where.str() << ")";
  return tried;
}


/// per interior edge {i, j} (i < j in the numbering `soup_index_of_vertex` of the view's vertices): x of the
/// halfedge i -> j, to compare connections across renumbered meshes
template <class Mesh>
std::map<std::pair<int, int>, double> x_by_vertex_pair(const Mesh_view<Mesh>& view, const std::vector<double>& x,
                                                       const std::vector<int>& soup_index_of_vertex)
{
  std::map<std::pair<int, int>, double> r;
  for(int h : view.interior_halfedges) {
    const int i = soup_index_of_vertex[view.src[h]], j = soup_index_of_vertex[view.tgt[h]];
    if(i < j) r[{i, j}] = x[h];
  }
  return r;
}

/*
  Local optimality of the chosen integers (for meshes too large for the box enumeration): no single free
  coordinate moved by ±1 (boundary loops in pairs, as above) lowers the energy, recomputed by us. The loops
  whose integer was prescribed (`prescribed[l]` set: the loop_periods of the solve) are not moved.
*/
template <class Mesh, class Solver>
void check_integers_locally_optimal(const Mesh_view<Mesh>& view, Solver& solver, const Singularities& sing, int n,
                                    const TC::Solve_report& best,
                                    const std::vector<std::optional<std::int64_t>>& prescribed = {})
{
  std::vector<std::int64_t> base;
  for(const auto& r : best.loops) base.push_back(r.period);
  std::vector<int> free, partner;
  free_coordinates(solver, free, partner);
  int improving = 0, first = -1;
  double gain = 0;
  for(std::size_t i = 0; i < free.size(); ++i)
    for(int d : {-1, 1}) {
      if(!prescribed.empty() && prescribed[std::size_t(free[i])])
        continue;
      std::vector<std::int64_t> periods = base;
      periods[free[i]] += d;
      if(partner[i] >= 0) periods[partner[i]] -= d;
      std::vector<double> x;
      const TC::Solve_report r = solver.solve(descriptors(view, sing), view.halfedge_map(x),
                                              TC::parameters::loop_periods(periods, TC::parameters::symmetry_order(n)));
      EXPECT_LT(r.max_vertex_residual, 1e-9);
      EXPECT_LT(r.max_loop_residual, 1e-9);
      const double E = energy(view, x, solver.weighting());
      if(E < best.energy - 1e-9 * std::max(1., best.energy)) {
        ++improving;
        if(best.energy - E > gain) { gain = best.energy - E; first = free[i]; }
      }
    }
  EXPECT_EQ(improving, 0) << improving << " single-loop changes of the integers lower the energy "
                          << best.energy << " (integers_proven_optimal = " << best.integers_proven_optimal
                          << "); the best lowers it by " << gain << " (loop " << first << ")";
}

} // namespace tc_test

#endif // CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_PLACEMENT_AND_INTEGERS_H
