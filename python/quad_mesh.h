// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Quad meshes: Solver.quad_mesh(), the quads of a cross field (CGAL::Trivial_connections::compute_quad_mesh()), and
// Solver.move_singularities_off_features(), the step before it (move_singularities_off_features()).
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
  d["border_corners"] = r.border_corners;
  d["feature_edges"] = r.feature_edges;
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
  d["factorizations"] = r.factorizations;
  d["rounding_seconds"] = r.rounding_seconds;
  d["naive_rounding_fallback"] = r.naive_rounding_fallback;
  d["inverted_before_untangling"] = r.inverted_before_untangling;
  d["untangled"] = r.untangled;
  d["untangled_energy"] = r.untangled_energy;
  d["untangling_seconds"] = r.untangling_seconds;
  d["wrongly_wound_singularities"] = r.wrongly_wound_singularities;
  d["cone_modes"] = r.cone_modes;
  d["branch_points"] = r.branch_points;
  return d;
}

// The feature edges given in Python, as pairs of vertices (i, j) in either order (a (m, 2) integer array or a
// sequence of pairs, as feature_curves() gives them), marked per edge of `mesh`; a pair that is not an edge of the
// mesh is the user's error. A pair listed twice marks its edge once.
std::vector<char> feature_edges_of(const Mesh& mesh, const py::object& pairs)
{
  std::vector<char> marked(mesh.number_of_edges(), 0);
  if(pairs.is_none())
    return marked;
  if(py::isinstance<py::array>(pairs)) {
    const py::array a = py::reinterpret_borrow<py::array>(pairs);
    if(a.size() == 0)
      return marked;
    if(a.ndim() != 2 || a.shape(1) != 2)
      throw py::value_error("feature_edges as an array must have shape (m, 2): rows (i, j), the vertices of an edge");
    if(a.dtype().kind() != 'i' && a.dtype().kind() != 'u')
      throw py::type_error("feature_edges must hold integers (vertices), got dtype " + std::string(py::str(a.dtype())));
  } else if(!py::isinstance<py::sequence>(pairs) || py::isinstance<py::str>(pairs) || py::isinstance<py::bytes>(pairs))
    throw py::type_error("feature_edges must be a sequence of pairs (i, j) or an (m, 2) integer array, got " +
                         std::string(py::str(py::type::of(pairs))));
  for(const py::handle row : py::iter(pairs)) {
    if(!py::isinstance<py::sequence>(row) && !py::isinstance<py::array>(row))
      throw py::type_error("each feature edge must be a pair of vertices (i, j), got " + std::string(py::repr(row)));
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(row);
    if(py::len(pair) != 2)
      throw py::value_error("each feature edge must be a pair of vertices (i, j), got " + std::string(py::repr(row)));
    const std::size_t i = vertex_number(pair[0]), j = vertex_number(pair[1]);
    const vertex_descriptor vi = vertex_of(mesh, i), vj = vertex_of(mesh, j);
    const auto [h, found] = CGAL::halfedge(vi, vj, mesh);
    if(!found || i == j)
      throw TC::Invalid_input(TC::Error_code::invalid_argument, "feature edge (" + std::to_string(i) + ", " +
                                                                   std::to_string(j) + ") is not an edge of the mesh");
    marked[std::size_t(mesh.edge(h))] = 1;
  }
  return marked;
}

// the quads of the cross field of `result` (with its singularities): (vertices (k, 3), quads (q, 4), report)
py::tuple Python_solver::quad_mesh(const Result& result, const py::object& singularities, const py::object& quad_size,
                                   const py::object& target_faces, const std::string& rounding, double max_quads,
                                   const py::object& feature_edges, double scale_smoothness, bool untangle,
                                   double cone_mode_weight)
{
  const Singularities s = singularities_of(singularities);
  const auto singular = vertex_descriptors(*m_mesh, s);
  const std::vector<char> features = feature_edges_of(*m_mesh, feature_edges);
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
    // always given (all false without feature edges: the same as none), so that one instantiation serves both
    auto feature_map = boost::make_function_property_map<edge_descriptor, bool>(
      [&features](edge_descriptor e) { return features[std::size_t(e)] != 0; });
    namespace P = TC::parameters;
    // (a negative or non-finite S is refused by compute_quad_mesh(): invalid_argument)
    const auto common =
      P::quad_cone_mode_weight(cone_mode_weight,
        P::quad_untangling(untangle, P::quad_scale_smoothness(scale_smoothness,
                                                              P::max_quads(max_quads, P::quad_rounding(scheme, P::symmetry_order(n))))))
        .edge_is_constrained_map(feature_map);
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

// the singularities closer than H to a feature edge moved H away: (singularities dict, report dict)
py::tuple Python_solver::move_singularities_off_features(const py::object& singularities,
                                                         const py::object& feature_edges, const py::object& quad_size,
                                                         const py::object& target_faces,
                                                         const py::object& fixed_vertices)
{
  const Singularities s = singularities_of(singularities);
  const auto singular = vertex_descriptors(*m_mesh, s);
  if(feature_edges.is_none())
    throw py::type_error("feature_edges must be given: the pairs of vertices (i, j) of the feature edges");
  const std::vector<char> features = feature_edges_of(*m_mesh, feature_edges);
  if(quad_size.is_none() == target_faces.is_none())
    throw py::value_error(quad_size.is_none() ? "give quad_size or target_faces"
                                               : "give quad_size or target_faces, not both");
  std::vector<vertex_descriptor> fixed;
  if(!fixed_vertices.is_none())
    for(const py::handle v : py::iter(fixed_vertices))
      fixed.push_back(vertex_of(*m_mesh, vertex_number(v)));
  double H = 0;
  if(quad_size.is_none()) {
    const long long N = target_faces.cast<long long>();
    if(N < 1)
      throw py::value_error("target_faces must be a positive integer, got " + std::to_string(N));
    H = reading([&] { return TC::quad_size_for_target_faces(*m_mesh, std::size_t(N)); });
  } else
    H = quad_size.cast<double>(); // checked by the library: positive and finite
  const auto r = reading([&] {
    auto feature_map = boost::make_function_property_map<edge_descriptor, bool>(
      [&features](edge_descriptor e) { return features[std::size_t(e)] != 0; });
    return TC::move_singularities_off_features(*m_mesh, singular, feature_map,
                                               TC::parameters::quad_size(H, TC::parameters::fixed_vertices(fixed)));
  });
  Singularities moved;
  for(const auto& [v, k] : r.singularities)
    moved.emplace_back(std::size_t(v), k);
  py::list moves;
  for(const auto& m : r.moves) {
    py::dict d;
    d["from"] = std::size_t(m.from);
    d["to"] = std::size_t(m.to);
    d["distance_before"] = m.distance_before;
    d["distance_after"] = m.distance_after;
    d["path_length"] = m.path_length;
    moves.append(d);
  }
  py::list stuck;
  for(const auto v : r.stuck)
    stuck.append(std::size_t(v));
  py::dict d;
  d["quad_size"] = r.quad_size;
  d["moves"] = moves;
  d["stuck"] = stuck;
  d["on_features"] = r.on_features;
  d["fixed"] = r.fixed;
  return py::make_tuple(singularity_dict(moved), d);
}

void bind_quad_mesh(py::class_<Python_solver>& solver)
{
  solver.def("quad_mesh", &Python_solver::quad_mesh, py::arg("result"), py::arg("singularities"),
             py::arg("quad_size") = py::none(), py::arg("target_faces") = py::none(), py::arg("rounding") = "greedy",
             py::arg("max_quads") = 1e7, py::arg("feature_edges") = py::none(), py::arg("scale_smoothness") = 0.,
             py::arg("untangle") = true, py::arg("cone_mode_weight") = 0.,
             "The quad mesh of result's cross field (n = 4) with its singularities: quad_size H (the quads' edge "
             "length) or target_faces N (H = sqrt(area / N)), one of them; rounding \"greedy\" or \"naive\"; more "
             "than max_quads quads is refused. feature_edges: edges put on integer iso-lines so that quad edges "
             "follow them, as pairs of vertices (i, j) (an (m, 2) integer array or a sequence of pairs, e.g. "
             "numpy.vstack(feature_curves(V, F)[0])); the field must follow them (Solver(..., align_features=...)). "
             "Border edges are always put on iso-lines: the field must follow the border (align_boundary=True), "
             "otherwise the call is refused. scale_smoothness S > 0: the field's length is first scaled per face to "
             "make it closer to a gradient (C++ quad_scale_smoothness, the program's --quad-scale-smoothness; 0: "
             "not scaled; the program tries 0.1 by itself when its quads have flaws, this call does not). untangle: a "
             "rounded map with folded or degenerate triangles is moved out of them, its integers kept (C++ "
             "quad_untangling; False: the rounded map as it is). cone_mode_weight W > 0: the map made to wind around "
             "every singular vertex as its index asks, in two stages (C++ quad_cone_mode_weight, the program's "
             "--quad-cone-modes; 0: off; the program tries 30 by itself when its quads have singular vertices wound "
             "wrongly, this call does not). Returns "
             "(vertices (k, 3), quads (q, 4) counter-clockwise, report dict: "
             "quad_size, quads, vertices, integer_points, valence_histogram, valence_errors, border_corners, "
             "feature_edges, folded_triangles, degenerate_triangles, rejected_polygons, open_edges, dangling_edges, "
             "flipped_quads, concave_quads, hausdorff_distance (and its two one-sided parts), split_vertices, "
             "continuous_energy, rounded_energy, solves, factorizations, rounding_seconds, naive_rounding_fallback: the "
             "greedy rounding's integers contradicted each other and the naive one made the map, "
             "inverted_before_untangling (the rounded map's folded and degenerate triangles), untangled (the quads "
             "come from the untangled map), untangled_energy, untangling_seconds, wrongly_wound_singularities (singular "
             "vertices the map winds around the wrong number of times: each a valence error), branch_points (regular "
             "vertices it winds around more than once), cone_modes (the map comes from those two stages)). Errors raise InvalidInput "
             "(a ValueError).");
  solver.def("move_singularities_off_features", &Python_solver::move_singularities_off_features,
             py::arg("singularities"), py::arg("feature_edges"), py::arg("quad_size") = py::none(),
             py::arg("target_faces") = py::none(), py::arg("fixed_vertices") = py::none(),
             "The step before quad_mesh(..., feature_edges=) (C++ move_singularities_off_features()): every "
             "singularity closer than H to a feature edge (graph distance along mesh edges to a vertex of one), but "
             "not on one, moves to the nearest vertex at least H from every feature edge (along paths through "
             "vertices of no feature edge; not on the border, not already singular; equal lengths: the smallest "
             "point). Indices are kept, so are the sums per component. It stays when no such vertex is reachable "
             "(listed in 'stuck'), and so do index 0 and fixed_vertices. quad_size H or target_faces N (H = "
             "sqrt(area / N), as quad_mesh reads it), one of them; feature_edges as for quad_mesh. The field must "
             "then be solved again with the new singularities (solve(moved, n=4)) before quad_mesh. Returns "
             "(singularities {vertex: Fraction} in the input's order, report dict: quad_size, moves (dicts from, to, "
             "distance_before, distance_after, path_length), stuck, on_features, fixed). Errors raise InvalidInput.");
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_QUAD_MESH_H
