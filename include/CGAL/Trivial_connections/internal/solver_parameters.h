// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SOLVER_PARAMETERS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SOLVER_PARAMETERS_H

// The named parameters of the coordinator (Trivial_connection_solver), read where they enter and turned into
// the plain values the layers take: the coordinator is the only caller, the layers never see named parameters.

#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/field/field_propagation.h>
#include <CGAL/Trivial_connections/internal/system/constraint_links.h>
#include <CGAL/Trivial_connections/internal/system/constraint_targets.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>

#include <CGAL/boost/graph/named_params_helper.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// the vertex point map of np, else tm's: the default is not made when np has one (Solver_access::make())
template <class TriangleMesh, class NamedParameters>
auto vertex_point_map_of(const TriangleMesh& tm, const NamedParameters& np)
{
  if constexpr(CGAL::parameters::is_default_parameter<NamedParameters, CGAL::internal_np::vertex_point_t>::value)
    return get_const_property_map(CGAL::vertex_point, tm);
  else
    return CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point);
}

template <class NamedParameters>
Progress_callback progress_of(const NamedParameters& np)
{
  return Progress_callback(
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::progress), Progress_callback()));
}

// `symmetry_order` (default 1), checked
template <class NamedParameters>
int symmetry_order_of(const NamedParameters& np)
{
  return checked_symmetry_order(
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1));
}

// compute_field()'s: `seed_face` as an index, -1 when not given (checked); `seed_angle` (finite); and the
// `symmetry_order` that rotates the field onto its targets, when given
template <class TriangleMesh, class NamedParameters>
int seed_face_of(const Mesh_arrays<TriangleMesh>& m, const NamedParameters& np)
{
  if constexpr(CGAL::parameters::is_default_parameter<NamedParameters, tc_np::seed_face_t>::value)
    return -1;
  else
    return checked_seed_face(m, CGAL::parameters::get_parameter(np, tc_np::seed_face));
}

template <class NamedParameters>
double seed_angle_of(const NamedParameters& np)
{
  const double seed_angle =
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::seed_angle), 0.);
  if(!std::isfinite(seed_angle))
    throw Invalid_input(Error_code::invalid_argument, "the seed angle is not finite");
  return seed_angle;
}

template <class NamedParameters>
std::optional<int> field_symmetry_order_of(const NamedParameters& np)
{
  if constexpr(CGAL::parameters::is_default_parameter<NamedParameters, tc_np::symmetry_order_t>::value)
    return std::nullopt;
  else
    return int(CGAL::parameters::get_parameter(np, tc_np::symmetry_order));
}

// `constrained_faces` and `guided_faces` as face indices, checked
template <class TriangleMesh, class NamedParameters>
void read_face_sets(const Mesh_arrays<TriangleMesh>& m, const NamedParameters& np, std::vector<int>& user_faces,
                    std::vector<int>& guided)
{
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::constrained_faces_t>::value)
    user_faces = checked_face_indices(m, CGAL::parameters::get_parameter(np, tc_np::constrained_faces), "constrained");
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::guided_faces_t>::value)
    guided = checked_face_indices(m, CGAL::parameters::get_parameter(np, tc_np::guided_faces), "guided");
  check_disjoint_face_sets(m.nf, user_faces, guided);
}

// With `face_directions` when the faces are set (constructor, set_constraints()): the user targets' angles, in
// the order of `user_faces`, so that touching targets that disagree are left to the lattice; and n (default 1)
template <class TriangleMesh, class GeomTraits, class NamedParameters>
int read_link_targets(const Mesh_arrays<TriangleMesh>& m, const GeomTraits& traits, const NamedParameters& np,
                      const std::vector<int>& user_faces, std::vector<double>& angles)
{
  const int n = symmetry_order_of(np);
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::face_directions_t>::value) {
    const auto& directions = CGAL::parameters::get_parameter(np, tc_np::face_directions);
    for(int f : user_faces) // a zero vector: not known yet (NaN: rounded like any touching pin)
      angles.push_back(get(directions, m.face_descriptors[std::size_t(f)]) == CGAL::NULL_VECTOR
                         ? std::numeric_limits<double>::quiet_NaN()
                         : user_target_angle(m, traits, directions, f));
  }
  return n;
}

// per constrained face, its target angle in its frame: the direction of its border halfedge when the boundary
// is aligned, otherwise the user's vector (`face_directions`) projected onto the face
template <class TriangleMesh, class GeomTraits, class NamedParameters>
std::vector<double> target_angles(const Mesh_arrays<TriangleMesh>& m, const GeomTraits& traits,
                                  const Constraint_links& links, const NamedParameters& np)
{
  std::vector<double> angle = boundary_target_angles(m, links);
  if(!links.has_user_constraints)
    return angle;
  if constexpr(CGAL::parameters::is_default_parameter<NamedParameters, tc_np::face_directions_t>::value) {
    throw Invalid_input(Error_code::invalid_constraint,
                        "the solver has constrained or guided faces: their directions (face_directions) are missing");
  } else {
    set_user_target_angles(m, links, traits, CGAL::parameters::get_parameter(np, tc_np::face_directions), angle);
    return angle;
  }
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SOLVER_PARAMETERS_H
