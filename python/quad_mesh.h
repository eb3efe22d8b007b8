// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Quad meshes: Solver.quad_mesh(), the quads of a cross field (CGAL::Trivial_connections::compute_quad_mesh()).
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_QUAD_MESH_H
#define TRIVIAL_CONNECTIONS_PYTHON_QUAD_MESH_H

namespace {

py::dict quad_report_dict(const TC::Quad_mesh_report& r)
{
  py::dict d;
  d["quad_size"] = r.quad_size;
  d["quads"] = r.number_of_quads;
  d["vertices"] = r.number_of_vertices;
  d["integer_points"] = r.integer_points;
  py::dict histogram;
  for(const auto& [valence, count] : r.valence_histogram)
    histogram[py::int_(valence)] = count;
  d["valence_histogram"] = histogram;
  d["valence_errors"] = r.valence_errors;
  d["folded_triangles"] = r.folded_triangles;
  d["degenerate_triangles"] = r.degenerate_triangles;
  d["rejected_polygons"] = r.rejected_polygons;
  d["open_edges"] = r.open_edges;
  d["dangling_edges"] = r.dangling_edges;
  d["flipped_quads"] = r.flipped_quads;
  d["concave_quads"] = r.concave_quads;
  d["hausdorff_distance"] = r.hausdorff_distance();
  d["hausdorff_quads_to_input"] = r.hausdorff_quads_to_input;
  d["hausdorff_input_to_quads"] = r.hausdorff_input_to_quads;
  d["split_vertices"] = r.split_vertices;
  d["continuous_energy"] = r.continuous_energy;
  d["rounded_energy"] = r.rounded_energy;
  d["solves"] = r.solves;
  return d;
}

// the quads of the cross field of `result` (with its singularities): (vertices (k, 3), quads (q, 4), report)
py::tuple Python_solver::quad_mesh(const Result& result, const py::object& singularities, const py::object& quad_size,
                                   const py::object& target_faces, const std::string& rounding, double max_quads)
{
  const Singularities s = singularities_of(singularities);
  const auto singular = vertex_descriptors(*m_mesh, s);
  if(rounding != "greedy" && rounding != "naive")
    throw py::value_error("rounding must be \"greedy\" or \"naive\", got \"" + rounding + "\"");
  if(quad_size.is_none() == target_faces.is_none())
    throw py::value_error(quad_size.is_none() ? "give quad_size or target_faces"
                                               : "give quad_size or target_faces, not both");
  const double H = quad_size.is_none() ? 0. : quad_size.cast<double>();
  long long N = 0;
  if(!target_faces.is_none()) {
    N = target_faces.cast<long long>();
    if(N < 1)
      throw py::value_error("target_faces must be a positive integer, got " + std::to_string(N));
  }
  const std::vector<double> x = halfedge_angles(result);
  const std::vector<Kernel::Vector_3> field = field_of(result);
  const int n = result.n.cast<int>();
  const TC::Quad_rounding scheme = rounding == "naive" ? TC::Quad_rounding::naive : TC::Quad_rounding::greedy;
  Mesh quads;
  const TC::Quad_mesh_report report = reading([&] {
    auto x_map = boost::make_function_property_map<halfedge_descriptor, double>(
      [&x](halfedge_descriptor h) { return x[std::size_t(h)]; });
    auto field_map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
      [&field](face_descriptor f) { return field[std::size_t(f)]; });
    namespace P = TC::parameters;
    const auto common = P::max_quads(max_quads, P::quad_rounding(scheme, P::symmetry_order(n)));
    return N > 0 ? TC::compute_quad_mesh(*m_mesh, x_map, field_map, singular, quads,
                                         P::target_faces(std::size_t(N), common))
                 : TC::compute_quad_mesh(*m_mesh, x_map, field_map, singular, quads, P::quad_size(H, common));
  });
  std::vector<double> points;
  points.reserve(3 * quads.number_of_vertices());
  for(auto v : quads.vertices()) // a fresh mesh: its vertices are numbered 0..k-1 in this order
    for(int a = 0; a < 3; ++a)
      points.push_back(quads.point(v)[a]);
  std::vector<std::int64_t> polygons;
  polygons.reserve(4 * quads.number_of_faces());
  for(auto f : quads.faces())
    for(auto v : CGAL::vertices_around_face(quads.halfedge(f), quads))
      polygons.push_back(std::int64_t(v));
  const py::ssize_t k = py::ssize_t(quads.number_of_vertices()), q = py::ssize_t(quads.number_of_faces());
  return py::make_tuple(owning_array(std::move(points), {k, 3}), owning_array(std::move(polygons), {q, 4}),
                        quad_report_dict(report));
}

void bind_quad_mesh(py::class_<Python_solver>& solver)
{
  solver.def("quad_mesh", &Python_solver::quad_mesh, py::arg("result"), py::arg("singularities"),
             py::arg("quad_size") = py::none(), py::arg("target_faces") = py::none(), py::arg("rounding") = "greedy",
             py::arg("max_quads") = 1e7,
             "The quad mesh of result's cross field (n = 4) with its singularities: quad_size H (the quads' edge "
             "length) or target_faces N (H = sqrt(area / N)), one of them; rounding \"greedy\" or \"naive\"; more "
             "than max_quads quads is refused. Returns (vertices (k, 3), quads (q, 4) counter-clockwise, report dict: "
             "quads, valence_histogram, valence_errors, folded_triangles, flipped_quads, hausdorff_distance, ...). "
             "Closed meshes only; errors raise InvalidInput.");
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_QUAD_MESH_H
