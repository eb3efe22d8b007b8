// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_EXTRACTION_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_EXTRACTION_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/quad/cut_graph.h>
#include <CGAL/Trivial_connections/internal/quad/seamless_parametrization.h>

#include <CGAL/assertions.h>
#include <CGAL/number_type_config.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The fourth layer of quad meshing (issue 43): the quad mesh of an integer-grid map (the approach of Ebke,
  Bommes, Chen and Kobbelt, "QEx", 2013, in our words). Its vertices are the points of the surface where u and v
  are both integers, its edges the pieces of the integer iso-lines (u or v integer) between them, its faces the
  cells the iso-lines cut the surface into.

  The iso-lines are cut, triangle by triangle, into pieces between "nodes": the integer points (quad vertices)
  and the points where an iso-line crosses an edge or passes through a mesh vertex with only one coordinate
  integer (pass-through nodes). A node is one object whatever the chart it is seen from:
  - at a mesh vertex: the vertex (integer-ness of a coordinate does not depend on the wedge: the transitions
    are grid automorphisms);
  - inside an edge: the edge and the line it is on, computed once in the chart of the edge's canonical face
    (the other face's lines are carried there by the transition, exactly: quarter turns and integers), so a
    point on a cut edge seen from both sides is one node;
  - inside a face: the face and its integer (u, v).
  To make "on a line" an exact test, every corner coordinate within snap_tolerance of an integer is set to it.
  Each piece leaves its two nodes in a direction; sorting the pieces counter-clockwise around every node (by the
  corner of the mesh vertex they leave into and the angle in that corner's chart; by the side and angle at an
  edge node; by angle at a face node) gives a rotation system, and its faces (next = the piece just clockwise of
  the way back, at the arrival node) are the quad mesh's faces, counter-clockwise like the input.

  Folded triangles (negative (u, v) area) and degenerate ones (zero area) are skipped: none of their interior
  points or pieces is made (the pieces along an edge of theirs still are, from the other side). The lines that
  enter one end there, so the cells around a fold are not quads. Every cycle of the rotation system that is not
  a simple quad (4 distinct integer points, only pass-through nodes of 2 pieces in between) is reported and
  kept apart, in rejected_polygons, never in faces: the faces are quads only. Where polygons were rejected the
  quad mesh has a hole, counted in open_edges. Nothing of this happens on a fold-free integer-grid map that winds
  around each singular vertex by its cone angle (one that winds less has the wrong valence there and cells around
  it that are not quads: map_untangling.h).

  Surfaces with border: every border edge must lie on an integer iso-line of its face's chart (put there by the
  parametrisation's feature flags, for a field aligned with the border); a border that is not is refused with an
  Invalid_input naming the edge. The pieces along the border close the cells along it; the cycles of the
  rotation system that run along the border on the outside (the border pieces walked backwards) are the holes,
  neither faces nor rejected polygons. At a mesh vertex of the border the pieces are sorted from the clockwise
  border edge to the counter-clockwise one (the open fan).

  Valence on the border: a quad vertex on the border has valence q + 1, q the number of quads at it, which is
  its (u, v) angle inside the surface in quarter turns: 3 where the border is straight in the map, 2 at a convex
  corner (a quarter turn), 4 at a concave one (three quarter turns), and so on. Written like the interior rule
  (valence 4 - 4 k at an interior vertex of index k), it is 3 - 4 k_b with k_b = (2 - q) / 4 the vertex's share
  of its border loop's index: a convex corner counts +1/4, a concave one -1/4, and they sum over a loop to its
  index k_B (CONVENTIONS.md: a square's border, a constant field's loop on a disk, has k_B = 1 = four +1/4).

  What follows the input's edges: for every quad edge, the input edges it runs along (edges on an iso-line, the
  pieces between its nodes), so that a caller can check that every feature edge is followed by quad edges.
*/

struct Quad_mesh
{
  // where a quad vertex is on the input: in face `face` at `barycentric` (weights of its corners 3 face + k);
  // mesh_vertex is the input vertex it is at, or -1
  struct Location
  {
    int face = -1;
    std::array<double, 3> barycentric = {{0, 0, 0}};
    int mesh_vertex = -1;
  };

  std::vector<Vec3> points;                       // per quad vertex: its position on the input
  std::vector<Location> locations;                // per quad vertex
  std::vector<int> valence;                       // per quad vertex: the iso-line pieces leaving it
  std::vector<std::array<int, 4>> faces;          // the quads, counter-clockwise like the input
  std::vector<std::vector<int>> rejected_polygons; // the other cycles (their integer points), not in faces
  std::vector<std::array<int, 2>> edges;          // per quad edge: its two quad vertices
  std::vector<std::vector<int>> edge_along;       // per quad edge: the input edges (cut graph numbering) it runs
                                                  // along, in order from edges[e][0] (empty: across faces)
  std::vector<char> on_border;                    // per quad vertex: on the border of the input
  int border_edges = 0;          // quad edges along the border
  int holes = 0;                 // outside cycles along the border (not faces)
  int quads = 0;
  int non_quads = 0;             // rejected polygons
  int folded_triangles = 0;      // negative (u, v) area
  int degenerate_triangles = 0;  // zero (u, v) area (after snapping)
  int quad_edges = 0;            // iso-line chains from an integer point to an integer point
  int dangling_edges = 0;        // chains from an integer point that end elsewhere (at a fold)
  int open_edges = 0;            // quad edges in fewer than two faces (fewer than one on the border)
};

// every corner coordinate within it of an integer is that integer for the extraction (see above)
inline constexpr double default_snap_tolerance = 1e-6;

namespace quad_extraction_impl {

using UV = Seamless_parametrization::UV;

// w -> R^turns w + t, R the counter-clockwise quarter turn: an automorphism of the integer grid
struct Grid_map
{
  int turns = 0;
  UV t = {{0, 0}};

  static UV turn(const UV& w, int q)
  {
    switch(modulo_quarter_turns(q)) {
      case 0: return w;
      case 1: return {{-w[1], w[0]}};
      case 2: return {{-w[0], -w[1]}};
      default: return {{w[1], -w[0]}};
    }
  }
  UV operator()(const UV& w) const
  {
    const UV r = turn(w, turns);
    return {{r[0] + t[0], r[1] + t[1]}};
  }
  UV inverse(const UV& w) const { return turn({{w[0] - t[0], w[1] - t[1]}}, -turns); }
  // the line {w[k] = c} mapped: it is {w[k'] = c'}
  std::pair<int, double> line(int k, double c) const
  {
    UV p = {{0, 0}}, q = {{0, 0}};
    p[k] = q[k] = c;
    q[1 - k] = 1;
    const UV a = (*this)(p), b = (*this)(q);
    return a[0] == b[0] ? std::make_pair(0, a[0]) : std::make_pair(1, a[1]);
  }
};

inline bool is_integer(double x) { return x == std::round(x); }

// x set to the integer nearest to it when within snap_tolerance of it
inline double snapped(double x, double snap_tolerance)
{
  return std::abs(x - std::round(x)) <= snap_tolerance ? std::round(x) : x;
}

// the (u, v) of face f's three corners in `map`, each coordinate snapped
inline std::array<UV, 3> snapped_face(const Seamless_parametrization::Map& map, std::size_t f, double snap_tolerance)
{
  std::array<UV, 3> p;
  for(int k = 0; k < 3; ++k)
    for(int j = 0; j < 2; ++j)
      p[k][j] = snapped(map.corner_uv[3 * f + k][j], snap_tolerance);
  return p;
}

// twice the signed (u, v) area of a triangle: > 0 counter-clockwise, < 0 folded, 0 degenerate
inline double twice_uv_area(const UV& p, const UV& q, const UV& r)
{
  return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
}

// the counter-clockwise angle from a to b, in [0, 2 pi)
inline double ccw_angle(const UV& a, const UV& b)
{
  const double angle = std::atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]);
  return angle < 0 ? angle + 2 * CGAL_PI : angle;
}

enum class Node_kind { vertex, edge, face };

struct Node
{
  Node_kind kind;
  int element;                 // vertex, edge or face index
  bool integer_point = false;
  Quad_mesh::Location location;
};

// a node inside an edge, in the chart of the edge's canonical face
struct Edge_node
{
  double s;    // from the source of the canonical corner halfedge (0) to its target (1)
  UV uv;
  int node;
};

// a piece of iso-line between two nodes; key: where it leaves each end in the counter-clockwise order there
struct Piece
{
  std::array<int, 2> node;
  std::array<double, 2> key;
  int along = -1;        // the input edge it runs along, or -1
  bool border = false;   // along a border edge, from its source to its target (the surface on its left)
};

} // namespace quad_extraction_impl

// folded (negative (u, v) area) + degenerate (zero) triangles of a map, as extract_quad_mesh() counts them (after
// its snapping), without building anything
inline int inverted_triangles(const Seamless_parametrization::Map& map, double snap_tolerance = default_snap_tolerance)
{
  using namespace quad_extraction_impl;
  int count = 0;
  for(std::size_t f = 0; 3 * f + 2 < map.corner_uv.size(); ++f) {
    const std::array<UV, 3> p = snapped_face(map, f, snap_tolerance);
    count += !(twice_uv_area(p[0], p[1], p[2]) > 0);
  }
  return count;
}

// The winding of a map around each vertex: the sum of the (u, v) angles of its corners (signed: negative in a
// folded triangle), after the extraction's snapping. It is the turning of the vertex's link, a whole number of
// turns plus the quarter turns of the transitions around it: 2 pi (1 - k) plus whole turns at an interior vertex
// of index k. A fold-free map winds once around each vertex, as its index says; one that winds a turn less
// around a singular vertex (fandisk: a quarter turn instead of five around some -1/4) and a turn more around a
// regular vertex nearby (a branch point: 4 pi) is fold-free too, but its iso-lines cannot make the valence 4 - 4 k
// there (the quads have valence errors and cells that are not quads).
struct Uv_windings
{
  std::vector<double> angle_sum;      // per vertex
  std::vector<char> beside_inverted;  // per vertex: a corner in a folded or degenerate triangle (the sum then
                                      // says nothing about the winding of the map's sheets)

  // the whole turns by which the map winds around interior vertex v otherwise than its index k4 / 4 asks (0: as
  // it asks)
  long turns_off(std::size_t v, long long k4) const
  {
    return std::lround((angle_sum[v] - 2 * CGAL_PI * (1 - double(k4) / 4)) / (2 * CGAL_PI));
  }
};

template <class TriangleMesh>
Uv_windings uv_windings(const Mesh_arrays<TriangleMesh>& m, const Seamless_parametrization::Map& map,
                        double snap_tolerance = default_snap_tolerance)
{
  using namespace quad_extraction_impl;
  CGAL_precondition(map.corner_uv.size() == std::size_t(3 * m.nf));
  Uv_windings w;
  w.angle_sum.assign(std::size_t(m.nv), 0.);
  w.beside_inverted.assign(std::size_t(m.nv), 0);
  for(int f = 0; f < m.nf; ++f) {
    const std::array<UV, 3> p = snapped_face(map, std::size_t(f), snap_tolerance);
    const bool inverted = !(twice_uv_area(p[0], p[1], p[2]) > 0);
    for(int k = 0; k < 3; ++k) {
      const UV &o = p[k], &a = p[(k + 1) % 3], &b = p[(k + 2) % 3];
      const double ax = a[0] - o[0], ay = a[1] - o[1], bx = b[0] - o[0], by = b[1] - o[1];
      const std::size_t v = std::size_t(m.corner_vertex[3 * f + k]);
      w.angle_sum[v] += std::atan2(ax * by - ay * bx, ax * bx + ay * by);
      w.beside_inverted[v] = w.beside_inverted[v] || inverted;
    }
  }
  return w;
}

/*
  The quad mesh of the integer-grid map `map` (corner_uv, translation) on the cut graph `cut` it was built on
  (layer 3's result). Throws Invalid_input when the map is not an integer-grid map (a transition that is not a
  quarter turn plus an integer translation, a singular vertex off the integer points), when a border edge is not
  on an integer iso-line, and when the map has more than max_quads cells (estimated by its (u, v) area before
  anything is built).
*/
template <class TriangleMesh>
Quad_mesh extract_quad_mesh(const Mesh_arrays<TriangleMesh>& m, const Cut_graph& cut,
                            const Seamless_parametrization::Map& map, double max_quads = 1e7,
                            double snap_tolerance = default_snap_tolerance)
{
  using namespace quad_extraction_impl;
  using MA = Mesh_arrays<TriangleMesh>;
  const int nc = 3 * m.nf;
  CGAL_precondition(map.corner_uv.size() == std::size_t(nc) && map.translation.size() == cut.arcs.size());
  CGAL_precondition(cut.edge_of_corner.size() == std::size_t(nc));
  Quad_mesh result;

  // the corners, snapped
  std::vector<UV> uv(nc);
  for(int c = 0; c < nc; ++c)
    for(int k = 0; k < 2; ++k) {
      const double x = map.corner_uv[c][k];
      if(!std::isfinite(x))
        throw Invalid_input(Error_code::invalid_argument, "the map is not finite at corner " + std::to_string(c));
      uv[c][k] = snapped(x, snap_tolerance);
    }

  // every border edge on an integer iso-line of its face's chart
  for(int i = 0; i < nc; ++i) {
    if(m.opposite_corner[i] >= 0)
      continue;
    const UV &a = uv[i], &b = uv[MA::next_corner(i)];
    bool on_line = false;
    for(int k = 0; k < 2; ++k)
      on_line = on_line || (a[k] == b[k] && is_integer(a[k]));
    if(!on_line)
      throw Invalid_input(Error_code::invalid_argument,
                          "the border edge from vertex " + std::to_string(m.source_of(i)) + " to vertex " +
                            std::to_string(m.target_of(i)) +
                            " is not on an integer iso-line of the map (the field is not aligned with the border, or "
                            "the border was not given to the parametrisation as a feature)",
                          std::size_t(i));
  }

  // per face: its (u, v) area; folded and degenerate faces are skipped
  std::vector<char> active(m.nf, 0);
  double total_area = 0;
  for(int f = 0; f < m.nf; ++f) {
    const double twice_area = twice_uv_area(uv[3 * f], uv[3 * f + 1], uv[3 * f + 2]);
    total_area += std::abs(twice_area) / 2;
    if(twice_area > 0)
      active[f] = 1;
    else if(twice_area < 0)
      ++result.folded_triangles;
    else
      ++result.degenerate_triangles;
  }
  if(!(total_area <= max_quads))
    throw Invalid_input(Error_code::invalid_argument,
                        "the quad mesh would have about " + std::to_string(total_area) + " quads, more than the " +
                          std::to_string(max_quads) + " allowed: the quad size is too small");

  // per corner halfedge: the grid map from its face's chart to the chart of its edge's canonical face, checked
  // on the corners at both ends
  std::vector<Grid_map> to_canonical(nc);
  for(std::size_t a = 0; a < cut.arcs.size(); ++a) {
    Grid_map left_to_right;
    left_to_right.turns = modulo_quarter_turns(-cut.arcs[a].matching);
    for(int k = 0; k < 2; ++k) {
      left_to_right.t[k] = std::round(map.translation[a][k]);
      if(std::abs(map.translation[a][k] - left_to_right.t[k]) > snap_tolerance)
        throw Invalid_input(Error_code::invalid_argument, "the map is not an integer-grid map: the translation of arc " +
                                                            std::to_string(a) + " is not an integer vector");
    }
    for(int l : cut.arcs[a].left_corners) {
      const int r = m.opposite_corner[l];
      for(int end = 0; end < 2; ++end) { // corner l's source is the target of r, and conversely
        const UV expected = left_to_right(uv[end == 0 ? l : MA::next_corner(l)]);
        const UV& right = uv[end == 0 ? MA::next_corner(r) : r];
        if(std::abs(expected[0] - right[0]) > snap_tolerance || std::abs(expected[1] - right[1]) > snap_tolerance)
          throw Invalid_input(Error_code::invalid_argument,
                              "the map is not an integer-grid map: its transition across the cut edge from vertex " +
                                std::to_string(m.source_of(l)) + " to vertex " + std::to_string(m.target_of(l)) +
                                " is not that of arc " + std::to_string(a));
      }
      if(cut.edge_corner[cut.edge_of_corner[l]] == r) { // the left face's chart to the right one's
        to_canonical[l] = left_to_right;
      } else {
        Grid_map right_to_left;
        right_to_left.turns = modulo_quarter_turns(-left_to_right.turns);
        const UV back = Grid_map::turn(left_to_right.t, -left_to_right.turns);
        right_to_left.t = {{-back[0], -back[1]}};
        to_canonical[r] = right_to_left;
      }
    }
  }
  for(int v = 0; v < m.nv; ++v)
    CGAL_precondition(cut.holonomy[v] == 0 || cut.is_singular[v]);
  for(int c = 0; c < nc; ++c) {
    const int v = m.source_of(c);
    if(cut.is_singular[v] && !(is_integer(uv[c][0]) && is_integer(uv[c][1])))
      throw Invalid_input(Error_code::invalid_argument,
                          "the map is not an integer-grid map: singular vertex " + std::to_string(v) +
                            " is not at an integer point",
                          std::size_t(v));
  }

  std::vector<Node> nodes;

  // vertex nodes, and the counter-clockwise ring of corners around each vertex
  // (on the border: an open fan, from the corner whose halfedge is a border edge)
  std::vector<int> vertex_node(m.nv, -1), ring_position(nc, -1), first_corner(m.nv, -1);
  for(int c = 0; c < nc; ++c) {
    int& first = first_corner[m.source_of(c)];
    if(first < 0 || (m.opposite_corner[c] < 0 && m.opposite_corner[first] >= 0))
      first = c;
  }
  for(int v = 0; v < m.nv; ++v) {
    const int start = first_corner[v];
    if(start < 0)
      continue;
    int position = 0;
    for(int c = start;;) {
      ring_position[c] = position++;
      c = m.opposite_corner[MA::prev_corner(c)];
      if(c == start || c < 0)
        break;
    }
    const UV& w = uv[start];
    if(is_integer(w[0]) || is_integer(w[1])) {
      vertex_node[v] = int(nodes.size());
      Node node{Node_kind::vertex, v, is_integer(w[0]) && is_integer(w[1]), {}};
      node.location.face = MA::face_of(start);
      node.location.barycentric[start % 3] = 1;
      node.location.mesh_vertex = v;
      nodes.push_back(node);
    }
  }

  // edge nodes: the crossings of every edge with the iso-lines, in its canonical chart
  const int ne = int(cut.edge_corner.size());
  std::vector<std::vector<Edge_node>> edge_nodes(ne);
  std::vector<std::map<std::pair<int, double>, int>> edge_node_of_line(ne); // (coordinate, value) -> edge_nodes index
  for(int e = 0; e < ne; ++e) {
    const int i = cut.edge_corner[e];
    const UV &a = uv[i], &b = uv[MA::next_corner(i)];
    for(int k = 0; k < 2; ++k) {
      const double lo = std::min(a[k], b[k]), hi = std::max(a[k], b[k]);
      for(double c = std::floor(lo); c <= std::ceil(hi); ++c) {
        if(!(c > lo && c < hi))
          continue;
        if(edge_node_of_line[e].count({k, c}))
          continue; // already met as an integer point
        const double s = (c - a[k]) / (b[k] - a[k]);
        UV w;
        w[k] = c;
        const double other = a[1 - k] + s * (b[1 - k] - a[1 - k]);
        const bool integer_point = std::abs(other - std::round(other)) <= snap_tolerance;
        w[1 - k] = integer_point ? std::round(other) : other;
        Node node{Node_kind::edge, e, integer_point, {}};
        node.location.face = MA::face_of(i);
        node.location.barycentric[i % 3] = 1 - s;
        node.location.barycentric[MA::next_corner(i) % 3] = s;
        const int index = int(edge_nodes[e].size());
        edge_nodes[e].push_back({s, w, int(nodes.size())});
        nodes.push_back(node);
        edge_node_of_line[e][{k, c}] = index;
        if(integer_point)
          edge_node_of_line[e][{1 - k, w[1 - k]}] = index;
      }
    }
    std::vector<Edge_node>& list = edge_nodes[e];
    std::vector<int> order(list.size());
    for(std::size_t j = 0; j < order.size(); ++j)
      order[j] = int(j);
    std::sort(order.begin(), order.end(), [&](int x, int y) { return list[x].s < list[y].s; });
    std::vector<Edge_node> sorted;
    std::vector<int> new_index(list.size());
    for(std::size_t j = 0; j < order.size(); ++j) {
      new_index[order[j]] = int(j);
      sorted.push_back(list[order[j]]);
    }
    list = sorted;
    for(auto& entry : edge_node_of_line[e])
      entry.second = new_index[entry.second];
  }

  std::vector<Piece> pieces;
  std::map<std::array<long long, 3>, int> face_node; // (face, u, v) in its chart

  // the key of a piece leaving, in face f, the node at corner c (source of c), on the edge of corner halfedge
  // i, or inside f, in chart direction d
  auto vertex_key = [&](int c, const UV& d) {
    return 8. * ring_position[c] + ccw_angle({{uv[MA::next_corner(c)][0] - uv[c][0], uv[MA::next_corner(c)][1] - uv[c][1]}}, d);
  };
  auto edge_key = [&](int i, const UV& d) {
    const double angle = ccw_angle({{uv[MA::next_corner(i)][0] - uv[i][0], uv[MA::next_corner(i)][1] - uv[i][1]}}, d);
    return cut.edge_corner[cut.edge_of_corner[i]] == i ? angle : CGAL_PI + angle;
  };
  auto face_key = [&](const UV& d) { return ccw_angle({{1, 0}}, d); };

  // pieces along edges that are on an iso-line, once per edge
  std::vector<char> along_done(ne, 0);
  auto add_along_edge = [&](int e) {
    if(along_done[e])
      return;
    along_done[e] = 1;
    const int i = cut.edge_corner[e], o = m.opposite_corner[i];
    std::vector<int> chain(1, vertex_node[m.source_of(i)]);
    for(const Edge_node& n : edge_nodes[e])
      chain.push_back(n.node);
    chain.push_back(vertex_node[m.target_of(i)]);
    CGAL_assertion(chain.front() >= 0 && chain.back() >= 0);
    for(std::size_t j = 0; j + 1 < chain.size(); ++j) {
      const double from_key = j == 0 ? 8. * ring_position[i] : 0.;
      // at the target of a border edge: the last corner of its open fan, after every direction in it
      const double to_key = j + 2 == chain.size() ? (o >= 0 ? 8. * ring_position[o] : 8. * ring_position[MA::next_corner(i)] + 7.)
                                                  : CGAL_PI;
      pieces.push_back({{{chain[j], chain[j + 1]}}, {{from_key, to_key}}, e, o < 0});
    }
  };

  // a point where iso-line {w[k] = c} of face f's chart crosses (inside) the edge of corner halfedge i of f
  struct End
  {
    int node;
    UV uv;      // in f's chart
    double key;
  };
  auto crossing = [&](int f, int i, int k, double c) -> End {
    const int e = cut.edge_of_corner[i];
    const std::pair<int, double> line = to_canonical[i].line(k, c);
    const auto found = edge_node_of_line[e].find(line);
    if(found == edge_node_of_line[e].end())
      throw Invalid_input(Error_code::invalid_argument,
                          "the quad extraction found an iso-line crossing into face " + std::to_string(f) +
                            " that the edge from vertex " + std::to_string(m.source_of(i)) + " to vertex " +
                            std::to_string(m.target_of(i)) + " does not have (a map that is not seamless there)",
                          std::size_t(f));
    const Edge_node& n = edge_nodes[e][found->second];
    End end{n.node, to_canonical[i].inverse(n.uv), 0.};
    end.uv[k] = c; // exact, whatever the turns did to it
    return end;
  };

  for(int f = 0; f < m.nf; ++f) {
    if(!active[f])
      continue;
    const std::array<UV, 3> P = {{uv[3 * f], uv[3 * f + 1], uv[3 * f + 2]}};
    for(int k = 0; k < 2; ++k) {
      const double lo = std::min({P[0][k], P[1][k], P[2][k]}), hi = std::max({P[0][k], P[1][k], P[2][k]});
      for(double c = std::ceil(lo); c <= hi; ++c) {
        std::array<int, 3> side;
        int zeros = 0;
        for(int j = 0; j < 3; ++j) {
          side[j] = P[j][k] < c ? -1 : P[j][k] > c ? 1 : 0;
          zeros += side[j] == 0;
        }
        std::vector<End> ends;
        if(zeros == 2) {
          for(int j = 0; j < 3; ++j)
            if(side[j] == 0 && side[(j + 1) % 3] == 0)
              add_along_edge(cut.edge_of_corner[3 * f + j]);
          continue;
        }
        if(zeros == 1) {
          int j = 0;
          while(side[j] != 0)
            ++j;
          if(side[(j + 1) % 3] == side[(j + 2) % 3])
            continue; // the line only touches the triangle at its vertex
          ends.push_back({vertex_node[m.corner_vertex[3 * f + j]], P[j], 0.});
          ends.back().key = -1 - j; // the corner, resolved below
          ends.push_back(crossing(f, 3 * f + (j + 1) % 3, k, c));
          ends.back().key = -4 - (j + 1) % 3;
        } else {
          for(int j = 0; j < 3; ++j)
            if(side[j] != side[(j + 1) % 3]) {
              ends.push_back(crossing(f, 3 * f + j, k, c));
              ends.back().key = -4 - j;
            }
        }
        CGAL_assertion(ends.size() == 2);
        // the integer points strictly between the two ends, in order from the first
        std::vector<End> chain(1, ends[0]);
        const double from = ends[0].uv[1 - k], to = ends[1].uv[1 - k];
        const double step = to > from ? 1 : -1;
        for(double w = to > from ? std::floor(from) + 1 : std::ceil(from) - 1; step * (to - w) > 0; w += step) {
          UV point;
          point[k] = c;
          point[1 - k] = w;
          const std::array<long long, 3> id = {{f, (long long)point[0], (long long)point[1]}};
          auto it = face_node.find(id);
          if(it == face_node.end()) {
            Node node{Node_kind::face, f, true, {}};
            node.location.face = f;
            const double twice_area = (P[1][0] - P[0][0]) * (P[2][1] - P[0][1]) - (P[1][1] - P[0][1]) * (P[2][0] - P[0][0]);
            for(int j = 0; j < 3; ++j) {
              const UV &q = P[(j + 1) % 3], &r = P[(j + 2) % 3];
              node.location.barycentric[j] =
                ((q[0] - point[0]) * (r[1] - point[1]) - (q[1] - point[1]) * (r[0] - point[0])) / twice_area;
            }
            it = face_node.emplace(id, int(nodes.size())).first;
            nodes.push_back(node);
          }
          chain.push_back({it->second, point, -7.});
        }
        chain.push_back(ends[1]);
        UV forward = {{0, 0}};
        forward[1 - k] = step;
        const UV backward = {{-forward[0], -forward[1]}};
        // the key of the end of a piece at a chain element, leaving in direction d
        auto key_at = [&](const End& x, const UV& d) {
          if(x.key <= -7)
            return face_key(d);
          if(x.key <= -4)
            return edge_key(3 * f + int(-4 - x.key), d);
          return vertex_key(3 * f + int(-1 - x.key), d);
        };
        for(std::size_t j = 0; j + 1 < chain.size(); ++j)
          pieces.push_back({{{chain[j].node, chain[j + 1].node}}, {{key_at(chain[j], forward), key_at(chain[j + 1], backward)}}, -1, false});
      }
    }
  }

  // the rotation system: per node its leaving half-pieces (2 p + end) sorted counter-clockwise
  const int nh = 2 * int(pieces.size());
  std::vector<std::vector<int>> leaving(nodes.size());
  for(int h = 0; h < nh; ++h)
    leaving[pieces[h / 2].node[h % 2]].push_back(h);
  std::vector<int> position_at_node(nh, -1);
  for(std::vector<int>& list : leaving) {
    std::sort(list.begin(), list.end(),
              [&](int x, int y) { return pieces[x / 2].key[x % 2] < pieces[y / 2].key[y % 2]; });
    for(std::size_t j = 0; j < list.size(); ++j)
      position_at_node[list[j]] = int(j);
  }
  auto twin = [](int h) { return h ^ 1; };
  auto head = [&](int h) { return pieces[h / 2].node[1 - h % 2]; };
  auto tail = [&](int h) { return pieces[h / 2].node[h % 2]; };
  auto next = [&](int h) {
    const std::vector<int>& list = leaving[head(h)];
    const int j = position_at_node[twin(h)];
    return list[(j + int(list.size()) - 1) % int(list.size())];
  };

  // the half-pieces outside the surface: border pieces walked backwards
  auto outside = [&](int h) { return pieces[h / 2].border && h % 2 == 1; };

  // the quad vertices
  std::vector<int> vertex_of_node(nodes.size(), -1);
  for(std::size_t n = 0; n < nodes.size(); ++n)
    if(nodes[n].integer_point) {
      vertex_of_node[n] = int(result.points.size());
      const Quad_mesh::Location& l = nodes[n].location;
      Vec3 p = {{0, 0, 0}};
      for(int j = 0; j < 3; ++j)
        for(int x = 0; x < 3; ++x)
          p[x] += l.barycentric[j] * m.points[m.corner_vertex[3 * l.face + j]][x];
      result.points.push_back(p);
      result.locations.push_back(l);
      result.valence.push_back(int(leaving[n].size()));
      bool border = false;
      for(int h : leaving[n])
        border = border || pieces[h / 2].border;
      result.on_border.push_back(border);
    }

  // the chains (quad edges) from the integer points through the pass-through nodes
  auto passes_through = [&](int n) { return !nodes[n].integer_point && leaving[n].size() == 2; };
  std::map<std::pair<int, int>, int> faces_at_edge; // (first half-piece of the chain from each end) -> faces
  std::vector<int> chain_id(nh, -1);                // per half-piece leaving an integer point: its chain
  std::vector<char> border_chain;
  for(int h = 0; h < nh; ++h) {
    if(!nodes[tail(h)].integer_point || chain_id[h] >= 0)
      continue;
    int g = h;
    std::vector<int> along;
    bool border = pieces[h / 2].border;
    auto note = [&](int x) {
      const int e = pieces[x / 2].along;
      if(e >= 0 && (along.empty() || along.back() != e))
        along.push_back(e);
    };
    note(g);
    while(passes_through(head(g))) {
      const std::vector<int>& list = leaving[head(g)];
      g = list[0] == twin(g) ? list[1] : list[0];
      note(g);
      border = border && pieces[g / 2].border;
    }
    if(nodes[head(g)].integer_point) {
      chain_id[h] = chain_id[twin(g)] = result.quad_edges++;
      result.edges.push_back({{vertex_of_node[tail(h)], vertex_of_node[head(g)]}});
      result.edge_along.push_back(along);
      border_chain.push_back(border);
      result.border_edges += border;
    } else {
      chain_id[h] = -2;
      ++result.dangling_edges;
    }
  }

  // the faces: the cycles of next
  std::vector<int> edge_face_count(result.quad_edges, 0);
  std::vector<char> visited(nh, 0);
  for(int h0 = 0; h0 < nh; ++h0) {
    if(visited[h0])
      continue;
    std::vector<int> polygon, edges;
    bool simple = true;
    int outside_pieces = 0, all_pieces = 0;
    int h = h0;
    do {
      visited[h] = 1;
      outside_pieces += outside(h);
      ++all_pieces;
      const int n = tail(h);
      if(nodes[n].integer_point) {
        polygon.push_back(vertex_of_node[n]);
        edges.push_back(chain_id[h]);
      } else if(!passes_through(n)) {
        simple = false;
      }
      h = next(h);
    } while(h != h0);
    std::vector<int> distinct(polygon);
    std::sort(distinct.begin(), distinct.end());
    simple = simple && std::unique(distinct.begin(), distinct.end()) == distinct.end();
    if(outside_pieces == all_pieces) { // (a cycle partly outside is no hole: rejected below)
      ++result.holes;
    } else if(simple && outside_pieces == 0 && polygon.size() == 4) { // (a cycle without integer point is never one: not on a valid map)
      result.faces.push_back({{polygon[0], polygon[1], polygon[2], polygon[3]}});
      for(int e : edges)
        if(e >= 0)
          ++edge_face_count[e];
    } else {
      result.rejected_polygons.push_back(polygon);
    }
  }
  result.quads = int(result.faces.size());
  result.non_quads = int(result.rejected_polygons.size());
  for(std::size_t e = 0; e < edge_face_count.size(); ++e)
    result.open_edges += edge_face_count[e] < (border_chain[e] ? 1 : 2);
  return result;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_EXTRACTION_H
