// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_HOMOLOGY_GENERATORS_H
#define CGAL_TRIVIAL_CONNECTIONS_HOMOLOGY_GENERATORS_H

#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>

#include <CGAL/boost/graph/named_params_helper.h>

#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
The homology generators of a triangle mesh as closed dual loops, 2g per connected component of genus g,
computed by a tree-cotree decomposition (a breadth-first spanning tree of faces, then a spanning tree of
the vertices, every boundary loop shrunk to one vertex, on the remaining edges): each edge in neither tree
closes one loop. A loop is the sequence of halfedges it crosses: `h_i` is crossed from `face(h_i)` to
`face(opposite(h_i))`, and `face(opposite(h_i)) == face(h_{i+1})` cyclically. Together with the loops
around each vertex and each boundary loop they span all closed dual loops. Boundary loops themselves are
not generators: see `Trivial_connection_solver::loops()`. Linear time in the mesh size plus the total
length of the loops.
\tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph` with triangle faces
\tparam NamedParameters a sequence of named parameters
\param tm the triangle mesh
\param np an optional sequence of named parameters among the ones listed below
\returns the generators, each as the sequence of the halfedges it crosses (see above), grouped by connected
         component: the generators of `Trivial_connection_solver::loops()` on the same mesh, in the same order
\cgalNamedParamsBegin
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{geom_traits} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
\cgalNamedParamsEnd
\throws Invalid_input `empty_mesh`, `not_triangle_mesh`, `non_manifold`, `degenerate_face`
*/
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::halfedge_descriptor>>
homology_generators(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  using Geom_traits = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;
  const internal::Mesh_arrays<TriangleMesh> mesh(
    tm,
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                       get_const_property_map(CGAL::vertex_point, tm)),
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits),
                                       Geom_traits()));
  const internal::Mesh_geometry geometry(mesh, Weighting::unit);
  internal::Mesh_topology topology(mesh);
  topology.build_trees(mesh, geometry.edge_of_corner, geometry.edge_corner);
  std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::halfedge_descriptor>> loops;
  for(const internal::Mesh_topology::Loop& loop : topology.loops) {
    if(loop.kind != Loop_kind::generator)
      continue;
    loops.emplace_back();
    for(int i : loop.crossings)
      loops.back().push_back(mesh.halfedges[i]);
  }
  return loops;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_HOMOLOGY_GENERATORS_H
