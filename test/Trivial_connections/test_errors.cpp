// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// Every bad input gets an Invalid_input with the right Error_code, the right where() and a message that
// names the place (vertex, face, component) and the figures; the mesh is never modified.

#include "test_support.h"

#include <CGAL/Trivial_connections/homology_generators.h>
#include <CGAL/Trivial_connections/trivial_connection.h>

#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace tc_test;
using TC::Error_code;
using TC::Invalid_input;
using SM = Surface_mesh;
using Solver = TC::Trivial_connection_solver<SM>;

/// runs f, expects an Invalid_input with `code`, returns it (nullopt, with a failure, otherwise)
template <class F>
std::optional<Invalid_input> expect_invalid(F&& f, Error_code code)
{
  try {
    f();
  } catch(const Invalid_input& e) {
    EXPECT_EQ(e.code(), code) << "got " << TC::error_code_name(e.code()) << ": " << e.what();
    EXPECT_FALSE(std::string(e.what()).empty());
    return e;
  } catch(const std::exception& e) {
    ADD_FAILURE() << "expected Invalid_input(" << TC::error_code_name(code) << "), got another exception: " << e.what();
    return std::nullopt;
  }
  ADD_FAILURE() << "expected Invalid_input(" << TC::error_code_name(code) << "), nothing was thrown";
  return std::nullopt;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

#define EXPECT_MESSAGE_HAS(e, part)                                                              \
  EXPECT_TRUE(contains((e).what(), part)) << "message \"" << (e).what() << "\" lacks \"" << (part) << "\""

/// a solve with default parameters and n
std::function<void()> solving(Solver& solver, const Mesh_view<SM>& view, const Singularities& s, int n)
{
  return [&solver, &view, s, n] {
    std::vector<double> x;
    solver.solve(descriptors(view, s), view.halfedge_map(x), TC::parameters::symmetry_order(n));
  };
}

// ---------------------------------------------------------------------------------------------------
// Bad meshes (constructor, free functions, homology_generators)
// ---------------------------------------------------------------------------------------------------

TEST(Bad_mesh, empty_mesh)
{
  SM empty;
  if(auto e = expect_invalid([&] { Solver s(empty); }, Error_code::empty_mesh))
    EXPECT_EQ(e->where(), Invalid_input::no_location);
  expect_invalid([&] { TC::homology_generators(empty); }, Error_code::empty_mesh);
  std::vector<std::pair<SM::Vertex_index, Index>> none;
  expect_invalid([&] { TC::compute_trivial_connection(empty, none, Indexed_map<SM::Halfedge_index, double>{}); },
                 Error_code::empty_mesh);
  // vertices but no face
  SM only_vertices;
  only_vertices.add_vertex(Point(0, 0, 0));
  only_vertices.add_vertex(Point(1, 0, 0));
  expect_invalid([&] { Solver s(only_vertices); }, Error_code::empty_mesh);
  Polyhedron empty_polyhedron;
  expect_invalid([&] { TC::Trivial_connection_solver<Polyhedron> s(empty_polyhedron); }, Error_code::empty_mesh);
}

TEST(Bad_mesh, non_triangle_face)
{
  // two triangles then a quad (face 2), flat, consistently oriented
  SM sm;
  std::vector<SM::Vertex_index> v;
  for(const Point& p : {Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0), Point(0, 1, 0), Point(1, 1, 0), Point(2, 1, 0)})
    v.push_back(sm.add_vertex(p));
  ASSERT_NE(sm.add_face(v[0], v[1], v[4]), SM::null_face());
  ASSERT_NE(sm.add_face(v[0], v[4], v[3]), SM::null_face());
  const SM::Face_index quad = sm.add_face(v[1], v[2], v[5], v[4]);
  ASSERT_NE(quad, SM::null_face());
  ASSERT_EQ(std::size_t(quad), 2u);
  if(auto e = expect_invalid([&] { Solver s(sm); }, Error_code::not_triangle_mesh)) {
    EXPECT_EQ(e->where(), 2u);
    EXPECT_MESSAGE_HAS(*e, "face 2");
  }
  expect_invalid([&] { TC::homology_generators(sm); }, Error_code::not_triangle_mesh);
  // the same as a Polyhedron_3
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0), Point(0, 1, 0), Point(1, 1, 0), Point(2, 1, 0)};
  std::vector<std::vector<std::size_t>> polygons = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5, 4}};
  Polyhedron P;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, P);
  ASSERT_EQ(P.size_of_facets(), 3u);
  expect_invalid([&] { TC::Trivial_connection_solver<Polyhedron> s(P); }, Error_code::not_triangle_mesh);
}

TEST(Bad_mesh, non_manifold_vertex)
{
  // A bowtie: two triangles sharing only vertex 2. Surface_mesh::add_face accepts it because vertex 2 is
  // still on the border. (A closed non-manifold vertex, e.g. two tetrahedra sharing a vertex, cannot be
  // built: add_face refuses a face at a vertex that is no longer on the border; checked below.)
  SM sm;
  std::vector<SM::Vertex_index> v;
  for(const Point& p : {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(2, 1, 0), Point(2, 2, 0)})
    v.push_back(sm.add_vertex(p));
  ASSERT_NE(sm.add_face(v[0], v[1], v[2]), SM::null_face());
  ASSERT_NE(sm.add_face(v[2], v[3], v[4]), SM::null_face());
  if(auto e = expect_invalid([&] { Solver s(sm); }, Error_code::non_manifold)) {
    EXPECT_EQ(e->where(), 2u);
    EXPECT_MESSAGE_HAS(*e, "vertex 2");
  }
  expect_invalid([&] { TC::homology_generators(sm); }, Error_code::non_manifold);

  // a bowtie inside a larger mesh: two icospheres glued at one vertex cannot be built...
  SM two;
  const Soup a = icosphere_soup(0);
  std::vector<SM::Vertex_index> w;
  for(const Point& p : a.points) w.push_back(two.add_vertex(p));
  for(const Tri& t : a.faces) ASSERT_NE(two.add_face(w[t[0]], w[t[1]], w[t[2]]), SM::null_face());
  const SM::Vertex_index p1 = two.add_vertex(Point(3, 0, 0)), p2 = two.add_vertex(Point(3, 1, 0));
  EXPECT_EQ(two.add_face(w[0], p1, p2), SM::null_face()) << "Surface_mesh built a closed non-manifold vertex";
  // ...but a disk pinched to another disk at a boundary vertex can: vertex 0 of the second fan
  SM pinched = to_surface_mesh(disk_soup(2, 8));
  const SM::Vertex_index rim(9); // a boundary vertex of the disk (rings of 8 after the centre: 9..16 outer)
  ASSERT_TRUE(is_border(rim, pinched));
  const SM::Vertex_index q1 = pinched.add_vertex(Point(3, 3, 0)), q2 = pinched.add_vertex(Point(3, 4, 0));
  ASSERT_NE(pinched.add_face(rim, q1, q2), SM::null_face());
  if(auto e = expect_invalid([&] { Solver s(pinched); }, Error_code::non_manifold)) {
    EXPECT_EQ(e->where(), 9u);
    EXPECT_MESSAGE_HAS(*e, "vertex 9");
  }
}

TEST(Bad_mesh, inconsistent_orientation_cannot_be_represented)
{
  // Error_code::inconsistent_orientation exists, but a halfedge data structure cannot hold two faces that
  // traverse a shared edge in the same direction: Surface_mesh::add_face refuses the second face.
  SM sm;
  std::vector<SM::Vertex_index> v;
  for(const Point& p : {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(1, 1, 0)}) v.push_back(sm.add_vertex(p));
  ASSERT_NE(sm.add_face(v[0], v[1], v[2]), SM::null_face());
  EXPECT_EQ(sm.add_face(v[0], v[1], v[3]), SM::null_face()); // edge 0->1 used twice in the same direction
}

TEST(Bad_mesh, degenerate_faces)
{
  // face 2 is collinear: (0,0,0), (2,0,0), (1,0,0)
  {
    SM sm;
    std::vector<SM::Vertex_index> v;
    for(const Point& q : {Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0), Point(0, 1, 0)}) v.push_back(sm.add_vertex(q));
    ASSERT_NE(sm.add_face(v[0], v[1], v[3]), SM::null_face());
    ASSERT_NE(sm.add_face(v[1], v[2], v[3]), SM::null_face());
    ASSERT_NE(sm.add_face(v[0], v[2], v[1]), SM::null_face()); // collinear, face 2
    if(auto e = expect_invalid([&] { Solver s(sm); }, Error_code::degenerate_face)) {
      EXPECT_EQ(e->where(), 2u);
      EXPECT_MESSAGE_HAS(*e, "face 2");
    }
    expect_invalid([&] { TC::homology_generators(sm); }, Error_code::degenerate_face);
  }
  // zero area: two distinct vertices at the same position (face 1)
  {
    SM sm;
    std::vector<SM::Vertex_index> v;
    for(const Point& q : {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(1, 0, 0)}) v.push_back(sm.add_vertex(q));
    ASSERT_NE(sm.add_face(v[0], v[1], v[2]), SM::null_face());
    ASSERT_NE(sm.add_face(v[1], v[3], v[2]), SM::null_face());
    if(auto e = expect_invalid([&] { Solver s(sm); }, Error_code::degenerate_face)) {
      EXPECT_EQ(e->where(), 1u);
      EXPECT_MESSAGE_HAS(*e, "face 1");
    }
  }
  // a nearly flat but valid sliver is accepted
  {
    SM sm;
    std::vector<SM::Vertex_index> v;
    for(const Point& q : {Point(0, 0, 0), Point(1, 0, 0), Point(2, 1e-9, 0)}) v.push_back(sm.add_vertex(q));
    ASSERT_NE(sm.add_face(v[0], v[1], v[2]), SM::null_face());
    EXPECT_NO_THROW(Solver s(sm));
  }
  // a cap whose largest angle is within about 1e-13 rad of pi: its plane is rounding noise, whatever the
  // placement (here rotated out of the coordinate planes, where the cross product cancels to its last bits);
  // the same shape within 1e-10 of pi is accepted, in both placements
  for(const double offset : {1e-13, 1e-10}) {
    for(const bool rotated : {false, true}) {
      SCOPED_TRACE("offset " + std::to_string(offset) + (rotated ? ", rotated" : ""));
      auto place = [&](double x, double y) {
        if(!rotated)
          return Point(x, y, 0);
        const double c = std::cos(0.7), s = std::sin(0.7); // about z by 0.7, then about x by 0.4
        const double xr = c * x - s * y, yr = s * x + c * y;
        return Point(xr, std::cos(0.4) * yr, std::sin(0.4) * yr);
      };
      SM sm;
      std::vector<SM::Vertex_index> v;
      for(const Point& q : {place(0, 0), place(1, 0), place(0.5, offset)}) v.push_back(sm.add_vertex(q));
      ASSERT_NE(sm.add_face(v[0], v[1], v[2]), SM::null_face());
      if(offset < 1e-12) {
        if(auto e = expect_invalid([&] { Solver solver(sm); }, Error_code::degenerate_face))
          EXPECT_MESSAGE_HAS(*e, "nearly collinear");
      } else {
        EXPECT_NO_THROW(Solver solver(sm));
      }
    }
  }
}

// A coordinate that is not a finite number is the vertex's fault, said as the file readers say it (it used to
// be reported as a degenerate face around the vertex); a vertex no face uses is checked too
TEST(Bad_mesh, non_finite_coordinates)
{
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for(const auto& [point, text] : {std::pair<Point, std::string>(Point(nan, 0, 0), "'nan'"),
                                   std::pair<Point, std::string>(Point(0, inf, 0), "'inf'"),
                                   std::pair<Point, std::string>(Point(0, 0, -inf), "'-inf'")})
    for(bool isolated : {false, true}) {
      SCOPED_TRACE(text + (isolated ? ", a vertex of no face" : ""));
      Soup s = icosphere_soup(1);
      int v = 5;
      if(isolated) {
        v = int(s.points.size());
        s.points.push_back(point);
      } else {
        s.points[5] = point;
      }
      const SM sm = to_surface_mesh(s); // keeps a vertex no face uses
      if(auto e = expect_invalid([&] { Solver solver(sm); }, Error_code::non_finite_point)) {
        EXPECT_EQ(e->where(), std::size_t(v));
        EXPECT_EQ(std::string(e->what()), "vertex " + std::to_string(v) + ": the coordinate " + text +
                                            " is not a finite number");
      }
      expect_invalid([&] { TC::homology_generators(sm); }, Error_code::non_finite_point);
    }
  EXPECT_STREQ(TC::error_code_name(Error_code::non_finite_point), "non_finite_point");
}

// The integers that set holonomies are bounded by 2^10 turns (min(2^10 n, 2^30) as n k or as a period): beyond,
// the rounding of 2 pi k shows in the residuals (a period of 10^12 gave a loop residual of 2.7e-5, and was
// accepted). At the bound the residuals are still below 1e-9.
TEST(Bad_parameters, integers_beyond_1024_turns)
{
  const std::int64_t turns = std::int64_t(1) << 10;
  std::vector<double> x;
  {
    const SM sm = to_surface_mesh(torus_soup(2, 0.7, 16, 8));
    const Mesh_view<SM> view(sm);
    Solver solver(sm);
    ASSERT_EQ(solver.loops().size(), 2u);
    for(int n : {1, 4}) {
      SCOPED_TRACE("n = " + std::to_string(n));
      const std::int64_t bound = turns * n;
      for(const std::vector<std::int64_t>& periods :
          {std::vector<std::int64_t>{bound, -bound}, std::vector<std::int64_t>{-bound, 3}}) {
        const TC::Solve_report r = solver.solve(descriptors(view, {}), view.halfedge_map(x),
                                                TC::parameters::loop_periods(periods, TC::parameters::symmetry_order(n)));
        EXPECT_LT(r.max_loop_residual, 1e-9);
        EXPECT_LT(r.max_vertex_residual, 1e-9);
      }
      for(const std::vector<std::int64_t>& periods :
          {std::vector<std::int64_t>{bound + 1, 0}, std::vector<std::int64_t>{0, -bound - 1},
           std::vector<std::int64_t>{std::int64_t(1e12), std::int64_t(-1e12)},
           std::vector<std::int64_t>{(std::numeric_limits<std::int64_t>::min)(), 0}})
        if(auto e = expect_invalid([&] {
               solver.solve(descriptors(view, {}), view.halfedge_map(x),
                            TC::parameters::loop_periods(periods, TC::parameters::symmetry_order(n)));
             }, Error_code::invalid_loop_periods)) {
          EXPECT_EQ(e->where(), periods[0] != 0 ? 0u : 1u);
          EXPECT_MESSAGE_HAS(*e, "too large");
          EXPECT_MESSAGE_HAS(*e, "at most " + std::to_string(bound));
        }
      // with optional entries, the others chosen by the solver
      expect_invalid([&] {
        solver.solve(descriptors(view, {}), view.halfedge_map(x),
                     TC::parameters::loop_periods(std::vector<std::optional<std::int64_t>>{std::nullopt, bound + 1},
                                                  TC::parameters::symmetry_order(n)));
      }, Error_code::invalid_loop_periods);
    }
  }
  {
    // vertex indices: 2^10 and 2 - 2^10 on a sphere are solved; 2^10 + 1 is refused
    const SM sm = to_surface_mesh(icosphere_soup(2));
    const Mesh_view<SM> view(sm);
    Solver solver(sm);
    const TC::Solve_report r = solver.solve(descriptors(view, {{0, Index(turns)}, {7, Index(2 - turns)}}),
                                            view.halfedge_map(x));
    EXPECT_LT(r.max_vertex_residual, 1e-9);
    if(auto e = expect_invalid(solving(solver, view, {{0, Index(turns + 1)}, {7, Index(1 - turns)}}, 1),
                               Error_code::invalid_index)) {
      EXPECT_EQ(e->where(), 0u);
      EXPECT_MESSAGE_HAS(*e, "at most 1024");
    }
    // in quarters (n = 4): 2^10 turns are 2^12 quarters
    expect_invalid(solving(solver, view, {{0, Index(4 * turns + 1, 4)}, {7, Index(-4 * turns + 7, 4)}}, 4),
                   Error_code::invalid_index);
  }
}

TEST(Bad_mesh, surface_mesh_with_removed_elements)
{
  // an isolated vertex 0, then an icosphere (vertices 1..n); removing vertex 0 without collect_garbage()
  // leaves vertex indices 1..n, not 0..n-1
  SM sm;
  const SM::Vertex_index extra = sm.add_vertex(Point(5, 5, 5));
  const Soup s = icosphere_soup(1);
  std::vector<SM::Vertex_index> v;
  for(const Point& p : s.points) v.push_back(sm.add_vertex(p));
  for(const Tri& t : s.faces) ASSERT_NE(sm.add_face(v[t[0]], v[t[1]], v[t[2]]), SM::null_face());
  sm.remove_vertex(extra);
  ASSERT_TRUE(sm.has_garbage());
  if(auto e = expect_invalid([&] { Solver s(sm); }, Error_code::invalid_argument))
    EXPECT_MESSAGE_HAS(*e, "collect_garbage");
  sm.collect_garbage();
  EXPECT_NO_THROW(Solver s(sm));
}

// ---------------------------------------------------------------------------------------------------
// Bad singularities and parameters (solve)
// ---------------------------------------------------------------------------------------------------

TEST(Bad_singularities, poincare_hopf_violated_on_a_closed_mesh)
{
  const SM sm = to_surface_mesh(icosphere_soup(2));
  const Mesh_view<SM> view(sm);
  ASSERT_EQ(view.chi[0], 2);
  Solver solver(sm);
  if(auto e = expect_invalid(solving(solver, view, {{10, Index(1)}}, 1), Error_code::poincare_hopf_violated)) {
    EXPECT_EQ(e->where(), 0u);
    EXPECT_MESSAGE_HAS(*e, "component 0");
    EXPECT_MESSAGE_HAS(*e, "sum to 1");
    EXPECT_MESSAGE_HAS(*e, "expected 2");
  }
  // fractional: seven +1/4 sum to 7/4
  Singularities seven;
  for(int v = 0; v < 7; ++v) seven.emplace_back(v * 20, Index(1, 4));
  if(auto e = expect_invalid(solving(solver, view, seven, 4), Error_code::poincare_hopf_violated)) {
    EXPECT_MESSAGE_HAS(*e, "7/4");
    EXPECT_MESSAGE_HAS(*e, "expected 2");
  }
  // no singularity at all on a sphere
  if(auto e = expect_invalid(solving(solver, view, {}, 1), Error_code::poincare_hopf_violated))
    EXPECT_MESSAGE_HAS(*e, "sum to 0");
  // genus 2: expected -2
  const SM g2 = to_surface_mesh(genus2_soup(1));
  const Mesh_view<SM> v2(g2);
  Solver s2(g2);
  if(auto e = expect_invalid(solving(s2, v2, {}, 1), Error_code::poincare_hopf_violated))
    EXPECT_MESSAGE_HAS(*e, "expected -2");
  // after a rejected solve, the solver still works
  const Solution<SM> ok = solve_and_check(view, solver, {{0, Index(1)}, {view.nv() - 1, Index(1)}}, 1);
  EXPECT_LT(ok.report.max_vertex_residual, 1e-9);
}

TEST(Bad_singularities, poincare_hopf_is_checked_per_component)
{
  const SM sm = to_surface_mesh(two_spheres_soup(1));
  const Mesh_view<SM> view(sm);
  ASSERT_EQ(view.ncomp, 2);
  Solver solver(sm);
  const std::vector<int> a = spread_interior_vertices(view, 0, 2), b = spread_interior_vertices(view, 1, 2);
  // the first sphere is right (two +1), the second has only one +1
  std::size_t second = 0;
  for(int f = 0; f < view.nf(); ++f)
    if(view.comp_of_face[f] == 1) second = solver.component(view.faces[f]);
  if(auto e = expect_invalid(solving(solver, view, {{a[0], Index(1)}, {a[1], Index(1)}, {b[0], Index(1)}}, 1),
                             Error_code::poincare_hopf_violated)) {
    EXPECT_EQ(e->where(), second);
    EXPECT_MESSAGE_HAS(*e, "component " + std::to_string(second));
    EXPECT_FALSE(contains(e->what(), "component " + std::to_string(1 - second))) << e->what();
    EXPECT_MESSAGE_HAS(*e, "sum to 1");
  }
  const std::vector<int> a3 = spread_interior_vertices(view, 0, 3);
  if(auto e = expect_invalid(solving(solver, view, {{a3[0], Index(1)}, {a3[1], Index(1)}, {a3[2], Index(1)}, {b[0], Index(1)}}, 1),
                             Error_code::poincare_hopf_violated)) {
    // global sum 4 = 2 + 2, but 3 and 1 per component: both components named
    EXPECT_MESSAGE_HAS(*e, "component 0");
    EXPECT_MESSAGE_HAS(*e, "component 1");
    EXPECT_MESSAGE_HAS(*e, "sum to 3");
    EXPECT_MESSAGE_HAS(*e, "sum to 1");
  }
}

TEST(Bad_singularities, index_not_a_multiple_of_one_over_n)
{
  const SM sm = to_surface_mesh(torus_soup(2, 0.7, 16, 8));
  const Mesh_view<SM> view(sm);
  Solver solver(sm);
  if(auto e = expect_invalid(solving(solver, view, {{3, Index(1, 3)}, {40, Index(-1, 3)}}, 4), Error_code::index_not_multiple)) {
    EXPECT_EQ(e->where(), 3u);
    EXPECT_MESSAGE_HAS(*e, "vertex 3");
    EXPECT_MESSAGE_HAS(*e, "1/3");
    EXPECT_MESSAGE_HAS(*e, "1/4");
  }
  expect_invalid(solving(solver, view, {{3, Index(1, 2)}, {40, Index(-1, 2)}}, 1), Error_code::index_not_multiple);
  // 1/2 is a multiple of 1/4 but not of 1/3
  EXPECT_NO_THROW(solving(solver, view, {{3, Index(1, 2)}, {40, Index(-1, 2)}}, 4)());
  expect_invalid(solving(solver, view, {{3, Index(1, 2)}, {40, Index(-1, 2)}}, 3), Error_code::index_not_multiple);
}

TEST(Bad_singularities, singularity_on_a_boundary_vertex)
{
  const SM sm = to_surface_mesh(disk_soup(3, 10));
  const Mesh_view<SM> view(sm);
  Solver solver(sm);
  int rim = -1;
  for(int v = view.nv() - 1; v >= 0 && rim < 0; --v)
    if(view.on_boundary[v]) rim = v;
  ASSERT_GE(rim, 0);
  if(auto e = expect_invalid(solving(solver, view, {{rim, Index(1)}}, 1), Error_code::singularity_on_boundary)) {
    EXPECT_EQ(e->where(), std::size_t(rim));
    EXPECT_MESSAGE_HAS(*e, "vertex " + std::to_string(rim));
  }
}

TEST(Bad_singularities, vertex_not_in_the_mesh_or_in_no_face)
{
  SM sm = to_surface_mesh(icosphere_soup(1));
  const SM::Vertex_index isolated = sm.add_vertex(Point(4, 4, 4));
  const Mesh_view<SM> view(sm);
  Solver solver(sm);
  const int iso = view.vid.at(isolated);
  if(auto e = expect_invalid(solving(solver, view, {{0, Index(1)}, {iso, Index(1)}}, 1), Error_code::invalid_vertex)) {
    EXPECT_EQ(e->where(), std::size_t(iso));
    EXPECT_MESSAGE_HAS(*e, "vertex " + std::to_string(iso));
    EXPECT_MESSAGE_HAS(*e, "no face");
  }
  // a descriptor beyond the mesh
  std::vector<std::pair<SM::Vertex_index, Index>> beyond = {{SM::Vertex_index(100000), Index(2)}};
  std::vector<double> x;
  expect_invalid([&] { solver.solve(beyond, view.halfedge_map(x)); }, Error_code::invalid_vertex);
  // the isolated vertex without singularity is harmless: every check passes, angle_defect is 0 there
  EXPECT_EQ(solver.angle_defect(isolated), 0.);
  const Singularities ok = {{0, Index(1)}, {nearest_interior_vertex(view, {{0, 0, -1}}), Index(1)}};
  solve_and_check(view, solver, ok, 1);
}

TEST(Bad_singularities, duplicate_singularity)
{
  const SM sm = to_surface_mesh(icosphere_soup(1));
  const Mesh_view<SM> view(sm);
  Solver solver(sm);
  // listed twice, even with indices that would sum correctly
  if(auto e = expect_invalid(solving(solver, view, {{7, Index(1)}, {7, Index(1)}}, 1), Error_code::duplicate_singularity)) {
    EXPECT_EQ(e->where(), 7u);
    EXPECT_MESSAGE_HAS(*e, "vertex 7");
  }
}

TEST(Bad_parameters, symmetry_order_below_1)
{
  const SM sm = to_surface_mesh(icosphere_soup(1));
  const Mesh_view<SM> view(sm);
  Solver solver(sm);
  for(int n : {0, -1, -4})
    if(auto e = expect_invalid(solving(solver, view, {{0, Index(1)}, {20, Index(1)}}, n), Error_code::invalid_symmetry_order))
      EXPECT_MESSAGE_HAS(*e, std::to_string(n));
}

TEST(Bad_parameters, loop_periods_of_the_wrong_size_or_violating_poincare_hopf)
{
  std::vector<double> x;
  {
    const SM sm = to_surface_mesh(torus_soup(2, 0.7, 16, 8));
    const Mesh_view<SM> view(sm);
    Solver solver(sm);
    ASSERT_EQ(solver.loops().size(), 2u);
    for(std::size_t size : {0u, 1u, 3u})
      if(auto e = expect_invalid([&] {
             solver.solve(descriptors(view, {}), view.halfedge_map(x),
                          TC::parameters::loop_periods(std::vector<std::int64_t>(size, 0)));
           }, Error_code::invalid_loop_periods)) {
        EXPECT_MESSAGE_HAS(*e, std::to_string(size) + " value");
        EXPECT_MESSAGE_HAS(*e, "2 loops");
      }
    // any integers are fine on generators
    EXPECT_NO_THROW(solver.solve(descriptors(view, {}), view.halfedge_map(x),
                                 TC::parameters::loop_periods(std::vector<std::int64_t>{5, -3})));
  }
  {
    // annulus: chi = 0, the two boundary indices must sum to -(vertex indices) = 0
    const SM sm = to_surface_mesh(annulus_soup(0.5, 1, 3, 16));
    const Mesh_view<SM> view(sm);
    Solver solver(sm);
    ASSERT_EQ(solver.loops().size(), 2u);
    if(auto e = expect_invalid([&] {
           solver.solve(descriptors(view, {}), view.halfedge_map(x),
                        TC::parameters::loop_periods(std::vector<std::int64_t>{1, 0}));
         }, Error_code::invalid_loop_periods)) {
      EXPECT_EQ(e->where(), 0u);
      EXPECT_MESSAGE_HAS(*e, "component 0");
      EXPECT_MESSAGE_HAS(*e, "expected 0");
    }
    // with n = 4 the periods are in quarters: {4, -3} sums to 1/4
    if(auto e = expect_invalid([&] {
           solver.solve(descriptors(view, {}), view.halfedge_map(x),
                        TC::parameters::loop_periods(std::vector<std::int64_t>{4, -3}, TC::parameters::symmetry_order(4)));
         }, Error_code::invalid_loop_periods))
      EXPECT_MESSAGE_HAS(*e, "1/4");
    EXPECT_NO_THROW(solver.solve(descriptors(view, {}), view.halfedge_map(x),
                                 TC::parameters::loop_periods(std::vector<std::int64_t>{4, -4}, TC::parameters::symmetry_order(4))));
  }
}

TEST(Bad_parameters, seed_face_and_angle)
{
  const SM sm = to_surface_mesh(icosphere_soup(1));
  const Mesh_view<SM> view(sm);
  Solver solver(sm);
  const Solution<SM> s = solve_and_check(view, solver, {{0, Index(1)}, {nearest_interior_vertex(view, {{0, 0, -1}}), Index(1)}}, 1, false);
  std::vector<double> x = s.x;
  std::vector<Vector> field;
  expect_invalid([&] {
      solver.compute_field(view.halfedge_map_const(x), view.face_map(field), TC::parameters::seed_face(SM::Face_index(100000)));
    }, Error_code::invalid_argument);
  expect_invalid([&] {
      solver.compute_field(view.halfedge_map_const(x), view.face_map(field), TC::parameters::seed_face(SM::null_face()));
    }, Error_code::invalid_argument);
  expect_invalid([&] {
      solver.compute_field(view.halfedge_map_const(x), view.face_map(field),
                           TC::parameters::seed_angle(std::numeric_limits<double>::infinity()));
    }, Error_code::invalid_argument);
}

TEST(Bad_parameters, singularity_index_construction)
{
  expect_invalid([] { Index(1, 0); }, Error_code::invalid_index);
  expect_invalid([] { Index(std::int64_t(1) << 62); }, Error_code::invalid_index);
  // an index so large that the sums could overflow is rejected by solve()
  const SM sm = to_surface_mesh(icosphere_soup(1));
  const Mesh_view<SM> view(sm);
  Solver solver(sm);
  if(auto e = expect_invalid(solving(solver, view, {{0, Index(std::int64_t(1) << 40)}, {20, Index(2 - (std::int64_t(1) << 40))}}, 4),
                             Error_code::invalid_index))
    EXPECT_MESSAGE_HAS(*e, "vertex 0");
}

// ---------------------------------------------------------------------------------------------------
// The mesh is never modified
// ---------------------------------------------------------------------------------------------------

struct Snapshot
{
  Soup soup;
  std::size_t vertices = 0, halfedges = 0, edges = 0, faces = 0;
  std::vector<std::string> vprops, hprops, eprops, fprops;
  bool garbage = false;
};

Snapshot snapshot(const SM& sm)
{
  Snapshot s;
  s.soup = mesh_to_soup(sm);
  s.vertices = sm.number_of_vertices(); s.halfedges = sm.number_of_halfedges();
  s.edges = sm.number_of_edges(); s.faces = sm.number_of_faces();
  s.vprops = sm.properties<SM::Vertex_index>(); s.hprops = sm.properties<SM::Halfedge_index>();
  s.eprops = sm.properties<SM::Edge_index>(); s.fprops = sm.properties<SM::Face_index>();
  s.garbage = sm.has_garbage();
  return s;
}

void expect_same(const Snapshot& a, const Snapshot& b)
{
  EXPECT_EQ(a.soup.points, b.soup.points);
  EXPECT_EQ(a.soup.faces, b.soup.faces);
  EXPECT_EQ(a.vertices, b.vertices); EXPECT_EQ(a.halfedges, b.halfedges);
  EXPECT_EQ(a.edges, b.edges); EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.vprops, b.vprops); EXPECT_EQ(a.hprops, b.hprops);
  EXPECT_EQ(a.eprops, b.eprops); EXPECT_EQ(a.fprops, b.fprops);
  EXPECT_EQ(a.garbage, b.garbage);
}

TEST(Mesh_is_never_modified, by_any_public_function)
{
  // a bordered, multi-component mesh: annulus + torus
  const Soup soup = concatenate(annulus_soup(0.5, 1, 3, 16), torus_soup(2, 0.7, 16, 8));
  SM sm = to_surface_mesh(soup);
  // the halfedge order of every vertex and face, to see any re-linking
  auto linking = [](const SM& m) {
    std::vector<std::size_t> r;
    for(auto v : vertices(m)) r.push_back(std::size_t(halfedge(v, m)));
    for(auto f : faces(m)) r.push_back(std::size_t(halfedge(f, m)));
    for(auto h : halfedges(m)) r.push_back(std::size_t(next(h, m)));
    return r;
  };
  const Snapshot before = snapshot(sm);
  const std::vector<std::size_t> links = linking(sm);
  {
    const Mesh_view<SM> view(sm);
    const Singularities sing = plan_singularities(view, 4);
    for(TC::Weighting w : {TC::Weighting::hodge_star, TC::Weighting::unit}) {
      Solver solver(sm, TC::parameters::weighting(w));
      solve_and_check(view, solver, sing, 4);
      const int inner = spread_interior_vertices(view, 0, 1).at(0);
      expect_invalid(solving(solver, view, {{inner, Index(1, 3)}}, 4), Error_code::index_not_multiple);
    }
    std::vector<double> x;
    std::vector<Vector> field;
    TC::compute_direction_field(sm, descriptors(view, sing), view.halfedge_map(x), view.face_map(field),
                                TC::parameters::symmetry_order(4));
    TC::homology_generators(sm);
  }
  expect_same(before, snapshot(sm));
  EXPECT_EQ(links, linking(sm));

  // Polyhedron_3: positions and connectivity
  Polyhedron P = to_polyhedron(soup);
  const Soup pb = mesh_to_soup(P);
  {
    const Mesh_view<Polyhedron> view(P);
    TC::Trivial_connection_solver<Polyhedron> solver(P);
    solve_and_check(view, solver, plan_singularities(view, 1), 1);
    TC::homology_generators(P);
  }
  const Soup pa = mesh_to_soup(P);
  EXPECT_EQ(pb.points, pa.points);
  EXPECT_EQ(pb.faces, pa.faces);
}

} // namespace
