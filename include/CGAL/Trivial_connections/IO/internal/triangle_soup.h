// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TRIANGLE_SOUP_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TRIANGLE_SOUP_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/exceptions.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
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
  Step 4 of the validation below, on `soup.triangles` (indices in range, three different vertices): fills
  `soup.opposite`, or returns false when an edge is in more than two faces or two faces traverse it the same
  way. The corners are bucketed by the smaller vertex of their edge (a counting sort, whose scattered writes
  are cheap where scattered reads are not), and each bucket sorted by the larger vertex: the corners of an
  edge are then adjacent.
*/
inline bool match_edges(Triangle_soup_connectivity& soup)
{
  const std::size_t number_of_points = soup.number_of_vertices, nf = soup.triangles.size();
  std::vector<int> first(number_of_points + 1, 0);
  for(const std::array<int, 3>& t : soup.triangles)
    for(std::size_t k = 0; k < 3; ++k)
      ++first[std::size_t((std::min)(t[k], t[(k + 1) % 3])) + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  // (larger vertex, corner c if it goes from the smaller vertex to the larger, else -1 - c)
  std::vector<std::pair<int, int>> bucket(3 * nf);
  {
    std::vector<int> fill(first.begin(), first.end() - 1);
    for(std::size_t f = 0; f < nf; ++f) {
      const std::array<int, 3>& t = soup.triangles[f];
      for(std::size_t k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3], c = int(3 * f + k);
        bucket[std::size_t(fill[std::size_t((std::min)(a, b))]++)] =
          a < b ? std::make_pair(b, c) : std::make_pair(a, -1 - c);
      }
    }
  }
  soup.opposite.assign(3 * nf, -1);
  for(std::size_t v = 0; v < number_of_points; ++v) {
    const auto begin = bucket.begin() + first[v], end = bucket.begin() + first[v + 1];
    std::sort(begin, end);
    for(auto it = begin; it != end;) {
      auto run = it + 1;
      while(run != end && run->first == it->first)
        ++run;
      if(run - it > 2)
        return false; // more than two faces
      if(run - it == 2) {
        // sorted: the corner going down (negative) first
        if(!(it->second < 0 && (it + 1)->second >= 0))
          return false; // both the same way
        const int down = -1 - it->second, up = (it + 1)->second;
        soup.opposite[std::size_t(down)] = up;
        soup.opposite[std::size_t(up)] = down;
      }
      it = run;
    }
  }
  return true;
}

/*
  Step 4 again when match_edges() failed, to name the first offending edge in corner order: directed edges
  are found in per-vertex lists of outgoing corners (lists longer than `sorted_from` are sorted by
  (target, corner) and searched by bisection), each edge once from its first corner. Throws (or, were
  match_edges() wrong, fills `soup.opposite` as it should have).
*/
inline void report_first_bad_edge(Triangle_soup_connectivity& soup)
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
    for(std::size_t f = 0; f < soup.triangles.size(); ++f) {
      const std::array<int, 3>& t = soup.triangles[f];
      for(std::size_t k = 0; k < 3; ++k)
        out[std::size_t(fill[std::size_t(t[k])]++)] = std::make_pair(t[(k + 1) % 3], int(3 * f + k));
    }
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
}

/*
  Step 5 of the validation below, once `soup.opposite` is filled: walks around every vertex; only when a
  vertex fails, the union-find below finds the fans to name in the message. Throws or returns.
*/
inline void check_fans(const Triangle_soup_connectivity& soup)
{
  const std::size_t number_of_points = soup.number_of_vertices;
  const int nc = int(3 * soup.triangles.size());
  // 5. one fan per vertex: walking around each vertex from one of its corners, through the faces that share
  // an edge at it, must meet all its corners
  std::vector<int> degree_of(number_of_points, 0), corner_at(number_of_points, -1);
  for(int c = nc - 1; c >= 0; --c) {
    const std::size_t v = std::size_t(soup.source(c));
    ++degree_of[v];
    corner_at[v] = c;
  }
  std::size_t first_bad_vertex = number_of_points;
  for(std::size_t v = 0; v < number_of_points && first_bad_vertex == number_of_points; ++v) {
    const int degree = degree_of[v];
    if(degree == 0)
      continue;
    const int c0 = corner_at[v];
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

// Steps 4 and 5 of the validation below: fills `soup.opposite` or throws.
inline void connect_triangle_soup(Triangle_soup_connectivity& soup)
{
  if(!match_edges(soup))
    report_first_bad_edge(soup);
  check_fans(soup);
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

} // namespace io
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TRIANGLE_SOUP_H
