// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_MESH_BUILDERS_H
#define CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_MESH_BUILDERS_H

// Test support: the mesh builders (polygon soups, Surface_mesh, Polyhedron_3), renumbering, CGAL data meshes;
// the types every part uses.

// The mesh types come before the package: see the note at the end of this block.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/graph_traits_Polyhedron_3.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

// Note: internal/mesh/mesh_arrays.h calls CGAL::vertices / CGAL::faces / CGAL::opposite qualified, so (two-phase
// lookup) the package only compiles when the mesh's graph_traits header is included before it.
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>

#include <Eigen/Dense>
#include <boost/property_map/property_map.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace tc_test {

namespace TC = CGAL::Trivial_connections;

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
// the crossover of Cost_based_solver_traits that every factor passes: always CHOLMOD
struct Always_supernodal
{
  static constexpr double flops_per_nonzero = 0, fixed_flops = -1;
};
#endif
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Vector = K::Vector_3;
using Surface_mesh = CGAL::Surface_mesh<Point>;
using Polyhedron = CGAL::Polyhedron_3<K>;
using Tri = std::array<int, 3>;
using Index = TC::Singularity_index;
/// singularities by vertex number (the number of the vertex in `Mesh_view::vertices`)
using Singularities = std::vector<std::pair<int, Index>>;

constexpr double pi = 3.14159265358979323846;
constexpr double two_pi = 2 * pi;

// =====================================================================================================
// (a) Builders
// =====================================================================================================

/// A triangle soup: points and faces (counter-clockwise seen from outside)
struct Soup
{
  std::vector<Point> points;
  std::vector<Tri> faces;
};

/// points of `b` appended to `a`, faces renumbered
inline Soup concatenate(const Soup& a, const Soup& b)
{
  Soup s = a;
  const int off = int(a.points.size());
  s.points.insert(s.points.end(), b.points.begin(), b.points.end());
  for(const Tri& t : b.faces)
    s.faces.push_back({{t[0] + off, t[1] + off, t[2] + off}});
  return s;
}

/// the unit icosahedron subdivided `level` times (each triangle into 4), projected on the sphere
inline Soup icosphere_soup(int level, double radius = 1, const Vector& center = Vector(0, 0, 0))
{
  const double t = (1 + std::sqrt(5.)) / 2;
  std::vector<std::array<double, 3>> P = {
    {{-1, t, 0}}, {{1, t, 0}}, {{-1, -t, 0}}, {{1, -t, 0}}, {{0, -1, t}}, {{0, 1, t}},
    {{0, -1, -t}}, {{0, 1, -t}}, {{t, 0, -1}}, {{t, 0, 1}}, {{-t, 0, -1}}, {{-t, 0, 1}}};
  std::vector<Tri> F = {{{0, 11, 5}}, {{0, 5, 1}}, {{0, 1, 7}}, {{0, 7, 10}}, {{0, 10, 11}},
                        {{1, 5, 9}}, {{5, 11, 4}}, {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},
                        {{3, 9, 4}}, {{3, 4, 2}}, {{3, 2, 6}}, {{3, 6, 8}}, {{3, 8, 9}},
                        {{4, 9, 5}}, {{2, 4, 11}}, {{6, 2, 10}}, {{8, 6, 7}}, {{9, 8, 1}}};
  auto normalize = [](std::array<double, 3> p) {
    const double l = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{{p[0] / l, p[1] / l, p[2] / l}};
  };
  for(auto& p : P) p = normalize(p);
  for(int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if(it != mid.end()) return it->second;
      P.push_back(normalize({{P[a][0] + P[b][0], P[a][1] + P[b][1], P[a][2] + P[b][2]}}));
      mid[key] = int(P.size()) - 1;
      return int(P.size()) - 1;
    };
    std::vector<Tri> G;
    for(const Tri& f : F) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      G.push_back({{f[0], ab, ca}}); G.push_back({{f[1], bc, ab}});
      G.push_back({{f[2], ca, bc}}); G.push_back({{ab, bc, ca}});
    }
    F.swap(G);
  }
  Soup s;
  for(const auto& p : P)
    s.points.emplace_back(center.x() + radius * p[0], center.y() + radius * p[1], center.z() + radius * p[2]);
  s.faces = F;
  return s;
}

/// torus of revolution about z: major radius R, minor radius r, m segments around z, n around the tube
inline Soup torus_soup(double R, double r, int m, int n)
{
  Soup s;
  for(int i = 0; i < m; ++i)
    for(int j = 0; j < n; ++j) {
      const double u = two_pi * i / m, v = two_pi * j / n;
      s.points.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [&](int i, int j) { return ((i + m) % m) * n + (j + n) % n; };
  for(int i = 0; i < m; ++i)
    for(int j = 0; j < n; ++j) {
      // (dP/du x dP/dv) points outward: the quad (i,j) (i+1,j) (i+1,j+1) (i,j+1) is counter-clockwise
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      s.faces.push_back({{a, b, c}});
      s.faces.push_back({{a, c, d}});
    }
  return s;
}

/// Boundary of a union of unit cubes (cells (i,j,k)), every cube face cut into s x s squares, two
/// triangles each, faces oriented outward. The caller must give a union whose boundary is a manifold.
inline Soup voxel_surface_soup(const std::set<std::array<int, 3>>& cells, int s)
{
  Soup soup;
  std::map<std::array<int, 3>, int> vertex_of;
  auto vertex = [&](const std::array<int, 3>& q) {
    auto it = vertex_of.find(q);
    if(it != vertex_of.end()) return it->second;
    soup.points.emplace_back(double(q[0]) / s, double(q[1]) / s, double(q[2]) / s);
    vertex_of[q] = int(soup.points.size()) - 1;
    return int(soup.points.size()) - 1;
  };
  for(const auto& c : cells)
    for(int a = 0; a < 3; ++a)
      for(int sign : {-1, 1}) {
        std::array<int, 3> nb = c;
        nb[a] += sign;
        if(cells.count(nb))
          continue;
        const int u = (a + 1) % 3, v = (a + 2) % 3; // e_u x e_v = e_a
        for(int p = 0; p < s; ++p)
          for(int q = 0; q < s; ++q) {
            auto corner = [&](int dp, int dq) {
              std::array<int, 3> L = {{c[0] * s, c[1] * s, c[2] * s}};
              L[a] += sign > 0 ? s : 0;
              L[u] += p + dp;
              L[v] += q + dq;
              return vertex(L);
            };
            int quad[4] = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};
            if(sign < 0)
              std::swap(quad[1], quad[3]);
            soup.faces.push_back({{quad[0], quad[1], quad[2]}});
            soup.faces.push_back({{quad[0], quad[2], quad[3]}});
          }
      }
  return soup;
}

/// a smooth, orientation-preserving deformation (|gradient| < 0.2) that breaks every symmetry
inline Soup warped(Soup s, double amplitude = 0.1)
{
  for(Point& p : s.points) {
    const double x = p.x(), y = p.y(), z = p.z();
    p = Point(x + amplitude * std::sin(1.7 * y + 0.3 * z + 0.2), y + amplitude * std::sin(1.3 * z + 0.9 * x + 0.7),
              z + amplitude * std::sin(1.1 * x + 0.5 * y + 1.3));
  }
  return s;
}

/// A closed genus-2 surface: the boundary of a 3 x 5 x 1 slab of cubes with two square holes
/// (a thickened figure eight), each cube face cut into s x s squares, then smoothly warped.
inline Soup genus2_soup(int s = 1)
{
  std::set<std::array<int, 3>> cells;
  for(int i = 0; i < 3; ++i)
    for(int j = 0; j < 5; ++j)
      if(!(i == 1 && (j == 1 || j == 3)))
        cells.insert({{i, j, 0}});
  return warped(voxel_surface_soup(cells, s));
}

/// A flat disk in the plane z = 0 (counter-clockwise seen from +z): a centre vertex and `rings` rings
/// of `sectors` vertices each, ring i at radius i / rings, rotated by half a sector from the previous.
inline Soup disk_soup(int rings, int sectors)
{
  Soup s;
  s.points.emplace_back(0, 0, 0);
  for(int i = 1; i <= rings; ++i)
    for(int j = 0; j < sectors; ++j) {
      const double a = two_pi * (j + 0.5 * i) / sectors, r = double(i) / rings;
      s.points.emplace_back(r * std::cos(a), r * std::sin(a), 0);
    }
  auto id = [&](int i, int j) { return 1 + (i - 1) * sectors + (j % sectors); };
  for(int j = 0; j < sectors; ++j)
    s.faces.push_back({{0, id(1, j), id(1, j + 1)}});
  for(int i = 1; i < rings; ++i)
    for(int j = 0; j < sectors; ++j) {
      // ring i+1 is rotated by half a sector: vertex (i+1, j) lies between (i, j) and (i, j+1)
      s.faces.push_back({{id(i, j), id(i + 1, j), id(i, j + 1)}});
      s.faces.push_back({{id(i, j + 1), id(i + 1, j), id(i + 1, j + 1)}});
    }
  return s;
}

/// A flat annulus r0 <= |p| <= r1 in z = 0 (counter-clockwise seen from +z), `rings` + 1 rings of
/// `sectors` vertices each, rotated by half a sector from ring to ring.
inline Soup annulus_soup(double r0, double r1, int rings, int sectors)
{
  Soup s;
  for(int i = 0; i <= rings; ++i)
    for(int j = 0; j < sectors; ++j) {
      const double a = two_pi * (j + 0.5 * i) / sectors, r = r0 + (r1 - r0) * i / rings;
      s.points.emplace_back(r * std::cos(a), r * std::sin(a), 0);
    }
  auto id = [&](int i, int j) { return i * sectors + (j % sectors); };
  for(int i = 0; i < rings; ++i)
    for(int j = 0; j < sectors; ++j) {
      s.faces.push_back({{id(i, j), id(i + 1, j), id(i, j + 1)}});
      s.faces.push_back({{id(i, j + 1), id(i + 1, j), id(i + 1, j + 1)}});
    }
  return s;
}

/// two disjoint spheres in one soup: icosphere(level) and a smaller icosphere(level) beside it
inline Soup two_spheres_soup(int level)
{
  return concatenate(icosphere_soup(level), icosphere_soup(level, 0.7, Vector(3, 0.2, 0.1)));
}

template <class Mesh>
Mesh soup_to_mesh(const Soup& s)
{
  Mesh m;
  std::vector<std::vector<std::size_t>> polygons;
  for(const Tri& t : s.faces)
    polygons.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(s.points, polygons, m);
  return m;
}

/// Surface_mesh with vertex i = point i and face j = triangle j of the soup (built by add_vertex/add_face)
inline Surface_mesh to_surface_mesh(const Soup& s)
{
  Surface_mesh m;
  std::vector<Surface_mesh::Vertex_index> v;
  for(const Point& p : s.points)
    v.push_back(m.add_vertex(p));
  for(const Tri& t : s.faces) {
    const Surface_mesh::Face_index f = m.add_face(v[t[0]], v[t[1]], v[t[2]]);
    if(f == Surface_mesh::null_face())
      throw std::runtime_error("to_surface_mesh: the soup is not an oriented 2-manifold");
  }
  return m;
}

/// Polyhedron_3 built with PMP::polygon_soup_to_polygon_mesh
inline Polyhedron to_polyhedron(const Soup& s) { return soup_to_mesh<Polyhedron>(s); }

/// the generated meshes directly as Surface_mesh (same vertex and face order as their soups)
inline Surface_mesh icosphere(int level) { return to_surface_mesh(icosphere_soup(level)); }
inline Surface_mesh torus(double R, double r, int m, int n) { return to_surface_mesh(torus_soup(R, r, m, n)); }
inline Surface_mesh genus2(int s = 1) { return to_surface_mesh(genus2_soup(s)); }
inline Surface_mesh disk(int rings, int sectors) { return to_surface_mesh(disk_soup(rings, sectors)); }
inline Surface_mesh annulus(double r0, double r1, int rings, int sectors)
{
  return to_surface_mesh(annulus_soup(r0, r1, rings, sectors));
}
inline Surface_mesh two_spheres(int level) { return to_surface_mesh(two_spheres_soup(level)); }

/// The soup of a mesh: vertices in the order of vertices(tm), faces in the order of faces(tm)
template <class Mesh>
Soup mesh_to_soup(const Mesh& tm)
{
  Soup s;
  std::unordered_map<typename boost::graph_traits<Mesh>::vertex_descriptor, int> id;
  for(auto v : vertices(tm)) {
    id[v] = int(s.points.size());
    s.points.push_back(get(CGAL::vertex_point, tm, v));
  }
  for(auto f : faces(tm)) {
    std::vector<int> c;
    for(auto v : vertices_around_face(halfedge(f, tm), tm))
      c.push_back(id[v]);
    if(c.size() != 3)
      throw std::runtime_error("mesh_to_soup: not a triangle mesh");
    s.faces.push_back({{c[0], c[1], c[2]}});
  }
  return s;
}

/// A renumbered copy: vertex i of `s` becomes vertex perm[i]; optionally the faces are shuffled and
/// each face's corners rotated (same surface, same orientation). `perm` receives the vertex map.
inline Soup renumbered(const Soup& s, unsigned seed, std::vector<int>* perm = nullptr, bool shuffle_faces = false)
{
  std::mt19937 rng(seed);
  std::vector<int> p(s.points.size());
  std::iota(p.begin(), p.end(), 0);
  std::shuffle(p.begin(), p.end(), rng);
  Soup r;
  r.points.resize(s.points.size(), Point(0, 0, 0));
  for(std::size_t i = 0; i < p.size(); ++i)
    r.points[p[i]] = s.points[i];
  for(const Tri& t : s.faces)
    r.faces.push_back({{p[t[0]], p[t[1]], p[t[2]]}});
  if(shuffle_faces) {
    std::shuffle(r.faces.begin(), r.faces.end(), rng);
    for(Tri& t : r.faces)
      std::rotate(t.begin(), t.begin() + int(rng() % 3), t.end());
  }
  if(perm) *perm = p;
  return r;
}

/// Directory of CGAL's data meshes (compile definition TC_CGAL_DATA_DIR), or "" when it is missing
inline std::string cgal_data_dir()
{
#ifdef TC_CGAL_DATA_DIR
  const std::string dir = TC_CGAL_DATA_DIR;
  std::ifstream probe(dir + "/sphere.off");
  return probe ? dir : std::string();
#else
  return std::string();
#endif
}

/// Reads CGAL data mesh `name` (e.g. "elephant.off"); false (and `why`) when the data set or file is missing
inline bool read_cgal_mesh(const std::string& name, Surface_mesh& sm, std::string& why)
{
  const std::string dir = cgal_data_dir();
  if(dir.empty()) {
    why = "CGAL's data set was not found (compile definition TC_CGAL_DATA_DIR";
#ifdef TC_CGAL_DATA_DIR
    why += " = '" + std::string(TC_CGAL_DATA_DIR) + "'";
#endif
    why += "): run scripts/fetch_cgal_data.sh or configure with -DCGAL_DATA_DIR=...";
    return false;
  }
  const std::string path = dir + "/" + name;
  if(!std::ifstream(path)) {
    why = "CGAL data mesh " + path + " is missing";
    return false;
  }
  sm.clear();
  if(!CGAL::IO::read_polygon_mesh(path, sm)) {
    why = "CGAL::IO::read_polygon_mesh failed on " + path;
    return false;
  }
  return true;
}

// Skips the current test (GTEST_SKIP) with a clear message when the CGAL data mesh is not available.
#define TC_READ_CGAL_MESH_OR_SKIP(name, sm)                                                      \
  do {                                                                                           \
    std::string tc_why_;                                                                         \
    if(!::tc_test::read_cgal_mesh(name, sm, tc_why_))                                           \
      GTEST_SKIP() << tc_why_;                                                                   \
  } while(0)

} // namespace tc_test

#endif // CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_MESH_BUILDERS_H
