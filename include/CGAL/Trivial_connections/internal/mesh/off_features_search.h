// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The graph searches of move_singularities_off_features() (singularities_off_features.h): Boost.Graph's Dijkstra on
// the mesh itself, weighted by edge length.

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_OFF_FEATURES_SEARCH_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_OFF_FEATURES_SEARCH_H

#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>

#include <CGAL/boost/graph/properties.h>

#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/graph/filtered_graph.hpp>
#include <boost/property_map/function_property_map.hpp>
#include <boost/property_map/property_map.hpp>

#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

template <class TriangleMesh>
class Off_features_search
{
  using GT = boost::graph_traits<TriangleMesh>;
  using edge_descriptor = typename GT::edge_descriptor;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using Arrays = Mesh_arrays<TriangleMesh>;

  // edges with no end on a feature edge's vertex: the paths a singularity moves along (default-constructible for
  // boost::filtered_graph)
  struct Off_features
  {
    const Off_features_search* search = nullptr;
    Off_features() {}
    explicit Off_features(const Off_features_search& s) : search(&s) {}
    bool operator()(edge_descriptor e) const
    {
      return !search->on_feature[search->index(source(e, search->tm))] &&
             !search->on_feature[search->index(target(e, search->tm))];
    }
  };
  struct Stop {}; // thrown by the visitor: the nearest vertex is known

public:
  const TriangleMesh& tm;
  const Arrays& m;
  std::vector<char> on_feature;    // per vertex: an end of a feature edge
  std::vector<double> to_features; // per vertex: the graph distance to the nearest such vertex

  Off_features_search(const TriangleMesh& mesh, const Arrays& arrays)
    : tm(mesh), m(arrays), on_feature(arrays.nv, 0),
      to_features(arrays.nv, std::numeric_limits<double>::infinity()), distance(arrays.nv, infinity()),
      color(arrays.nv, boost::white_color)
  {}

  void mark_feature_edge(edge_descriptor e)
  {
    on_feature[index(source(e, tm))] = on_feature[index(target(e, tm))] = 1;
  }

  // to_features, by one search from all the feature edges' vertices
  void distances_to_features()
  {
    std::vector<vertex_descriptor> sources;
    for(int v = 0; v < m.nv; ++v)
      if(on_feature[v])
        sources.push_back(m.vertex_descriptors[v]);
    if(sources.empty())
      return;
    boost::dijkstra_shortest_paths(tm, sources.begin(), sources.end(), boost::dummy_property_map(),
                                   boost::make_iterator_property_map(to_features.begin(), m.vertex_index), weight(),
                                   m.vertex_index, std::less<double>(), std::plus<double>(), infinity(), 0.,
                                   boost::default_dijkstra_visitor());
  }

  // The vertex w with is_free(w) nearest to v along paths through vertices of no feature edge, and that path's
  // length; (-1, infinity) when there is none. Equal lengths: the smallest point (x, y, z), not the smallest
  // index, so that the answer does not depend on the numbering.
  template <class IsFree>
  std::pair<int, double> nearest(int v, const IsFree& is_free)
  {
    struct Visitor : boost::default_dijkstra_visitor
    {
      Off_features_search* search;
      const IsFree* is_free;
      int* best;
      std::vector<int>* reached;
      void discover_vertex(vertex_descriptor u, const boost::filtered_graph<TriangleMesh, Off_features>&) const
      {
        reached->push_back(search->index(u));
      }
      void examine_vertex(vertex_descriptor u, const boost::filtered_graph<TriangleMesh, Off_features>&) const
      {
        const int i = search->index(u);
        const double d = search->distance[i];
        if(*best >= 0 && d > search->distance[*best])
          throw Stop();
        if((*is_free)(i) && (*best < 0 || search->points_less(i, *best)))
          *best = i;
      }
    };
    int best = -1;
    std::vector<int> reached;
    Visitor visitor;
    visitor.search = this;
    visitor.is_free = &is_free;
    visitor.best = &best;
    visitor.reached = &reached;
    const boost::filtered_graph<TriangleMesh, Off_features> graph(tm, Off_features(*this));
    const vertex_descriptor start = m.vertex_descriptors[v];
    distance[v] = 0;
    try {
      boost::dijkstra_shortest_paths_no_init(graph, start, boost::dummy_property_map(),
                                             boost::make_iterator_property_map(distance.begin(), m.vertex_index),
                                             weight(), m.vertex_index, std::less<double>(), std::plus<double>(), 0.,
                                             visitor, boost::make_iterator_property_map(color.begin(), m.vertex_index));
    } catch(const Stop&) {
    }
    const std::pair<int, double> found(best, best >= 0 ? distance[best] : infinity());
    // ready for the next search: only what this one touched
    distance[v] = infinity();
    color[v] = boost::white_color;
    for(int u : reached) {
      distance[u] = infinity();
      color[u] = boost::white_color;
    }
    return found;
  }

private:
  std::vector<double> distance;                   // of the current search, infinity elsewhere
  std::vector<boost::default_color_type> color;   // of the current search, white elsewhere

  static double infinity() { return std::numeric_limits<double>::infinity(); }
  int index(vertex_descriptor v) const { return int(get(m.vertex_index, v)); }
  bool points_less(int a, int b) const { return m.points[a] < m.points[b]; } // lexicographic x, y, z

  auto weight() const
  {
    const Off_features_search* self = this;
    return boost::make_function_property_map<edge_descriptor, double>([self](edge_descriptor e) {
      return norm(sub(self->m.points[self->index(source(e, self->tm))], self->m.points[self->index(target(e, self->tm))]));
    });
  }
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_OFF_FEATURES_SEARCH_H
