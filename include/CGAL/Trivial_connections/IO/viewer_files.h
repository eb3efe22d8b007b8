// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_VIEWER_FILES_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_VIEWER_FILES_H

#include <CGAL/Trivial_connections/IO/connection_file.h>
#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/streamlines.h>
#include <CGAL/Trivial_connections/parameters.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <ostream>
#include <string>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

namespace internal {
namespace io {

// What the viewer files show of a mesh: points, triangles, per face its n directions (the field's vector
// turned by 2 pi k / n about the face normal), per vertex its singularity index (0 for a regular vertex).
template <class TriangleMesh>
struct Viewer_data
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::vector<std::vector<std::array<double, 3>>> directions; // [k][face]
  std::vector<double> index;                                   // per vertex

  template <class FaceVectorMap, class SingularityRange, class NamedParameters>
  Viewer_data(const TriangleMesh& tm, FaceVectorMap field, const SingularityRange& singularities,
              const NamedParameters& np)
  {
    using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
    const auto vpm = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                                        get_const_property_map(CGAL::vertex_point, tm));
    const int n = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1);
    std::unordered_map<vertex_descriptor, std::size_t> number;
    for(vertex_descriptor v : vertices(tm)) {
      number.emplace(v, points.size());
      const auto& p = get(vpm, v);
      points.push_back({{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}});
    }
    index.assign(points.size(), 0.);
    for(const auto& s : singularities) {
      const auto it = number.find(s.first);
      if(it != number.end())
        index[it->second] = s.second.to_double();
    }
    directions.assign(std::size_t(n > 0 ? n : 1), {});
    for(auto f : faces(tm)) {
      const auto h = halfedge(f, tm);
      const std::array<std::size_t, 3> t = {{number.at(source(h, tm)), number.at(target(h, tm)),
                                             number.at(target(next(h, tm), tm))}};
      triangles.push_back(t);
      const auto& a = points[t[0]];
      const auto& b = points[t[1]];
      const auto& c = points[t[2]];
      const std::array<double, 3> u = {{b[0] - a[0], b[1] - a[1], b[2] - a[2]}}, w = {{c[0] - a[0], c[1] - a[1], c[2] - a[2]}};
      std::array<double, 3> normal = {{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]}};
      const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
      for(double& x : normal)
        x = length > 0 ? x / length : 0.;
      const auto d = get(field, f);
      const std::array<double, 3> v = {{CGAL::to_double(d.x()), CGAL::to_double(d.y()), CGAL::to_double(d.z())}};
      const std::array<double, 3> nv = {{normal[1] * v[2] - normal[2] * v[1], normal[2] * v[0] - normal[0] * v[2],
                                         normal[0] * v[1] - normal[1] * v[0]}};
      for(std::size_t k = 0; k < directions.size(); ++k) {
        const double angle = 2 * CGAL_PI * double(k) / double(directions.size());
        const double cs = k == 0 ? 1. : std::cos(angle), sn = k == 0 ? 0. : std::sin(angle);
        directions[k].push_back({{cs * v[0] + sn * nv[0], cs * v[1] + sn * nv[1], cs * v[2] + sn * nv[2]}});
      }
    }
  }
};

inline void write_text(Number_writer& out, const std::string& text)
{
  for(char c : text)
    out.character(c);
}

// "x y z" and `end`
inline void write_triple(Number_writer& out, const std::array<double, 3>& p, char end = '\n')
{
  out.number(p[0]);
  out.character(' ');
  out.number(p[1]);
  out.character(' ');
  out.number(p[2]);
  out.character(end);
}

// the header of a legacy ASCII VTK POLYDATA file, up to the POINTS line (the points follow)
inline void write_vtk_header(Number_writer& out, const std::string& title, std::size_t points)
{
  write_text(out, "# vtk DataFile Version 3.0\n" + title + " (CGAL Trivial Connections)\nASCII\nDATASET POLYDATA\nPOINTS " +
                    std::to_string(points) + " double\n");
}

} // namespace io
} // namespace internal

/*!
\ingroup PkgTrivialConnectionsIO
Writes the mesh with its direction field as a legacy VTK file (ASCII `POLYDATA`, read by ParaView and VisIt):
the points of `vertices(tm)` and the triangles of `faces(tm)` in that order; per face (`CELL_DATA`) the vectors
`direction_0` ... `direction_{n-1}`, the field's vector turned by `2 pi k / n` about the face normal (all the
directions of an n-direction field, for glyphs); per vertex (`POINT_DATA`) the scalar `singularity_index`
(0 on regular vertices).
\param os the output stream
\param tm the triangle mesh
\param field a readable property map `face_descriptor -> Vector_3` (from `compute_field()`)
\param singularities a range of pairs (`vertex_descriptor`, `Singularity_index`), as given to `solve()`
\param np an optional sequence of named parameters among the ones listed below
\cgalNamedParamsBegin
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{symmetry_order} \cgalParamType{`int`} \cgalParamDefault{1} \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class TriangleMesh, class FaceVectorMap, class SingularityRange,
          class NamedParameters = parameters::Default_named_parameters>
void write_field_vtk(std::ostream& os, const TriangleMesh& tm, FaceVectorMap field, const SingularityRange& singularities,
                     const NamedParameters& np = parameters::default_values())
{
  const internal::io::Viewer_data<TriangleMesh> data(tm, field, singularities, np);
  internal::io::Number_writer out(os);
  auto text = [&](const std::string& s) { internal::io::write_text(out, s); };
  internal::io::write_vtk_header(out, "direction field", data.points.size());
  for(const auto& p : data.points)
    internal::io::write_triple(out, p);
  text("POLYGONS ");
  out.index(data.triangles.size());
  out.character(' ');
  out.index(4 * data.triangles.size());
  out.character('\n');
  for(const auto& t : data.triangles) {
    text("3 ");
    out.index(t[0]);
    out.character(' ');
    out.index(t[1]);
    out.character(' ');
    out.index(t[2]);
    out.character('\n');
  }
  text("CELL_DATA ");
  out.index(data.triangles.size());
  out.character('\n');
  for(std::size_t k = 0; k < data.directions.size(); ++k) {
    text("VECTORS direction_");
    out.index(k);
    text(" double\n");
    for(const auto& v : data.directions[k])
      internal::io::write_triple(out, v);
  }
  text("POINT_DATA ");
  out.index(data.points.size());
  text("\nSCALARS singularity_index double 1\nLOOKUP_TABLE default\n");
  for(double i : data.index) {
    out.number(i);
    out.character('\n');
  }
  out.flush();
}

/*!
\ingroup PkgTrivialConnectionsIO
Writes the mesh with its direction field as an ASCII PLY file (MeshLab, ParaView, Blender): vertex properties
`x y z singularity_index`, face properties `vertex_indices` and, per direction k of the n-direction field,
`dk_x dk_y dk_z` (the field's vector turned by `2 pi k / n` about the face normal), in the order of
`vertices(tm)` and `faces(tm)`. Same parameters as `write_field_vtk()`.
\param os the output stream
\param tm the triangle mesh
\param field a readable property map `face_descriptor -> Vector_3` (from `compute_field()`)
\param singularities a range of pairs (`vertex_descriptor`, `Singularity_index`), as given to `solve()`
\param np an optional sequence of named parameters among the ones listed below
\cgalNamedParamsBegin
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{symmetry_order} \cgalParamType{`int`} \cgalParamDefault{1} \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class TriangleMesh, class FaceVectorMap, class SingularityRange,
          class NamedParameters = parameters::Default_named_parameters>
void write_field_ply(std::ostream& os, const TriangleMesh& tm, FaceVectorMap field, const SingularityRange& singularities,
                     const NamedParameters& np = parameters::default_values())
{
  const internal::io::Viewer_data<TriangleMesh> data(tm, field, singularities, np);
  internal::io::Number_writer out(os);
  auto text = [&](const std::string& s) { internal::io::write_text(out, s); };
  text("ply\nformat ascii 1.0\ncomment direction field (CGAL Trivial Connections): per face the n directions dk\n"
       "element vertex " + std::to_string(data.points.size()) +
       "\nproperty double x\nproperty double y\nproperty double z\nproperty double singularity_index\n"
       "element face " + std::to_string(data.triangles.size()) + "\nproperty list uchar int vertex_indices\n");
  for(std::size_t k = 0; k < data.directions.size(); ++k)
    for(const char* axis : {"x", "y", "z"})
      text("property double d" + std::to_string(k) + "_" + axis + "\n");
  text("end_header\n");
  for(std::size_t v = 0; v < data.points.size(); ++v) {
    internal::io::write_triple(out, data.points[v], ' ');
    out.number(data.index[v]);
    out.character('\n');
  }
  for(std::size_t f = 0; f < data.triangles.size(); ++f) {
    text("3");
    for(std::size_t i : data.triangles[f]) {
      out.character(' ');
      out.index(i);
    }
    for(const auto& direction : data.directions)
      for(double x : direction[f]) {
        out.character(' ');
        out.number(x);
      }
    out.character('\n');
  }
  out.flush();
}

/*!
\ingroup PkgTrivialConnectionsIO
Writes the singular vertices as a small point file: a `#` header, then one line `x y z k` per singularity
(its position and index `k` as `p` or `p/q`), in the order of the range.
\param os the output stream
\param tm the triangle mesh
\param singularities a range of pairs (`vertex_descriptor` of `tm`, `Singularity_index`), as given to `solve()`
\param np an optional sequence of named parameters among the ones listed below
\cgalNamedParamsBegin
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class TriangleMesh, class SingularityRange, class NamedParameters = parameters::Default_named_parameters>
void write_singularity_points(std::ostream& os, const TriangleMesh& tm, const SingularityRange& singularities,
                              const NamedParameters& np = parameters::default_values())
{
  const auto vpm = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                                      get_const_property_map(CGAL::vertex_point, tm));
  os << "# singularities: one line 'x y z k' per singular vertex (its position and index)\n";
  internal::io::Number_writer out(os);
  for(const auto& s : singularities) {
    const auto& p = get(vpm, s.first);
    internal::io::write_triple(out, {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}}, ' ');
    internal::io::write_text(out, s.second.to_string() + "\n");
  }
  out.flush();
}

/*!
\ingroup PkgTrivialConnectionsIO
Writes streamlines (from `trace_streamlines()`) as a legacy VTK file of polylines (ASCII `POLYDATA` with
`LINES`), for ParaView.
\param os the output stream
\param lines the streamlines, written as one polyline each, in order
*/
template <class TriangleMesh>
void write_streamlines_vtk(std::ostream& os, const std::vector<Streamline<TriangleMesh>>& lines)
{
  internal::io::Number_writer out(os);
  std::size_t points = 0;
  for(const auto& line : lines)
    points += line.points.size();
  internal::io::write_vtk_header(out, "streamlines", points);
  for(const auto& line : lines)
    for(const auto& p : line.points)
      internal::io::write_triple(out, p);
  internal::io::write_text(out, "LINES " + std::to_string(lines.size()) + " " + std::to_string(points + lines.size()) + "\n");
  std::size_t first = 0;
  for(const auto& line : lines) {
    out.index(line.points.size());
    for(std::size_t i = 0; i < line.points.size(); ++i) {
      out.character(' ');
      out.index(first + i);
    }
    out.character('\n');
    first += line.points.size();
  }
  out.flush();
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_VIEWER_FILES_H
