// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// Test support shared by the GoogleTest files:
//  (a) mesh builders (polygon soups, Surface_mesh, Polyhedron_3), renumbering, CGAL data meshes;
//  (b) INDEPENDENT checks of everything CONVENTIONS.md promises, recomputed from the vertex positions
//      and the connectivity only: nothing here calls the package's internals for geometry. From the
//      package we only read what it outputs (the connection x, the field, the loops, the report) and the
//      values it documents (weight, angle_defect, transport_angle), which are compared with our own.

#ifndef CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_H
#define CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_H

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

// =====================================================================================================
// (b) Independent geometry and topology, from positions and connectivity only
// =====================================================================================================

using V3 = std::array<double, 3>;
inline V3 operator+(const V3& a, const V3& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
inline V3 operator-(const V3& a, const V3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline V3 operator*(double s, const V3& a) { return {{s * a[0], s * a[1], s * a[2]}}; }
inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(const V3& a, const V3& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }
inline V3 unit(const V3& a) { return (1 / norm(a)) * a; }

/// a - (multiple of period) in (-period/2, period/2]
inline double wrap(double a, double period = two_pi)
{
  double r = std::fmod(a, period);
  if(r > period / 2) r -= period;
  if(r <= -period / 2) r += period;
  return r;
}

/// signed angle from u to w about the unit normal N (both tangent)
inline double signed_angle(const V3& u, const V3& w, const V3& N)
{
  return std::atan2(dot(cross(u, w), N), dot(u, w));
}

/// the counter-clockwise rotation of tangent vector u by angle t about the unit normal N
inline V3 rotate(const V3& u, const V3& N, double t) { return std::cos(t) * u + std::sin(t) * cross(N, u); }

/// Key -> Value property map over a std::vector, through a hash map from descriptors to numbers
template <class Key, class Value>
struct Indexed_map
{
  using key_type = Key;
  using value_type = Value;
  using reference = Value&;
  using category = boost::lvalue_property_map_tag;
  const std::unordered_map<Key, int>* index = nullptr;
  std::vector<Value>* values = nullptr;
  Value& operator[](const Key& k) const { return (*values)[index->at(k)]; }
  friend Value& get(const Indexed_map& m, const Key& k) { return m[k]; }
  friend void put(const Indexed_map& m, const Key& k, const Value& v) { m[k] = v; }
};

/*
  The mesh as flat arrays, numbered in the iteration order of vertices(tm), faces(tm), halfedges(tm),
  with every quantity of CONVENTIONS.md recomputed from the positions: corner angles, angle defects,
  unit normals, components, Euler characteristics, boundary loops, Hodge-star weights.
*/
template <class Mesh>
struct Mesh_view
{
  using GT = boost::graph_traits<Mesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;

  const Mesh& tm;
  std::vector<vertex_descriptor> vertices;
  std::vector<face_descriptor> faces;
  std::vector<halfedge_descriptor> halfedges;
  std::unordered_map<vertex_descriptor, int> vid;
  std::unordered_map<face_descriptor, int> fid;
  std::unordered_map<halfedge_descriptor, int> hid;

  std::vector<V3> P;                         // per vertex
  std::vector<int> src, tgt, hface, opp, nxt; // per halfedge (hface = -1: border halfedge)
  std::vector<std::array<int, 3>> face_he;    // per face: halfedge(f), next, next
  std::vector<V3> N, bary;                    // per face: unit normal, barycentre
  std::vector<double> angle_sum;              // per vertex
  std::vector<int> faces_at;                  // per vertex
  std::vector<char> on_boundary;              // per vertex
  std::vector<int> interior_halfedges;        // the halfedges of interior edges (both)
  std::vector<int> interior_edges;            // one halfedge per interior edge (the smaller number)

  std::vector<int> comp_of_face, comp_of_vertex; // own component numbering
  int ncomp = 0;
  std::vector<long long> chi;                    // per component
  std::vector<int> boundary_count, genus;        // per component
  struct Boundary_loop { int component; std::vector<int> vertices; double kappa; };
  std::vector<Boundary_loop> boundary_loops;
  std::vector<int> loop_of_vertex;               // -1 for interior vertices

  int nv() const { return int(vertices.size()); }
  int nf() const { return int(faces.size()); }
  int nh() const { return int(halfedges.size()); }
  bool interior_halfedge(int h) const { return hface[h] >= 0 && hface[opp[h]] >= 0; }
  bool interior_vertex(int v) const { return faces_at[v] > 0 && !on_boundary[v]; }
  /// angle defect: 2 pi - angle sum (interior), pi - angle sum (boundary)
  double defect(int v) const { return (on_boundary[v] ? pi : two_pi) - angle_sum[v]; }

  explicit Mesh_view(const Mesh& m) : tm(m)
  {
    for(auto v : CGAL::vertices(tm)) { vid[v] = int(vertices.size()); vertices.push_back(v); }
    for(auto f : CGAL::faces(tm)) { fid[f] = int(faces.size()); faces.push_back(f); }
    for(auto h : CGAL::halfedges(tm)) { hid[h] = int(halfedges.size()); halfedges.push_back(h); }
    auto vpm = get(CGAL::vertex_point, tm);
    for(auto v : vertices) {
      const Point& p = get(vpm, v);
      P.push_back({{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}});
    }
    const int H = nh();
    src.resize(H); tgt.resize(H); hface.resize(H); opp.resize(H); nxt.resize(H);
    for(int h = 0; h < H; ++h) {
      const halfedge_descriptor d = halfedges[h];
      src[h] = vid.at(source(d, tm));
      tgt[h] = vid.at(target(d, tm));
      hface[h] = is_border(d, tm) ? -1 : fid.at(face(d, tm));
      opp[h] = hid.at(opposite(d, tm));
      nxt[h] = hid.at(next(d, tm));
    }
    angle_sum.assign(nv(), 0.);
    faces_at.assign(nv(), 0);
    on_boundary.assign(nv(), 0);
    for(int f = 0; f < nf(); ++f) {
      const int h0 = hid.at(halfedge(faces[f], tm)), h1 = nxt[h0], h2 = nxt[h1];
      face_he.push_back({{h0, h1, h2}});
      const V3 &a = P[src[h0]], &b = P[src[h1]], &c = P[src[h2]];
      // from the two edges of the largest angle (opposite the longest edge): exact to rounding on needles too
      const double la = dot(c - b, c - b), lb = dot(a - c, a - c), lc = dot(b - a, b - a);
      N.push_back(unit(la >= lb && la >= lc ? cross(b - a, c - a) : lb >= lc ? cross(c - b, a - b) : cross(a - c, b - c)));
      bary.push_back((1. / 3) * (a + b + c));
      for(int k = 0; k < 3; ++k) {
        const int h = face_he[f][k], hp = face_he[f][(k + 2) % 3];
        const V3 u = P[tgt[h]] - P[src[h]], w = P[src[hp]] - P[src[h]]; // the two edges at src(h)
        angle_sum[src[h]] += std::atan2(norm(cross(u, w)), dot(u, w));
        ++faces_at[src[h]];
      }
    }
    for(int h = 0; h < H; ++h) {
      if(hface[h] < 0) { on_boundary[src[h]] = on_boundary[tgt[h]] = 1; continue; }
      if(hface[opp[h]] >= 0) {
        interior_halfedges.push_back(h);
        if(h < opp[h]) interior_edges.push_back(h);
      }
    }
    // components: union-find of faces through interior edges
    std::vector<int> parent(nf());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
    for(int h : interior_edges) parent[find(hface[h])] = find(hface[opp[h]]);
    std::map<int, int> comp_id;
    comp_of_face.assign(nf(), -1);
    for(int f = 0; f < nf(); ++f) {
      const int r = find(f);
      if(!comp_id.count(r)) comp_id[r] = ncomp++;
      comp_of_face[f] = comp_id[r];
    }
    comp_of_vertex.assign(nv(), -1);
    std::vector<long long> V(ncomp, 0), E(ncomp, 0), F(ncomp, 0);
    for(int f = 0; f < nf(); ++f) ++F[comp_of_face[f]];
    for(int h = 0; h < H; ++h) {
      const int f = hface[h] >= 0 ? hface[h] : hface[opp[h]];
      comp_of_vertex[src[h]] = comp_of_face[f];
      if(h < opp[h]) ++E[comp_of_face[f]];
    }
    for(int v = 0; v < nv(); ++v)
      if(faces_at[v] > 0) ++V[comp_of_vertex[v]];
    chi.resize(ncomp);
    for(int c = 0; c < ncomp; ++c) chi[c] = V[c] - E[c] + F[c];
    // boundary loops: cycles of border halfedges through next()
    loop_of_vertex.assign(nv(), -1);
    boundary_count.assign(ncomp, 0);
    std::vector<char> seen(H, 0);
    for(int h = 0; h < H; ++h) {
      if(hface[h] >= 0 || seen[h]) continue;
      Boundary_loop B{comp_of_face[hface[opp[h]]], {}, 0.};
      int c = h;
      do {
        seen[c] = 1;
        B.vertices.push_back(tgt[c]);
        c = nxt[c];
      } while(c != h);
      for(int v : B.vertices) {
        B.kappa += pi - angle_sum[v];
        loop_of_vertex[v] = int(boundary_loops.size());
      }
      ++boundary_count[B.component];
      boundary_loops.push_back(B);
    }
    genus.resize(ncomp);
    for(int c = 0; c < ncomp; ++c) genus[c] = int((2 - chi[c] - boundary_count[c]) / 2);
  }

  /// Hodge-star weight w_e = |e| / |e*|, |e*| = |b_f - m_e| + |m_e - b_g| (barycentres, edge midpoint)
  double hodge_weight(int h) const
  {
    const V3 m = 0.5 * (P[src[h]] + P[tgt[h]]);
    return norm(P[tgt[h]] - P[src[h]]) / (norm(bary[hface[h]] - m) + norm(m - bary[hface[opp[h]]]));
  }
  double weight(int h, TC::Weighting w) const { return w == TC::Weighting::unit ? 1. : hodge_weight(h); }

  /// Levi-Civita transport of tangent vector u of face(h) to face(opposite(h)), by unfolding about the edge
  V3 transport(int h, const V3& u) const
  {
    const V3 e = unit(P[tgt[h]] - P[src[h]]);
    const V3& Nf = N[hface[h]];
    const V3& Ng = N[hface[opp[h]]];
    return dot(u, e) * e + dot(u, cross(Nf, e)) * cross(Ng, e);
  }

  /// direction of halfedge(f): the frame the package documents for face f
  V3 frame(int f) const { const int h = face_he[f][0]; return unit(P[tgt[h]] - P[src[h]]); }

  /// a halfedge property map over a vector indexed by our halfedge numbers
  Indexed_map<halfedge_descriptor, double> halfedge_map(std::vector<double>& values) const
  {
    values.assign(nh(), std::numeric_limits<double>::quiet_NaN());
    return Indexed_map<halfedge_descriptor, double>{&hid, &values};
  }
  /// the same map over values already computed (not reset)
  Indexed_map<halfedge_descriptor, double> halfedge_map_const(std::vector<double>& values) const
  {
    return Indexed_map<halfedge_descriptor, double>{&hid, &values};
  }
  Indexed_map<face_descriptor, Vector> face_map(std::vector<Vector>& values) const
  {
    values.assign(nf(), Vector(0, 0, 0));
    return Indexed_map<face_descriptor, Vector>{&fid, &values};
  }
  /// halfedge from vertex i to vertex j (-1 when none)
  int halfedge_between(int i, int j) const
  {
    auto r = halfedge(vertices[i], vertices[j], tm);
    return r.second ? hid.at(r.first) : -1;
  }
};

template <class Mesh>
std::vector<std::pair<typename boost::graph_traits<Mesh>::vertex_descriptor, Index>>
descriptors(const Mesh_view<Mesh>& view, const Singularities& s)
{
  std::vector<std::pair<typename boost::graph_traits<Mesh>::vertex_descriptor, Index>> r;
  for(const auto& p : s) r.emplace_back(view.vertices[p.first], p.second);
  return r;
}

/// n times the prescribed index of every vertex
inline std::vector<long long> scaled_indices(int nv, const Singularities& s, int n)
{
  std::vector<long long> k(nv, 0);
  for(const auto& p : s) {
    EXPECT_TRUE(p.second.is_multiple_of_one_over(n)) << "test set-up: index " << p.second << " with n = " << n;
    k[p.first] = (long long)p.second.numerator() * (n / p.second.denominator());
  }
  return k;
}

/// Σ over the interior halfedges h with target(h) = v of x(h): the counter-clockwise ring sum at v
template <class Mesh>
std::vector<double> ring_sums(const Mesh_view<Mesh>& view, const std::vector<double>& x)
{
  std::vector<double> S(view.nv(), 0.);
  for(int h : view.interior_halfedges) S[view.tgt[h]] += x[h];
  return S;
}

/// energy Σ_e w_e x_e^2 with our own weights
template <class Mesh>
double energy(const Mesh_view<Mesh>& view, const std::vector<double>& x, TC::Weighting w)
{
  double E = 0;
  for(int h : view.interior_edges) E += view.weight(h, w) * x[h] * x[h];
  return E;
}

/// Transports a vector once around a closed dual loop (halfedge numbers), turning by x at each crossing
/// when `x` is given; returns the angle (about the normal of the first face) from the start vector to the
/// end vector. `closed` receives whether face(opposite(h_i)) == face(h_{i+1}) cyclically. An empty loop
/// (the boundary loop of a component whose boundary vertices have no interior edge, e.g. one triangle)
/// stays in one face: closed, rotation 0.
template <class Mesh>
double loop_rotation(const Mesh_view<Mesh>& view, const std::vector<int>& loop, const std::vector<double>* x,
                     bool& closed)
{
  closed = true;
  if(loop.empty()) return 0;
  for(std::size_t i = 0; i < loop.size() && closed; ++i) {
    const int h = loop[i], h2 = loop[(i + 1) % loop.size()];
    closed = view.interior_halfedge(h) && view.hface[view.opp[h]] == view.hface[h2];
  }
  if(!closed) return std::numeric_limits<double>::quiet_NaN();
  const int f0 = view.hface[loop[0]];
  const V3 u0 = view.frame(f0);
  V3 u = u0;
  for(int h : loop) {
    u = view.transport(h, u);
    if(x) u = rotate(u, view.N[view.hface[view.opp[h]]], (*x)[h]);
    u = unit(u);
  }
  return signed_angle(u0, u, view.N[f0]);
}

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

// =====================================================================================================
// Homology: the generators are independent of the vertex and boundary stars
// =====================================================================================================

/*
  Over the interior edges, the rows of every node star (interior vertex: its ring; boundary loop: the
  open fans of its vertices) span the null-homologous dual cycles (rank = nodes - components). The
  generator loops form a basis of H_1 of the surface with every boundary loop collapsed iff adding
  them raises the rank by exactly their number. Dense: for small meshes only.
*/
template <class Mesh>
void check_generators_independent(const Mesh_view<Mesh>& view, const std::vector<std::vector<int>>& generators)
{
  std::map<int, int> col;
  for(int h : view.interior_edges) col[h] = int(col.size());
  std::vector<std::vector<int>> rows;
  int nodes = 0;
  for(int v = 0; v < view.nv(); ++v)
    if(view.interior_vertex(v)) {
      ++nodes; rows.emplace_back();
      for(int h : view.interior_halfedges) if(view.tgt[h] == v) rows.back().push_back(h);
    }
  for(const auto& B : view.boundary_loops) {
    ++nodes; rows.emplace_back();
    for(int v : B.vertices)
      for(int h : view.interior_halfedges) if(view.tgt[h] == v) rows.back().push_back(h);
  }
  const int star_rows = int(rows.size());
  for(const auto& g : generators) rows.push_back(g);
  auto matrix = [&](int count) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(count, Eigen::Index(col.size()));
    for(int r = 0; r < count; ++r)
      for(const auto& kv : crossing_counts(view, rows[r])) A(r, col.at(kv.first)) += kv.second;
    return A;
  };
  const Eigen::MatrixXd stars = matrix(star_rows), all = matrix(int(rows.size()));
  Eigen::FullPivLU<Eigen::MatrixXd> lu_stars(stars), lu_all(all);
  EXPECT_EQ(int(lu_stars.rank()), nodes - view.ncomp) << "test self-check: rank of the node stars";
  EXPECT_EQ(int(lu_all.rank()), nodes - view.ncomp + int(generators.size()))
    << "generators are not independent in homology (or are null-homologous)";
  int expected = 0;
  for(int c = 0; c < view.ncomp; ++c) expected += 2 * view.genus[c];
  EXPECT_EQ(int(generators.size()), expected) << "number of generators (2g per component)";
}

} // namespace tc_test

#endif // CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_H
