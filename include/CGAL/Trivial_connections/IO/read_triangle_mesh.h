// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/exceptions.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/container/small_vector.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsIO
The elements of a mesh built by `read_triangle_mesh()` or `triangle_soup_to_mesh()`, by input index:
`vertices[i]` is vertex `i` of the file (also the `i`-th vertex of `vertices(tm)`), `faces[f]` is face `f`
(also the `f`-th face of `faces(tm)`).
*/
template <class TriangleMesh>
struct Mesh_input_order
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  std::vector<vertex_descriptor> vertices;
  std::vector<face_descriptor> faces;
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

/*
  Validates a polygon soup as an oriented 2-manifold triangle mesh (possibly with boundary and isolated
  vertices) and returns its connectivity. Checks, in this order, each over all faces in input order:
    1. at least one face (empty_mesh);
    2. every vertex index is in range (invalid_vertex), before any other use of the indices;
    3. every face is a triangle (not_triangle_mesh) with three different vertices (degenerate_face);
    4. no edge is shared by more than two faces (non_manifold), no two faces traverse the same directed
       edge (inconsistent_orientation);
    5. the faces around each vertex form a single fan (non_manifold).
  Linear time: directed edges are found in per-vertex lists of outgoing halfedges sorted by target.
*/
template <class PolygonRange>
Triangle_soup_connectivity validate_triangle_soup(std::size_t number_of_points, const PolygonRange& polygons)
{
  Triangle_soup_connectivity soup;
  soup.number_of_vertices = number_of_points;
  const std::size_t nf = polygons.size();
  if(nf == 0)
    throw Invalid_input(Error_code::empty_mesh, "the mesh has no face" + std::string(number_of_points > 0 ?
                          " (" + std::to_string(number_of_points) + " vertices, 0 faces)" : ""));
  constexpr std::size_t limit = std::size_t((std::numeric_limits<int>::max)());
  if(number_of_points >= limit || nf >= limit / 3)
    throw Invalid_input(Error_code::invalid_argument, "the mesh is too large (" + std::to_string(number_of_points) +
                                                        " vertices, " + std::to_string(nf) + " faces)");

  // 2. indices in range
  std::size_t f = 0;
  for(const auto& polygon : polygons) {
    for(const auto& index : polygon) {
      const std::size_t v = std::size_t(index);
      if(v >= number_of_points)
        throw Invalid_input(Error_code::invalid_vertex,
                            "face " + std::to_string(f) + " uses vertex " +
                              std::to_string(static_cast<long long>(v)) + " but the mesh has only " +
                              std::to_string(number_of_points) + " vertices (0-based indices 0 to " +
                              (number_of_points == 0 ? std::string("none") : std::to_string(number_of_points - 1)) +
                              ")",
                            f);
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
    if(t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      throw Invalid_input(Error_code::degenerate_face,
                          "face " + std::to_string(f) + " (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) +
                            ", " + std::to_string(t[2]) + ") uses the same vertex twice",
                          f);
    ++f;
  }

  // Outgoing corner halfedges of each vertex, sorted by (target, corner).
  const int nc = int(3 * nf);
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
  for(std::size_t v = 0; v < number_of_points; ++v)
    if(first[v + 1] - first[v] > 1)
      std::sort(out.begin() + first[v], out.begin() + first[v + 1]);
  auto halfedges_from_to = [&](int a, int b) {
    const auto begin = out.begin() + first[std::size_t(a)], end = out.begin() + first[std::size_t(a) + 1];
    return std::equal_range(begin, end, std::make_pair(b, -1),
                            [](const std::pair<int, int>& x, const std::pair<int, int>& y) { return x.first < y.first; });
  };

  // 4. edges: at most two faces, traversed in opposite directions
  soup.opposite.assign(std::size_t(nc), -1);
  for(int c = 0; c < nc; ++c) {
    const int a = soup.source(c), b = soup.target(c);
    const auto ab = halfedges_from_to(a, b);
    const auto ba = halfedges_from_to(b, a);
    const std::ptrdiff_t n_ab = ab.second - ab.first, n_ba = ba.second - ba.first;
    if(n_ab + n_ba > 2) {
      std::vector<int> faces;
      for(auto it = ab.first; it != ab.second; ++it) faces.push_back(it->second / 3);
      for(auto it = ba.first; it != ba.second; ++it) faces.push_back(it->second / 3);
      std::sort(faces.begin(), faces.end());
      throw Invalid_input(Error_code::non_manifold,
                          "non-manifold edge: the edge between vertices " + std::to_string(a) + " and " +
                            std::to_string(b) + " is shared by " + std::to_string(faces.size()) + " faces (" +
                            face_list(faces) + ")",
                          std::size_t(faces.front()));
    }
    if(n_ab == 2) {
      const int f0 = ab.first->second / 3, f1 = (ab.first + 1)->second / 3;
      throw Invalid_input(Error_code::inconsistent_orientation,
                          "inconsistent orientation: faces " + std::to_string((std::min)(f0, f1)) + " and " +
                            std::to_string((std::max)(f0, f1)) + " both traverse the edge from vertex " +
                            std::to_string(a) + " to vertex " + std::to_string(b) +
                            " (neighbouring faces must traverse their common edge in opposite directions)",
                          std::size_t((std::max)(f0, f1)));
    }
    if(n_ba == 1)
      soup.opposite[std::size_t(c)] = ba.first->second;
  }

  // 5. one fan per vertex: join the corners of two faces that share an edge at each of its vertices
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
  return soup;
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
  order.vertices.resize(nv);
  order.faces.resize(nf);
  auto vpm = get(CGAL::vertex_point, tm);
  std::size_t i = 0;
  for(const auto& p : points) {
    order.vertices[i] = add_vertex(tm);
    put(vpm, order.vertices[i], p);
    ++i;
  }
  for(std::size_t f = 0; f < nf; ++f)
    order.faces[f] = add_face(tm);

  std::vector<halfedge_descriptor> h(nc);
  for(std::size_t c = 0; c < nc; ++c) {
    const int t = soup.opposite[c];
    h[c] = (t >= 0 && std::size_t(t) < c) ? opposite(h[std::size_t(t)], tm) : halfedge(add_edge(tm), tm);
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
  Called when CGAL could not read an ASCII OFF file: finds why, line by line, and throws a precise
  Invalid_input (parse_error with the line, invalid_vertex with the face). Returns if it finds nothing.
*/
inline void diagnose_off(const std::string& path)
{
  std::ifstream is(path);
  if(!is)
    return;
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
  if(!next_tokens())
    throw Invalid_input(Error_code::parse_error, path + ": the file is empty");
  std::size_t k = 0;
  const std::string& magic = t[0];
  if(magic.size() >= 3 && magic.compare(magic.size() - 3, 3, "OFF") == 0) {
    if(magic != "OFF" && magic != "COFF" && magic != "NOFF" && magic != "CNOFF" && magic != "STOFF" &&
       magic != "STCOFF")
      return; // a variant we do not diagnose
    if(t.size() > 1 && t[1] == "BINARY")
      return;
    k = 1;
  }
  if(k == t.size()) {
    if(!next_tokens())
      throw Invalid_input(Error_code::parse_error, path + ": unexpected end of file: expected the vertex and face counts");
    k = 0;
  }
  long long nv = -1, nf = -1;
  if(t.size() < k + 2 || !parse_integer(t[k], nv) || !parse_integer(t[k + 1], nf) || nv < 0 || nf < 0)
    throw Invalid_input(Error_code::parse_error, at + std::to_string(line_number) +
                                                   ": expected the vertex, face and edge counts of the OFF header");
  for(long long v = 0; v < nv; ++v) {
    if(!next_tokens())
      throw Invalid_input(Error_code::parse_error,
                          path + ": unexpected end of file: the header announces " + std::to_string(nv) +
                            " vertices, the file has " + std::to_string(v));
    if(t.size() < 3 || !parse_number(t[0]) || !parse_number(t[1]) || !parse_number(t[2]))
      throw Invalid_input(Error_code::parse_error, at + std::to_string(line_number) + ": vertex " + std::to_string(v) +
                                                     ": expected three coordinates",
                          std::size_t(v));
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
    }
  }
  if(nf == 0)
    throw Invalid_input(Error_code::empty_mesh, path + ": the mesh has no face (" + std::to_string(nv) + " vertices)");
}

// Same for OBJ: no face at all, or a face index out of range.
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
    throw Invalid_input(Error_code::empty_mesh, path + ": the mesh has no face (" + std::to_string(nv) + " vertices)");
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
Reads a triangle mesh from an OFF, OBJ, PLY or STL file (by extension, any letter case) with
`CGAL::IO::read_polygon_soup()`, validates it and builds it in `tm` with `triangle_soup_to_mesh()`:
vertex `i` of the file is the `i`-th vertex of `tm` and face `f` its `f`-th face, unused vertices included.
Every message starts with `path: `.

\pre `tm` is empty
\throws Invalid_input
  - `io_error`: the file does not exist, is a directory or cannot be read;
  - `parse_error`: unknown or missing extension, or the file cannot be parsed (for OFF with the line);
  - `invalid_vertex`: a face uses a vertex index out of range (`where()`: the face);
  - `empty_mesh`, `not_triangle_mesh`, `degenerate_face`, `non_manifold`, `inconsistent_orientation`:
    as `triangle_soup_to_mesh()`.
*/
template <class TriangleMesh>
Mesh_input_order<TriangleMesh> read_triangle_mesh(const std::string& path, TriangleMesh& tm)
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
  if(ext != "off" && ext != "obj" && ext != "ply" && ext != "stl")
    throw Invalid_input(Error_code::parse_error,
                        "cannot read mesh file '" + path + "': " +
                          (ext.empty() ? std::string("no file extension") : "unknown file extension '." + ext + "'") +
                          " (supported: .off, .obj, .ply, .stl)");

  std::vector<Point> points;
  std::vector<boost::container::small_vector<std::size_t, 3>> polygons;
  if(!CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false))) {
    if(ext == "off")
      internal::io::diagnose_off(path);
    else if(ext == "obj")
      internal::io::diagnose_obj(path);
    throw Invalid_input(Error_code::parse_error, "cannot parse '" + path + "' as a " + ext + " mesh file");
  }
  try {
    return triangle_soup_to_mesh(points, polygons, tm);
  } catch(const Invalid_input& e) {
    throw Invalid_input(e.code(), path + ": " + e.what(), e.where());
  }
}

} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H
