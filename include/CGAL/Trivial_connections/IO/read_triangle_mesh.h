// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/read_ply.h>
#include <CGAL/Trivial_connections/parameters.h>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh/Surface_mesh.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/assertions.h>
#include <CGAL/exceptions.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/container/small_vector.hpp>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsIO
The elements of a mesh built by `read_triangle_mesh()` or `triangle_soup_to_mesh()`, by input index:
`vertices[i]` is vertex `i` of the file (also the `i`-th vertex of `vertices(tm)`), `faces[f]` is face `f`
(also the `f`-th face of `faces(tm)`). When `read_triangle_mesh()` triangulated faces of the file
(`parameters::triangulate(true)`), `faces[t]` is the `t`-th triangle and `source_faces[t]` the face of the
file it comes from (the triangles of a face are consecutive, faces in file order); otherwise `source_faces`
is empty and triangles and faces of the file are the same.
*/
template <class TriangleMesh>
struct Mesh_input_order
{
  /// the mesh's vertex type
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  /// the mesh's face type
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  std::vector<vertex_descriptor> vertices; ///< vertex `i` of the file
  std::vector<face_descriptor> faces;      ///< face (or triangle) `f`
  std::vector<std::size_t> source_faces;   ///< the face of the file each triangle comes from, when triangulated
};

namespace internal {
namespace io {

/*
  Connectivity of a validated triangle soup. Face f owns the corner halfedges 3f, 3f+1, 3f+2; corner
  halfedge c = 3f+k goes from triangles[f][k] to triangles[f][(k+1)%3]. opposite[c] is the corner halfedge
  going the other way in the neighbouring face, or -1 on a border edge.
*/
struct Triangle_soup_connectivity
{
  std::size_t number_of_vertices = 0;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> opposite;

  static int next(int c) { return c % 3 == 2 ? c - 2 : c + 1; }
  int source(int c) const { return triangles[std::size_t(c / 3)][std::size_t(c % 3)]; }
  int target(int c) const { return source(next(c)); }
};

inline std::string face_list(const std::vector<int>& faces)
{
  std::string s;
  const std::size_t shown = (std::min)(faces.size(), std::size_t(6));
  for(std::size_t i = 0; i < shown; ++i)
    s += (i == 0 ? "" : (i + 1 == faces.size() ? " and " : ", ")) + std::to_string(faces[i]);
  if(shown < faces.size())
    s += ", ...";
  return s;
}

// Union-find with path halving.
inline int find_root(std::vector<int>& parent, int i)
{
  while(parent[std::size_t(i)] != i) {
    parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
    i = parent[std::size_t(i)];
  }
  return i;
}

inline void check_soup_size(std::size_t number_of_points, std::size_t nf)
{
  if(nf == 0)
    throw Invalid_input(Error_code::empty_mesh, "the mesh has no face" + std::string(number_of_points > 0 ?
                          " (" + std::to_string(number_of_points) + " vertices, 0 faces)" : ""));
  constexpr std::size_t limit = std::size_t((std::numeric_limits<int>::max)());
  if(number_of_points >= limit || nf >= limit / 3)
    throw Invalid_input(Error_code::invalid_argument, "the mesh is too large (" + std::to_string(number_of_points) +
                                                        " vertices, " + std::to_string(nf) + " faces)");
}

[[noreturn]] inline void throw_vertex_out_of_range(std::size_t f, std::size_t v, std::size_t number_of_points)
{
  throw Invalid_input(Error_code::invalid_vertex,
                      "face " + std::to_string(f) + " uses vertex " + std::to_string(static_cast<long long>(v)) +
                        " but the mesh has only " + std::to_string(number_of_points) + " vertices (0-based indices 0 to " +
                        (number_of_points == 0 ? std::string("none") : std::to_string(number_of_points - 1)) + ")",
                      f);
}

inline void check_not_degenerate(std::size_t f, const std::array<int, 3>& t)
{
  if(t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    throw Invalid_input(Error_code::degenerate_face,
                        "face " + std::to_string(f) + " (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) +
                          ", " + std::to_string(t[2]) + ") uses the same vertex twice",
                        f);
}

/*
  Steps 4 and 5 of the validation below, on `soup.triangles` (indices in range, three different vertices):
  fills `soup.opposite` or throws.
  Directed edges are found in per-vertex lists of outgoing corners (in corner order; lists longer than
  `sorted_from` are sorted by (target, corner) and searched by bisection), each edge once from its first
  corner. The fan check walks around every vertex; only when a vertex fails it, the union-find below finds
  the fans to name in the message.
*/
inline void connect_triangle_soup(Triangle_soup_connectivity& soup)
{
  const std::size_t number_of_points = soup.number_of_vertices;
  const int nc = int(3 * soup.triangles.size());
  std::vector<int> first(number_of_points + 1, 0);
  for(int c = 0; c < nc; ++c)
    ++first[std::size_t(soup.source(c)) + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<std::pair<int, int>> out(static_cast<std::size_t>(nc)); // (target, corner)
  {
    std::vector<int> fill(first.begin(), first.end() - 1);
    for(int c = 0; c < nc; ++c)
      out[std::size_t(fill[std::size_t(soup.source(c))]++)] = std::make_pair(soup.target(c), c);
  }
  constexpr int sorted_from = 16;
  for(std::size_t v = 0; v < number_of_points; ++v)
    if(first[v + 1] - first[v] > sorted_from)
      std::sort(out.begin() + first[v], out.begin() + first[v + 1]);
  // the corners from a to b, in increasing order: their number, the first two in `corners`
  auto corners_from_to = [&](int a, int b, int* corners) {
    const auto begin = out.begin() + first[std::size_t(a)], end = out.begin() + first[std::size_t(a) + 1];
    int n = 0;
    if(end - begin > sorted_from) {
      const auto range = std::equal_range(begin, end, std::make_pair(b, -1),
                                          [](const std::pair<int, int>& x, const std::pair<int, int>& y) {
                                            return x.first < y.first;
                                          });
      for(auto it = range.first; it != range.second; ++it, ++n)
        if(n < 2) corners[n] = it->second;
    } else {
      for(auto it = begin; it != end; ++it)
        if(it->first == b) {
          if(n < 2) corners[n] = it->second;
          ++n;
        }
    }
    return n;
  };

  // 4. edges: at most two faces, traversed in opposite directions
  soup.opposite.assign(std::size_t(nc), -1);
  std::vector<bool> done(static_cast<std::size_t>(nc), false); // the opposite of an earlier corner
  for(int c = 0; c < nc; ++c) {
    if(done[std::size_t(c)])
      continue; // its edge was checked from the opposite corner: one corner each way
    const int a = soup.source(c), b = soup.target(c);
    int ab[2] = {-1, -1}, ba[2] = {-1, -1};
    const int n_ab = corners_from_to(a, b, ab);
    const int n_ba = corners_from_to(b, a, ba);
    if(n_ab + n_ba > 2) {
      std::vector<int> faces;
      for(const auto& [from, to] : {std::make_pair(a, b), std::make_pair(b, a)})
        for(int i = first[std::size_t(from)]; i < first[std::size_t(from) + 1]; ++i)
          if(out[std::size_t(i)].first == to)
            faces.push_back(out[std::size_t(i)].second / 3);
      std::sort(faces.begin(), faces.end());
      throw Invalid_input(Error_code::non_manifold,
                          "non-manifold edge: the edge between vertices " + std::to_string(a) + " and " +
                            std::to_string(b) + " is shared by " + std::to_string(faces.size()) + " faces (" +
                            face_list(faces) + ")",
                          std::size_t(faces.front()));
    }
    if(n_ab == 2) {
      const int f0 = ab[0] / 3, f1 = ab[1] / 3;
      throw Invalid_input(Error_code::inconsistent_orientation,
                          "inconsistent orientation: faces " + std::to_string((std::min)(f0, f1)) + " and " +
                            std::to_string((std::max)(f0, f1)) + " both traverse the edge from vertex " +
                            std::to_string(a) + " to vertex " + std::to_string(b) +
                            " (neighbouring faces must traverse their common edge in opposite directions)",
                          std::size_t((std::max)(f0, f1)));
    }
    if(n_ba == 1) {
      soup.opposite[std::size_t(c)] = ba[0];
      soup.opposite[std::size_t(ba[0])] = c;
      done[std::size_t(ba[0])] = true;
    }
  }

  // 5. one fan per vertex: walking around each vertex from one of its corners, through the faces that share
  // an edge at it, must meet all its corners
  std::size_t first_bad_vertex = number_of_points;
  for(std::size_t v = 0; v < number_of_points && first_bad_vertex == number_of_points; ++v) {
    const int degree = first[v + 1] - first[v];
    if(degree == 0)
      continue;
    const int c0 = out[std::size_t(first[v])].second;
    int seen = 1;
    // forward: the corner of the face across the edge that ends at v (the previous corner of c)
    int c = soup.opposite[std::size_t(Triangle_soup_connectivity::next(Triangle_soup_connectivity::next(c0)))];
    while(c >= 0 && c != c0 && seen <= degree) {
      ++seen;
      c = soup.opposite[std::size_t(Triangle_soup_connectivity::next(Triangle_soup_connectivity::next(c)))];
    }
    if(c < 0) { // open fan: walk backward too
      c = soup.opposite[std::size_t(c0)];
      while(c >= 0 && seen <= degree) {
        c = Triangle_soup_connectivity::next(c);
        ++seen;
        c = soup.opposite[std::size_t(c)];
      }
    }
    if(seen != degree)
      first_bad_vertex = v;
  }
  if(first_bad_vertex == number_of_points)
    return;

  // a vertex has several fans: find them all to report the first such vertex exactly
  std::vector<int> parent(static_cast<std::size_t>(nc));
  std::iota(parent.begin(), parent.end(), 0);
  for(int c = 0; c < nc; ++c) {
    const int t = soup.opposite[std::size_t(c)];
    if(t < 0)
      continue;
    // c starts at a = source(c); next(t) is the corner of the other face starting at a
    const int r0 = find_root(parent, c), r1 = find_root(parent, Triangle_soup_connectivity::next(t));
    if(r0 != r1)
      parent[std::size_t((std::max)(r0, r1))] = (std::min)(r0, r1);
  }
  std::vector<int> fans(number_of_points, 0);
  std::vector<int> fan_face(number_of_points, -1); // a face of the first fan of each vertex
  std::size_t bad_vertex = number_of_points;
  int bad_face = -1;
  for(int c = 0; c < nc; ++c) {
    if(find_root(parent, c) != c)
      continue;
    const std::size_t v = std::size_t(soup.source(c));
    if(++fans[v] == 1) {
      fan_face[v] = c / 3;
    } else if(v < bad_vertex) {
      bad_vertex = v;
      bad_face = c / 3;
    }
  }
  if(bad_vertex < number_of_points)
    throw Invalid_input(Error_code::non_manifold,
                        "non-manifold vertex " + std::to_string(bad_vertex) + ": the faces around it form " +
                          std::to_string(fans[bad_vertex]) + " separate fans (e.g. faces " +
                          std::to_string(fan_face[bad_vertex]) + " and " + std::to_string(bad_face) +
                          " share it but are not connected through edges around it)",
                        bad_vertex);
  throw Invalid_input(Error_code::non_manifold, "non-manifold vertex " + std::to_string(first_bad_vertex) +
                                                  ": the faces around it form separate fans", first_bad_vertex);
}

/*
  Validates a polygon soup as an oriented 2-manifold triangle mesh (possibly with boundary and isolated
  vertices) and returns its connectivity. Checks, in this order, each over all faces in input order:
    1. at least one face (empty_mesh);
    2. every vertex index is in range (invalid_vertex), before any other use of the indices;
    3. every face is a triangle (not_triangle_mesh) with three different vertices (degenerate_face);
    4. no edge is shared by more than two faces (non_manifold), no two faces traverse the same directed
       edge (inconsistent_orientation);
    5. the faces around each vertex form a single fan (non_manifold).
  Linear time (plus sorts of the outgoing edges of vertices of high degree).
*/
template <class PolygonRange>
Triangle_soup_connectivity validate_triangle_soup(std::size_t number_of_points, const PolygonRange& polygons)
{
  Triangle_soup_connectivity soup;
  soup.number_of_vertices = number_of_points;
  const std::size_t nf = polygons.size();
  check_soup_size(number_of_points, nf);

  // 2. indices in range
  std::size_t f = 0;
  for(const auto& polygon : polygons) {
    for(const auto& index : polygon) {
      const std::size_t v = std::size_t(index);
      if(v >= number_of_points)
        throw_vertex_out_of_range(f, v, number_of_points);
    }
    ++f;
  }

  // 3. triangles with three different vertices
  soup.triangles.resize(nf);
  f = 0;
  for(const auto& polygon : polygons) {
    if(polygon.size() != 3)
      throw Invalid_input(Error_code::not_triangle_mesh,
                          "face " + std::to_string(f) + " has " + std::to_string(polygon.size()) +
                            " vertices: only triangle meshes are supported",
                          f);
    std::array<int, 3>& t = soup.triangles[f];
    std::size_t k = 0;
    for(const auto& index : polygon)
      t[k++] = int(std::size_t(index));
    check_not_degenerate(f, t);
    ++f;
  }

  connect_triangle_soup(soup);
  return soup;
}

// The same for triangles given as a vector, which is moved into the result (no copy).
inline Triangle_soup_connectivity validate_triangles(std::size_t number_of_points,
                                                     std::vector<std::array<int, 3>>&& triangles)
{
  Triangle_soup_connectivity soup;
  soup.number_of_vertices = number_of_points;
  const std::size_t nf = triangles.size();
  check_soup_size(number_of_points, nf);
  for(std::size_t f = 0; f < nf; ++f)
    for(int index : triangles[f])
      if(index < 0 || std::size_t(index) >= number_of_points)
        throw_vertex_out_of_range(f, std::size_t(index), number_of_points);
  for(std::size_t f = 0; f < nf; ++f)
    check_not_degenerate(f, triangles[f]);
  soup.triangles = std::move(triangles);
  connect_triangle_soup(soup);
  return soup;
}

// Adds nv vertices, ne edges and nf faces (in this order of indices), as add_vertex(), add_edge() and add_face()
// would one by one.
template <class TriangleMesh>
void add_elements(TriangleMesh& tm, std::size_t nv, std::size_t ne, std::size_t nf,
                  std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& vertex,
                  std::vector<typename boost::graph_traits<TriangleMesh>::halfedge_descriptor>& edge_halfedge,
                  std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>& face)
{
  vertex.resize(nv);
  edge_halfedge.resize(ne);
  face.resize(nf);
  for(std::size_t i = 0; i < nv; ++i)
    vertex[i] = add_vertex(tm);
  for(std::size_t f = 0; f < nf; ++f)
    face[f] = add_face(tm);
  for(std::size_t e = 0; e < ne; ++e)
    edge_halfedge[e] = halfedge(add_edge(tm), tm);
}

// Surface_mesh: all at once (an empty Surface_mesh numbers its elements 0, 1, ... in the order they are added,
// and edge e holds the halfedges 2e and 2e + 1)
template <class P>
void add_elements(CGAL::Surface_mesh<P>& tm, std::size_t nv, std::size_t ne, std::size_t nf,
                  std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>& vertex,
                  std::vector<typename CGAL::Surface_mesh<P>::Halfedge_index>& edge_halfedge,
                  std::vector<typename CGAL::Surface_mesh<P>::Face_index>& face)
{
  using SM = CGAL::Surface_mesh<P>;
  using size_type = typename SM::size_type;
  CGAL_precondition(tm.number_of_vertices() == 0 && tm.number_of_halfedges() == 0 && tm.number_of_faces() == 0);
  tm.resize(size_type(nv), size_type(ne), size_type(nf));
  vertex.resize(nv);
  edge_halfedge.resize(ne);
  face.resize(nf);
  for(std::size_t i = 0; i < nv; ++i)
    vertex[i] = typename SM::Vertex_index(size_type(i));
  for(std::size_t f = 0; f < nf; ++f)
    face[f] = typename SM::Face_index(size_type(f));
  for(std::size_t e = 0; e < ne; ++e)
    edge_halfedge[e] = typename SM::Halfedge_index(size_type(2 * e));
}

/*
  Builds the mesh from validated connectivity with the low-level functions of `MutableFaceGraph`:
  vertex i is the i-th vertex added, face f the f-th face added; isolated vertices are kept.
*/
template <class TriangleMesh, class PointRange>
Mesh_input_order<TriangleMesh> build_mesh(const PointRange& points, const Triangle_soup_connectivity& soup,
                                          TriangleMesh& tm)
{
  using GT = boost::graph_traits<TriangleMesh>;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using vertices_size_type = typename GT::vertices_size_type;
  using edges_size_type = typename GT::edges_size_type;
  using faces_size_type = typename GT::faces_size_type;

  const std::size_t nv = soup.number_of_vertices, nf = soup.triangles.size(), nc = 3 * nf;
  std::size_t interior = 0, border = 0;
  for(std::size_t c = 0; c < nc; ++c)
    (soup.opposite[c] >= 0 ? interior : border) += 1;
  reserve(tm, vertices_size_type(nv), edges_size_type(interior / 2 + border), faces_size_type(nf));

  Mesh_input_order<TriangleMesh> order;
  std::vector<halfedge_descriptor> edge_halfedge;
  add_elements(tm, nv, interior / 2 + border, nf, order.vertices, edge_halfedge, order.faces);
  auto vpm = get(CGAL::vertex_point, tm);
  std::size_t i = 0;
  for(const auto& p : points)
    put(vpm, order.vertices[i++], p);

  // edge k is the k-th edge met in corner order
  std::vector<halfedge_descriptor> h(nc);
  std::size_t next_edge = 0;
  for(std::size_t c = 0; c < nc; ++c) {
    const int t = soup.opposite[c];
    h[c] = (t >= 0 && std::size_t(t) < c) ? opposite(h[std::size_t(t)], tm) : edge_halfedge[next_edge++];
  }
  std::vector<halfedge_descriptor> incoming(nv, GT::null_halfedge());
  std::vector<halfedge_descriptor> border_from(nv, GT::null_halfedge()); // the border halfedge leaving a vertex
  for(std::size_t c = 0; c < nc; ++c) {
    const int ci = int(c);
    const std::size_t a = std::size_t(soup.source(ci)), b = std::size_t(soup.target(ci));
    set_target(h[c], order.vertices[b], tm);
    set_next(h[c], h[std::size_t(Triangle_soup_connectivity::next(ci))], tm);
    set_face(h[c], order.faces[c / 3], tm);
    if(incoming[b] == GT::null_halfedge())
      incoming[b] = h[c];
    if(soup.opposite[c] < 0) {
      // the border halfedge b -> a (validation guarantees one per vertex at most)
      const halfedge_descriptor g = opposite(h[c], tm);
      set_target(g, order.vertices[a], tm);
      set_face(g, GT::null_face(), tm);
      border_from[b] = g;
    }
  }
  for(std::size_t c = 0; c < nc; ++c)
    if(soup.opposite[c] < 0) {
      const std::size_t a = std::size_t(soup.source(int(c)));
      const halfedge_descriptor g = opposite(h[c], tm);
      set_next(g, border_from[a], tm);
      incoming[a] = g; // a border vertex points to its incoming border halfedge
    }
  for(std::size_t f = 0; f < nf; ++f)
    set_halfedge(order.faces[f], h[3 * f], tm);
  for(std::size_t v = 0; v < nv; ++v)
    if(incoming[v] != GT::null_halfedge())
      set_halfedge(order.vertices[v], incoming[v], tm);
  return order;
}

inline std::string lower_extension(const std::string& path)
{
  std::string ext = std::filesystem::path(path).extension().string();
  if(!ext.empty() && ext[0] == '.')
    ext.erase(0, 1);
  for(char& ch : ext)
    ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

inline bool parse_integer(const std::string& s, long long& value)
{
  if(s.empty())
    return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(s.c_str(), &end, 10);
  return errno == 0 && end == s.c_str() + s.size();
}

inline bool parse_number(const std::string& s)
{
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

// Throws parse_error if one of the first three tokens of a vertex line is not a finite number.
inline void check_coordinates(const std::vector<std::string>& t, std::size_t first, const std::string& where,
                              std::size_t v)
{
  if(t.size() < first + 3)
    throw Invalid_input(Error_code::parse_error, where + ": expected three coordinates", v);
  for(std::size_t k = first; k < first + 3; ++k) {
    if(!parse_number(t[k]))
      throw Invalid_input(Error_code::parse_error, where + ": expected three coordinates, '" + t[k] +
                                                     "' is not a number", v);
    if(!std::isfinite(std::strtod(t[k].c_str(), nullptr)))
      throw Invalid_input(Error_code::parse_error, where + ": the coordinate '" + t[k] +
                                                     "' is not a finite number", v);
  }
}

inline std::vector<std::string> tokens_of(const std::string& line)
{
  std::vector<std::string> out;
  std::istringstream ss(line.substr(0, line.find('#')));
  std::string t;
  while(ss >> t)
    out.push_back(t);
  return out;
}

/*
  ASCII OFF read line by line, for the files the fast path does not take (polygons, colours, normals,
  comments in odd places): we read OFF ourselves rather than with CGAL's reader, which trusts facet sizes
  (a 60-byte file asks for gigabytes), casts negative sizes and indices read as doubles to unsigned, and
  reads the rest of a counts line with extra numbers as the first vertex. Accepted: the keyword
  `[ST][C][N]OFF` (texture coordinates, colours and normals are read past), the counts `nv nf ne` on one
  line, nv vertex lines of at least three finite coordinates, nf face lines `size i_1 ... i_size` with
  0-based indices < nv (a face colour may follow); `#` comments and blank lines anywhere. Refused with a
  parse_error naming the line: binary, homogeneous (4OFF) and n-dimensional (nOFF) variants, and anything
  malformed. Memory is proportional to the file's size whatever its counts say.
*/
template <class Point, class PolygonRange>
void read_off_soup(const std::string& path, std::vector<Point>& points, PolygonRange& polygons)
{
  std::ifstream is(path, std::ios::binary);
  if(!is)
    throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "'");
  std::string line;
  std::size_t line_number = 0;
  std::vector<std::string> t;
  auto next_tokens = [&]() {
    while(std::getline(is, line)) {
      ++line_number;
      t = tokens_of(line);
      if(!t.empty())
        return true;
    }
    return false;
  };
  const std::string at = path + ":";
  auto fail = [&](const std::string& what) {
    throw Invalid_input(Error_code::parse_error, at + std::to_string(line_number) + ": " + what);
  };
  if(!next_tokens())
    throw Invalid_input(Error_code::parse_error, path + ": the file is empty");
  {
    // CGAL's keyword grammar: [ST][C][N][4][n]OFF
    const std::string& magic = t[0];
    std::size_t j = 0;
    if(magic.compare(0, 2, "ST") == 0)
      j += 2;
    for(const char letter : {'C', 'N', '4', 'n'})
      if(j < magic.size() && magic[j] == letter)
        ++j;
    if(magic.compare(j, std::string::npos, "OFF") != 0)
      fail("expected the keyword OFF (or COFF, NOFF, STOFF, ...) at the start of an OFF file, found '" + magic + "'");
    if(magic.find_first_of("4n") != std::string::npos)
      fail("the OFF variant '" + magic + "' (homogeneous or n-dimensional coordinates) is not supported");
  }
  if(t.size() > 1 && t[1] == "BINARY")
    fail("binary OFF is not supported: write the mesh as ASCII OFF, or as PLY (ASCII or binary)");
  std::size_t k = 1;
  if(k == t.size()) {
    if(!next_tokens())
      throw Invalid_input(Error_code::parse_error, path + ": unexpected end of file: expected the vertex and face counts");
    k = 0;
  }
  long long nv = -1, nf = -1, ne = -1;
  if(t.size() != k + 3 || !parse_integer(t[k], nv) || !parse_integer(t[k + 1], nf) || !parse_integer(t[k + 2], ne) ||
     nv < 0 || nf < 0)
    fail("expected the vertex, face and edge counts of the OFF header, three integers on one line");
  for(long long v = 0; v < nv; ++v) {
    if(!next_tokens())
      throw Invalid_input(Error_code::parse_error,
                          path + ": unexpected end of file: the header announces " + std::to_string(nv) +
                            " vertices, the file has " + std::to_string(v));
    check_coordinates(t, 0, at + std::to_string(line_number) + ": vertex " + std::to_string(v), std::size_t(v));
    points.push_back(Point(std::strtod(t[0].c_str(), nullptr), std::strtod(t[1].c_str(), nullptr),
                           std::strtod(t[2].c_str(), nullptr)));
  }
  for(long long f = 0; f < nf; ++f) {
    if(!next_tokens())
      throw Invalid_input(Error_code::parse_error,
                          path + ": unexpected end of file: the header announces " + std::to_string(nf) +
                            " faces, the file has " + std::to_string(f));
    const std::string where = at + std::to_string(line_number) + ": face " + std::to_string(f);
    long long size = 0;
    if(!parse_integer(t[0], size) || size < 1)
      throw Invalid_input(Error_code::parse_error, where + ": expected the number of its vertices", std::size_t(f));
    if(t.size() < std::size_t(size) + 1)
      throw Invalid_input(Error_code::parse_error, where + ": expected " + std::to_string(size) + " vertex indices",
                          std::size_t(f));
    polygons.emplace_back();
    for(long long j = 1; j <= size; ++j) {
      long long v = 0;
      if(!parse_integer(t[std::size_t(j)], v))
        throw Invalid_input(Error_code::parse_error, where + ": the vertex index '" + t[std::size_t(j)] +
                                                       "' is not an integer", std::size_t(f));
      if(v < 0 || v >= nv)
        throw Invalid_input(Error_code::invalid_vertex,
                            where + " uses vertex " + std::to_string(v) + " but the mesh has only " +
                              std::to_string(nv) + " vertices (0-based indices 0 to " +
                              (nv == 0 ? std::string("none") : std::to_string(nv - 1)) + ")",
                            std::size_t(f));
      polygons.back().push_back(std::size_t(v));
    }
  }
  if(nf == 0)
    throw Invalid_input(Error_code::empty_mesh, path + ": the mesh has no face (" + std::to_string(nv) + " vertices, 0 faces)");
}

// Same for OBJ: a vertex without three finite coordinates, a face index out of range, no face at all.
inline void diagnose_obj(const std::string& path)
{
  std::ifstream is(path);
  if(!is)
    return;
  std::string line;
  std::size_t line_number = 0, nv = 0, nf = 0;
  while(std::getline(is, line)) {
    ++line_number;
    const std::vector<std::string> t = tokens_of(line);
    if(t.empty())
      continue;
    if(t[0] == "v") {
      check_coordinates(t, 1, path + ":" + std::to_string(line_number) + ": vertex " + std::to_string(nv), nv);
      ++nv;
    } else if(t[0] == "f") {
      for(std::size_t j = 1; j < t.size(); ++j) {
        long long v = 0;
        if(!parse_integer(t[j].substr(0, t[j].find('/')), v))
          continue;
        const long long index = v < 0 ? (long long)(nv) + v : v - 1;
        if(index < 0 || index >= (long long)(nv))
          throw Invalid_input(Error_code::invalid_vertex,
                              path + ":" + std::to_string(line_number) + ": face " + std::to_string(nf) +
                                " uses vertex " + t[j] + " (1-based) but only " + std::to_string(nv) +
                                " vertices are defined before it",
                              nf);
      }
      ++nf;
    }
  }
  if(nf == 0)
    throw Invalid_input(Error_code::empty_mesh, path + ": the mesh has no face (" + std::to_string(nv) + " vertices, 0 faces)");
}

/*
  Fast path for the common ASCII OFF and OBJ files: the whole file is read into memory in one go and parsed
  with std::from_chars. It accepts only a strict subset of what CGAL's readers accept, and for that subset
  it produces exactly the polygon soup CGAL's reader produces (same points: the same correctly rounded
  doubles; same indices). Whenever it meets anything outside that subset (another OFF variant, colours,
  trailing values, a malformed or non-finite number, a truncated file, an index out of range, a polygon
  that is not a triangle, ...) it returns false and the caller falls back to CGAL's reader, so the set of
  accepted files and every error message stay exactly those of the CGAL path.
*/

// The whole content of a file, read in one go: mapped into memory where POSIX mmap is available (no copy),
// else read into a buffer. `ok()` is false if the file could not be read (the caller then falls back to
// CGAL's reader, which reports the problem).
class File_contents
{
public:
  explicit File_contents(const std::string& path)
  {
#if defined(__unix__) || defined(__APPLE__)
    const int fd = ::open(path.c_str(), O_RDONLY);
    if(fd >= 0) {
      struct stat st;
      if(::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
        int flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
        flags |= MAP_POPULATE; // fault all pages in at once
#endif
        void* p = ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, flags, fd, 0);
        if(p != MAP_FAILED) {
          m_map = p;
          m_data = static_cast<const char*>(p);
          m_size = std::size_t(st.st_size);
          m_ok = true;
        }
      }
      ::close(fd);
      if(m_ok)
        return;
    }
#endif
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if(file == nullptr)
      return;
    bool ok = std::fseek(file, 0, SEEK_END) == 0;
    const long size = ok ? std::ftell(file) : -1L;
    ok = ok && size >= 0 && std::fseek(file, 0, SEEK_SET) == 0;
    if(ok) {
      m_buffer.reset(new char[std::size_t(size) + 1]);
      ok = size == 0 || std::fread(m_buffer.get(), 1, std::size_t(size), file) == std::size_t(size);
      m_data = m_buffer.get();
      m_size = std::size_t(size);
    }
    std::fclose(file);
    m_ok = ok;
  }
  ~File_contents()
  {
#if defined(__unix__) || defined(__APPLE__)
    if(m_map != nullptr)
      ::munmap(m_map, m_size);
#endif
  }
  File_contents(const File_contents&) = delete;
  File_contents& operator=(const File_contents&) = delete;

  bool ok() const { return m_ok; }
  const char* begin() const { return m_data; }
  const char* end() const { return m_data + m_size; }

private:
  bool m_ok = false;
  void* m_map = nullptr;
  std::unique_ptr<char[]> m_buffer;
  const char* m_data = nullptr;
  std::size_t m_size = 0;
};

inline const char* end_of_line(const char* p, const char* end)
{
  const void* eol = std::memchr(p, '\n', std::size_t(end - p));
  return eol != nullptr ? static_cast<const char*>(eol) : end;
}

// The finite double written in [first, last) (an optional '+' first, as `operator>>` allows).
inline bool parse_finite_double(const char* first, const char* last, double& d)
{
  if(first != last && *first == '+') {
    ++first;
    if(first != last && (*first == '+' || *first == '-'))
      return false;
  }
  const std::from_chars_result r = std::from_chars(first, last, d, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == last && std::isfinite(d);
}

// The unsigned integer written with decimal digits only in [first, last), at most `max`.
inline bool parse_plain_index(const char* first, const char* last, std::uint64_t max, std::uint64_t& i)
{
  if(first == last || *first < '0' || *first > '9')
    return false;
  const std::from_chars_result r = std::from_chars(first, last, i, 10);
  return r.ec == std::errc() && r.ptr == last && i <= max;
}

// Reads exactly three finite numbers in [p, last), separated and surrounded by blanks, nothing else.
inline bool parse_three_doubles(const char* p, const char* last, double (&xyz)[3])
{
  for(int k = 0; k < 3; ++k) {
    p = skip_blanks(p, last);
    const char* e = token_end(p, last);
    if(!parse_finite_double(p, e, xyz[k]))
      return false;
    p = e;
  }
  return skip_blanks(p, last) == last;
}

// The comment-and-blank skipping of CGAL's OFF scanner (skip_comment_OFF): blanks, and lines whose first
// non-blank character is '#'.
inline const char* skip_off_comments(const char* p, const char* end)
{
  for(;;) {
    p = skip_blanks(p, end);
    if(p == end || *p != '#')
      return p;
    p = end_of_line(p, end);
  }
}

/*
  Plain ASCII OFF: the keyword `OFF`, the counts `nv nf ne`, nv lines of exactly three finite coordinates,
  nf lines `3 i j k` with 0-based indices < nv; `#` comments and blank lines where CGAL's scanner skips them.
*/
template <class Point>
bool fast_parse_off(const char* p, const char* end, std::vector<Point>& points,
                    std::vector<std::array<int, 3>>& triangles)
{
  p = skip_off_comments(p, end);
  if(end - p < 4 || p[0] != 'O' || p[1] != 'F' || p[2] != 'F' || !is_blank(p[3]))
    return false;
  p = skip_off_comments(p + 4, end);
  constexpr std::uint64_t int_max = std::uint64_t((std::numeric_limits<int>::max)());
  std::uint64_t counts[3];
  for(int k = 0; k < 3; ++k) {
    if(k > 0)
      p = skip_blanks(p, end); // CGAL reads the face and edge counts with operator>>: no comment there
    const char* e = token_end(p, end);
    if(!parse_plain_index(p, e, int_max, counts[k]))
      return false;
    p = e;
  }
  const std::size_t nv = std::size_t(counts[0]), nf = std::size_t(counts[1]);
  if(nv == 0 || nf == 0)
    return false;
  // a vertex line has at least 6 characters, a face line at least 7: do not trust absurd counts
  const std::size_t size = std::size_t(end - p);
  if(nv > size / 6 || nf > size / 7)
    return false;
  points.clear();
  triangles.clear();
  points.reserve(nv);
  triangles.reserve(nf);
  for(std::size_t v = 0; v < nv; ++v) {
    p = skip_off_comments(p, end);
    const char* eol = end_of_line(p, end);
    if(eol == end) // CGAL's reader fails when a vertex line ends the file
      return false;
    const void* hash = std::memchr(p, '#', std::size_t(eol - p));
    double xyz[3];
    if(!parse_three_doubles(p, hash != nullptr ? static_cast<const char*>(hash) : eol, xyz))
      return false;
    points.emplace_back();
    CGAL::IO::internal::fill_point(xyz[0], xyz[1], xyz[2], 1., points.back());
    p = eol;
  }
  for(std::size_t f = 0; f < nf; ++f) {
    p = skip_off_comments(p, end);
    if(p == end)
      return false;
    const char* eol = end_of_line(p, end);
    const void* hash = std::memchr(p, '#', std::size_t(eol - p));
    const char* last = hash != nullptr ? static_cast<const char*>(hash) : eol;
    const char* e = token_end(p, last);
    std::uint64_t n = 0;
    if(!parse_plain_index(p, e, 3, n) || n != 3)
      return false;
    std::array<int, 3> t;
    for(int k = 0; k < 3; ++k) {
      p = skip_blanks(e, last);
      e = token_end(p, last);
      std::uint64_t i = 0;
      if(!parse_plain_index(p, e, std::uint64_t(nv - 1), i))
        return false;
      t[std::size_t(k)] = int(i);
    }
    if(skip_blanks(e, last) != last)
      return false;
    triangles.push_back(t);
    p = eol;
  }
  return true;
}

/*
  Plain OBJ: lines `v x y z` (exactly three finite numbers), `f a b c` (three positive 1-based indices, each
  optionally followed by `/...`, separated by a space), comments, blank lines, and the lines CGAL's reader
  ignores (vt, vn, vp, o, g, s, usemtl, mtllib). Indices may refer to vertices defined later, as in CGAL's reader.
*/
template <class Point>
bool fast_parse_obj(const char* p, const char* end, std::vector<Point>& points,
                    std::vector<std::array<int, 3>>& triangles)
{
  points.clear();
  triangles.clear();
  const std::size_t size = std::size_t(end - p);
  points.reserve(size / 48 + 1);
  triangles.reserve(size / 24 + 1);
  constexpr std::uint64_t int_max = std::uint64_t((std::numeric_limits<int>::max)());
  std::uint64_t max_index = 0;
  while(p != end) {
    const char* eol = end_of_line(p, end);
    const char* first = p;
    p = eol == end ? end : eol + 1;
    first = skip_blanks(first, eol);
    if(first == eol || *first == '#')
      continue;
    const char* e = token_end(first, eol);
    const std::size_t length = std::size_t(e - first);
    if(length == 1 && *first == 'v') {
      double xyz[3];
      if(!parse_three_doubles(e, eol, xyz))
        return false;
      points.emplace_back();
      CGAL::IO::internal::fill_point(xyz[0], xyz[1], xyz[2], 1., points.back());
    } else if(length == 1 && *first == 'f') {
      std::array<int, 3> t;
      const char* q = e;
      for(int k = 0; k < 3; ++k) {
        q = skip_blanks(q, eol);
        const char* digits_end = q;
        while(digits_end != eol && *digits_end >= '0' && *digits_end <= '9')
          ++digits_end;
        const char* te = token_end(q, eol);
        std::uint64_t i = 0;
        // CGAL reads the integer, then skips past the next space (at most 256 characters)
        if(!parse_plain_index(q, digits_end, int_max, i) || i == 0 || te - q > 200 ||
           (digits_end != te && *digits_end != '/') || (k < 2 && (te == eol || *te != ' ')))
          return false;
        t[std::size_t(k)] = int(i - 1);
        max_index = (std::max)(max_index, i - 1);
        q = te;
      }
      if(skip_blanks(q, eol) != eol)
        return false;
      triangles.push_back(t);
    } else {
      const std::string keyword(first, e);
      if(keyword != "vt" && keyword != "vn" && keyword != "vp" && keyword != "o" && keyword != "g" &&
         keyword != "s" && keyword != "usemtl" && keyword != "mtllib")
        return false;
    }
  }
  // CGAL's reader refuses an empty soup and an index beyond the vertex count (it lets index nv through,
  // which the validation then reports)
  return !points.empty() && !triangles.empty() && max_index <= std::uint64_t(points.size());
}

/*
  Triangulates a polygon of five or more corners: projected onto the plane of its Newell normal, it must be
  simple (no two edges meet except consecutive ones at their common corner; exact predicates on the
  projected points) and within 5% of its size from planar, else false. Its triangles, the faces of the
  constrained Delaunay triangulation of the projected corners inside the polygon (m - 2 of them, no new
  vertex), are appended to `out` as point indices, with the polygon's orientation. We do not call
  PMP::triangulate_face() for these: it asserts, crashes, loops or corrupts its mesh (an endless face cycle)
  on faces it projects differently, which the fuzzer kept finding.
*/
template <class Point>
bool triangulate_simple_polygon(const std::vector<Point>& points, const std::vector<std::size_t>& corners,
                                std::vector<std::array<int, 3>>& out)
{
  using K2 = CGAL::Exact_predicates_inexact_constructions_kernel;
  const std::size_t m = corners.size();
  double n[3] = {0, 0, 0};
  for(std::size_t k = 0; k < m; ++k) {
    const Point& a = points[corners[k]];
    const Point& b = points[corners[(k + 1) % m]];
    const double ax = CGAL::to_double(a.x()), ay = CGAL::to_double(a.y()), az = CGAL::to_double(a.z());
    const double bx = CGAL::to_double(b.x()), by = CGAL::to_double(b.y()), bz = CGAL::to_double(b.z());
    n[0] += (ay - by) * (az + bz);
    n[1] += (az - bz) * (ax + bx);
    n[2] += (ax - bx) * (ay + by);
  }
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if(!(length > 0) || !std::isfinite(length))
    return false;
  for(double& c : n)
    c /= length;
  // u: perpendicular to n, along the axis n is furthest from; v = n x u
  double u[3] = {0, 0, 0};
  const int axis = std::abs(n[0]) <= std::abs(n[1]) && std::abs(n[0]) <= std::abs(n[2]) ? 0
                   : std::abs(n[1]) <= std::abs(n[2])                                   ? 1
                                                                                        : 2;
  u[axis] = 1;
  const double d = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
  for(int i = 0; i < 3; ++i)
    u[i] -= d * n[i];
  const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for(double& c : u)
    c /= lu;
  const double v[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
  // far from planar: CGAL's triangulation of such a face can loop forever (found by fuzzing), so a corner
  // more than 5% of the face's size away from its mean plane is refused
  double centre[3] = {0, 0, 0}, size = 0;
  for(std::size_t i : corners) {
    centre[0] += CGAL::to_double(points[i].x()) / double(m);
    centre[1] += CGAL::to_double(points[i].y()) / double(m);
    centre[2] += CGAL::to_double(points[i].z()) / double(m);
  }
  double height = 0;
  for(std::size_t i : corners) {
    const double p[3] = {CGAL::to_double(points[i].x()) - centre[0], CGAL::to_double(points[i].y()) - centre[1],
                         CGAL::to_double(points[i].z()) - centre[2]};
    size = (std::max)(size, std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
    height = (std::max)(height, std::abs(p[0] * n[0] + p[1] * n[1] + p[2] * n[2]));
  }
  if(!(height <= 0.05 * size))
    return false;
  std::vector<K2::Point_2> q;
  for(std::size_t i : corners) {
    const double p[3] = {CGAL::to_double(points[i].x()), CGAL::to_double(points[i].y()), CGAL::to_double(points[i].z())};
    q.emplace_back(p[0] * u[0] + p[1] * u[1] + p[2] * u[2], p[0] * v[0] + p[1] * v[1] + p[2] * v[2]);
  }
  for(std::size_t i = 0; i < m; ++i) {
    const K2::Segment_2 s(q[i], q[(i + 1) % m]);
    if(s.is_degenerate())
      return false;
    for(std::size_t j = i + 1; j < m; ++j) {
      const K2::Segment_2 t(q[j], q[(j + 1) % m]);
      const bool next = j == i + 1, previous = (j + 1) % m == i;
      if(next || previous) {
        // consecutive edges share one corner: they must not overlap beyond it
        const K2::Point_2& shared = next ? q[j] : q[i];
        const K2::Point_2& other_s = next ? q[i] : q[(i + 1) % m];
        const K2::Point_2& other_t = next ? q[(j + 1) % m] : q[j];
        if(CGAL::collinear(other_s, shared, other_t) && !CGAL::collinear_are_strictly_ordered_along_line(other_s, shared, other_t))
          return false;
      } else if(CGAL::do_intersect(s, t)) {
        return false;
      }
    }
  }
  // (u, v, n) is right-handed, so the polygon turns counter-clockwise in (u, v), as the faces of the CDT
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K2>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<K2, CGAL::Triangulation_face_base_with_info_2<int, K2>>;
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<K2, CGAL::Triangulation_data_structure_2<Vb, Fb>,
                                                         CGAL::No_constraint_intersection_tag>;
  CDT cdt;
  std::vector<typename CDT::Vertex_handle> handles;
  for(std::size_t k = 0; k < m; ++k) {
    handles.push_back(cdt.insert(q[k]));
    handles.back()->info() = corners[k];
  }
  if(cdt.number_of_vertices() != m)
    return false;
  for(std::size_t k = 0; k < m; ++k)
    cdt.insert_constraint(handles[k], handles[(k + 1) % m]);
  if(cdt.number_of_vertices() != m) // no Steiner point, but for safety
    return false;
  // inside: reached from the infinite face by crossing an odd number of constraints (exactly one: simple)
  for(auto fh = cdt.all_faces_begin(); fh != cdt.all_faces_end(); ++fh)
    fh->info() = -1;
  std::vector<typename CDT::Face_handle> stack(1, cdt.infinite_face());
  cdt.infinite_face()->info() = 0;
  while(!stack.empty()) {
    const typename CDT::Face_handle fh = stack.back();
    stack.pop_back();
    for(int i = 0; i < 3; ++i) {
      const typename CDT::Face_handle g = fh->neighbor(i);
      if(g->info() != -1)
        continue;
      g->info() = fh->info() + (cdt.is_constrained(typename CDT::Edge(fh, i)) ? 1 : 0);
      stack.push_back(g);
    }
  }
  const std::size_t first = out.size();
  for(auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh)
    if(fh->info() % 2 == 1)
      out.push_back({{int(fh->vertex(0)->info()), int(fh->vertex(1)->info()), int(fh->vertex(2)->info())}});
  if(out.size() - first != m - 2) {
    out.resize(first);
    return false;
  }
  return true;
}

/*
  Splits every polygon of more than three vertices into triangles (a quad along its better diagonal with
  PMP::triangulate_face(), larger polygons by triangulate_simple_polygon(): a constrained Delaunay
  triangulation in their plane), keeping the polygon's orientation and the vertex indices. Triangles of a polygon are consecutive, polygons in order;
  source[t] is the polygon of triangle t. Indices are checked first; polygons of fewer than three vertices are
  left to the validation, which rejects them.
*/
template <class Point, class PolygonRange>
void triangulate_polygons(const std::vector<Point>& points, const PolygonRange& polygons,
                          std::vector<std::array<int, 3>>& triangles, std::vector<std::size_t>& source)
{
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  using Patches = CGAL::Surface_mesh<typename Kernel::Point_3>;
  using Patch_vertex = typename Patches::Vertex_index;
  using Patch_face = typename Patches::Face_index;
  const std::size_t nf = polygons.size();
  check_soup_size(points.size(), nf);

  // Each polygon on its own copies of its vertices: one disk per polygon, whatever the soup's connectivity.
  Patches patches;
  auto point_index = patches.template add_property_map<Patch_vertex, int>("v:tc_point", -1).first;
  // by vertex: the faces split_face() creates have no property of their own, their vertices do
  auto polygon_of = patches.template add_property_map<Patch_vertex, std::size_t>("v:tc_polygon", 0).first;
  std::vector<Patch_face> to_split;
  std::vector<std::pair<std::size_t, std::array<int, 3>>> pieces; // (polygon, triangle)
  std::size_t f = 0;
  for(const auto& polygon : polygons) {
    for(const auto& index : polygon)
      if(std::size_t(index) >= points.size())
        throw_vertex_out_of_range(f, std::size_t(index), points.size());
    if(polygon.size() > 3) {
      std::vector<std::size_t> corners(polygon.begin(), polygon.end());
      std::vector<std::size_t> sorted = corners;
      std::sort(sorted.begin(), sorted.end());
      const auto repeated = std::adjacent_find(sorted.begin(), sorted.end());
      if(repeated != sorted.end())
        throw Invalid_input(Error_code::degenerate_face, "face " + std::to_string(f) + " uses vertex " +
                                                          std::to_string(*repeated) + " twice", f);
      if(polygon.size() > 4) {
        std::vector<std::array<int, 3>> split;
        if(!triangulate_simple_polygon(points, corners, split))
          throw Invalid_input(Error_code::degenerate_face,
                              "face " + std::to_string(f) +
                                " cannot be triangulated (it is far from planar, or seen along its normal its boundary"
                                " crosses itself)", f);
        for(const std::array<int, 3>& t : split)
          pieces.emplace_back(f, t);
        ++f;
        continue;
      }
      // a quad: PMP::triangulate_face() splits it along its better diagonal
      std::vector<Patch_vertex> corner_vertices;
      for(std::size_t i : corners) {
        const Point& p = points[i];
        const Patch_vertex v = patches.add_vertex(typename Kernel::Point_3(p.x(), p.y(), p.z()));
        put(point_index, v, int(i));
        put(polygon_of, v, f);
        corner_vertices.push_back(v);
      }
      to_split.push_back(patches.add_face(corner_vertices));
    }
    ++f;
  }
  for(const Patch_face pf : to_split) {
    const std::size_t bad = get(polygon_of, patches.target(patches.halfedge(pf)));
    bool split = false;
    try {
      split = CGAL::Polygon_mesh_processing::triangulate_face(pf, patches);
    } catch(const CGAL::Failure_exception&) {
      // CGAL's triangulation asserts on some faces that are far from planar or have coincident corners
      split = false;
    }
    if(!split)
      throw Invalid_input(Error_code::degenerate_face,
                          "face " + std::to_string(bad) + " cannot be triangulated (it is degenerate, or far from planar)",
                          bad);
  }

  // Triangles of each split polygon, gathered by polygon (new faces are appended, so sort by polygon).
  for(const Patch_face pf : patches.faces()) {
    std::array<int, 3> t;
    std::size_t k = 0;
    for(const Patch_vertex v : CGAL::vertices_around_face(patches.halfedge(pf), patches)) {
      if(k == 3) { // more corners (and no endless walk if the face cycle is broken)
        ++k;
        break;
      }
      t[k++] = get(point_index, v);
    }
    const std::size_t polygon = get(polygon_of, patches.target(patches.halfedge(pf)));
    if(k != 3) // triangulate_face() reported success but left a larger face (non-planar faces, found by fuzzing)
      throw Invalid_input(Error_code::degenerate_face,
                          "face " + std::to_string(polygon) + " cannot be triangulated (it is far from planar)",
                          polygon);
    pieces.emplace_back(polygon, t);
  }
  std::stable_sort(pieces.begin(), pieces.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });

  triangles.clear();
  source.clear();
  auto piece = pieces.begin();
  f = 0;
  for(const auto& polygon : polygons) {
    if(polygon.size() > 3) {
      for(; piece != pieces.end() && piece->first == f; ++piece) {
        triangles.push_back(piece->second);
        source.push_back(f);
      }
    } else if(polygon.size() == 3) {
      std::array<int, 3> t;
      std::size_t k = 0;
      for(const auto& index : polygon)
        t[k++] = int(std::size_t(index));
      triangles.push_back(t);
      source.push_back(f);
    } else {
      throw Invalid_input(Error_code::not_triangle_mesh,
                          "face " + std::to_string(f) + " has " + std::to_string(polygon.size()) + " vertices", f);
    }
    ++f;
  }
}

} // namespace io
} // namespace internal

/*!
\ingroup PkgTrivialConnectionsIO
Validates a polygon soup as an oriented 2-manifold triangle mesh (possibly with boundary) and builds it in
`tm` such that point `i` becomes the `i`-th vertex and polygon `f` the `f`-th face of `tm` in iteration
order. Points used by no polygon are kept as isolated vertices, so indices never shift. Checks, in this
order: at least one face; every index in range (before anything else uses them); triangles only; three
different vertices per face; no edge in more than two faces; no two faces traversing the same directed edge;
the faces around every vertex form one fan. Runs in linear time (plus small per-vertex sorts).

\tparam TriangleMesh a model of `MutableFaceGraph` with an internal vertex point map (e.g.
        `CGAL::Surface_mesh<Point_3>`, `CGAL::Polyhedron_3<K>`); \pre `tm` is empty
\tparam PointRange a range of values assignable to the mesh's points
\tparam PolygonRange a random-access range of ranges of integer indices (0-based)

\param points the points of the soup
\param polygons the faces of the soup, each the 0-based indices in `points` of its vertices, in order
\param tm the empty mesh that receives the result
\returns the vertices and faces of `tm` by input index (`source_faces` is empty)

\throws Invalid_input `empty_mesh`, `invalid_vertex`, `not_triangle_mesh`, `degenerate_face`, `non_manifold`,
        `inconsistent_orientation`; `where()` is the face (vertex for a non-manifold vertex) concerned
*/
template <class TriangleMesh, class PointRange, class PolygonRange>
Mesh_input_order<TriangleMesh> triangle_soup_to_mesh(const PointRange& points, const PolygonRange& polygons,
                                                     TriangleMesh& tm)
{
  const internal::io::Triangle_soup_connectivity soup =
    internal::io::validate_triangle_soup(std::size_t(std::distance(points.begin(), points.end())), polygons);
  return internal::io::build_mesh(points, soup, tm);
}

/*!
\ingroup PkgTrivialConnectionsIO
Reads a triangle mesh from an OFF, OBJ, PLY, STL or GOCAD (`.ts`) file (by extension, any letter case: the
formats `CGAL::IO::read_polygon_mesh()` reads without VTK), validates it and builds it in `tm` with
`triangle_soup_to_mesh()`: vertex `i` of the file is the `i`-th vertex of `tm` and face `f` its `f`-th face,
unused vertices included. Every message starts with `path: `.

OFF and PLY are read by the package's own readers, which check every count against the size of the file
before using it (CGAL 5.5's readers trust them: a file of a few bytes can ask for gigabytes or crash them).
OFF: ASCII, keyword `OFF`, `COFF`, `NOFF`, `CNOFF`, `STOFF`, ... (normals, colours and texture coordinates
are read past); binary, homogeneous (`4OFF`) and n-dimensional (`nOFF`) OFF files are refused. PLY: ASCII
and binary of either endianness; the `x`, `y`, `z` properties of the `vertex` element, of any numeric type,
and the `vertex_indices` (or `vertex_index`) list of the `face` element, of any integer type; other elements
and properties are read past. OBJ is checked by the package and then read, like STL and GOCAD, with
`CGAL::IO::read_polygon_soup()`.

\tparam TriangleMesh as for `triangle_soup_to_mesh()`
\tparam NamedParameters a sequence of named parameters
\param path the file to read; its extension gives the format
\param tm the empty mesh that receives the result
\param np an optional sequence of named parameters among the ones listed below
\returns the vertices and faces of `tm` by index in the file, and the face of the file each triangle comes from
         when faces were triangulated

\cgalNamedParamsBegin
  \cgalParamNBegin{triangulate}
    \cgalParamDescription{whether faces of more than three vertices are split into triangles (a quad along
      its better diagonal with `CGAL::Polygon_mesh_processing::triangulate_face()`, a larger face by a
      constrained Delaunay triangulation of its corners in the plane of its normal, without new vertices; a
      larger face more than 5% of its size from planar, or whose boundary crosses itself in that plane, is a
      `degenerate_face` error), keeping their orientation and the vertex numbering.
      Triangle `t` of `tm` then comes from face `source_faces[t]` of the file; see `Mesh_input_order`.}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`: such a face is a `not_triangle_mesh` error}
  \cgalParamNEnd
\cgalNamedParamsEnd

\pre `tm` is empty
\throws Invalid_input
  - `io_error`: the file does not exist, is a directory or cannot be read;
  - `parse_error`: unknown or missing extension, or the file cannot be parsed (the message names the line
    for OFF, OBJ and a PLY header, the element and item in a PLY body), or is a refused OFF variant;
  - `invalid_vertex`: a face uses a vertex index out of range (`where()`: the face);
  - `not_triangle_mesh`: a face of more than three vertices without `triangulate(true)`, or of fewer than
    three; `degenerate_face`: also a face that `triangulate(true)` cannot split (a zero normal) or that uses
    a vertex twice;
  - `empty_mesh`, `non_manifold`, `inconsistent_orientation`: as `triangle_soup_to_mesh()`, on the triangles
    (faces are then numbered as the triangles of `tm`).
*/
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Mesh_input_order<TriangleMesh> read_triangle_mesh(const std::string& path, TriangleMesh& tm,
                                                  const NamedParameters& np = parameters::default_values())
{
  using Point = typename boost::property_traits<
    typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type>::value_type;

  std::error_code ec;
  if(!std::filesystem::exists(path, ec))
    throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "': no such file");
  if(std::filesystem::is_directory(path, ec))
    throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "': it is a directory");
  {
    errno = 0;
    std::ifstream probe(path);
    if(!probe) {
      const int err = errno;
      throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "'" +
                                                  (err != 0 ? std::string(": ") + std::strerror(err) : std::string()));
    }
  }
  const std::string ext = internal::io::lower_extension(path);
  if(ext != "off" && ext != "obj" && ext != "ply" && ext != "stl" && ext != "ts")
    throw Invalid_input(Error_code::parse_error,
                        "cannot read mesh file '" + path + "': " +
                          (ext.empty() ? std::string("no file extension") : "unknown file extension '." + ext + "'") +
                          " (supported: .off, .obj, .ply, .stl, .ts)");
  const bool triangulate =
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::triangulate), false);

  if(ext == "off" || ext == "obj") {
    std::vector<Point> points;
    std::vector<std::array<int, 3>> triangles;
    bool parsed = false;
    {
      const internal::io::File_contents data(path);
      if(data.ok())
        parsed = ext == "off" ? internal::io::fast_parse_off(data.begin(), data.end(), points, triangles)
                              : internal::io::fast_parse_obj(data.begin(), data.end(), points, triangles);
    }
    if(parsed) {
      try {
        const internal::io::Triangle_soup_connectivity soup =
          internal::io::validate_triangles(points.size(), std::move(triangles));
        return internal::io::build_mesh(points, soup, tm);
      } catch(const Invalid_input& e) {
        throw Invalid_input(e.code(), path + ": " + e.what(), e.where());
      }
    }
  }

  // OFF and PLY are read by our own readers (see read_off_soup() and Ply_reader for what CGAL's do with
  // malformed files); OBJ is diagnosed by ours first, then read by CGAL's, like STL and GOCAD.
  std::vector<Point> points;
  std::vector<boost::container::small_vector<std::size_t, 3>> polygons;
  bool read = true;
  if(ext == "off") {
    internal::io::read_off_soup(path, points, polygons);
  } else if(ext == "ply") {
    const internal::io::File_contents data(path);
    if(!data.ok())
      throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "'");
    internal::io::Ply_reader(data.begin(), data.end(), path).read(points, polygons);
  } else {
    if(ext == "obj")
      internal::io::diagnose_obj(path);
    try {
      read = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
    } catch(const std::length_error&) {
      read = false; // a count too large for a vector
    }
  }
  if(!read)
    throw Invalid_input(Error_code::parse_error, "cannot parse '" + path + "' as a " + ext + " mesh file");
  try {
    const bool has_polygons = std::any_of(polygons.begin(), polygons.end(),
                                          [](const auto& polygon) { return polygon.size() > 3; });
    if(!triangulate || !has_polygons)
      return triangle_soup_to_mesh(points, polygons, tm);
    std::vector<std::array<int, 3>> triangles;
    std::vector<std::size_t> source_faces;
    internal::io::triangulate_polygons(points, polygons, triangles, source_faces);
    const internal::io::Triangle_soup_connectivity soup =
      internal::io::validate_triangles(points.size(), std::move(triangles));
    Mesh_input_order<TriangleMesh> order = internal::io::build_mesh(points, soup, tm);
    order.source_faces = std::move(source_faces);
    return order;
  } catch(const Invalid_input& e) {
    throw Invalid_input(e.code(), path + ": " + e.what(), e.where());
  }
}

} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H
