// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// Tests on meshes built here (icosphere, torus, genus-2 surface, flat disk, flat annulus, two spheres),
// every answer checked by the independent code of test_support.h (CONVENTIONS.md from first principles).

#include "test_support.h"

#include <CGAL/Trivial_connections/streamlines.h>

#include <CGAL/Trivial_connections/homology_generators.h>
#include <CGAL/Trivial_connections/trivial_connection.h>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <optional>
#include <vector>

namespace {

using namespace tc_test;
using TC::Weighting;

// ---------------------------------------------------------------------------------------------------
// The generated meshes and what we know about them by construction
// ---------------------------------------------------------------------------------------------------

struct Generated
{
  std::string name;
  Soup soup;
  int components;
  std::vector<long long> chi;     // per component (in our component numbering: face order)
  std::vector<int> boundaries;    // per component
};

const std::vector<Generated>& generated_meshes()
{
  static const std::vector<Generated> meshes = {
    {"icosphere", icosphere_soup(3), 1, {2}, {0}},
    {"torus", torus_soup(2, 0.7, 32, 16), 1, {0}, {0}},
    {"genus2", genus2_soup(2), 1, {-2}, {0}},
    {"disk", disk_soup(6, 20), 1, {1}, {1}},
    {"annulus", annulus_soup(0.5, 1, 5, 30), 1, {0}, {2}},
    {"two_spheres", two_spheres_soup(2), 2, {2, 2}, {0, 0}},
  };
  return meshes;
}

const Generated& generated(const std::string& name)
{
  for(const Generated& g : generated_meshes())
    if(g.name == name) return g;
  throw std::runtime_error("no generated mesh " + name);
}

V3 on_torus(double R, double r, double u, double v)
{
  return {{(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)}};
}

/*
  Singularities chosen for each mesh and n (indices multiples of 1/n, Poincaré–Hopf by hand):
  icosphere: n=1 two +1 at the poles; n=2 four +1/2 at tetrahedron corners; n=4 eight +1/4 at cube
  corners; n=6 twelve +1/6 at the icosahedron's vertices. torus: +1/n and -1/n at generic places.
  genus 2 (chi = -2): n=1 two -1; n=2 four -1/2; n=4 eight -1/4; n=6 -1/2, -1/2, -1/3, -2/3.
  disk: +1/n at the centre, -2/n elsewhere. annulus: +1/n, -1/n. two spheres: 2n times +1/n on the
  first, +1 and n times +1/n on the second.
*/
template <class Mesh>
Singularities designed_singularities(const std::string& name, const Mesh_view<Mesh>& view, int n)
{
  Singularities s;
  auto at = [&](const V3& q, Index k, int comp = -1) { s.emplace_back(nearest_interior_vertex(view, q, comp), k); };
  if(name == "icosphere") {
    const double t = (1 + std::sqrt(5.)) / 2;
    std::vector<V3> dirs;
    if(n == 1) dirs = {{{0, 0, 1}}, {{0, 0, -1}}};
    else if(n == 2) dirs = {{{1, 1, 1}}, {{1, -1, -1}}, {{-1, 1, -1}}, {{-1, -1, 1}}};
    else if(n == 4) { for(int i = 0; i < 8; ++i) dirs.push_back({{i & 1 ? 1. : -1., i & 2 ? 1. : -1., i & 4 ? 1. : -1.}}); }
    else if(n == 6) dirs = {{{-1, t, 0}}, {{1, t, 0}}, {{-1, -t, 0}}, {{1, -t, 0}}, {{0, -1, t}}, {{0, 1, t}},
                            {{0, -1, -t}}, {{0, 1, -t}}, {{t, 0, -1}}, {{t, 0, 1}}, {{-t, 0, -1}}, {{-t, 0, 1}}};
    for(const V3& d : dirs) at(unit(d), Index(1, n));
  } else if(name == "torus") {
    at(on_torus(2, 0.7, 0.3, 0.2), Index(1, n));
    at(on_torus(2, 0.7, 2.5, 3.0), Index(-1, n));
  } else if(name == "genus2") {
    std::vector<Index> k;
    if(n == 6) k = {Index(-1, 2), Index(-1, 2), Index(-1, 3), Index(-2, 3)};
    else k.assign(std::size_t(2 * n), Index(-1, n));
    const std::vector<int> v = spread_interior_vertices(view, 0, int(k.size()));
    for(std::size_t i = 0; i < k.size(); ++i) s.emplace_back(v[i], k[i]);
  } else if(name == "disk") {
    at({{0, 0, 0}}, Index(1, n));
    at({{0.45, 0.2, 0}}, Index(-2, n));
  } else if(name == "annulus") {
    at({{0.7, 0.1, 0}}, Index(1, n));
    at({{-0.2, -0.8, 0}}, Index(-1, n));
  } else if(name == "two_spheres") {
    const std::vector<int> a = spread_interior_vertices(view, 0, 2 * n);
    for(int v : a) s.emplace_back(v, Index(1, n));
    const std::vector<int> b = spread_interior_vertices(view, 1, n + 1);
    s.emplace_back(b[0], Index(1));
    for(int i = 1; i <= n; ++i) s.emplace_back(b[i], Index(1, n));
  }
  // test self-check: distinct interior vertices
  std::set<int> seen;
  for(const auto& p : s) {
    EXPECT_TRUE(p.first >= 0 && view.interior_vertex(p.first));
    EXPECT_TRUE(seen.insert(p.first).second) << "test set-up: vertex " << p.first << " chosen twice";
  }
  return s;
}

template <class Mesh>
using Solver = TC::Trivial_connection_solver<Mesh>;

/// soup number of each vertex of a mesh built from `soup` (matched by exact position)
template <class Mesh>
std::vector<int> soup_numbers(const Mesh_view<Mesh>& view, const Soup& soup)
{
  std::map<std::array<double, 3>, int> of;
  for(std::size_t i = 0; i < soup.points.size(); ++i) {
    const Point& p = soup.points[i];
    EXPECT_TRUE(of.emplace(std::array<double, 3>{{p.x(), p.y(), p.z()}}, int(i)).second) << "duplicate point";
  }
  std::vector<int> r(view.nv(), -1);
  for(int v = 0; v < view.nv(); ++v) r[v] = of.at(view.P[v]);
  return r;
}

void expect_same_connection(const std::map<std::pair<int, int>, double>& a,
                            const std::map<std::pair<int, int>, double>& b, double tol, const std::string& what)
{
  ASSERT_EQ(a.size(), b.size()) << what << ": number of interior edges";
  double worst = 0;
  std::pair<int, int> at{-1, -1};
  for(const auto& kv : a) {
    auto it = b.find(kv.first);
    ASSERT_TRUE(it != b.end()) << what << ": edge " << kv.first.first << "-" << kv.first.second << " missing";
    const double d = std::abs(kv.second - it->second);
    if(!(d <= worst)) { worst = d; at = kv.first; }
  }
  EXPECT_LT(worst, tol) << what << ": largest difference of x at edge " << at.first << "-" << at.second;
}

// ---------------------------------------------------------------------------------------------------
// The builders themselves
// ---------------------------------------------------------------------------------------------------

TEST(Generated_meshes, have_the_intended_topology_and_orientation)
{
  for(const Generated& g : generated_meshes()) {
    SCOPED_TRACE(g.name);
    const Surface_mesh sm = to_surface_mesh(g.soup);
    ASSERT_TRUE(CGAL::is_valid_polygon_mesh(sm));
    ASSERT_TRUE(CGAL::is_triangle_mesh(sm));
    const Mesh_view<Surface_mesh> view(sm);
    ASSERT_EQ(view.ncomp, g.components);
    for(int c = 0; c < view.ncomp; ++c) {
      EXPECT_EQ(view.chi[c], g.chi[c]) << "component " << c;
      EXPECT_EQ(view.boundary_count[c], g.boundaries[c]) << "component " << c;
    }
    // every vertex is manifold: its faces form one fan
    for(auto v : vertices(sm)) {
      int faces_reached = 0, borders = 0;
      for(auto h : CGAL::halfedges_around_target(v, sm)) (is_border(h, sm) ? borders : faces_reached)++;
      EXPECT_EQ(faces_reached, view.faces_at[view.vid.at(v)]) << "vertex " << view.vid.at(v);
      EXPECT_LE(borders, 1);
    }
    // non-degenerate faces; outward orientation: positive volume (closed) or +z normals (flat)
    double min_area = 1e300, volume = 0;
    for(int f = 0; f < view.nf(); ++f) {
      const auto& h = view.face_he[f];
      const V3 &a = view.P[view.src[h[0]]], &b = view.P[view.src[h[1]]], &c = view.P[view.src[h[2]]];
      min_area = std::min(min_area, 0.5 * norm(cross(b - a, c - a)));
      volume += dot(a, cross(b, c)) / 6;
      if(g.boundaries[0] > 0) EXPECT_GT(view.N[f][2], 0.999) << "flat mesh face " << f << " not facing +z";
    }
    EXPECT_GT(min_area, 1e-4);
    if(g.boundaries[0] == 0) EXPECT_GT(volume, 0.1) << "closed mesh not oriented outward";
  }
  // the Polyhedron_3 copy has the same vertices in the same order
  const Soup& s = generated("genus2").soup;
  const Polyhedron P = to_polyhedron(s);
  const Mesh_view<Polyhedron> pv(P);
  ASSERT_EQ(pv.nv(), int(s.points.size()));
  ASSERT_EQ(pv.nf(), int(s.faces.size()));
  EXPECT_EQ(pv.chi[0], -2);
  // renumbering keeps the surface
  std::vector<int> perm;
  const Soup r = renumbered(s, 7, &perm, true);
  const Surface_mesh rs = to_surface_mesh(r);
  const Mesh_view<Surface_mesh> rv(rs);
  EXPECT_EQ(rv.chi[0], -2);
  for(std::size_t i = 0; i < perm.size(); ++i) EXPECT_EQ(r.points[perm[i]], s.points[i]);
}

// ---------------------------------------------------------------------------------------------------
// Every check, on every generated mesh, n = 1, 2, 4, 6, both weightings, Surface_mesh and Polyhedron_3
// ---------------------------------------------------------------------------------------------------

using Case = std::tuple<std::string, int, Weighting>;

class All_checks : public ::testing::TestWithParam<Case>
{
};

template <class Mesh>
void run_all_checks(const std::string& name, int n, Weighting w)
{
  const Mesh tm = soup_to_mesh<Mesh>(generated(name).soup);
  const Mesh_view<Mesh> view(tm);
  Solver<Mesh> solver(tm, TC::parameters::weighting(w));
  EXPECT_EQ(solver.weighting(), w);
  {
    SCOPED_TRACE("solver geometry");
    check_solver_geometry(view, solver);
  }
  {
    SCOPED_TRACE("solver loops");
    check_loops(view, solver);
  }
  const Singularities sing = designed_singularities(name, view, n);
  const Solution<Mesh> s = solve_and_check(view, solver, sing, n);
  EXPECT_LT(s.report.max_vertex_residual, 1e-9);
  EXPECT_LT(s.report.max_loop_residual, 1e-9);
}

TEST_P(All_checks, surface_mesh)
{
  const auto& [name, n, w] = GetParam();
  run_all_checks<Surface_mesh>(name, n, w);
}

TEST_P(All_checks, polyhedron)
{
  const auto& [name, n, w] = GetParam();
  run_all_checks<Polyhedron>(name, n, w);
}

std::string case_name(const ::testing::TestParamInfo<Case>& info)
{
  return std::get<0>(info.param) + "_n" + std::to_string(std::get<1>(info.param)) +
         (std::get<2>(info.param) == Weighting::unit ? "_unit" : "_hodge");
}

INSTANTIATE_TEST_SUITE_P(Generated, All_checks,
                         ::testing::Combine(::testing::Values("icosphere", "torus", "genus2", "disk", "annulus",
                                                              "two_spheres"),
                                            ::testing::Values(1, 2, 4, 6),
                                            ::testing::Values(Weighting::hodge_star, Weighting::unit)),
                         case_name);

// ---------------------------------------------------------------------------------------------------
// Values known from CONVENTIONS.md alone
// ---------------------------------------------------------------------------------------------------

// Meshes large enough for the numeric factorization to run on two threads (ldlt_on_two_threads.h, above about
// 1e7 flops): a torus (its generator rows come last, with the separators at the root) and a disk (its boundary
// one node), every check.
TEST(Large_meshes, every_check_with_the_factorization_on_two_threads)
{
  const std::vector<std::pair<std::string, Surface_mesh>> meshes = {{"torus", torus(1, 0.4, 240, 96)},
                                                                    {"disk", disk(100, 300)}};
  for(const auto& [name, tm] : meshes) {
    SCOPED_TRACE(name);
    const Mesh_view<Surface_mesh> view(tm);
    Solver<Surface_mesh> solver(tm);
    check_loops(view, solver);
    const Singularities sing = plan_singularities(view, 4);
    const Solution<Surface_mesh> s = solve_and_check(view, solver, sing, 4);
    EXPECT_LT(s.report.max_vertex_residual, 1e-9);
    EXPECT_LT(s.report.max_loop_residual, 1e-9);
  }
}

TEST(Known_values, flat_disk_without_singularities_is_a_constant_field_with_boundary_index_1)
{
  // a constant field is parallel for x = 0 (flat), has energy 0 (optimal) and k_B = 1 (CONVENTIONS.md)
  for(Weighting w : {Weighting::hodge_star, Weighting::unit})
    for(int n : {1, 4}) {
      const Surface_mesh sm = to_surface_mesh(generated("disk").soup);
      const Mesh_view<Surface_mesh> view(sm);
      Solver<Surface_mesh> solver(sm, TC::parameters::weighting(w));
      const Solution<Surface_mesh> s = solve_and_check(view, solver, {}, n);
      for(int h : view.interior_halfedges) ASSERT_LT(std::abs(s.x[h]), 1e-12);
      EXPECT_LT(s.report.energy, 1e-20);
      ASSERT_EQ(s.report.loops.size(), 1u);
      EXPECT_EQ(s.report.loops[0].index, Index(1));
      for(int f = 1; f < view.nf(); ++f)
        ASSERT_LT(norm(V3{{s.field[f].x() - s.field[0].x(), s.field[f].y() - s.field[0].y(), 0}}), 1e-12);
    }
}

TEST(Known_values, flat_annulus_without_singularities_has_boundary_indices_plus_and_minus_1)
{
  const Surface_mesh sm = to_surface_mesh(generated("annulus").soup);
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm);
  const Solution<Surface_mesh> s = solve_and_check(view, solver, {}, 1);
  EXPECT_LT(s.report.energy, 1e-20);
  for(int h : view.interior_halfedges) ASSERT_LT(std::abs(s.x[h]), 1e-12);
  ASSERT_EQ(s.report.loops.size(), 2u);
  // the outer loop turns by +2pi, the inner one by -2pi
  for(std::size_t l = 0; l < 2; ++l) {
    const int b = boundary_loop_of(view, solver, l);
    const bool outer = norm(view.P[view.boundary_loops[b].vertices[0]]) > 0.75;
    EXPECT_EQ(s.report.loops[l].index, Index(outer ? 1 : -1)) << "loop " << l;
  }
}

TEST(Known_values, sphere_levi_civita_holonomy_and_defects_sum_to_4pi)
{
  // Gauss–Bonnet: the angle defects of a closed genus-0 mesh sum to 4 pi
  const Surface_mesh sm = to_surface_mesh(generated("icosphere").soup);
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm);
  double sum = 0;
  for(auto v : vertices(sm)) sum += solver.angle_defect(v);
  EXPECT_NEAR(sum, 4 * pi, 1e-9);
}

// ---------------------------------------------------------------------------------------------------
// Energy-optimal integers: never worse than rounding, and best among all neighbours (brute force)
// ---------------------------------------------------------------------------------------------------

class Brute_force : public ::testing::TestWithParam<Case>
{
};

TEST_P(Brute_force, no_neighbouring_integers_have_lower_energy)
{
  const auto& [name, n, w] = GetParam();
  const Surface_mesh sm = to_surface_mesh(generated(name).soup);
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm, TC::parameters::weighting(w));
  const Singularities sing = designed_singularities(name, view, n);
  const Solution<Surface_mesh> best = solve_and_check(view, solver, sing, n, false);
  ASSERT_FALSE(best.report.loops.empty());
  EXPECT_LE(best.report.energy, best.report.rounding_energy * (1 + 1e-12) + 1e-12);
  int dimension = 0;
  const long long tried = check_integers_by_enumeration(view, solver, sing, n, best.report, 2, &dimension);
  // free integers: 2g generators + (boundary loops - 1), known by construction
  const int expected_dimension = name == "torus" ? 2 : name == "genus2" ? 4 : 1;
  EXPECT_EQ(dimension, expected_dimension);
  EXPECT_EQ(tried, (long long)std::pow(5, expected_dimension));
  // after the prescribed solves, the default solve still gives the same answer
  std::vector<double> x;
  const TC::Solve_report again = solver.solve(descriptors(view, sing), view.halfedge_map(x),
                                              TC::parameters::symmetry_order(n));
  for(int h : view.interior_halfedges) ASSERT_EQ(x[h], best.x[h]);
  for(std::size_t l = 0; l < again.loops.size(); ++l) EXPECT_FALSE(again.loops[l].prescribed);
}

INSTANTIATE_TEST_SUITE_P(Small_genus, Brute_force,
                         ::testing::Combine(::testing::Values("torus", "genus2", "annulus"), ::testing::Values(1, 4),
                                            ::testing::Values(Weighting::hodge_star, Weighting::unit)),
                         case_name);

// ---------------------------------------------------------------------------------------------------
// Independence of the representation: vertex numbering, face order, Surface_mesh vs Polyhedron_3
// ---------------------------------------------------------------------------------------------------

class Representation : public ::testing::TestWithParam<std::string>
{
};

TEST_P(Representation, result_does_not_depend_on_vertex_numbering_or_face_order)
{
  const Generated& g = generated(GetParam());
  for(int n : {1, 4}) {
    const Surface_mesh a = to_surface_mesh(g.soup);
    const Mesh_view<Surface_mesh> va(a);
    Solver<Surface_mesh> sa(a);
    const Singularities sing = designed_singularities(g.name, va, n);
    const Solution<Surface_mesh> ra = solve_and_check(va, sa, sing, n, false);
    const auto xa = x_by_vertex_pair(va, ra.x, soup_numbers(va, g.soup));
    for(bool shuffle_faces : {false, true}) {
      SCOPED_TRACE(std::string("n = ") + std::to_string(n) + (shuffle_faces ? ", faces shuffled" : ", vertices only"));
      std::vector<int> perm;
      const Soup r = renumbered(g.soup, 12345u + unsigned(n), &perm, shuffle_faces);
      const Surface_mesh b = to_surface_mesh(r);
      const Mesh_view<Surface_mesh> vb(b);
      Solver<Surface_mesh> sb(b);
      Singularities moved;
      for(const auto& p : sing) moved.emplace_back(perm[p.first], p.second);
      const Solution<Surface_mesh> rb = solve_and_check(vb, sb, moved, n, false);
      EXPECT_NEAR(rb.report.energy, ra.report.energy, 1e-9 * std::max(1., ra.report.energy));
      // compare in the numbering of the original soup
      std::vector<int> back(perm.size());
      for(std::size_t i = 0; i < perm.size(); ++i) back[perm[i]] = int(i);
      std::vector<int> original_of(vb.nv());
      const std::vector<int> numbers = soup_numbers(vb, r);
      for(int v = 0; v < vb.nv(); ++v) original_of[v] = back[numbers[v]];
      expect_same_connection(xa, x_by_vertex_pair(vb, rb.x, original_of), 1e-9, "renumbered");
    }
  }
}

TEST_P(Representation, surface_mesh_and_polyhedron_give_the_same_connection)
{
  const Generated& g = generated(GetParam());
  for(Weighting w : {Weighting::hodge_star, Weighting::unit}) {
    const Surface_mesh a = to_surface_mesh(g.soup);
    const Polyhedron b = to_polyhedron(g.soup);
    const Mesh_view<Surface_mesh> va(a);
    const Mesh_view<Polyhedron> vb(b);
    Solver<Surface_mesh> sa(a, TC::parameters::weighting(w));
    Solver<Polyhedron> sb(b, TC::parameters::weighting(w));
    EXPECT_EQ(sa.loops().size(), sb.loops().size());
    const std::vector<int> na = soup_numbers(va, g.soup), nb = soup_numbers(vb, g.soup);
    // same singularities by soup number
    const Singularities sing_a = designed_singularities(g.name, va, 4);
    std::vector<int> vb_of_soup(nb.size());
    for(int v = 0; v < vb.nv(); ++v) vb_of_soup[nb[v]] = v;
    Singularities sing_b;
    for(const auto& p : sing_a) sing_b.emplace_back(vb_of_soup[na[p.first]], p.second);
    const Solution<Surface_mesh> ra = solve_and_check(va, sa, sing_a, 4);
    const Solution<Polyhedron> rb = solve_and_check(vb, sb, sing_b, 4);
    EXPECT_NEAR(ra.report.energy, rb.report.energy, 1e-9 * std::max(1., ra.report.energy));
    expect_same_connection(x_by_vertex_pair(va, ra.x, na), x_by_vertex_pair(vb, rb.x, nb), 1e-9,
                           "Surface_mesh vs Polyhedron_3");
  }
}

INSTANTIATE_TEST_SUITE_P(Generated, Representation,
                         ::testing::Values("icosphere", "torus", "genus2", "disk", "annulus", "two_spheres"));

// ---------------------------------------------------------------------------------------------------
// One prefactored solver, many solves = fresh solvers; free functions = the class
// ---------------------------------------------------------------------------------------------------

TEST(Prefactored_solver, gives_the_same_answers_as_fresh_solvers)
{
  for(const std::string name : {"torus", "genus2", "annulus", "two_spheres"}) {
    SCOPED_TRACE(name);
    const Surface_mesh sm = to_surface_mesh(generated(name).soup);
    const Mesh_view<Surface_mesh> view(sm);
    const Singularities A = designed_singularities(name, view, 4);
    const Singularities B = designed_singularities(name, view, 2);
    Solver<Surface_mesh> reused(sm);
    const Solution<Surface_mesh> a1 = solve_and_check(view, reused, A, 4);
    const Solution<Surface_mesh> b1 = solve_and_check(view, reused, B, 2);
    const Solution<Surface_mesh> a2 = solve_and_check(view, reused, A, 4);
    Solver<Surface_mesh> fresh_a(sm), fresh_b(sm);
    const Solution<Surface_mesh> a3 = solve_and_check(view, fresh_a, A, 4);
    const Solution<Surface_mesh> b3 = solve_and_check(view, fresh_b, B, 2);
    for(int h : view.interior_halfedges) {
      ASSERT_NEAR(a2.x[h], a3.x[h], 1e-12);
      ASSERT_NEAR(a1.x[h], a3.x[h], 1e-12);
      ASSERT_NEAR(b1.x[h], b3.x[h], 1e-12);
    }
    EXPECT_NEAR(a2.report.energy, a3.report.energy, 1e-12 * std::max(1., a3.report.energy));
    EXPECT_NEAR(b1.report.energy, b3.report.energy, 1e-12 * std::max(1., b3.report.energy));
    for(std::size_t l = 0; l < a3.report.loops.size(); ++l) {
      EXPECT_EQ(a2.report.loops[l].period, a3.report.loops[l].period);
      EXPECT_EQ(b1.report.loops[l].period, b3.report.loops[l].period);
    }
    for(int f = 0; f < view.nf(); ++f) {
      ASSERT_LT(std::abs(a2.field[f].x() - a3.field[f].x()) + std::abs(a2.field[f].y() - a3.field[f].y()) +
                  std::abs(a2.field[f].z() - a3.field[f].z()), 1e-12);
    }
  }
}

/*
  Thread safety: one prefactored solver, solve() and compute_field() called from four threads at once, each
  thread cycling through singularity sets of different n, give exactly the answers of the same calls made one
  after the other. With the package's backends the substitutions only read the factor; with a backend it
  does not know (Eigen's LDLT with its own ordering) the solver serialises the backend's solves.
*/
template <class Traits>
void expect_concurrent_solves_like_sequential_ones()
{
  for(const std::string name : {"torus", "genus2", "annulus", "two_spheres"}) {
    SCOPED_TRACE(name);
    const Surface_mesh sm = to_surface_mesh(generated(name).soup);
    const Mesh_view<Surface_mesh> view(sm);
    const std::vector<std::pair<Singularities, int>> tasks = {{designed_singularities(name, view, 4), 4},
                                                              {designed_singularities(name, view, 2), 2},
                                                              {designed_singularities(name, view, 1), 1}};
    TC::Trivial_connection_solver<Surface_mesh, CGAL::Default, Traits> solver(sm);
    struct Answer
    {
      std::vector<double> x;
      std::vector<K::Vector_3> field;
      std::vector<std::int64_t> periods;
    };
    auto answer = [&](std::size_t t) {
      Answer a;
      const TC::Solve_report r = solver.solve(descriptors(view, tasks[t].first), view.halfedge_map(a.x),
                                              TC::parameters::symmetry_order(tasks[t].second));
      solver.compute_field(view.halfedge_map_const(a.x), view.face_map(a.field));
      for(const TC::Loop_report& l : r.loops)
        a.periods.push_back(l.period);
      return a;
    };
    std::vector<Answer> sequential;
    for(std::size_t t = 0; t < tasks.size(); ++t)
      sequential.push_back(answer(t));

    const int threads = 4, rounds = 6;
    std::vector<std::vector<Answer>> concurrent(threads);
    std::vector<std::string> errors(threads);
    std::vector<std::thread> pool;
    for(int i = 0; i < threads; ++i)
      pool.emplace_back([&, i] {
        try {
          for(int r = 0; r < rounds; ++r)
            concurrent[i].push_back(answer(std::size_t(i + r) % tasks.size()));
        } catch(const std::exception& e) {
          errors[i] = e.what();
        }
      });
    for(std::thread& t : pool)
      t.join();
    for(int i = 0; i < threads; ++i) {
      ASSERT_EQ(errors[i], "") << "thread " << i;
      ASSERT_EQ(concurrent[i].size(), std::size_t(rounds));
      for(int r = 0; r < rounds; ++r) {
        const Answer& got = concurrent[i][r];
        const Answer& expected = sequential[std::size_t(i + r) % tasks.size()];
        EXPECT_EQ(got.periods, expected.periods) << "thread " << i << ", round " << r;
        ASSERT_EQ(got.x.size(), expected.x.size());
        std::size_t differing = 0;
        for(std::size_t h = 0; h < got.x.size(); ++h)
          differing += got.x[h] != expected.x[h];
        for(std::size_t f = 0; f < got.field.size(); ++f)
          differing += got.field[f] != expected.field[f];
        EXPECT_EQ(differing, 0u) << "thread " << i << ", round " << r << ": values not bitwise identical";
      }
    }
  }
}

TEST(Thread_safety, concurrent_solves_on_one_solver_give_the_sequential_answers)
{
  expect_concurrent_solves_like_sequential_ones<TC::Default_solver_traits>();
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  expect_concurrent_solves_like_sequential_ones<TC::Cholmod_solver_traits>();
  expect_concurrent_solves_like_sequential_ones<TC::Automatic_solver_traits>();
  expect_concurrent_solves_like_sequential_ones<TC::Cost_based_solver_traits<Always_supernodal>>();
#endif
  // a backend without factor access: its solves run under the solver's lock
  expect_concurrent_solves_like_sequential_ones<
    CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>>();
}

/*
  The progress callback: every phase starts (fraction 0) before it ends (fraction 1), fractions stay in
  [0, 1], phases come in the documented order, the constructor reports mesh set-up to loop metric, solve()
  its solve (with loop integers inside it on a torus), compute_field() the field. A callback that throws
  cancels the call, and the exception reaches the caller.
*/
TEST(Progress, phases_are_reported_in_order_and_can_cancel)
{
  const Surface_mesh sm = to_surface_mesh(generated("torus").soup);
  const Mesh_view<Surface_mesh> view(sm);
  std::vector<std::pair<TC::Phase, double>> events;
  TC::Progress_callback record = [&](TC::Phase p, double fraction) { events.emplace_back(p, fraction); };
  auto check_events = [&](std::initializer_list<TC::Phase> expected_outer) {
    std::vector<TC::Phase> open, started;
    for(const auto& [p, fraction] : events) {
      EXPECT_GE(fraction, 0.);
      EXPECT_LE(fraction, 1.);
      if(fraction == 0) {
        open.push_back(p);
        started.push_back(p);
      } else if(fraction == 1) {
        ASSERT_FALSE(open.empty()) << TC::phase_name(p) << " ended without starting";
        EXPECT_EQ(open.back(), p) << TC::phase_name(p) << " ended inside another phase";
        open.pop_back();
      }
    }
    EXPECT_TRUE(open.empty());
    for(std::size_t i = 1; i < started.size(); ++i)
      EXPECT_LT(int(started[i - 1]), int(started[i])) << "phases out of order";
    std::vector<TC::Phase> expected(expected_outer);
    for(TC::Phase p : expected)
      EXPECT_NE(std::find(started.begin(), started.end(), p), started.end()) << TC::phase_name(p) << " missing";
    events.clear();
  };
  Solver<Surface_mesh> solver(sm, TC::parameters::progress(record));
  check_events({TC::Phase::mesh_setup, TC::Phase::geometry, TC::Phase::trees, TC::Phase::assembly,
                TC::Phase::factorization, TC::Phase::loop_metric});
  std::vector<double> x;
  solver.solve(descriptors(view, Singularities()), view.halfedge_map(x), TC::parameters::progress(record));
  check_events({TC::Phase::solve, TC::Phase::loop_integers});
  std::vector<Vector> field(std::size_t(view.nf()));
  solver.compute_field(view.halfedge_map_const(x), view.face_map(field), TC::parameters::progress(record));
  check_events({TC::Phase::field});
  solver.solve(descriptors(view, Singularities()), view.halfedge_map(x));
  EXPECT_TRUE(events.empty()) << "the constructor's callback must not be called after it returned";

  struct Cancelled {};
  TC::Progress_callback cancel = [](TC::Phase p, double) { if(p == TC::Phase::factorization) throw Cancelled(); };
  EXPECT_THROW(Solver<Surface_mesh>(sm, TC::parameters::progress(cancel)), Cancelled);
}

TEST(Free_functions, agree_with_the_class)
{
  for(const std::string name : {"genus2", "annulus", "two_spheres"})
    for(Weighting w : {Weighting::hodge_star, Weighting::unit}) {
      SCOPED_TRACE(name);
      const Surface_mesh sm = to_surface_mesh(generated(name).soup);
      const Mesh_view<Surface_mesh> view(sm);
      const Singularities sing = designed_singularities(name, view, 4);
      Solver<Surface_mesh> solver(sm, TC::parameters::weighting(w));
      const Solution<Surface_mesh> s = solve_and_check(view, solver, sing, 4);

      std::vector<double> x1, x2;
      std::vector<Vector> field;
      const TC::Solve_report r1 = TC::compute_trivial_connection(
        sm, descriptors(view, sing), view.halfedge_map(x1), TC::parameters::weighting(w, TC::parameters::symmetry_order(4)));
      const int seed = view.nf() / 2;
      const TC::Solve_report r2 = TC::compute_direction_field(
        sm, descriptors(view, sing), view.halfedge_map(x2), view.face_map(field),
        TC::parameters::seed_angle(0.3, TC::parameters::seed_face(view.faces[seed],
                                        TC::parameters::weighting(w, TC::parameters::symmetry_order(4)))));
      for(int h = 0; h < view.nh(); ++h) {
        ASSERT_NEAR(x1[h], s.x[h], 1e-12);
        ASSERT_NEAR(x2[h], s.x[h], 1e-12);
      }
      EXPECT_NEAR(r1.energy, s.report.energy, 1e-12 * std::max(1., s.report.energy));
      EXPECT_NEAR(r2.energy, s.report.energy, 1e-12 * std::max(1., s.report.energy));
      for(int f = 0; f < view.nf(); ++f)
        ASSERT_LT(std::abs(field[f].x() - s.field[f].x()) + std::abs(field[f].y() - s.field[f].y()) +
                    std::abs(field[f].z() - s.field[f].z()), 1e-12);
      check_field(view, x2, field, 4, seed, 0.3);
    }
}

// ---------------------------------------------------------------------------------------------------
// homology_generators(): 2g closed loops per component, a basis of the homology
// ---------------------------------------------------------------------------------------------------

Soup genus3_soup()
{
  std::set<std::array<int, 3>> cells;
  for(int i = 0; i < 3; ++i)
    for(int j = 0; j < 7; ++j)
      if(!(i == 1 && (j == 1 || j == 3 || j == 5))) cells.insert({{i, j, 0}});
  return warped(voxel_surface_soup(cells, 1));
}

template <class Mesh>
void check_homology_generators(const Soup& soup, int expected_generators)
{
  const Mesh tm = soup_to_mesh<Mesh>(soup);
  const Mesh_view<Mesh> view(tm);
  const auto loops = TC::homology_generators(tm);
  ASSERT_EQ(int(loops.size()), expected_generators);
  std::vector<std::vector<int>> numbered;
  for(const auto& L : loops) {
    numbered.emplace_back();
    for(auto h : L) numbered.back().push_back(view.hid.at(h));
    bool closed = false;
    loop_rotation(view, numbered.back(), nullptr, closed);
    EXPECT_TRUE(closed) << "generator " << numbered.size() - 1 << " is not a closed dual loop";
  }
  check_generators_independent(view, numbered);
  // the solver's generators too
  Solver<Mesh> solver(tm);
  std::vector<std::vector<int>> from_solver;
  const auto all = loops_as_numbers(view, solver);
  for(std::size_t l = 0; l < all.size(); ++l)
    if(solver.loops()[l].kind == TC::Loop_kind::generator) from_solver.push_back(all[l]);
  EXPECT_EQ(int(from_solver.size()), expected_generators);
  check_generators_independent(view, from_solver);
}

TEST(Homology_generators, are_2g_closed_independent_loops_per_component)
{
  struct C { std::string what; Soup soup; int generators; };
  const std::vector<C> cases = {
    {"icosphere", icosphere_soup(1), 0},
    {"torus", torus_soup(2, 0.7, 12, 8), 2},
    {"genus2", genus2_soup(1), 4},
    {"genus3", genus3_soup(), 6},
    {"annulus", annulus_soup(0.5, 1, 2, 12), 0},
    {"two tori", concatenate(torus_soup(2, 0.7, 12, 8), torus_soup(1, 0.3, 10, 6)), 4},
    {"torus and genus2", concatenate(torus_soup(2, 0.7, 12, 8), genus2_soup(1)), 6},
  };
  for(const C& c : cases) {
    SCOPED_TRACE(c.what);
    check_homology_generators<Surface_mesh>(c.soup, c.generators);
    check_homology_generators<Polyhedron>(c.soup, c.generators);
  }
}

TEST(Homology_generators, multi_component_meshes_get_every_check)
{
  // a torus and a genus-2 surface in one mesh: Poincaré–Hopf per component (0 and -2)
  const Soup soup = concatenate(torus_soup(2, 0.7, 24, 12), genus2_soup(1));
  const Surface_mesh sm = to_surface_mesh(soup);
  const Mesh_view<Surface_mesh> view(sm);
  ASSERT_EQ(view.ncomp, 2);
  Solver<Surface_mesh> solver(sm);
  check_solver_geometry(view, solver);
  check_loops(view, solver);
  for(int n : {1, 4}) {
    const Singularities sing = plan_singularities(view, n);
    const Solution<Surface_mesh> s = solve_and_check(view, solver, sing, n);
    check_integers_by_enumeration(view, solver, sing, n, s.report, 1);
  }
}

// ---------------------------------------------------------------------------------------------------
// The independent checks are not vacuous: deliberately wrong answers must fail them
// ---------------------------------------------------------------------------------------------------

/// true when running f() records a failure whose message contains `text` (failures are intercepted)
template <class F>
bool fails_with(F&& f, const std::string& text)
{
  ::testing::TestPartResultArray results;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(
      ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    f();
  }
  for(int i = 0; i < results.size(); ++i)
    if(std::string(results.GetTestPartResult(i).message()).find(text) != std::string::npos) return true;
  return false;
}

TEST(Checker_self_test, wrong_connections_fields_and_integers_are_caught)
{
  const Surface_mesh sm = to_surface_mesh(generated("torus").soup);
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm);
  const Singularities sing = designed_singularities("torus", view, 2);
  const Solution<Surface_mesh> s = solve_and_check(view, solver, sing, 2);
  std::vector<double> negated = s.x;
  for(double& t : negated) t = -t;
  EXPECT_TRUE(fails_with([&] { check_connection(view, solver, sing, 2, negated, s.report); }, "holonomy residual"));
  std::vector<double> perturbed = s.x;
  perturbed[view.interior_edges[7]] += 1e-6;
  perturbed[view.opp[view.interior_edges[7]]] -= 1e-6;
  EXPECT_TRUE(fails_with([&] { check_connection(view, solver, sing, 2, perturbed, s.report); }, "holonomy residual"));
  // moving a unit of curl around one face keeps every holonomy but breaks optimality
  std::vector<double> curl = s.x;
  for(int h : view.face_he[3])
    if(view.interior_halfedge(h)) { curl[h] += 0.1; curl[view.opp[h]] -= 0.1; }
  EXPECT_TRUE(fails_with([&] { check_connection(view, solver, sing, 2, curl, s.report); }, "face optimality"));
  EXPECT_TRUE(fails_with([&] { check_field(view, negated, s.field, 2); }, "not parallel"));
  std::vector<Vector> turned = s.field;
  turned[5] = -turned[5]; // fine for n = 2, not for n = 1
  check_field(view, s.x, turned, 2);
  EXPECT_TRUE(fails_with([&] { check_field(view, s.x, turned, 1); }, "not parallel"));
  // a report whose integers are one off is beaten by the brute force
  TC::Solve_report worse = s.report;
  std::vector<std::int64_t> periods;
  for(const auto& l : worse.loops) periods.push_back(l.period);
  periods[0] += 1;
  std::vector<double> xw;
  worse = solver.solve(descriptors(view, sing), view.halfedge_map(xw),
                       TC::parameters::loop_periods(periods, TC::parameters::symmetry_order(2)));
  EXPECT_GT(worse.energy, s.report.energy);
  EXPECT_TRUE(fails_with([&] { check_integers_by_enumeration(view, solver, sing, 2, worse, 1); }, "brute force found lower energy"));
}


// ---------------------------------------------------------------------------------------------------
// The closest-vector search on its own: random lattices against an exhaustive search of a box that
// contains the optimum (a ball of radius sqrt(q(rounding)) around c, bounded through G's smallest eigenvalue)
// ---------------------------------------------------------------------------------------------------

TEST(Closest_vector, matches_exhaustive_search_on_random_lattices)
{
  std::mt19937 random(20261123);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  int proven = 0;
  for(int trial = 0; trial < 300; ++trial) {
    const int k = 1 + trial % 4;
    // G = B^T B with a skewed B, so that rounding c is often not optimal
    Eigen::MatrixXd B(k, k);
    for(int i = 0; i < k; ++i)
      for(int j = 0; j < k; ++j)
        B(i, j) = uniform(random) + (i == j ? 0.3 : 0.);
    const Eigen::MatrixXd G = B.transpose() * B + 1e-3 * Eigen::MatrixXd::Identity(k, k);
    Eigen::VectorXd c(k);
    for(int i = 0; i < k; ++i)
      c[i] = 3 * uniform(random);
    Eigen::LLT<Eigen::MatrixXd> llt(G);
    ASSERT_EQ(llt.info(), Eigen::Success);
    const Eigen::MatrixXd R = llt.matrixU();
    std::vector<std::int64_t> rounded(k);
    for(int i = 0; i < k; ++i)
      rounded[i] = std::int64_t(std::llround(c[i]));
    auto q = [&](const std::vector<std::int64_t>& m) {
      Eigen::VectorXd d(k);
      for(int i = 0; i < k; ++i)
        d[i] = double(m[i]) - c[i];
      return d.dot(G * d);
    };

    const TC::internal::Closest_vector_result result = TC::internal::closest_vector(G, c, {rounded});
    ASSERT_EQ(int(result.m.size()), k);
    EXPECT_NEAR(result.value, q(result.m), 1e-9 * (1 + q(result.m)));
    EXPECT_LE(q(result.m), q(rounded) + 1e-12);
    if(!result.proven)
      continue;
    ++proven;

    // every integer point with q < q(rounded) lies within |m - c| <= sqrt(q(rounded) / lambda_min(G))
    const double lambda_min = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(G).eigenvalues()[0];
    const double radius = std::sqrt(q(rounded) / lambda_min);
    std::vector<std::int64_t> low(k), high(k), m(k);
    for(int i = 0; i < k; ++i) {
      low[i] = std::int64_t(std::floor(c[i] - radius));
      high[i] = std::int64_t(std::ceil(c[i] + radius));
    }
    if(std::pow(double(high[0] - low[0] + 1), k) > 2e6)
      continue; // too large a box for a test
    double best = std::numeric_limits<double>::infinity();
    m = low;
    while(true) {
      best = (std::min)(best, q(m));
      int i = 0;
      while(i < k && m[i] == high[i])
        m[i] = low[i], ++i;
      if(i == k)
        break;
      ++m[i];
    }
    EXPECT_NEAR(q(result.m), best, 1e-9 * (1 + best)) << "trial " << trial << ", k = " << k;
  }
  EXPECT_GT(proven, 250); // small k: the enumeration finishes
}

} // namespace

// ---------------------------------------------------------------------------------------------------
// Loop integers prescribed in part (std::optional entries of loop_periods): the prescribed ones are
// kept, the others minimise the energy with them fixed (checked by brute force over the others), and
// the boundary loops of a component are prescribed all or none.
// ---------------------------------------------------------------------------------------------------

namespace {

// a torus with two triangular holes: genus 1, two boundary loops, chi = -2
Soup holed_torus_soup()
{
  Soup s = torus_soup(2, 0.7, 16, 8);
  s.faces.erase(s.faces.begin() + 120);
  s.faces.erase(s.faces.begin());
  return s;
}

std::vector<std::int64_t> periods_of(const TC::Solve_report& r)
{
  std::vector<std::int64_t> p;
  for(const auto& l : r.loops) p.push_back(l.period);
  return p;
}

// Every combination of the loops in `free` within +-radius of `chosen` (the others as in `chosen`),
// prescribed in full, has an energy (recomputed by us) at least the one of `chosen`, and `chosen` itself
// gives that energy.
void expect_best_over(const Mesh_view<Surface_mesh>& view, Solver<Surface_mesh>& solver, const Singularities& sing,
                      int n, const std::vector<std::int64_t>& chosen, double energy, const std::vector<int>& free,
                      int radius)
{
  std::vector<int> offset(free.size(), -radius);
  for(;;) {
    std::vector<std::int64_t> periods = chosen;
    for(std::size_t i = 0; i < free.size(); ++i) periods[free[i]] += offset[i];
    std::vector<double> x;
    const TC::Solve_report r = solver.solve(descriptors(view, sing), view.halfedge_map(x),
                                            TC::parameters::loop_periods(periods, TC::parameters::symmetry_order(n)));
    EXPECT_LT(r.max_vertex_residual, 1e-9);
    EXPECT_LT(r.max_loop_residual, 1e-9);
    const double E = tc_test::energy(view, x, solver.weighting());
    const bool at_chosen = std::all_of(offset.begin(), offset.end(), [](int o) { return o == 0; });
    if(at_chosen)
      EXPECT_NEAR(E, energy, 1e-9 * std::max(1., energy));
    else
      EXPECT_GE(E, energy - 1e-9 * std::max(1., energy)) << "brute force found a lower energy";
    std::size_t i = 0;
    for(; i < offset.size(); ++i) {
      if(++offset[i] <= radius) break;
      offset[i] = -radius;
    }
    if(i == offset.size()) break;
  }
}

} // namespace

TEST(Partial_loop_periods, boundary_loops_prescribed_generators_chosen_optimally)
{
  const Surface_mesh sm = to_surface_mesh(holed_torus_soup());
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm);
  const auto& loops = solver.loops();
  ASSERT_EQ(loops.size(), 4u); // two boundary loops, two generators
  const int n = 4;
  const Singularities none;
  std::vector<double> x0;
  const TC::Solve_report free_report = solver.solve(descriptors(view, none), view.halfedge_map(x0),
                                                    TC::parameters::symmetry_order(n));
  // move one unit of index from one hole to the other (Poincare-Hopf keeps the sum)
  std::vector<std::optional<std::int64_t>> given(loops.size());
  std::vector<int> boundary, generators;
  for(std::size_t l = 0; l < loops.size(); ++l)
    (loops[l].kind == TC::Loop_kind::boundary ? boundary : generators).push_back(int(l));
  ASSERT_EQ(boundary.size(), 2u);
  given[boundary[0]] = free_report.loops[boundary[0]].period + n;
  given[boundary[1]] = free_report.loops[boundary[1]].period - n;
  std::vector<double> x;
  const TC::Solve_report r = solver.solve(descriptors(view, none), view.halfedge_map(x),
                                          TC::parameters::loop_periods(given, TC::parameters::symmetry_order(n)));
  EXPECT_LT(r.max_vertex_residual, 1e-9);
  EXPECT_LT(r.max_loop_residual, 1e-9);
  for(int l : boundary) {
    EXPECT_EQ(r.loops[l].period, *given[l]);
    EXPECT_TRUE(r.loops[l].prescribed);
  }
  for(int l : generators)
    EXPECT_FALSE(r.loops[l].prescribed);
  EXPECT_TRUE(r.integers_proven_optimal);
  EXPECT_NEAR(r.energy, tc_test::energy(view, x, solver.weighting()), 1e-9 * std::max(1., r.energy));
  EXPECT_GE(r.rounding_energy, r.energy - 1e-9 * std::max(1., r.energy));
  expect_best_over(view, solver, none, n, periods_of(r), r.energy, generators, 2);
}

TEST(Partial_loop_periods, some_generators_prescribed_the_others_chosen_optimally)
{
  const Surface_mesh sm = to_surface_mesh(generated("genus2").soup);
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm);
  const int n = 1;
  const Singularities sing = designed_singularities("genus2", view, n);
  std::vector<double> x0;
  const TC::Solve_report free_report = solver.solve(descriptors(view, sing), view.halfedge_map(x0),
                                                    TC::parameters::symmetry_order(n));
  const std::size_t loops = solver.loops().size();
  ASSERT_EQ(loops, 4u);
  std::vector<std::optional<std::int64_t>> given(loops);
  given[0] = free_report.loops[0].period + 1;
  std::vector<double> x;
  const TC::Solve_report r = solver.solve(descriptors(view, sing), view.halfedge_map(x),
                                          TC::parameters::loop_periods(given, TC::parameters::symmetry_order(n)));
  EXPECT_LT(r.max_vertex_residual, 1e-9);
  EXPECT_LT(r.max_loop_residual, 1e-9);
  EXPECT_EQ(r.loops[0].period, *given[0]);
  EXPECT_TRUE(r.loops[0].prescribed);
  EXPECT_GT(r.energy, free_report.energy); // a generator forced away from its best integer
  expect_best_over(view, solver, sing, n, periods_of(r), r.energy, {1, 2, 3}, 1);

  // every entry given: the same as the plain vector
  std::vector<std::optional<std::int64_t>> all(loops);
  for(std::size_t l = 0; l < loops; ++l) all[l] = r.loops[l].period;
  std::vector<double> x_all, x_plain;
  const TC::Solve_report r_all = solver.solve(descriptors(view, sing), view.halfedge_map(x_all),
                                              TC::parameters::loop_periods(all, TC::parameters::symmetry_order(n)));
  const TC::Solve_report r_plain = solver.solve(
    descriptors(view, sing), view.halfedge_map(x_plain),
    TC::parameters::loop_periods(periods_of(r), TC::parameters::symmetry_order(n)));
  EXPECT_EQ(x_all, x_plain);
  EXPECT_NEAR(r_all.energy, r.energy, 1e-9 * std::max(1., r.energy));
}

TEST(Partial_loop_periods, boundary_loops_of_a_component_are_prescribed_all_or_none)
{
  const Surface_mesh sm = to_surface_mesh(holed_torus_soup());
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm);
  const auto& loops = solver.loops();
  std::vector<std::optional<std::int64_t>> given(loops.size());
  for(std::size_t l = 0; l < loops.size(); ++l)
    if(loops[l].kind == TC::Loop_kind::boundary) {
      given[l] = -4;
      break;
    }
  std::vector<double> x;
  try {
    solver.solve(descriptors(view, Singularities()), view.halfedge_map(x),
                 TC::parameters::loop_periods(given, TC::parameters::symmetry_order(4)));
    ADD_FAILURE() << "one of two boundary loops prescribed was accepted";
  } catch(const TC::Invalid_input& e) {
    EXPECT_EQ(e.code(), TC::Error_code::invalid_loop_periods);
    EXPECT_NE(std::string(e.what()).find("all of them or none"), std::string::npos) << e.what();
  }
}

// the same choice through the other solve paths: the metric by back-substitutions (a backend whose factor
// the solver does not read) and CHOLMOD's whole-factor substitutions
template <class Traits>
void expect_same_partial_choice(const Surface_mesh& sm, const Mesh_view<Surface_mesh>& view,
                                const std::vector<std::optional<std::int64_t>>& given, const TC::Solve_report& reference)
{
  TC::Trivial_connection_solver<Surface_mesh, CGAL::Default, Traits> solver(sm);
  std::vector<double> x;
  const TC::Solve_report r = solver.solve(descriptors(view, Singularities()), view.halfedge_map(x),
                                          TC::parameters::loop_periods(given, TC::parameters::symmetry_order(4)));
  EXPECT_NEAR(r.energy, reference.energy, 1e-9 * std::max(1., reference.energy));
  EXPECT_NEAR(r.rounding_energy, reference.rounding_energy, 1e-9 * std::max(1., reference.rounding_energy));
  EXPECT_EQ(periods_of(r), periods_of(reference));
}

TEST(Partial_loop_periods, same_choice_with_every_backend)
{
  const Surface_mesh sm = to_surface_mesh(holed_torus_soup());
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm);
  const auto& loops = solver.loops();
  std::vector<std::optional<std::int64_t>> given(loops.size());
  std::vector<std::int64_t> holes = {-12, 4}; // indices -3 and 1 for n = 4: sum -2 = chi
  for(std::size_t l = 0, b = 0; l < loops.size(); ++l)
    if(loops[l].kind == TC::Loop_kind::boundary) given[l] = holes[b++];
  std::vector<double> x;
  const TC::Solve_report reference = solver.solve(descriptors(view, Singularities()), view.halfedge_map(x),
                                                  TC::parameters::loop_periods(given, TC::parameters::symmetry_order(4)));
  EXPECT_LT(reference.max_loop_residual, 1e-9);
  expect_same_partial_choice<CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>>(
    sm, view, given, reference);
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  expect_same_partial_choice<TC::Cholmod_solver_traits>(sm, view, given, reference);
#endif
}

// boundary_loop_of: a boundary vertex names the loop whose crossings include its fan, an interior one none
TEST(Partial_loop_periods, boundary_loop_of_names_the_loop_around_the_vertex)
{
  for(const Soup& soup : {holed_torus_soup(), generated("annulus").soup}) {
    const Surface_mesh sm = to_surface_mesh(soup);
    Solver<Surface_mesh> solver(sm);
    std::set<std::size_t> named;
    for(auto v : vertices(sm)) {
      const std::optional<std::size_t> l = solver.boundary_loop_of(v);
      if(!sm.is_border(v, /*check_all_incident_halfedges=*/true)) {
        EXPECT_FALSE(l);
        continue;
      }
      ASSERT_TRUE(l);
      const auto& loop = solver.loops()[*l];
      EXPECT_EQ(loop.kind, TC::Loop_kind::boundary);
      // the loop crosses every interior edge at v (its open fan)
      std::set<Surface_mesh::Edge_index> crossed;
      for(auto h : loop.halfedges) crossed.insert(edge(h, sm));
      for(auto h : halfedges_around_target(halfedge(v, sm), sm))
        if(!is_border(edge(h, sm), sm))
          EXPECT_TRUE(crossed.count(edge(h, sm))) << "an interior edge at boundary vertex " << v << " is not crossed";
      named.insert(*l);
    }
    std::size_t boundary_loops = 0;
    for(const auto& loop : solver.loops())
      boundary_loops += loop.kind == TC::Loop_kind::boundary ? 1 : 0;
    EXPECT_EQ(named.size(), boundary_loops);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Streamlines
// ---------------------------------------------------------------------------------------------------------

namespace {
// Every segment of every streamline lies in its face (its midpoint inside the triangle, both ends on the
// face's plane) along one of the field's n directions there; consecutive segments meet. Returns the
// streamlines.
template <class Mesh>
std::vector<TC::Streamline<Mesh>> check_streamlines(const Mesh_view<Mesh>& view, const std::vector<double>& x,
                                                    const std::vector<Vector>& field, const Singularities& sing, int n,
                                                    std::size_t seed_count)
{
  std::vector<typename Mesh_view<Mesh>::face_descriptor> seeds;
  for(std::size_t i = 0; i < seed_count; ++i) seeds.push_back(view.faces[i * std::size_t(view.nf()) / seed_count]);
  std::vector<double> xs = x;
  std::vector<Vector> fs = field;
  const auto lines = TC::trace_streamlines(view.tm, view.halfedge_map_const(xs),
                                           Indexed_map<typename Mesh_view<Mesh>::face_descriptor, Vector>{&view.fid, &fs},
                                           descriptors(view, sing), seeds, TC::parameters::symmetry_order(n));
  EXPECT_FALSE(lines.empty());
  double worst_angle = 0, worst_inside = 0, worst_plane = 0;
  for(const auto& line : lines) {
    EXPECT_EQ(line.faces.size() + 1, line.points.size());
    for(std::size_t i = 0; i + 1 < line.points.size(); ++i) {
      const int f = view.fid.at(line.faces[i]);
      const V3 a = line.points[i], b = line.points[i + 1];
      const V3 m = 0.5 * (a + b);
      // barycentric coordinates of the midpoint
      const int h0 = view.face_he[f][0];
      const V3 p0 = view.P[view.src[h0]], p1 = view.P[view.tgt[h0]], p2 = view.P[view.tgt[view.nxt[h0]]];
      const double area = dot(cross(p1 - p0, p2 - p0), view.N[f]);
      const double l0 = dot(cross(p1 - m, p2 - m), view.N[f]) / area, l1 = dot(cross(p2 - m, p0 - m), view.N[f]) / area;
      worst_inside = std::max(worst_inside, std::max(0., -std::min({l0, l1, 1 - l0 - l1})));
      worst_plane = std::max({worst_plane, std::abs(dot(a - p0, view.N[f])), std::abs(dot(b - p0, view.N[f]))});
      const V3 u = V3{{field[f].x(), field[f].y(), field[f].z()}};
      worst_angle = std::max(worst_angle, std::abs(wrap(signed_angle(u, b - a, view.N[f]), two_pi / n)));
    }
  }
  // rays through a vertex cross the edge 1e-9 of its length away from it: the segment turns by about that
  EXPECT_LT(worst_angle, 1e-7) << "a segment is not along the field";
  EXPECT_LT(worst_inside, 1e-9) << "a segment leaves its face";
  EXPECT_LT(worst_plane, 1e-9) << "a point is off its face's plane";
  return lines;
}
} // namespace

TEST(Streamlines, straight_lines_of_a_constant_field_on_a_flat_disk_end_on_the_boundary)
{
  const Surface_mesh m = disk(6, 16); // flat: the field without singularity is constant, its streamlines straight
  const Mesh_view<Surface_mesh> view(m);
  Solver<Surface_mesh> solver(m);
  for(int n : {1, 4}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const auto s = solve_and_check(view, solver, Singularities(), n);
    const auto lines = check_streamlines(view, s.x, s.field, Singularities(), n, 10);
    EXPECT_EQ(lines.size(), std::size_t(10 * (n == 1 ? 1 : 2)));
    for(const auto& line : lines) {
      const V3 a = line.points.front(), b = line.points.back(), d = unit(b - a);
      double off = 0;
      for(const V3& p : line.points) off = std::max(off, norm(cross(p - a, d)));
      EXPECT_LT(off, 1e-7) << "not a straight line";
      // both ends on the boundary circle (radius 1: the disk's border is a polygon inscribed in it)
      EXPECT_GT(norm(a), 0.98);
      EXPECT_GT(norm(b), 0.98);
    }
  }
}

TEST(Streamlines, on_a_Polyhedron_3)
{
  const Polyhedron m = to_polyhedron(warped(icosphere_soup(2)));
  const Mesh_view<Polyhedron> view(m);
  Solver<Polyhedron> solver(m);
  const Singularities sing = plan_singularities(view, 4);
  const auto s = solve_and_check(view, solver, sing, 4);
  check_streamlines(view, s.x, s.field, sing, 4, 10);
}

TEST(Streamlines, follow_the_field_across_every_edge_and_stop_at_singularities)
{
  const Surface_mesh m = icosphere(3);
  const Mesh_view<Surface_mesh> view(m);
  Solver<Surface_mesh> solver(m);
  for(int n : {1, 2, 4}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const Singularities sing = plan_singularities(view, n);
    const auto s = solve_and_check(view, solver, sing, n);
    const auto lines = check_streamlines(view, s.x, s.field, sing, n, 25);
    // a line stops on entering a face with a singular vertex: such faces are only at its ends
    std::set<int> singular;
    for(const auto& p : sing) singular.insert(p.first);
    int inner = 0, ends = 0;
    for(const auto& line : lines)
      for(std::size_t i = 0; i < line.faces.size(); ++i) {
        const int f = view.fid.at(line.faces[i]);
        bool touches = false;
        for(int h : view.face_he[f]) touches = touches || singular.count(view.src[h]) > 0;
        if(!touches) continue;
        (i == 0 || i + 1 == line.faces.size() ? ends : inner) += 1;
      }
    EXPECT_EQ(inner, 0) << "a streamline goes on through a face with a singular vertex";
  }
}

TEST(Streamlines, radial_lines_run_from_the_boundary_to_the_singularity)
{
  // a flat disk with a +1 singularity at its centre: the field turned to be radial at one face is radial
  // everywhere, and every streamline is a radius ending at the centre's faces and at the boundary
  const Surface_mesh m = disk(6, 16);
  const Mesh_view<Surface_mesh> view(m);
  Solver<Surface_mesh> solver(m);
  const Singularities sing = {{0, Index(1)}};
  std::vector<double> x;
  solver.solve(descriptors(view, sing), view.halfedge_map(x));
  const int seed = view.nf() - 1;
  const V3 e = view.frame(seed), r = unit(view.bary[seed]);
  const double radial = std::atan2(dot(cross(e, r), view.N[seed]), dot(e, r));
  std::vector<Vector> field;
  solver.compute_field(view.halfedge_map_const(x), view.face_map(field),
                       TC::parameters::seed_angle(radial, TC::parameters::seed_face(view.faces[seed])));
  const auto lines = check_streamlines(view, x, field, sing, 1, 12);
  const double ring = 1. / 6; // the first ring of vertices around the centre
  for(const auto& line : lines) {
    const V3 a = line.points.front(), b = line.points.back();
    const double inner = std::min(norm(a), norm(b)), outer = std::max(norm(a), norm(b));
    EXPECT_GT(outer, 0.98) << "a radius that does not reach the boundary";
    EXPECT_LE(inner, ring + 1e-9) << "a radius that stops before the centre's faces";
    double off = 0; // on the line through the centre
    for(const V3& p : line.points) off = std::max(off, norm(cross(p, unit(b - a))));
    EXPECT_LT(off, 1e-7) << "not a radius";
  }
}
