// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRESS_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRESS_H

#include <functional>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
The phases reported through the `progress` named parameter.
The constructor of `Trivial_connection_solver` runs `mesh_setup` to `loop_metric`, in this order, `solve()` runs `solve`
and `loop_integers`, `compute_field()` runs `field`, and `place_singularities()` runs `placement`.
*/
enum class Phase {
  mesh_setup,    ///< flat arrays of the mesh, validation
  geometry,      ///< corner angles, frames, transport angles, weights
  trees,         ///< dual and primal spanning trees, tree-cotree loops
  assembly,      ///< the sparse constraint system
  factorization, ///< the sparse factorization (analysis + numeric)
  loop_metric,   ///< the metric of the loop integers, read from the factorization
  solve,         ///< back-substitutions of one `solve()`
  loop_integers, ///< the closest-vector search for the loop integers
  field,         ///< propagation of the direction field along the dual tree
  placement      ///< the smooth field of `place_singularities()` and the reading of its singularities; in
                 ///< between, 0.99 times the eigensolver's iterations over their budget of 100
};

/// a short lower-case name of the phase (`"factorization"`, ...)
/// \param p the phase
/// \returns its name (a string literal; `"mesh setup"` and `"loop metric"` contain a space), or `"unknown"`
///          for a value that is not one of the enumerators
inline const char* phase_name(Phase p)
{
  switch(p) {
  case Phase::mesh_setup: return "mesh setup";
  case Phase::geometry: return "geometry";
  case Phase::trees: return "trees";
  case Phase::assembly: return "assembly";
  case Phase::factorization: return "factorization";
  case Phase::loop_metric: return "loop metric";
  case Phase::solve: return "solve";
  case Phase::loop_integers: return "loop integers";
  case Phase::field: return "field";
  case Phase::placement: return "placement";
  }
  return "unknown";
}

/*!
\ingroup PkgTrivialConnectionsRef
The type of the `progress` named parameter: called with `fraction == 0` when a phase starts and
`fraction == 1` when it ends, and possibly with values in between. It is called on the calling thread;
the library never prints. An exception thrown by the callback propagates out of the call (a way to cancel);
the solver object is then unusable if it came from the constructor.
*/
using Progress_callback = std::function<void(Phase phase, double fraction)>;

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRESS_H
