// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FIELD_REPORT_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FIELD_REPORT_H

#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>

#include <CGAL/number_type_config.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// The outputs of a solve: the connection into the user's map, and the report.

// x per interior edge into a writable halfedge -> double map: x(h) and -x(opposite(h)), 0 on border edges
template <class TriangleMesh, class HalfedgeAngleMap>
void write_connection(const TriangleMesh& tm, const Mesh_arrays<TriangleMesh>& m, const Constraint_rows& rows,
                      const Eigen::VectorXd& xe, HalfedgeAngleMap x)
{
  // by edges: both halfedges of an interior edge at once (much faster than corner by corner on some meshes)
  for(int e = 0; e < int(xe.size()); ++e) {
    const int i = rows.geometry().edge_corner[e];
    put(x, m.halfedges[i], xe[e]);
    put(x, m.halfedges[m.opposite_corner[i]], -xe[e]);
  }
  for(int i : rows.border_corners) {
    put(x, m.halfedges[i], 0.);
    put(x, opposite(m.halfedges[i], tm), 0.);
  }
}

/*
  The report of a solve from the constraint sums of its connection: energies, the residual of every vertex,
  loop and link, every integer (the pinned boundary loop's, not a row of the system, follows from
  Poincare-Hopf and is written into `periods`), the guidance mismatches. `report.components` is set already,
  with the vertex index sums.
  `loop_holonomy`: per loop, H_L; `holonomy`: per slot, the H of its row.
*/
inline void fill_report(const Constraint_rows& rows, const Constraint_sums& sums, const std::vector<double>& loop_holonomy,
                        const std::vector<std::int64_t>& k, std::vector<std::int64_t>& periods,
                        const std::vector<char>& prescribed, const std::vector<double>& holonomy, int n,
                        Solve_report& report)
{
  const Mesh_topology& t = rows.topology();
  const Constraint_links& links = rows.links();
  const std::vector<Mesh_topology::Loop>& loops = t.loops;
  const double unit = 2 * CGAL_PI / n;
  report.energy = sums.energy;

  // every interior vertex, the pinned ones included
  report.max_vertex_residual = 0;
  for(int node = 0; node < t.number_of_interior_nodes; ++node) {
    const int v = rows.vertex_of_node[node];
    report.max_vertex_residual = (std::max)(
      report.max_vertex_residual, std::abs(rows.geometry().angle_defect(v) + sums.node[node] - unit * double(k[v])));
  }

  // the pinned boundary loop's integer follows from Poincare-Hopf
  std::vector<std::int64_t> total = scaled_vertex_index_sums(report.components, n);
  for(std::size_t l = 0; l < loops.size(); ++l)
    if(loops[l].kind == Loop_kind::boundary && rows.row_of_slot[l] >= 0)
      total[loops[l].component] += periods[l];
  for(std::size_t l = 0; l < loops.size(); ++l)
    if(loops[l].kind == Loop_kind::boundary && rows.row_of_slot[l] < 0 && !prescribed[l])
      periods[l] = n * report.components[loops[l].component].euler_characteristic - total[loops[l].component];

  report.max_loop_residual = 0;
  report.loops.resize(loops.size());
  for(std::size_t l = 0; l < loops.size(); ++l) {
    const double sum = sums.loop[l];
    Loop_report& r = report.loops[l];
    r.kind = loops[l].kind;
    r.component = std::size_t(loops[l].component);
    r.period = periods[l];
    r.index = Singularity_index(periods[l], n);
    r.prescribed = prescribed[l] != 0;
    r.residual = std::abs(loop_holonomy[l] + sum - unit * double(periods[l]));
    report.max_loop_residual = (std::max)(report.max_loop_residual, r.residual);
  }
  report.guidance_energy = sums.guidance_energy;
  report.guidance.resize(sums.slack.size());
  for(std::size_t g = 0; g < sums.slack.size(); ++g)
    report.guidance[g] = {std::size_t(links.faces[std::size_t(links.first_guided) + g].face), sums.slack[g]};
  report.max_constraint_residual = 0;
  report.constraints.resize(links.links.size());
  for(std::size_t j = 0; j < links.links.size(); ++j) {
    const std::size_t l = loops.size() + j;
    Constraint_report& r = report.constraints[j];
    r.component = std::size_t(links.links[j].component);
    r.from_face = std::size_t(links.faces[links.links[j].from].face);
    r.to_face = std::size_t(links.faces[links.links[j].to].face);
    r.length = links.links[j].length;
    r.period = periods[l];
    r.decided = links.links[j].decided;
    r.residual = std::abs(holonomy[l] + sums.loop[l] - unit * double(periods[l]));
    report.max_constraint_residual = (std::max)(report.max_constraint_residual, r.residual);
  }
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FIELD_REPORT_H
