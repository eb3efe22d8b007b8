// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_DUAL_LOOP_H
#define CGAL_TRIVIAL_CONNECTIONS_DUAL_LOOP_H

#include <CGAL/Trivial_connections/Solve_report.h>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
A closed dual loop given by the halfedges it crosses: `halfedges[i]` is crossed from `face(halfedges[i])`
to `face(opposite(halfedges[i]))`, and `face(opposite(halfedges[i])) == face(halfedges[i+1])` cyclically.
A boundary loop crosses, vertex after vertex of the boundary, every interior edge of each vertex's open
fan counter-clockwise (an interior edge joining two of its vertices is crossed twice, once each way).
*/
template <class HalfedgeDescriptor>
struct Dual_loop
{
  Loop_kind kind = Loop_kind::generator;     ///< boundary loop or homology generator
  std::size_t component = 0;                 ///< index of the loop's component
  std::vector<HalfedgeDescriptor> halfedges; ///< the halfedges crossed, in order (see above)
};

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_DUAL_LOOP_H
