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

} // namespace
