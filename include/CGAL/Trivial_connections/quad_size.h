// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_QUAD_SIZE_H
#define CGAL_TRIVIAL_CONNECTIONS_QUAD_SIZE_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// The area of the mesh, summed face by face in the arrays' order (the same number wherever the quad size is
// worked out from it).
template <class TriangleMesh>
double surface_area(const Mesh_arrays<TriangleMesh>& m)
{
  double area = 0;
  for(int f = 0; f < m.nf; ++f)
    area += norm(cross(sub(m.points[m.corner_vertex[3 * f + 1]], m.points[m.corner_vertex[3 * f]]),
                       sub(m.points[m.corner_vertex[3 * f + 2]], m.points[m.corner_vertex[3 * f]]))) / 2;
  return area;
}

// H from the named parameters `quad_size` or `target_faces` (exactly one of them), for a mesh of this area: the
// one rule of compute_quad_mesh() and move_singularities_off_features(). Refused: neither or both, N < 1, H not
// positive and finite.
template <class NamedParameters>
double quad_size_from_parameters(double area, const NamedParameters& np)
{
  using CGAL::parameters::get_parameter;
  constexpr bool has_size = !CGAL::parameters::is_default_parameter<NamedParameters, tc_np::quad_size_t>::value;
  constexpr bool has_target = !CGAL::parameters::is_default_parameter<NamedParameters, tc_np::target_faces_t>::value;
  if(has_size == has_target)
    throw Invalid_input(Error_code::invalid_argument, has_size ? "give the quad size or the target number of faces, not both"
                                                               : "give the quad size or the target number of faces");
  double H = 0;
  if constexpr(has_size) {
    H = double(get_parameter(np, tc_np::quad_size));
  } else if constexpr(has_target) {
    const double target = double(get_parameter(np, tc_np::target_faces));
    if(!(target >= 1) || !std::isfinite(target))
      throw Invalid_input(Error_code::invalid_argument, "the target number of faces must be at least 1");
    H = std::sqrt(area / target); // N squares of side H cover the area
  }
  if(!(H > 0) || !std::isfinite(H)) {
    std::ostringstream s;
    s << "the quad size H must be positive and finite (got " << H << ")";
    throw Invalid_input(Error_code::invalid_argument, s.str());
  }
  return H;
}

} // namespace internal

/*!
\ingroup PkgTrivialConnectionsRef
The quad size H that `compute_quad_mesh()` and `move_singularities_off_features()` use for a target number of
quads N (their named parameter `target_faces`): H = sqrt(A / N), A the area of the mesh (the sum of its
triangles' areas), so that N squares of side H have the area of the mesh. The quad mesh has about N quads (the
rounding, borders and feature lines change the count a little).

\param tm a triangle mesh
\param target_faces N, at least 1
\param np a sequence of named parameters among the ones listed below
\returns H
\throws Invalid_input `invalid_argument` when N < 1; the mesh errors of the solver (`empty_mesh`,
        `not_triangle_mesh`, `non_manifold`, `non_finite_point`, `degenerate_face`, ...)
\cgalNamedParamsBegin
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{geom_traits} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
double quad_size_for_target_faces(const TriangleMesh& tm, std::size_t target_faces,
                                  const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using Geom_traits = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;
  if(target_faces < 1)
    throw Invalid_input(Error_code::invalid_argument, "the target number of faces must be at least 1");
  const internal::Mesh_arrays<TriangleMesh> m(
    tm, choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm)),
    choose_parameter(get_parameter(np, CGAL::internal_np::geom_traits), Geom_traits()));
  return internal::quad_size_from_parameters(internal::surface_area(m), parameters::target_faces(target_faces));
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_QUAD_SIZE_H
