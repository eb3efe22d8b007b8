// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_SOLVER_CHECKS_H
#define CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_SOLVER_CHECKS_H

// Test support: the solver's documented geometry, its loops, the connection, the report and the field checked
// against them; solve_and_check().

#include "independent_geometry.h"

namespace tc_test {

// =====================================================================================================
// Checks of the solver's documented geometry against our own
// =====================================================================================================

template <class Mesh, class Solver>
void check_solver_geometry(const Mesh_view<Mesh>& view, const Solver& solver)
{
  // angle defects
  double worst_defect = 0; int worst_v = -1;
  for(int v = 0; v < view.nv(); ++v) {
    const double mine = view.faces_at[v] > 0 ? view.defect(v) : 0.;
    const double d = std::abs(solver.angle_defect(view.vertices[v]) - mine);
    if(d > worst_defect) { worst_defect = d; worst_v = v; }
  }
  EXPECT_LT(worst_defect, 1e-11) << "angle_defect differs from 2pi (pi) - sum of corner angles at vertex " << worst_v;

  // transport angles: a direction at angle t in the frame of face(h) (halfedge(f)) arrives at
  // t + rho(h) in the frame of face(opposite(h)); check with our own unfolding of the frame vector
  double worst_rho = 0; int worst_h = -1;
  for(int h : view.interior_halfedges) {
    const int g = view.hface[view.opp[h]];
    const V3 u = view.transport(h, view.frame(view.hface[h]));
    const double mine = signed_angle(view.frame(g), u, view.N[g]);
    const double d = std::abs(wrap(solver.transport_angle(view.halfedges[h]) - mine));
    if(d > worst_rho) { worst_rho = d; worst_h = h; }
  }
  EXPECT_LT(worst_rho, 1e-11) << "transport_angle differs from our Levi-Civita unfolding at halfedge "
                              << (worst_h >= 0 ? std::to_string(view.src[worst_h]) + "->" + std::to_string(view.tgt[worst_h]) : "");

  // Σ_ccw transport_angle around an interior vertex ≡ K_v (mod 2 pi)
  std::vector<double> rho_sum(view.nv(), 0.);
  for(int h : view.interior_halfedges) rho_sum[view.tgt[h]] += solver.transport_angle(view.halfedges[h]);
  double worst_ring = 0; worst_v = -1;
  for(int v = 0; v < view.nv(); ++v)
    if(view.interior_vertex(v)) {
      const double d = std::abs(wrap(rho_sum[v] - view.defect(v)));
      if(d > worst_ring) { worst_ring = d; worst_v = v; }
    }
  EXPECT_LT(worst_ring, 1e-9) << "sum of transport angles around vertex " << worst_v << " is not K_v mod 2pi";

  // weights: unit = 1, Hodge star = |e| / (|b_f - m_e| + |m_e - b_g|), all positive
  double worst_w = 0; int worst_e = -1;
  for(int h : view.interior_edges) {
    const auto e = edge(view.halfedges[h], view.tm);
    EXPECT_TRUE(solver.is_interior(e));
    const double mine = view.weight(h, solver.weighting());
    const double w = solver.weight(e);
    ASSERT_TRUE(w > 0 && std::isfinite(w)) << "weight of edge " << view.src[h] << "-" << view.tgt[h] << " = " << w;
    const double d = std::abs(w - mine) / mine;
    if(d > worst_w) { worst_w = d; worst_e = h; }
  }
  EXPECT_LT(worst_w, 1e-12) << "weight differs from the documented one (relative) at edge "
                            << (worst_e >= 0 ? std::to_string(view.src[worst_e]) + "-" + std::to_string(view.tgt[worst_e]) : "");
  for(int h = 0; h < view.nh(); ++h)
    if(view.hface[h] < 0) EXPECT_FALSE(solver.is_interior(edge(view.halfedges[h], view.tm)));

  // topology of the components, matched through solver.component(face)
  const auto& comps = solver.components();
  ASSERT_EQ(int(comps.size()), view.ncomp) << "number of connected components";
  std::vector<int> mine_of(comps.size(), -1);
  for(int f = 0; f < view.nf(); ++f) {
    const std::size_t c = solver.component(view.faces[f]);
    ASSERT_LT(c, comps.size());
    if(mine_of[c] < 0) mine_of[c] = view.comp_of_face[f];
    ASSERT_EQ(mine_of[c], view.comp_of_face[f]) << "faces of one component in two solver components";
  }
  for(std::size_t c = 0; c < comps.size(); ++c) {
    const int m = mine_of[c];
    EXPECT_EQ(comps[c].euler_characteristic, view.chi[m]) << "component " << c;
    EXPECT_EQ(int(comps[c].number_of_boundary_loops), view.boundary_count[m]) << "component " << c;
    EXPECT_EQ(int(comps[c].genus), view.genus[m]) << "component " << c;
  }
}

// =====================================================================================================
// The loops of solver.loops(): closed, right counts, boundary loops are the fans of CONVENTIONS.md
// =====================================================================================================

template <class Mesh, class Solver>
std::vector<std::vector<int>> loops_as_numbers(const Mesh_view<Mesh>& view, const Solver& solver)
{
  std::vector<std::vector<int>> r;
  for(const auto& L : solver.loops()) {
    r.emplace_back();
    for(auto h : L.halfedges) r.back().push_back(view.hid.at(h));
  }
  return r;
}

/// our component of each of the solver's components (through solver.component(face))
template <class Mesh, class Solver>
std::vector<int> our_components(const Mesh_view<Mesh>& view, const Solver& solver)
{
  std::vector<int> mine(solver.components().size(), -1);
  for(int f = 0; f < view.nf(); ++f) mine.at(solver.component(view.faces[f])) = view.comp_of_face[f];
  return mine;
}

/// the interior halfedges entering the vertices of our boundary loop b (its open fans)
template <class Mesh>
std::vector<int> fan_halfedges(const Mesh_view<Mesh>& view, int b)
{
  std::vector<int> r;
  for(int h : view.interior_halfedges)
    if(view.loop_of_vertex[view.tgt[h]] == b) r.push_back(h);
  return r;
}

/// our boundary loop that solver loop l goes around: the loop of the target of its first crossing; for
/// an empty loop, the boundary loop of its component with empty fans; -1 if none
template <class Mesh, class Solver>
int boundary_loop_of(const Mesh_view<Mesh>& view, const Solver& solver, std::size_t l)
{
  const auto& L = solver.loops()[l];
  if(!L.halfedges.empty()) return view.loop_of_vertex[view.tgt[view.hid.at(L.halfedges[0])]];
  const int comp = our_components(view, solver).at(L.component);
  int found = -1;
  for(std::size_t b = 0; b < view.boundary_loops.size(); ++b)
    if(view.boundary_loops[b].component == comp && fan_halfedges(view, int(b)).empty()) {
      if(found >= 0) return -1; // ambiguous
      found = int(b);
    }
  return found;
}

/// signed crossing count per interior edge (+1 when crossed through its smaller-numbered halfedge)
template <class Mesh>
std::map<int, int> crossing_counts(const Mesh_view<Mesh>& view, const std::vector<int>& halfedges)
{
  std::map<int, int> c;
  for(int h : halfedges) {
    const int e = std::min(h, view.opp[h]);
    c[e] += h == e ? 1 : -1;
  }
  for(auto it = c.begin(); it != c.end();)
    it = it->second == 0 ? c.erase(it) : std::next(it);
  return c;
}

template <class Mesh, class Solver>
void check_loops(const Mesh_view<Mesh>& view, const Solver& solver)
{
  const auto loops = loops_as_numbers(view, solver);
  std::vector<int> boundary_seen(view.boundary_loops.size(), 0);
  std::map<std::size_t, std::pair<int, int>> counts; // solver component -> (boundary, generator)
  std::size_t last_component = 0;
  bool generator_seen_in_component = false;
  for(std::size_t l = 0; l < loops.size(); ++l) {
    const auto& L = solver.loops()[l];
    SCOPED_TRACE("loop " + std::to_string(l));
    bool closed = false;
    loop_rotation(view, loops[l], nullptr, closed);
    EXPECT_TRUE(closed) << "loop is not a closed dual loop of interior edges";
    if(!closed) continue;
    for(int h : loops[l])
      EXPECT_EQ(solver.component(view.faces[view.hface[h]]), L.component) << "loop leaves its component";
    // per component: boundary loops first, then generators; components in increasing order
    if(l == 0 || L.component != last_component) {
      EXPECT_TRUE(l == 0 || L.component > last_component) << "loops not grouped by component";
      generator_seen_in_component = false;
    }
    last_component = L.component;
    if(L.kind == TC::Loop_kind::boundary) {
      EXPECT_FALSE(generator_seen_in_component) << "boundary loop after a generator";
      ++counts[L.component].first;
      const int b = boundary_loop_of(view, solver, l);
      ASSERT_GE(b, 0) << "boundary loop that goes around no boundary loop of its component";
      ++boundary_seen[b];
      // the loop crosses exactly the interior edges of the open fans of the loop's vertices
      EXPECT_TRUE(crossing_counts(view, loops[l]) == crossing_counts(view, fan_halfedges(view, b)))
        << "boundary loop does not cross the open fans of its boundary vertices counter-clockwise";
      // documented Levi-Civita holonomy of a boundary loop: its exact geodesic curvature
      EXPECT_NEAR(solver.levi_civita_holonomy(l), view.boundary_loops[b].kappa, 1e-9);
      const double rot = loop_rotation(view, loops[l], nullptr, closed);
      EXPECT_LT(std::abs(wrap(rot - view.boundary_loops[b].kappa)), 1e-9)
        << "transport around the boundary loop is not kappa_B mod 2pi";
    } else {
      generator_seen_in_component = true;
      EXPECT_FALSE(loops[l].empty()) << "empty generator";
      ++counts[L.component].second;
      const double rot = loop_rotation(view, loops[l], nullptr, closed);
      EXPECT_LT(std::abs(wrap(rot - solver.levi_civita_holonomy(l))), 1e-9)
        << "levi_civita_holonomy differs from our transport around the generator";
    }
  }
  for(std::size_t b = 0; b < boundary_seen.size(); ++b)
    EXPECT_EQ(boundary_seen[b], 1) << "boundary loop " << b << " (our numbering) has " << boundary_seen[b]
                                   << " loops in solver.loops()";
  for(std::size_t c = 0; c < solver.components().size(); ++c) {
    int mine = -1;
    for(int f = 0; f < view.nf() && mine < 0; ++f)
      if(solver.component(view.faces[f]) == c) mine = view.comp_of_face[f];
    EXPECT_EQ(counts[c].first, view.boundary_count[mine]) << "boundary loops of component " << c;
    EXPECT_EQ(counts[c].second, 2 * view.genus[mine]) << "generators of component " << c;
  }
}

// =====================================================================================================
// The connection and the report
// =====================================================================================================

struct Tolerances
{
  double holonomy = 1e-9;   // angle residuals (vertex, boundary, loops, field)
  double optimality = 1e-8; // max_f |Σ w x| / max_f Σ |w x|
  double energy = 1e-9;     // relative
};

/*
  Checks a connection x (per halfedge number) against CONVENTIONS.md, and the solver's report against
  our own figures: vertex holonomy, boundary indices (multiples of 1/n, equal to the report's),
  Poincaré–Hopf per component (exact, in units of 1/n), trivial holonomy around every loop of
  solver.loops() by our own transport, face optimality, energy.
*/
template <class Mesh, class Solver>
void check_connection(const Mesh_view<Mesh>& view, const Solver& solver, const Singularities& sing, int n,
                      const std::vector<double>& x, const TC::Solve_report& report,
                      bool all_cycles_constrained = true, const Tolerances& tol = Tolerances())
{
  const double unit_angle = two_pi / n;
  // x is antisymmetric, 0 on border halfedges, finite
  int bad = 0;
  for(int h = 0; h < view.nh(); ++h) {
    if(!std::isfinite(x[h])) { ++bad; continue; }
    if(view.interior_halfedge(h) ? x[view.opp[h]] != -x[h] : x[h] != 0) ++bad;
  }
  EXPECT_EQ(bad, 0) << "halfedges with x(opposite(h)) != -x(h), or x != 0 on a border edge, or not written";

  // vertex holonomy: K_v + Σ_ccw x = 2 pi k_v
  const std::vector<long long> k = scaled_indices(view.nv(), sing, n);
  const std::vector<double> S = ring_sums(view, x);
  double worst = 0; int worst_v = -1;
  for(int v = 0; v < view.nv(); ++v)
    if(view.interior_vertex(v)) {
      const double r = std::abs(view.defect(v) + S[v] - unit_angle * double(k[v]));
      if(!(r <= worst)) { worst = r; worst_v = v; }
    }
  EXPECT_LT(worst, tol.holonomy) << "holonomy residual |K_v + sum x - 2 pi k_v| at vertex " << worst_v;
  EXPECT_LT(report.max_vertex_residual, tol.holonomy);
  EXPECT_LT(report.max_loop_residual, tol.holonomy);

  // boundary loops: k_B = (kappa_B + Σ_B x) / 2pi is a multiple of 1/n
  std::vector<long long> nk_B(view.boundary_loops.size(), 0);
  for(std::size_t b = 0; b < view.boundary_loops.size(); ++b) {
    double sum = view.boundary_loops[b].kappa;
    for(int v : view.boundary_loops[b].vertices) sum += S[v];
    const double m = sum / unit_angle;
    nk_B[b] = std::llround(m);
    EXPECT_LT(std::abs(sum - unit_angle * double(nk_B[b])), tol.holonomy)
      << "boundary loop " << b << ": k_B = " << sum / two_pi << " is not a multiple of 1/" << n;
  }
  // Poincaré–Hopf per component, exactly in units of 1/n
  std::vector<long long> total(view.ncomp, 0);
  for(int v = 0; v < view.nv(); ++v)
    if(k[v] != 0) total[view.comp_of_vertex[v]] += k[v];
  for(std::size_t b = 0; b < nk_B.size(); ++b) total[view.boundary_loops[b].component] += nk_B[b];
  for(int c = 0; c < view.ncomp; ++c)
    EXPECT_EQ(total[c], n * view.chi[c]) << "Poincare-Hopf (times n) on our component " << c;

  // the report's loops, and our transport around each of them with the connection
  const auto loops = loops_as_numbers(view, solver);
  ASSERT_EQ(report.loops.size(), loops.size());
  EXPECT_EQ(report.symmetry_order, n);
  double worst_loop = 0; std::size_t worst_l = 0;
  for(std::size_t l = 0; l < loops.size(); ++l) {
    const TC::Loop_report& r = report.loops[l];
    EXPECT_EQ(r.kind, solver.loops()[l].kind) << "loop " << l;
    EXPECT_EQ(r.component, solver.loops()[l].component) << "loop " << l;
    EXPECT_LT(r.residual, tol.holonomy) << "loop " << l;
    EXPECT_EQ(r.index, Index(r.period, n)) << "loop " << l;
    bool closed = false;
    const double rot = loop_rotation(view, loops[l], &x, closed);
    ASSERT_TRUE(closed) << "loop " << l;
    const double d = std::abs(wrap(rot, unit_angle));
    if(!(d <= worst_loop)) { worst_loop = d; worst_l = l; }
    double xsum = 0;
    for(int h : loops[l]) xsum += x[h];
    if(r.kind == TC::Loop_kind::boundary) {
      const int b = boundary_loop_of(view, solver, l);
      ASSERT_GE(b, 0);
      EXPECT_EQ(r.period, nk_B[b]) << "loop " << l << ": reported boundary index " << r.index
                                   << " but the connection gives " << Index(nk_B[b], n);
      EXPECT_NEAR(view.boundary_loops[b].kappa + xsum, unit_angle * double(r.period), tol.holonomy) << "loop " << l;
    } else {
      // H_L (our transport, wrapped) + Σ_L x = 2 pi period / n, up to a multiple of 2 pi
      bool c2 = false;
      const double H = loop_rotation(view, loops[l], nullptr, c2);
      EXPECT_LT(std::abs(wrap(H + xsum - unit_angle * double(r.period))), tol.holonomy) << "loop " << l;
    }
  }
  EXPECT_LT(worst_loop, tol.holonomy) << "holonomy of loop " << worst_l
                                      << " (our transport with x) is not a multiple of 2pi/" << n;

  // components of the report
  ASSERT_EQ(report.components.size(), solver.components().size());
  std::vector<Index> sums(report.components.size());
  for(const auto& s : sing) {
    // component of a vertex through one of its faces
    int f = -1;
    for(auto h : CGAL::halfedges_around_target(view.vertices[s.first], view.tm))
      if(!is_border(h, view.tm)) { f = view.fid.at(face(h, view.tm)); break; }
    ASSERT_GE(f, 0);
    sums[solver.component(view.faces[f])] = sums[solver.component(view.faces[f])] + s.second;
  }
  for(std::size_t c = 0; c < sums.size(); ++c)
    EXPECT_EQ(report.components[c].vertex_index_sum, sums[c]) << "component " << c;

  // face optimality: Σ_{interior halfedges h of f} w_e x(h) = 0, measured against the largest face sum of
  // |w_e x(h)| over the mesh (as check_connection.py does): a per-face ratio is meaningless on faces
  // where x is ~0 (flat regions), where it is only round-off over round-off
  if(all_cycles_constrained) {
    double worst_div = 0, scale = 0; int worst_f = -1;
    for(int f = 0; f < view.nf(); ++f) {
      double div = 0, s = 0;
      for(int h : view.face_he[f])
        if(view.interior_halfedge(h)) {
          const double t = view.weight(h, solver.weighting()) * x[h];
          div += t; s += std::abs(t);
        }
      scale = std::max(scale, s);
      if(!(std::abs(div) <= worst_div)) { worst_div = std::abs(div); worst_f = f; }
    }
    EXPECT_LE(worst_div, tol.optimality * scale)
      << "face optimality violated at face " << worst_f << ": |sum w x| = " << worst_div
      << ", largest face sum of |w x| = " << scale;
  }

  // energy, and the integer choice against per-loop rounding
  const double E = energy(view, x, solver.weighting());
  EXPECT_NEAR(report.energy, E, tol.energy * std::max(1., E)) << "reported energy vs our sum of w_e x_e^2";
  EXPECT_LE(report.energy, report.rounding_energy + tol.energy * std::max(1., report.rounding_energy))
    << "energy-optimal integers are worse than per-loop rounding";
}

/*
  Checks a field (per face number) against a connection: unit, tangent, parallel across every interior
  edge modulo 2 pi / n (our transport, then the rotation by x(h) about the arrival normal), and the seed.
*/
template <class Mesh>
void check_field(const Mesh_view<Mesh>& view, const std::vector<double>& x, const std::vector<Vector>& field, int n,
                 int seed_face = -1, double seed_angle = 0, double tol = 1e-9)
{
  auto V = [&](int f) { return V3{{field[f].x(), field[f].y(), field[f].z()}}; };
  double worst_norm = 0, worst_normal = 0;
  for(int f = 0; f < view.nf(); ++f) {
    const V3 u = V(f);
    worst_norm = std::max(worst_norm, std::abs(norm(u) - 1));
    worst_normal = std::max(worst_normal, std::abs(dot(u, view.N[f])));
    if(!std::isfinite(norm(u))) worst_norm = std::numeric_limits<double>::infinity();
  }
  EXPECT_LT(worst_norm, 1e-12) << "field vectors are not unit";
  EXPECT_LT(worst_normal, 1e-12) << "field vectors are not tangent";
  double worst = 0; int worst_h = -1;
  for(int h : view.interior_edges) {
    const int g = view.hface[view.opp[h]];
    const V3 u = rotate(view.transport(h, V(view.hface[h])), view.N[g], x[h]);
    const double d = std::abs(wrap(signed_angle(u, V(g), view.N[g]), two_pi / n));
    if(!(d <= worst)) { worst = d; worst_h = h; }
  }
  EXPECT_LT(worst, tol) << "field not parallel (mod 2pi/" << n << ") across edge "
                        << (worst_h >= 0 ? std::to_string(view.src[worst_h]) + "-" + std::to_string(view.tgt[worst_h]) : "");
  if(seed_face >= 0) {
    const V3 e = view.frame(seed_face);
    const V3 expected = std::cos(seed_angle) * e + std::sin(seed_angle) * cross(view.N[seed_face], e);
    EXPECT_LT(norm(V(seed_face) - expected), 1e-12) << "field in the seed face is not at the seed angle";
  }
}

// =====================================================================================================
// Solving and checking in one call (the shared helper of test_generated.cpp and test_real_meshes.cpp)
// =====================================================================================================

template <class Mesh>
struct Solution
{
  std::vector<double> x;
  std::vector<Vector> field;
  TC::Solve_report report;
};

/// solve on `solver`, check the connection, then the field seeded at face nf/2 with angle 0.3
template <class Mesh, class Solver>
Solution<Mesh> solve_and_check(const Mesh_view<Mesh>& view, Solver& solver, const Singularities& sing, int n,
                               bool with_field = true, const Tolerances& tol = Tolerances())
{
  Solution<Mesh> s;
  s.report = solver.solve(descriptors(view, sing), view.halfedge_map(s.x), TC::parameters::symmetry_order(n));
  {
    SCOPED_TRACE("connection, n = " + std::to_string(n));
    check_connection(view, solver, sing, n, s.x, s.report, true, tol);
  }
  if(with_field) {
    SCOPED_TRACE("field, n = " + std::to_string(n));
    const int seed = view.nf() / 2;
    solver.compute_field(view.halfedge_map_const(s.x), view.face_map(s.field),
                         TC::parameters::seed_angle(0.3, TC::parameters::seed_face(view.faces[seed])));
    check_field(view, s.x, s.field, n, seed, 0.3, tol.holonomy);
  }
  return s;
}

} // namespace tc_test

#endif // CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_SOLVER_CHECKS_H
