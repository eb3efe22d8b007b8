// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_TARGETS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_TARGETS_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/system/constraint_links.h>

#include <CGAL/number_utils.h>

#include <cmath>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// Per constrained face, its target angle in its frame where the boundary gives it (the direction of its
// border halfedge when the boundary is aligned), 0 elsewhere.
template <class TriangleMesh>
std::vector<double> boundary_target_angles(const Mesh_arrays<TriangleMesh>& m, const Constraint_links& links)
{
  std::vector<double> angle(links.faces.size(), 0.);
  for(std::size_t a = 0; a < links.faces.size(); ++a) {
    const int i = links.faces[a].border_corner;
    if(i >= 0)
      angle[a] = edge_angle_in_frame(m, i);
  }
  return angle;
}

// The target angle of face f from the direction `face_directions` gives it (a readable property map
// face_descriptor -> GeomTraits::Vector_3), projected onto the face; checked.
template <class TriangleMesh, class GeomTraits, class DirectionMap>
double user_target_angle(const Mesh_arrays<TriangleMesh>& m, const GeomTraits& traits, const DirectionMap& directions,
                         int f)
{
  typename GeomTraits::Compute_x_3 x = traits.compute_x_3_object();
  typename GeomTraits::Compute_y_3 y = traits.compute_y_3_object();
  typename GeomTraits::Compute_z_3 z = traits.compute_z_3_object();
  const typename GeomTraits::Vector_3 d = get(directions, m.face_descriptors[f]);
  const Vec3 v = {{CGAL::to_double(x(d)), CGAL::to_double(y(d)), CGAL::to_double(z(d))}};
  Vec3 ex, ey;
  Mesh_geometry::frame(m, f, ex, ey);
  const double along_x = dot(v, ex), along_y = dot(v, ey), length = norm(v);
  // a vector within 1e-9 rad of the normal has no meaningful tangent direction
  if(!std::isfinite(length) || !(std::hypot(along_x, along_y) > 1e-9 * length))
    throw Invalid_input(Error_code::invalid_constraint,
                        "the direction given for face " + std::to_string(f) +
                          (std::isfinite(length) && length > 0 ? " is normal to the face" : " is zero or not finite"),
                        std::size_t(f));
  return std::atan2(along_y, along_x);
}

// The target angles of the user's faces (targets and guides) from `face_directions` (see user_target_angle())
template <class TriangleMesh, class GeomTraits, class DirectionMap>
void set_user_target_angles(const Mesh_arrays<TriangleMesh>& m, const Constraint_links& links, const GeomTraits& traits,
                            const DirectionMap& directions, std::vector<double>& angle)
{
  for(std::size_t a = 0; a < links.faces.size(); ++a)
    if(links.faces[a].border_corner < 0)
      angle[a] = user_target_angle(m, traits, directions, links.faces[a].face);
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_TARGETS_H
