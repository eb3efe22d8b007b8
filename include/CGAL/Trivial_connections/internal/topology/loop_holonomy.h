// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_LOOP_HOLONOMY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_LOOP_HOLONOMY_H

#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>

#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The Levi-Civita holonomy H_L of every loop of the tree-cotree decomposition, in its order: for a boundary
  loop its exact geodesic curvature (the sum over its vertices of pi minus their angle sums, never wrapped:
  Poincare-Hopf needs it whole), for a generator the transport angles along it wrapped to (-pi, pi] (only
  known modulo 2 pi, which the loop's free integer absorbs). Needs the corner angles.
*/
template <class TriangleMesh>
std::vector<double> levi_civita_holonomies(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& geometry,
                                           const Mesh_topology& topology)
{
  std::vector<double> geodesic_curvature(topology.number_of_nodes - topology.number_of_interior_nodes, 0.);
  for(int v = 0; v < m.nv; ++v)
    if(m.faces_at_vertex[v] > 0 && geometry.on_boundary[v])
      geodesic_curvature[topology.node_of_vertex[v] - topology.number_of_interior_nodes] += geometry.angle_defect(v);
  std::vector<double> holonomies;
  for(const Mesh_topology::Loop& l : topology.loops) {
    double holonomy = 0;
    if(l.kind == Loop_kind::boundary) {
      holonomy = geodesic_curvature[l.node - topology.number_of_interior_nodes];
    } else {
      for(int i : l.crossings)
        holonomy += geometry.transport_angle(i);
      holonomy = wrap_angle(holonomy);
    }
    holonomies.push_back(holonomy);
  }
  return holonomies;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_LOOP_HOLONOMY_H
