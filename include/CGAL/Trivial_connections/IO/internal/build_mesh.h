// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_BUILD_MESH_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_BUILD_MESH_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/IO/internal/triangle_soup.h>

#include <CGAL/Surface_mesh/Surface_mesh.h>
#include <CGAL/assertions.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/graph/graph_traits.hpp>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

// the public result of build_mesh(): declared here for it, defined and documented in IO/read_triangle_mesh.h
template <class TriangleMesh>
struct Mesh_input_order;

namespace internal {
namespace io {

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

// The halfedge of each corner in the mesh build_mesh() makes: edge k is the k-th edge met in corner order; its
// first corner gets edge_halfedge(k), the corner across it the opposite of that.
template <class Halfedge, class EdgeHalfedge, class Opposite>
std::vector<Halfedge> corner_halfedges(const Triangle_soup_connectivity& soup, EdgeHalfedge edge_halfedge,
                                       Opposite opposite)
{
  const std::size_t nc = soup.opposite.size();
  std::vector<Halfedge> h(nc);
  std::size_t next_edge = 0;
  for(std::size_t c = 0; c < nc; ++c) {
    const int t = soup.opposite[c];
    h[c] = (t >= 0 && std::size_t(t) < c) ? opposite(h[std::size_t(t)]) : edge_halfedge(next_edge++);
  }
  return h;
}

// The same for a Surface_mesh, known before build_mesh() has made it (add_elements(): edge k holds the halfedges 2k
// and 2k + 1, each the other's opposite), so that the mesh can be built while its halfedges are used elsewhere.
template <class P>
std::vector<typename CGAL::Surface_mesh<P>::Halfedge_index>
surface_mesh_corner_halfedges(const Triangle_soup_connectivity& soup)
{
  using SM = CGAL::Surface_mesh<P>;
  using H = typename SM::Halfedge_index;
  return corner_halfedges<H>(
    soup, [](std::size_t k) { return H(typename SM::size_type(2 * k)); },
    [](H g) { return H(typename SM::size_type(std::size_t(g) ^ 1)); });
}

/*
  Builds the mesh from validated connectivity with the low-level functions of `MutableFaceGraph`:
  vertex i is the i-th vertex added, face f the f-th face added; isolated vertices are kept. Corner c of the
  soup (from vertex soup.source(c) to soup.target(c), in face c / 3) is the halfedge corner_halfedges() gives.
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

  std::vector<halfedge_descriptor> h = corner_halfedges<halfedge_descriptor>(
    soup, [&](std::size_t k) { return edge_halfedge[k]; }, [&](halfedge_descriptor g) { return opposite(g, tm); });
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

} // namespace io
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_BUILD_MESH_H
