// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// The public quad-mesh call compute_quad_mesh() (quad_mesh.h, issue 43), through the public API only: a cross
// field solved and propagated by the solver, the quads read back from the output mesh and checked from their
// definitions (all quads, each edge in two quads with opposite directions, V - E + F, the valence of every vertex
// from the output's faces, the quads on the cube's faces facing out), and the bad inputs refused.

#include "test_support.h"

#include <CGAL/Trivial_connections/quad_mesh.h>
#include <CGAL/Trivial_connections/quad_size.h>
#include <CGAL/Trivial_connections/singularities_off_features.h>

#include <boost/property_map/function_property_map.hpp>

#include <queue>

namespace {

using namespace tc_test;
using vertex_descriptor = Surface_mesh::Vertex_index;
using face_descriptor = Surface_mesh::Face_index;
using halfedge_descriptor = Surface_mesh::Halfedge_index;

// A cross field solved on a soup with the given singularities (soup vertex numbers). along_axes: the field seeded
// along an edge of face 0 that is parallel to a coordinate axis (on a voxel cube, whose connection is Levi-Civita,
// the field is then along the cube's edges everywhere).
struct Solved
{
  Surface_mesh mesh;
  Surface_mesh::Property_map<halfedge_descriptor, double> x;
  Surface_mesh::Property_map<face_descriptor, Vector> field;
  std::vector<std::pair<vertex_descriptor, Index>> singularities;

  Solved(const Soup& soup, const Singularities& s, bool along_axes = false, int n = 4)
    : mesh(to_surface_mesh(soup))
  {
    x = mesh.add_property_map<halfedge_descriptor, double>("h:x", 0.).first;
    field = mesh.add_property_map<face_descriptor, Vector>("f:field", CGAL::NULL_VECTOR).first;
    for(const auto& p : s)
      singularities.emplace_back(vertex_descriptor(p.first), p.second);
    TC::Trivial_connection_solver<Surface_mesh> solver(mesh);
    solver.solve(singularities, x, TC::parameters::symmetry_order(n));
    const face_descriptor f0(0);
    double angle = 0;
    if(along_axes) {
      const halfedge_descriptor h0 = mesh.halfedge(f0);
      const Vector e0 = mesh.point(mesh.target(h0)) - mesh.point(mesh.source(h0));
      for(halfedge_descriptor h : CGAL::halfedges_around_face(h0, mesh)) {
        const Vector e = mesh.point(mesh.target(h)) - mesh.point(mesh.source(h));
        if(int(e.x() == 0) + int(e.y() == 0) + int(e.z() == 0) == 2) {
          const Vector N = CGAL::cross_product(e0, mesh.point(mesh.target(mesh.next(h0))) - mesh.point(mesh.target(h0)));
          angle = std::atan2(CGAL::cross_product(e0, e) * N / std::sqrt(N.squared_length()), e0 * e);
          break;
        }
      }
    }
    solver.compute_field(x, field, TC::parameters::seed_angle(angle, TC::parameters::seed_face(f0, TC::parameters::symmetry_order(n))));
  }
};

// What the output mesh is, counted from its faces alone
struct Quad_counts
{
  std::size_t faces = 0, non_quads = 0, vertices = 0, edges = 0;
  std::size_t unpaired = 0;             // directed edges without their opposite, or used twice
  std::map<std::size_t, std::size_t> valence; // valence (distinct neighbours through the faces) -> vertices
  long long euler = 0;
};

Quad_counts count(const Surface_mesh& out)
{
  Quad_counts c;
  std::vector<std::vector<int>> polygons;
  for(face_descriptor f : out.faces()) {
    std::vector<int> p;
    for(vertex_descriptor v : CGAL::vertices_around_face(out.halfedge(f), out))
      p.push_back(int(v));
    c.non_quads += p.size() != 4;
    polygons.push_back(p);
  }
  c.faces = polygons.size();
  std::map<std::pair<int, int>, int> directed;
  std::vector<std::set<int>> neighbours(out.number_of_vertices());
  for(const auto& p : polygons)
    for(std::size_t k = 0; k < p.size(); ++k) {
      const int a = p[k], b = p[(k + 1) % p.size()];
      ++directed[{a, b}];
      neighbours[a].insert(b);
      neighbours[b].insert(a);
    }
  std::set<std::pair<int, int>> undirected;
  for(const auto& [e, times] : directed) {
    c.unpaired += times != 1 || !directed.count({e.second, e.first});
    undirected.insert({(std::min)(e.first, e.second), (std::max)(e.first, e.second)});
  }
  c.edges = undirected.size();
  for(const auto& n : neighbours)
    if(!n.empty()) {
      ++c.vertices;
      ++c.valence[n.size()];
    }
  c.euler = (long long)c.vertices - (long long)c.edges + (long long)c.faces;
  return c;
}

std::vector<int> corners_of_unit_cube(const Soup& soup)
{
  std::vector<int> corners;
  for(int v = 0; v < int(soup.points.size()); ++v) {
    const Point& p = soup.points[v];
    if((p.x() == 0 || p.x() == 1) && (p.y() == 0 || p.y() == 1) && (p.z() == 0 || p.z() == 1))
      corners.push_back(v);
  }
  return corners;
}

Singularities quarter_turns(const std::vector<int>& vertices)
{
  Singularities s;
  for(int v : vertices)
    s.emplace_back(v, Index(1, 4));
  return s;
}

// The unit cube [0, 1]^3 with quads of side H = 1/k: 6 k^2 quads, 6 k^2 + 2 vertices (Euler), the eight corners of
// valence 3 and all others 4, every quad on one face of the cube (its four vertices on the face's plane) with its
// normal pointing out, every vertex on the cube, the report agreeing.
void check_cube(const Solved& cube, int k, const std::string& name)
{
  SCOPED_TRACE(name);
  Surface_mesh out;
  const double H = 1. / k;
  const TC::Quad_mesh_report r =
    TC::compute_quad_mesh(cube.mesh, cube.x, cube.field, cube.singularities, out, TC::parameters::quad_size(H));
  Quad_counts c = count(out);
  EXPECT_EQ(c.faces, std::size_t(6 * k * k));
  EXPECT_EQ(c.non_quads, 0u);
  EXPECT_EQ(c.unpaired, 0u) << "an edge not in exactly two quads with opposite directions";
  EXPECT_EQ(c.euler, 2);
  EXPECT_EQ(c.vertices, std::size_t(6 * k * k + 2));
  EXPECT_EQ(c.valence[3], 8u);
  EXPECT_EQ(c.valence[4], c.vertices - 8);
  // the eight valence-3 vertices are the cube's corners
  for(vertex_descriptor v : out.vertices()) {
    const Point& p = out.point(v);
    for(int a = 0; a < 3; ++a) {
      EXPECT_GE(p[a], -1e-9);
      EXPECT_LE(p[a], 1 + 1e-9);
    }
    int on_faces = 0;
    for(int a = 0; a < 3; ++a)
      on_faces += std::abs(p[a]) < 1e-9 || std::abs(p[a] - 1) < 1e-9;
    EXPECT_GE(on_faces, 1) << "a quad vertex off the cube";
    if(out.degree(v) == 3)
      EXPECT_EQ(on_faces, 3) << "a valence-3 vertex that is not a corner of the cube";
  }
  // each quad on a face of the cube, facing out, of side H
  int flipped = 0, off_face = 0, wrong_size = 0;
  for(face_descriptor f : out.faces()) {
    std::vector<Point> p;
    for(vertex_descriptor v : CGAL::vertices_around_face(out.halfedge(f), out))
      p.push_back(out.point(v));
    if(p.size() != 4)
      continue;
    Vector newell(0, 0, 0);
    for(int j = 0; j < 4; ++j)
      newell = newell + CGAL::cross_product(p[j] - CGAL::ORIGIN, p[(j + 1) % 4] - CGAL::ORIGIN);
    int face_axis = -1;
    double side = 0;
    for(int a = 0; a < 3; ++a)
      for(double plane : {0., 1.}) {
        bool all = true;
        for(const Point& q : p)
          all = all && std::abs(q[a] - plane) < 1e-9;
        if(all) {
          face_axis = a;
          side = plane == 0 ? -1 : 1;
        }
      }
    if(face_axis < 0) {
      ++off_face;
      continue;
    }
    flipped += newell[face_axis] * side <= 0;
    for(int j = 0; j < 4; ++j)
      wrong_size += std::abs(std::sqrt(CGAL::squared_distance(p[j], p[(j + 1) % 4])) - H) > 1e-9;
  }
  EXPECT_EQ(off_face, 0) << "quads not on one face of the cube";
  EXPECT_EQ(flipped, 0) << "quads facing into the cube";
  EXPECT_EQ(wrong_size, 0) << "quad edges whose length is not H";
  // the report
  EXPECT_EQ(r.quad_size, H);
  EXPECT_EQ(r.number_of_quads, c.faces);
  EXPECT_EQ(r.number_of_vertices, c.vertices);
  EXPECT_EQ(r.valence_errors, 0u);
  EXPECT_EQ(r.wrongly_wound_singularities, 0u);
  EXPECT_EQ(r.valence_histogram.at(3), 8u);
  EXPECT_EQ(r.folded_triangles + r.degenerate_triangles + r.rejected_polygons + r.open_edges, 0u);
  EXPECT_EQ(r.flipped_quads, 0u);
  EXPECT_EQ(r.concave_quads, 0u);
  EXPECT_EQ(r.split_vertices, 0u);
  EXPECT_LE(r.hausdorff_distance(), H / 2);
  EXPECT_LT(r.hausdorff_distance(), 1e-9) << "the quads are on the cube's faces";
}

TEST(QuadMesh, CubeKnownAnswers)
{
  for(int s : {6, 5}) {
    const Soup soup = voxel_surface_soup({{{0, 0, 0}}}, s);
    const Solved cube(soup, quarter_turns(corners_of_unit_cube(soup)), true);
    for(int k : {1, 2, 3})
      if(s == 6 || k > 1)
        check_cube(cube, k, "cube " + std::to_string(s) + "x" + std::to_string(s) + ", H = 1/" + std::to_string(k));
  }
}

// The same counts whatever the numbering of the vertices, the order of the faces and their first corners.
TEST(QuadMesh, CubeIndependentOfNumbering)
{
  for(unsigned seed : {1u, 7u}) {
    const Soup soup = renumbered(voxel_surface_soup({{{0, 0, 0}}}, 5), seed, nullptr, true);
    const Solved cube(soup, quarter_turns(corners_of_unit_cube(soup)), true);
    check_cube(cube, 2, "renumbered cube, seed " + std::to_string(seed));
  }
}

// target_faces N gives H = sqrt(area / N): on the cube of area 6, N = 54 is H = 1/3 and 54 quads; the naive rounding
// gives the same quads on the cube (nothing to round but integers); another output mesh type (Polyhedron_3).
TEST(QuadMesh, TargetFacesRoundingAndPolyhedronOutput)
{
  const Soup soup = voxel_surface_soup({{{0, 0, 0}}}, 6);
  const Solved cube(soup, quarter_turns(corners_of_unit_cube(soup)), true);
  Surface_mesh out;
  const TC::Quad_mesh_report r = TC::compute_quad_mesh(cube.mesh, cube.x, cube.field, cube.singularities, out,
                                                       TC::parameters::target_faces(std::size_t(54)));
  EXPECT_NEAR(r.quad_size, 1. / 3, 1e-12);
  EXPECT_EQ(out.number_of_faces(), 54u);
  Polyhedron poly;
  const TC::Quad_mesh_report naive = TC::compute_quad_mesh(
    cube.mesh, cube.x, cube.field, cube.singularities, poly,
    TC::parameters::quad_rounding(TC::Quad_rounding::naive, TC::parameters::quad_size(0.5)));
  EXPECT_EQ(poly.size_of_facets(), 24u);
  EXPECT_TRUE(CGAL::is_closed(poly));
  EXPECT_TRUE(CGAL::is_quad_mesh(poly));
  EXPECT_EQ(naive.valence_errors, 0u);
}

// A torus of revolution without singularity: every vertex of valence 4, a closed surface of Euler characteristic 0,
// where the map has no fold.
TEST(QuadMesh, TorusAllValenceFour)
{
  const Solved torus(torus_soup(3, 1, 24, 12), {});
  Surface_mesh out;
  const double H = 0.3;
  const TC::Quad_mesh_report r =
    TC::compute_quad_mesh(torus.mesh, torus.x, torus.field, torus.singularities, out, TC::parameters::quad_size(H));
  Quad_counts c = count(out);
  EXPECT_GT(c.faces, 0u);
  EXPECT_EQ(c.non_quads, 0u);
  if(r.folded_triangles == 0 && r.degenerate_triangles == 0) {
    EXPECT_EQ(c.valence[4], c.vertices);
    EXPECT_EQ(c.unpaired, 0u);
    EXPECT_EQ(c.euler, 0);
    EXPECT_EQ(r.valence_errors, 0u);
    EXPECT_EQ(r.wrongly_wound_singularities, 0u);
    EXPECT_EQ(r.flipped_quads, 0u);
  }
  EXPECT_LE(r.hausdorff_distance(), H / 2);
}

// A sphere with eight +1/4: eight vertices of valence 3 (at the singular vertices), all others 4, Euler
// characteristic 2, where the map has no fold.
TEST(QuadMesh, SphereEightValenceThree)
{
  const Soup soup = icosphere_soup(3);
  const Solved sphere(soup, quarter_turns({0, 1, 2, 3, 4, 5, 6, 7}));
  Surface_mesh out;
  const double H = 0.2;
  const TC::Quad_mesh_report r =
    TC::compute_quad_mesh(sphere.mesh, sphere.x, sphere.field, sphere.singularities, out, TC::parameters::quad_size(H));
  Quad_counts c = count(out);
  EXPECT_EQ(c.non_quads, 0u);
  if(r.folded_triangles == 0 && r.degenerate_triangles == 0) {
    EXPECT_EQ(c.valence[3], 8u);
    EXPECT_EQ(c.valence[4], c.vertices - 8);
    EXPECT_EQ(c.unpaired, 0u);
    EXPECT_EQ(c.euler, 2);
    EXPECT_EQ(r.valence_errors, 0u);
    EXPECT_EQ(r.wrongly_wound_singularities, 0u);
    EXPECT_EQ(r.flipped_quads, 0u);
    // every quad faces out: its vector area along the sphere's normal (the position) at its centre
    int inward = 0;
    for(face_descriptor f : out.faces()) {
      Vector area(0, 0, 0), centre(0, 0, 0);
      const halfedge_descriptor h0 = out.halfedge(f);
      for(halfedge_descriptor h : CGAL::halfedges_around_face(h0, out)) {
        area = area + CGAL::cross_product(out.point(out.source(h)) - CGAL::ORIGIN, out.point(out.target(h)) - CGAL::ORIGIN);
        centre = centre + (out.point(out.source(h)) - CGAL::ORIGIN);
      }
      inward += area * centre <= 0;
    }
    EXPECT_EQ(inward, 0);
    // the valence-3 vertices are at the singular vertices
    for(vertex_descriptor v : out.vertices())
      if(out.degree(v) == 3) {
        double nearest = 1e9;
        for(int s = 0; s < 8; ++s)
          nearest = (std::min)(nearest, std::sqrt(CGAL::squared_distance(out.point(v), soup.points[s])));
        EXPECT_LT(nearest, 1e-9);
      }
  }
  EXPECT_LE(r.hausdorff_distance(), H / 2);
}

// Bad inputs: a field that is not a cross field (n = 2), H not positive or not finite, H too small, neither or
// both of quad_size and target_faces, a border: Invalid_input with its code, the output untouched.
TEST(QuadMesh, BadInputsAreRefused)
{
  const Soup soup = voxel_surface_soup({{{0, 0, 0}}}, 3);
  const Solved cube(soup, quarter_turns(corners_of_unit_cube(soup)), true);
  auto code = [&](auto np) {
    Surface_mesh out;
    try {
      TC::compute_quad_mesh(cube.mesh, cube.x, cube.field, cube.singularities, out, np);
    } catch(const TC::Invalid_input& e) {
      EXPECT_EQ(out.number_of_faces(), 0u) << "the output was touched";
      EXPECT_FALSE(std::string(e.what()).empty());
      return e.code();
    }
    ADD_FAILURE() << "not refused";
    return TC::Error_code::empty_mesh;
  };
  namespace P = TC::parameters;
  EXPECT_EQ(code(P::symmetry_order(2, P::quad_size(0.5))), TC::Error_code::invalid_symmetry_order);
  EXPECT_EQ(code(P::quad_size(0.)), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(P::quad_size(-0.5)), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(P::quad_size(std::numeric_limits<double>::quiet_NaN())), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(P::quad_size(std::numeric_limits<double>::infinity())), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(P::quad_size(1e-4)), TC::Error_code::invalid_argument); // 6e8 quads > 1e7
  EXPECT_EQ(code(P::max_quads(100., P::quad_size(0.1))), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(P::target_faces(std::size_t(24), P::quad_size(0.5))), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(P::max_quads(100.)), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(P::target_faces(std::size_t(0))), TC::Error_code::invalid_argument);
  {
    // a line field (n = 2) with +1/2 singularities, said to be one: refused as not a cross field
    const Soup sphere = icosphere_soup(2);
    const Singularities halves = {{0, Index(1, 2)}, {3, Index(1, 2)}, {5, Index(1, 2)}, {9, Index(1, 2)}};
    const Solved lines(sphere, halves, false, 2);
    Surface_mesh out;
    try {
      TC::compute_quad_mesh(lines.mesh, lines.x, lines.field, lines.singularities, out,
                            P::symmetry_order(2, P::quad_size(0.3)));
      ADD_FAILURE() << "a line field was taken";
    } catch(const TC::Invalid_input& e) {
      EXPECT_EQ(e.code(), TC::Error_code::invalid_symmetry_order);
    }
  }
  {
    // a singularity given with an index that is not a multiple of 1/4
    std::vector<std::pair<vertex_descriptor, Index>> wrong = cube.singularities;
    wrong[0].second = Index(1, 3);
    Surface_mesh out;
    try {
      TC::compute_quad_mesh(cube.mesh, cube.x, cube.field, wrong, out, P::quad_size(0.5));
      ADD_FAILURE() << "an index 1/3 was taken";
    } catch(const TC::Invalid_input& e) {
      EXPECT_EQ(e.code(), TC::Error_code::index_not_multiple);
    }
  }
  {
    // the corners not declared singular: the field turns around them
    Surface_mesh out;
    EXPECT_THROW(TC::compute_quad_mesh(cube.mesh, cube.x, cube.field,
                                       std::vector<std::pair<vertex_descriptor, Index>>(), out, P::quad_size(0.5)),
                 TC::Invalid_input);
    EXPECT_EQ(out.number_of_faces(), 0u);
  }
  {
    // a surface with border: not handled by the extraction yet
    const Solved flat(disk_soup(6, 16), {});
    Surface_mesh out;
    EXPECT_THROW(TC::compute_quad_mesh(flat.mesh, flat.x, flat.field, flat.singularities, out, P::quad_size(0.2)),
                 TC::Invalid_input);
    EXPECT_EQ(out.number_of_faces(), 0u);
  }
}


// ---- move_singularities_off_features() (singularities_off_features.h), checked from its definitions ----

// The test's own view of a soup: sharp edges by the angle of the face normals (over 30 degrees), the graph distance
// along edges to their vertices, and the shortest path lengths through vertices of no sharp edge (plain Dijkstras,
// written here independently of the library's Boost.Graph searches).
struct Feature_view
{
  std::vector<std::vector<std::pair<int, double>>> next; // per vertex: (neighbour, edge length)
  std::set<std::pair<int, int>> sharp;                  // (i < j)
  std::vector<char> on_sharp, on_border;
  std::vector<double> to_sharp;
  std::vector<int> component;

  explicit Feature_view(const Soup& soup)
    : next(soup.points.size()), on_sharp(soup.points.size(), 0), on_border(soup.points.size(), 0),
      component(soup.points.size(), -1)
  {
    std::map<std::pair<int, int>, std::vector<Vector>> normals;
    for(const Tri& t : soup.faces) {
      const Vector n = CGAL::cross_product(soup.points[t[1]] - soup.points[t[0]], soup.points[t[2]] - soup.points[t[0]]);
      for(int k = 0; k < 3; ++k)
        normals[std::minmax(t[k], t[(k + 1) % 3])].push_back(n / std::sqrt(n.squared_length()));
    }
    for(const auto& [e, n] : normals) {
      const double length = std::sqrt(CGAL::squared_distance(soup.points[e.first], soup.points[e.second]));
      next[e.first].emplace_back(e.second, length);
      next[e.second].emplace_back(e.first, length);
      if(n.size() == 1)
        on_border[e.first] = on_border[e.second] = 1;
      else if(n[0] * n[1] < std::cos(30 * pi / 180)) {
        sharp.insert(e);
        on_sharp[e.first] = on_sharp[e.second] = 1;
      }
    }
    std::vector<int> all;
    for(int v = 0; v < int(next.size()); ++v)
      if(on_sharp[v])
        all.push_back(v);
    to_sharp = dijkstra(all, false);
    for(int v = 0, c = 0; v < int(next.size()); ++v)
      if(component[v] < 0) {
        std::vector<int> stack{v};
        component[v] = c;
        while(!stack.empty()) {
          const int u = stack.back();
          stack.pop_back();
          for(const auto& [w, l] : next[u])
            if(component[w] < 0) {
              component[w] = c;
              stack.push_back(w);
            }
        }
        ++c;
      }
  }
  // from the sources, through every vertex or (off_sharp) only through vertices of no sharp edge
  std::vector<double> dijkstra(const std::vector<int>& sources, bool off_sharp) const
  {
    std::vector<double> d(next.size(), std::numeric_limits<double>::infinity());
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for(int s : sources) {
      d[s] = 0;
      queue.push({0., s});
    }
    while(!queue.empty()) {
      const auto [du, u] = queue.top();
      queue.pop();
      if(du > d[u])
        continue;
      for(const auto& [w, l] : next[u])
        if(!(off_sharp && on_sharp[w]) && du + l < d[w]) {
          d[w] = du + l;
          queue.push({d[w], w});
        }
    }
    return d;
  }
};

// The unit cube cut into 10 x 10 squares per face (its 12 edges sharp), and a cube of side 0.3 cut into 3 x 3 beside
// it (no vertex at least H = 0.25 from its edges)
Soup two_boxes()
{
  Soup small = voxel_surface_soup({{{0, 0, 0}}}, 3);
  for(Point& p : small.points)
    p = Point(3 + 0.3 * p.x(), 0.3 * p.y(), 0.3 * p.z());
  return concatenate(voxel_surface_soup({{{0, 0, 0}}}, 10), small);
}

int vertex_at(const Soup& soup, const Point& p)
{
  for(int v = 0; v < int(soup.points.size()); ++v)
    if(CGAL::squared_distance(soup.points[v], p) < 1e-20)
      return v;
  ADD_FAILURE() << "no vertex at " << p;
  return -1;
}

struct Off_features_case
{
  Singularities singularities; // soup numbering
  std::vector<int> fixed;
};

// the singularities of the test, found by their points (so the same ones in any numbering)
Off_features_case off_features_case(const Soup& soup)
{
  Off_features_case c;
  for(const Point& p : {Point(0, 0, 0), Point(1, 1, 1)}) // on the features: they stay
    c.singularities.emplace_back(vertex_at(soup, p), Index(1, 4));
  c.singularities.emplace_back(vertex_at(soup, Point(0.5, 0.1, 0)), Index(1, 4));   // 0.1 from an edge: moves
  c.singularities.emplace_back(vertex_at(soup, Point(0.2, 0.5, 1)), Index(-1, 4));  // 0.2: moves
  c.singularities.emplace_back(vertex_at(soup, Point(0.5, 0.6, 0)), Index(-1, 4));  // 0.4: stays
  c.singularities.emplace_back(vertex_at(soup, Point(0.1, 0.5, 0)), Index(0));      // index 0: stays
  c.singularities.emplace_back(vertex_at(soup, Point(0.5, 0.9, 1)), Index(1, 2));   // fixed
  c.singularities.emplace_back(vertex_at(soup, Point(0, 0.3, 0.8)), Index(1, 4));   // 0.2 on x = 0: moves
  c.singularities.emplace_back(vertex_at(soup, Point(3.1, 0.1, 0)), Index(1, 4));   // small box: stuck
  c.fixed.push_back(vertex_at(soup, Point(0.5, 0.9, 1)));
  return c;
}

// the result as points: (from, to) per singularity, in the input's order
std::vector<std::pair<Point, Point>> off_features_result(const Soup& soup, const Off_features_case& c, double H,
                                                         TC::Off_features_report<Surface_mesh>* out = nullptr)
{
  const Surface_mesh mesh = to_surface_mesh(soup);
  const Feature_view view(soup);
  std::vector<char> sharp(mesh.number_of_edges(), 0);
  for(auto e : edges(mesh))
    sharp[std::size_t(e)] = view.sharp.count(std::minmax(int(source(e, mesh)), int(target(e, mesh)))) > 0;
  std::vector<std::pair<vertex_descriptor, Index>> singularities;
  for(const auto& [v, k] : c.singularities)
    singularities.emplace_back(vertex_descriptor(v), k);
  std::vector<vertex_descriptor> fixed;
  for(int v : c.fixed)
    fixed.push_back(vertex_descriptor(v));
  const auto before = singularities;
  const auto report = TC::move_singularities_off_features(
    mesh, singularities, boost::make_iterator_property_map(sharp.begin(), get(boost::edge_index, mesh)),
    TC::parameters::quad_size(H, TC::parameters::fixed_vertices(fixed)));
  EXPECT_EQ(singularities, before) << "the input was modified";
  std::vector<std::pair<Point, Point>> result;
  for(std::size_t i = 0; i < singularities.size(); ++i)
    result.emplace_back(mesh.point(singularities[i].first), mesh.point(report.singularities[i].first));
  if(out)
    *out = report;
  return result;
}

// Every moved singularity ends at least H (graph distance) from every sharp edge, at the nearest such free vertex
// reachable off the sharp edges; the others are unchanged; indices and their sums per component are kept; nothing
// depends on the numbering of the vertices.
TEST(SingularitiesOffFeatures, MovedAtLeastHAwayNearestAndIndependentOfNumbering)
{
  const double H = 0.25;
  const Soup soup = two_boxes();
  const Feature_view view(soup);
  EXPECT_EQ(view.sharp.size(), 12u * 10 + 12u * 3) << "the cubes' edges";
  const Off_features_case c = off_features_case(soup);
  TC::Off_features_report<Surface_mesh> report;
  const auto result = off_features_result(soup, c, H, &report);
  EXPECT_EQ(report.quad_size, H);
  ASSERT_EQ(report.singularities.size(), c.singularities.size());
  std::map<int, Index> sum_before, sum_after;
  std::set<int> taken;
  std::size_t moved = 0;
  for(std::size_t i = 0; i < c.singularities.size(); ++i) {
    const int from = c.singularities[i].first, to = int(report.singularities[i].first);
    EXPECT_EQ(report.singularities[i].second, c.singularities[i].second) << "the index of singularity " << i;
    sum_before[view.component[from]] = sum_before[view.component[from]] + c.singularities[i].second;
    sum_after[view.component[to]] = sum_after[view.component[to]] + report.singularities[i].second;
    EXPECT_TRUE(taken.insert(to).second) << "two singularities on vertex " << to;
    const double d = view.to_sharp[from];
    const bool should_move = c.singularities[i].second != Index(0) && d > 0 && d < H && from != c.fixed[0] &&
                             view.component[from] == 0;
    if(!should_move) {
      EXPECT_EQ(from, to) << "singularity " << i << " moved";
      continue;
    }
    ++moved;
    EXPECT_GE(view.to_sharp[to], H) << "singularity " << i;
    EXPECT_FALSE(view.on_border[to]);
    // the nearest vertex at least H away, off the border and free, through vertices of no sharp edge
    const std::vector<double> path = view.dijkstra({from}, true);
    double nearest = std::numeric_limits<double>::infinity();
    for(int w = 0; w < int(soup.points.size()); ++w) {
      bool listed = false;
      for(std::size_t j = 0; j < c.singularities.size(); ++j)
        listed = listed || (j < i && int(report.singularities[j].first) == w) || (j > i && c.singularities[j].first == w);
      if(view.to_sharp[w] >= H && !view.on_border[w] && (!listed || w == to))
        nearest = std::min(nearest, path[w]);
    }
    EXPECT_EQ(path[to], nearest) << "singularity " << i << " did not go to the nearest vertex";
  }
  EXPECT_EQ(moved, 3u);
  EXPECT_EQ(report.moves.size(), 3u);
  EXPECT_EQ(sum_before, sum_after) << "an index sum per component changed";
  EXPECT_EQ(report.on_features, 2u);
  EXPECT_EQ(report.fixed, 1u);
  ASSERT_EQ(report.stuck.size(), 1u) << "the small box has no vertex H away from its edges";
  EXPECT_EQ(int(report.stuck[0]), c.singularities[8].first);
  for(const auto& m : report.moves) {
    EXPECT_DOUBLE_EQ(m.distance_before, view.to_sharp[int(m.from)]);
    EXPECT_DOUBLE_EQ(m.distance_after, view.to_sharp[int(m.to)]);
    EXPECT_DOUBLE_EQ(m.path_length, view.dijkstra({int(m.from)}, true)[int(m.to)]);
  }
  // the grid has ties (equal path lengths): decided by the points, so any numbering gives the same points
  for(unsigned seed : {3u, 11u}) {
    const Soup r = renumbered(soup, seed, nullptr, true);
    EXPECT_EQ(off_features_result(r, off_features_case(r), H), result) << "renumbered, seed " << seed;
  }
  // another mesh type: the same vertices (Polyhedron_3, vertex order of the soup)
  const Polyhedron poly = to_polyhedron(soup);
  using Poly_vertex = boost::graph_traits<Polyhedron>::vertex_descriptor;
  const std::vector<Poly_vertex> handle(vertices(poly).begin(), vertices(poly).end());
  std::map<const void*, int> number;
  for(int v = 0; v < int(handle.size()); ++v)
    number[&*handle[v]] = v;
  std::vector<std::pair<Poly_vertex, Index>> on_poly;
  for(const auto& [v, k] : c.singularities)
    on_poly.emplace_back(handle[v], k);
  const auto poly_report = TC::move_singularities_off_features(
    poly, on_poly,
    boost::make_function_property_map<boost::graph_traits<Polyhedron>::edge_descriptor, bool>(
      [&](boost::graph_traits<Polyhedron>::edge_descriptor e) {
        return view.sharp.count(std::minmax(number[&*source(e, poly)], number[&*target(e, poly)])) > 0;
      }),
    TC::parameters::quad_size(H, TC::parameters::fixed_vertices(std::vector<Poly_vertex>{handle[c.fixed[0]]})));
  for(std::size_t i = 0; i < on_poly.size(); ++i)
    EXPECT_EQ(poly_report.singularities[i].first->point(), result[i].second) << "Polyhedron_3, singularity " << i;
}

// target_faces N is H = sqrt(area / N), the rule compute_quad_mesh() reads; no feature edge: nothing moves; bad
// inputs refused with their codes
TEST(SingularitiesOffFeatures, QuadSizeRuleAndBadInputs)
{
  const Surface_mesh cube = to_surface_mesh(voxel_surface_soup({{{0, 0, 0}}}, 6));
  EXPECT_NEAR(TC::quad_size_for_target_faces(cube, 54), 1. / 3, 1e-12); // area 6
  namespace P = TC::parameters;
  std::vector<char> sharp(cube.number_of_edges(), 0);
  const auto none = boost::make_iterator_property_map(sharp.begin(), get(boost::edge_index, cube));
  const std::vector<std::pair<vertex_descriptor, Index>> s = {{vertex_descriptor(7), Index(1, 4)}};
  const auto r = TC::move_singularities_off_features(cube, s, none, P::target_faces(std::size_t(54)));
  EXPECT_EQ(r.quad_size, TC::quad_size_for_target_faces(cube, 54));
  EXPECT_EQ(r.singularities, s);
  EXPECT_TRUE(r.moves.empty());
  auto code = [&](const Surface_mesh& mesh, const auto& singularities, auto np) {
    try {
      TC::move_singularities_off_features(mesh, singularities, none, np);
    } catch(const TC::Invalid_input& e) {
      EXPECT_FALSE(std::string(e.what()).empty());
      return e.code();
    }
    ADD_FAILURE() << "not refused";
    return TC::Error_code::empty_mesh;
  };
  EXPECT_EQ(code(cube, s, P::quad_size(0.)), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(cube, s, P::quad_size(-1.)), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(cube, s, P::quad_size(std::numeric_limits<double>::quiet_NaN())), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(cube, s, P::target_faces(std::size_t(0))), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(cube, s, P::quad_size(0.5, P::target_faces(std::size_t(5)))), TC::Error_code::invalid_argument);
  EXPECT_EQ(code(cube, s, P::fixed_vertices(std::vector<vertex_descriptor>{})), TC::Error_code::invalid_argument);
  const std::vector<std::pair<vertex_descriptor, Index>> twice = {{vertex_descriptor(7), Index(1, 4)},
                                                                   {vertex_descriptor(7), Index(-1, 4)}};
  EXPECT_EQ(code(cube, twice, P::quad_size(0.5)), TC::Error_code::duplicate_singularity);
  const std::vector<std::pair<vertex_descriptor, Index>> missing = {{vertex_descriptor(100000), Index(1, 4)}};
  EXPECT_EQ(code(cube, missing, P::quad_size(0.5)), TC::Error_code::invalid_vertex);
  const Surface_mesh disk = to_surface_mesh(disk_soup(3, 8));
  std::vector<char> no_edge(disk.number_of_edges(), 0);
  const std::vector<std::pair<vertex_descriptor, Index>> rim = {{vertex_descriptor(20), Index(1, 4)}};
  try {
    TC::move_singularities_off_features(disk, rim, boost::make_iterator_property_map(no_edge.begin(), get(boost::edge_index, disk)),
                                        P::quad_size(0.5));
    ADD_FAILURE() << "a singularity on the border was accepted";
  } catch(const TC::Invalid_input& e) {
    EXPECT_EQ(e.code(), TC::Error_code::singularity_on_boundary);
  }
}


// Exact ties: a flat grid (squares of side 1/4 split at their centres, symmetric under x -> -x), the row y = 1/4
// as feature line, a singularity at (0, 1/2) and the vertex straight above at H = 3/4 taken: mirror vertices are
// equally near, to the last bit. The smallest point wins, whatever the numbering.
TEST(SingularitiesOffFeatures, ExactTiesDecidedByThePoints)
{
  Soup soup;
  std::map<std::pair<int, int>, int> at; // (16 x, 16 y): the grid's corners at multiples of 4, the centres between
  auto vertex = [&](int x, int y) {
    const auto it = at.find({x, y});
    if(it != at.end())
      return it->second;
    soup.points.emplace_back(x / 16., y / 16., 0);
    return at[{x, y}] = int(soup.points.size()) - 1;
  };
  for(int i = -4; i < 4; ++i)
    for(int j = 0; j < 8; ++j) {
      const int c = vertex(4 * i + 2, 4 * j + 2), a = vertex(4 * i, 4 * j), b = vertex(4 * i + 4, 4 * j),
                d = vertex(4 * i + 4, 4 * j + 4), e = vertex(4 * i, 4 * j + 4);
      soup.faces.push_back({{a, b, c}});
      soup.faces.push_back({{b, d, c}});
      soup.faces.push_back({{d, e, c}});
      soup.faces.push_back({{e, a, c}});
    }
  const double H = 0.75;
  auto run = [&](const Soup& mesh_soup, const std::vector<int>& number) {
    const Surface_mesh mesh = to_surface_mesh(mesh_soup);
    std::vector<char> feature(mesh.number_of_edges(), 0);
    for(auto e : edges(mesh))
      feature[std::size_t(e)] = mesh.point(source(e, mesh)).y() == 0.25 && mesh.point(target(e, mesh)).y() == 0.25;
    const std::vector<std::pair<vertex_descriptor, Index>> s = {
      {vertex_descriptor(number[at.at({0, 8})]), Index(1, 4)}, {vertex_descriptor(number[at.at({0, 16})]), Index(-1, 4)}};
    const auto r = TC::move_singularities_off_features(
      mesh, s, boost::make_iterator_property_map(feature.begin(), get(boost::edge_index, mesh)), TC::parameters::quad_size(H));
    EXPECT_EQ(r.moves.size(), 1u);
    return mesh.point(r.singularities[0].first);
  };
  std::vector<int> identity(soup.points.size());
  std::iota(identity.begin(), identity.end(), 0);
  const Point chosen = run(soup, identity);
  // the test's own distances: the free vertices at the least path length, at least two of them
  Feature_view view(soup); // flat: no sharp edge; the line marked here
  std::vector<int> line;
  for(int x = -16; x <= 16; x += 4)
    line.push_back(at.at({x, 4}));
  for(int v : line)
    view.on_sharp[v] = 1;
  const std::vector<double> to_line = view.dijkstra(line, false);
  const std::vector<double> path = view.dijkstra({at.at({0, 8})}, true);
  double least = std::numeric_limits<double>::infinity();
  for(int w = 0; w < int(soup.points.size()); ++w)
    if(to_line[w] >= H && !view.on_border[w] && w != at.at({0, 16}))
      least = std::min(least, path[w]);
  std::vector<Point> tied;
  for(int w = 0; w < int(soup.points.size()); ++w)
    if(to_line[w] >= H && !view.on_border[w] && w != at.at({0, 16}) && path[w] == least)
      tied.push_back(soup.points[w]);
  ASSERT_GE(tied.size(), 2u) << "no exact tie: the test does not test what it says";
  EXPECT_EQ(chosen, *std::min_element(tied.begin(), tied.end()));
  for(unsigned seed : {2u, 5u, 9u}) {
    std::vector<int> perm;
    const Soup r = renumbered(soup, seed, &perm, true);
    EXPECT_EQ(run(r, perm), chosen) << "renumbered, seed " << seed;
  }
}

} // namespace
