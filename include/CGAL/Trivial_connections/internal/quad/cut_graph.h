// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_CUT_GRAPH_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_CUT_GRAPH_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>

#include <CGAL/assertions.h>
#include <CGAL/number_type_config.h>

#include <boost/graph/breadth_first_search.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The first layer of quad meshing (issue 43): a cross field (n = 4) seen as four directions per face, with
  - the matching: per interior edge, the number r in Z/4 of quarter turns (counter-clockwise about the arrival
    normal) that maps the representative direction of face(i), moved by Levi-Civita transport, onto the
    representative of face(opposite(i)), for i the edge's canonical corner halfedge (Mesh_geometry numbering);
  - a cut graph: edges along which every component, cut open, is a topological disk through every singular
    vertex (a dual spanning tree, its complement pruned of dangling edges, the singular vertices joined to what
    is left by shortest paths);
  - a combing: per face a quarter-turn offset c_f of its representative such that the matching of the combed
    representatives, r + c_g - c_f, is 0 across every edge off the cut;
  - the arcs of the cut: maximal chains of interior cut edges between nodes (singular, boundary and branch
    vertices), along which the combed matching is constant (the holonomy of a regular vertex is 0).
  Going counter-clockwise around an interior vertex v (crossing the corner halfedges that end at v), the
  matchings sum to -4 k_v modulo 4 for a field of index k_v at v: the connection carries the turn 2 pi k_v
  that the representatives, single-valued per face, must give back.
*/

inline constexpr int cross_field_directions = 4;

// r modulo 4, in 0..3
inline int modulo_quarter_turns(long long r) { return int(((r % 4) + 4) % 4); }

// the matching of corner halfedge i of an interior edge (from face(i) to the face of opposite(i)), from a
// per-interior-edge value stored for the canonical corner halfedge
inline int matching_across(const Mesh_geometry& g, const std::vector<int>& per_edge, int i)
{
  const int e = g.edge_of_corner[i];
  CGAL_precondition(e >= 0);
  return g.edge_corner[e] == i ? per_edge[e] : modulo_quarter_turns(-per_edge[e]);
}

/*
  The matching of a cross field given as an angle per face in its frame (Mesh_geometry::frame()):
  r_e = round((angle_g - angle_f - rho_e - x_e) / (pi / 2)) modulo 4 for the canonical corner halfedge of e,
  with rho_e the transport angle (compute_angles() must have run) and x_e the connection the field is parallel
  for (per interior edge, x of the canonical corner halfedge; empty: 0, the field's own smallest turns).
  With the connection the quotient is an integer up to rounding: a field that is not parallel for it
  (more than a tenth of a quarter turn off on an edge) is an error of the caller's data.
*/
template <class TriangleMesh>
std::vector<int> cross_field_matching(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g,
                                      const std::vector<double>& angle, const std::vector<double>& connection)
{
  using MA = Mesh_arrays<TriangleMesh>;
  const int ne = g.number_of_interior_edges();
  CGAL_precondition(angle.size() == std::size_t(m.nf) && g.transport.size() == std::size_t(ne));
  CGAL_precondition(connection.empty() || connection.size() == std::size_t(ne));
  const double quarter = CGAL_PI / 2;
  std::vector<int> matching(ne);
  for(int e = 0; e < ne; ++e) {
    const int i = g.edge_corner[e];
    const int f = MA::face_of(i), h = MA::face_of(m.opposite_corner[i]);
    const double turns = (angle[h] - angle[f] - g.transport[e] - (connection.empty() ? 0. : connection[e])) / quarter;
    if(!std::isfinite(turns))
      throw Invalid_input(Error_code::invalid_argument,
                          "the field or the connection is not finite across interior edge " + std::to_string(e),
                          std::size_t(e));
    const double r = std::round(turns);
    if(!connection.empty() && std::abs(turns - r) > 0.1)
      throw Invalid_input(Error_code::invalid_argument,
                          "the cross field is not parallel for the connection across the edge from vertex " +
                            std::to_string(m.source_of(i)) + " to vertex " + std::to_string(m.target_of(i)) + " (off by " +
                            std::to_string(std::abs(turns - r)) + " of a quarter turn)",
                          std::size_t(e));
    matching[e] = modulo_quarter_turns((long long)(std::fmod(r, 4.)));
  }
  return matching;
}

// Per vertex: the sum of the matchings crossed going counter-clockwise around it, modulo 4 (0 at boundary and
// isolated vertices). Crossing corner halfedge i turns counter-clockwise around its target.
template <class TriangleMesh>
std::vector<int> matching_holonomy(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g,
                                   const std::vector<int>& matching)
{
  std::vector<long long> sum(m.nv, 0);
  for(int e = 0; e < g.number_of_interior_edges(); ++e) {
    const int i = g.edge_corner[e];
    sum[m.target_of(i)] += matching[e];
    sum[m.source_of(i)] -= matching[e];
  }
  std::vector<int> holonomy(m.nv, 0);
  for(int v = 0; v < m.nv; ++v)
    if(m.faces_at_vertex[v] > 0 && !g.on_boundary[v])
      holonomy[v] = modulo_quarter_turns(sum[v]);
  return holonomy;
}

struct Cut_graph
{
  // an arc: interior cut edges from node to node (or a cycle through one node), walked from its first vertex;
  // left_corners[j] is the corner halfedge of its j-th edge that goes along the walk (its face is on the left)
  struct Arc
  {
    std::vector<int> left_corners;
    int matching = 0; // the combed matching from the left faces to the right faces, the same on every edge
  };

  // every edge, border edges too: corner halfedge i and its opposite (if any) are edge edge_of_corner[i], whose
  // corner halfedge edge_corner[e] is the smaller of the two
  std::vector<int> edge_of_corner;
  std::vector<int> edge_corner;
  std::vector<char> is_cut;            // per edge: border edges are cut (the surface is open there already)
  std::vector<char> is_singular;       // per vertex: the given singular vertices
  std::vector<int> holonomy;           // per vertex: matching_holonomy()
  std::vector<int> component_of_face;
  int number_of_components = 0;
  std::vector<int> combing;            // per face: quarter turns added to its representative direction
  std::vector<int> combed_matching;    // per interior edge (Mesh_geometry numbering): r + c_g - c_f, 0 off the cut
  std::vector<Arc> arcs;
  std::vector<int> arc_of_edge;        // per edge: its arc, -1 off the cut and on border edges
};

namespace cut_graph_impl {

struct Graph_edge
{
  int corner = -1;     // the corner halfedge the edge was made from (-1: an edge of the super source)
  double length = 0;
};
using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, Graph_edge>;

// records, per vertex reached, the corner of the tree edge that reached it and the component of the search
struct Tree_recorder : boost::default_bfs_visitor
{
  std::vector<int>* parent_corner;
  std::vector<int>* component;
  int current;
  void discover_vertex(Graph::vertex_descriptor v, const Graph&) const { (*component)[v] = current; }
  void tree_edge(Graph::edge_descriptor e, const Graph& graph) const
  {
    (*parent_corner)[boost::target(e, graph)] = graph[e].corner;
  }
};

inline Graph make_graph(int vertices, const std::vector<std::pair<int, int>>& ends, const std::vector<Graph_edge>& props)
{
  return Graph(boost::edges_are_unsorted_multi_pass, ends.begin(), ends.end(), props.begin(), std::size_t(vertices));
}

} // namespace cut_graph_impl

/*
  The cut graph, combing and arcs of a cross field with the given matching (cross_field_matching()).
  `singular` lists the singular vertices (interior vertices, each once): every interior vertex whose matching
  holonomy is not 0 must be among them (the field has a singularity there that the caller did not declare:
  an error of its data); a listed vertex with holonomy 0 (an index that is a multiple of 1) is put on the cut
  all the same.
*/
template <class TriangleMesh>
Cut_graph build_cut_graph(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g,
                          const std::vector<int>& matching, const std::vector<int>& singular)
{
  using MA = Mesh_arrays<TriangleMesh>;
  using namespace cut_graph_impl;
  CGAL_precondition(matching.size() == std::size_t(g.number_of_interior_edges()));
  const int nc = 3 * m.nf;
  Cut_graph cut;
  cut.is_singular.assign(m.nv, 0);
  for(int v : singular) {
    CGAL_precondition(v >= 0 && v < m.nv && m.faces_at_vertex[v] > 0 && !g.on_boundary[v] && !cut.is_singular[v]);
    cut.is_singular[v] = 1;
  }
  cut.holonomy = matching_holonomy(m, g, matching);
  for(int v = 0; v < m.nv; ++v)
    if(cut.holonomy[v] != 0 && !cut.is_singular[v])
      throw Invalid_input(Error_code::invalid_argument,
                          "the cross field turns by " + std::to_string(cut.holonomy[v]) +
                            " quarter turns around vertex " + std::to_string(v) +
                            ", which is not among its singular vertices",
                          std::size_t(v));

  // all edges
  cut.edge_of_corner.assign(nc, -1);
  for(int i = 0; i < nc; ++i) {
    const int o = m.opposite_corner[i];
    if(o < 0 || i < o) {
      cut.edge_of_corner[i] = int(cut.edge_corner.size());
      if(o >= 0)
        cut.edge_of_corner[o] = int(cut.edge_corner.size());
      cut.edge_corner.push_back(i);
    }
  }
  const int ne = int(cut.edge_corner.size());
  auto length = [&](int i) { return norm(sub(m.points[m.target_of(i)], m.points[m.source_of(i)])); };

  // 1. a breadth-first dual spanning forest (faces across interior edges), one tree per component
  std::vector<char> crossed_by_tree(ne, 0);
  cut.component_of_face.assign(m.nf, -1);
  {
    std::vector<std::pair<int, int>> ends;
    std::vector<Graph_edge> props;
    for(int i = 0; i < nc; ++i)
      if(m.opposite_corner[i] >= 0) {
        ends.emplace_back(MA::face_of(i), MA::face_of(m.opposite_corner[i]));
        props.push_back({i, 0.});
      }
    const Graph dual = make_graph(m.nf, ends, props);
    std::vector<int> parent_corner(m.nf, -1);
    std::vector<boost::default_color_type> color(m.nf, boost::white_color);
    auto color_map = boost::make_iterator_property_map(color.begin(), boost::get(boost::vertex_index, dual));
    for(int root = 0; root < m.nf; ++root) {
      if(color[root] != boost::white_color)
        continue;
      boost::queue<Graph::vertex_descriptor> queue;
      boost::breadth_first_visit(dual, Graph::vertex_descriptor(root), queue,
                                 Tree_recorder{{}, &parent_corner, &cut.component_of_face, cut.number_of_components++},
                                 color_map);
    }
    for(int f = 0; f < m.nf; ++f)
      if(parent_corner[f] >= 0)
        crossed_by_tree[cut.edge_of_corner[parent_corner[f]]] = 1;
  }

  // 2. the complement of the tree, pruned of its dangling edges: what is left is the boundary, the
  //    generators' loops and the paths between them
  cut.is_cut.assign(ne, 0);
  std::vector<int> degree(m.nv, 0);
  std::vector<std::vector<int>> edges_at(m.nv);
  for(int e = 0; e < ne; ++e) {
    const int i = cut.edge_corner[e];
    edges_at[m.source_of(i)].push_back(e);
    edges_at[m.target_of(i)].push_back(e);
    if(!crossed_by_tree[e]) {
      cut.is_cut[e] = 1;
      ++degree[m.source_of(i)];
      ++degree[m.target_of(i)];
    }
  }
  {
    std::vector<int> leaves;
    for(int v = 0; v < m.nv; ++v)
      if(degree[v] == 1)
        leaves.push_back(v);
    while(!leaves.empty()) {
      const int v = leaves.back();
      leaves.pop_back();
      if(degree[v] != 1)
        continue;
      for(int e : edges_at[v])
        if(cut.is_cut[e]) {
          cut.is_cut[e] = 0;
          const int i = cut.edge_corner[e];
          const int w = m.source_of(i) == v ? m.target_of(i) : m.source_of(i);
          --degree[v];
          if(--degree[w] == 1)
            leaves.push_back(w);
          break;
        }
    }
  }

  // 3. every singular vertex joined to the cut by a shortest path (edge lengths) to what is on the cut: one
  //    Dijkstra from a super source joined to the cut's vertices, and to the first singular vertex of each
  //    component whose cut is empty (a sphere-like component). Each path is followed back only until it meets
  //    the cut as it stands (other paths included): it meets the cut only at its end, so cutting along it slits
  //    the disk from its border inwards and leaves a disk.
  std::vector<char> on_cut(m.nv, 0);
  for(int v = 0; v < m.nv; ++v)
    on_cut[v] = degree[v] > 0;
  std::vector<int> vertex_component(m.nv, -1);
  for(int i = 0; i < nc; ++i)
    vertex_component[m.corner_vertex[i]] = cut.component_of_face[MA::face_of(i)];
  std::vector<char> component_has_cut(cut.number_of_components, 0);
  for(int v = 0; v < m.nv; ++v)
    if(on_cut[v])
      component_has_cut[vertex_component[v]] = 1;
  std::vector<int> seeds; // per component without cut: its first singular vertex
  for(int v = 0; v < m.nv; ++v)
    if(cut.is_singular[v] && !component_has_cut[vertex_component[v]]) {
      component_has_cut[vertex_component[v]] = 1;
      on_cut[v] = 1;
      seeds.push_back(v);
    }
  bool any_singular_off_cut = false;
  for(int v = 0; v < m.nv; ++v)
    any_singular_off_cut = any_singular_off_cut || (cut.is_singular[v] && !on_cut[v]);
  if(any_singular_off_cut) {
    const int source = m.nv; // the super source
    std::vector<std::pair<int, int>> ends;
    std::vector<Graph_edge> props;
    for(int e = 0; e < ne; ++e) {
      const int i = cut.edge_corner[e];
      ends.emplace_back(m.source_of(i), m.target_of(i));
      props.push_back({i, length(i)});
      ends.emplace_back(m.target_of(i), m.source_of(i));
      props.push_back({i, length(i)});
    }
    for(int v = 0; v < m.nv; ++v)
      if(on_cut[v]) {
        ends.emplace_back(source, v);
        props.push_back({-1, 0.});
      }
    const Graph primal = make_graph(m.nv + 1, ends, props);
    std::vector<Graph::vertex_descriptor> predecessor(m.nv + 1);
    std::vector<double> distance(m.nv + 1, std::numeric_limits<double>::infinity());
    std::vector<int> predecessor_corner(m.nv + 1, -1);
    struct Record_corner : boost::default_dijkstra_visitor
    {
      std::vector<int>* corner;
      void edge_relaxed(Graph::edge_descriptor e, const Graph& graph) const
      {
        (*corner)[boost::target(e, graph)] = graph[e].corner;
      }
    } recorder;
    recorder.corner = &predecessor_corner;
    const auto index = boost::get(boost::vertex_index, primal);
    boost::dijkstra_shortest_paths(
      primal, Graph::vertex_descriptor(source),
      boost::weight_map(boost::get(&Graph_edge::length, primal))
        .predecessor_map(boost::make_iterator_property_map(predecessor.begin(), index))
        .distance_map(boost::make_iterator_property_map(distance.begin(), index))
        .visitor(recorder));
    std::vector<int> order;
    for(int v = 0; v < m.nv; ++v)
      if(cut.is_singular[v] && !on_cut[v])
        order.push_back(v);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return distance[a] < distance[b]; });
    for(int s : order) {
      CGAL_assertion(std::isfinite(distance[s])); // every component with a singular vertex has a source
      int v = s;
      while(!on_cut[v]) {
        const int i = predecessor_corner[v];
        CGAL_assertion(i >= 0);
        cut.is_cut[cut.edge_of_corner[i]] = 1;
        on_cut[v] = 1;
        v = m.source_of(i) == v ? m.target_of(i) : m.source_of(i);
      }
    }
  }
  // a closed component cut along nothing (a sphere with at most one singular vertex) is cut along one edge at
  // its singular vertex, or at its first vertex: a sphere slit along an edge is a disk
  {
    std::vector<char> has_edge(cut.number_of_components, 0);
    for(int e = 0; e < ne; ++e)
      if(cut.is_cut[e])
        has_edge[cut.component_of_face[MA::face_of(cut.edge_corner[e])]] = 1;
    std::vector<int> start(cut.number_of_components, -1);
    for(int v : seeds)
      start[vertex_component[v]] = v;
    for(int v = 0; v < m.nv; ++v)
      if(m.faces_at_vertex[v] > 0 && start[vertex_component[v]] < 0)
        start[vertex_component[v]] = v;
    for(int c = 0; c < cut.number_of_components; ++c)
      if(!has_edge[c]) {
        int best = -1;
        for(int e : edges_at[start[c]])
          if(best < 0 || length(cut.edge_corner[e]) < length(cut.edge_corner[best]))
            best = e;
        cut.is_cut[best] = 1;
      }
  }

  // 4. the combing: breadth-first over the cut surface, each face turned so that the matching across the
  //    edge it was reached through is 0
  cut.combing.assign(m.nf, -1);
  for(int root = 0; root < m.nf; ++root) {
    if(cut.combing[root] >= 0)
      continue;
    cut.combing[root] = 0;
    std::deque<int> queue(1, root);
    while(!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      for(int i = 3 * f; i < 3 * f + 3; ++i) {
        const int o = m.opposite_corner[i];
        if(o < 0 || cut.is_cut[cut.edge_of_corner[i]] || cut.combing[MA::face_of(o)] >= 0)
          continue;
        cut.combing[MA::face_of(o)] = modulo_quarter_turns(cut.combing[f] - matching_across(g, matching, i));
        queue.push_back(MA::face_of(o));
      }
    }
  }
  cut.combed_matching.assign(matching.size(), 0);
  for(int e = 0; e < g.number_of_interior_edges(); ++e) {
    const int i = g.edge_corner[e];
    cut.combed_matching[e] = modulo_quarter_turns(matching[e] + cut.combing[MA::face_of(m.opposite_corner[i])] -
                                                  cut.combing[MA::face_of(i)]);
    // a disk's interior vertices have holonomy 0: the combing is consistent off the cut
    CGAL_assertion(cut.is_cut[cut.edge_of_corner[i]] || cut.combed_matching[e] == 0);
  }

  // 5. the arcs: from each node (singular, boundary, or not of interior cut degree 2) along each of its
  //    interior cut edges to the next node; the cycles left have no node and start anywhere
  std::vector<int> interior_degree(m.nv, 0);
  for(int e = 0; e < ne; ++e)
    if(cut.is_cut[e] && m.opposite_corner[cut.edge_corner[e]] >= 0) {
      ++interior_degree[m.source_of(cut.edge_corner[e])];
      ++interior_degree[m.target_of(cut.edge_corner[e])];
    }
  auto is_node = [&](int v) { return cut.is_singular[v] || g.on_boundary[v] || interior_degree[v] != 2; };
  cut.arc_of_edge.assign(ne, -1);
  auto walk = [&](int v, int e) {
    Cut_graph::Arc arc;
    const int a = int(cut.arcs.size());
    for(;;) {
      const int i = cut.edge_corner[e];
      const int left = m.source_of(i) == v ? i : m.opposite_corner[i];
      cut.arc_of_edge[e] = a;
      arc.left_corners.push_back(left);
      v = m.target_of(left);
      if(is_node(v))
        break;
      int next_edge = -1;
      for(int f : edges_at[v])
        if(cut.is_cut[f] && f != e && m.opposite_corner[cut.edge_corner[f]] >= 0)
          next_edge = f;
      CGAL_assertion(next_edge >= 0);
      if(cut.arc_of_edge[next_edge] >= 0) // back at the start of a cycle without node
        break;
      e = next_edge;
    }
    arc.matching = matching_across(g, cut.combed_matching, arc.left_corners.front());
    for(int l : arc.left_corners) // constant along the arc: its inner vertices are regular
      CGAL_assertion(matching_across(g, cut.combed_matching, l) == arc.matching);
    cut.arcs.push_back(std::move(arc));
  };
  for(int pass = 0; pass < 2; ++pass)
    for(int v = 0; v < m.nv; ++v)
      if(pass == 1 || is_node(v))
        for(int e : edges_at[v])
          if(cut.is_cut[e] && m.opposite_corner[cut.edge_corner[e]] >= 0 && cut.arc_of_edge[e] < 0)
            walk(v, e);
  return cut;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_CUT_GRAPH_H
