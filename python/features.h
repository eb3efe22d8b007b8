// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Sharp features: feature_aligned_faces(), feature_curves() and the options of Solver(align_features=...).
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_FEATURES_H
#define TRIVIAL_CONNECTIONS_PYTHON_FEATURES_H

namespace {

// ---- sharp features (feature_alignment.h) ----------------------------------------------------------------

// What feature_aligned_faces() found on a mesh: the faces beside the feature curves, in increasing face number,
// and the direction of the curve on each
struct Feature_pins
{
  TC::Feature_alignment_report report;
  std::vector<std::size_t> faces;
  std::vector<double> directions; // 3 per face of `faces`
};

Feature_pins feature_pins_of(const Mesh& mesh, double threshold, int n, int smoothing)
{
  Feature_pins out;
  std::vector<double> xyz(3 * mesh.number_of_faces(), 0.);
  std::vector<face_descriptor> faces;
  out.report = TC::feature_aligned_faces(mesh, threshold, std::back_inserter(faces), Face_vector_map{xyz.data()},
                                         TC::parameters::symmetry_order(n, TC::parameters::feature_smoothing(smoothing)));
  out.faces.reserve(faces.size());
  out.directions.reserve(3 * faces.size());
  for(face_descriptor f : faces) {
    out.faces.push_back(std::size_t(f));
    out.directions.insert(out.directions.end(), xyz.begin() + 3 * std::ptrdiff_t(f), xyz.begin() + 3 * std::ptrdiff_t(f) + 3);
  }
  return out;
}

py::dict feature_report_dict(const TC::Feature_alignment_report& r)
{
  py::dict d;
  d["threshold_degrees"] = r.threshold_degrees;
  d["number_of_sharp_edges"] = r.number_of_sharp_edges;
  d["number_of_curves"] = r.number_of_curves;
  d["dropped_curves"] = r.dropped_curves;
  d["dropped_edges"] = r.dropped_edges;
  d["number_of_pinned_faces"] = r.number_of_pinned_faces;
  d["faces_with_several_edges"] = r.faces_with_several_edges;
  d["number_of_cusps"] = r.number_of_cusps;
  d["sector_rule_faces"] = r.sector_rule_faces;
  d["neighbouring_pairs"] = r.neighbouring_pairs;
  d["disagreeing_pairs"] = r.disagreeing_pairs;
  d["max_disagreement_degrees"] = r.max_disagreement_degrees;
  return d;
}

// Solver(align_features=...): off (None, False), the default threshold (True) or a threshold in degrees
struct Feature_options
{
  bool on = false;
  double threshold = TC::default_feature_angle_degrees;
  int n = 4;
  int smoothing = TC::default_feature_smoothing;
};

Feature_options feature_options_of(const py::object& align, int n, int smoothing)
{
  Feature_options o;
  o.n = n;
  o.smoothing = smoothing;
  if(align.is_none())
    return o;
  if(py::isinstance<py::bool_>(align)) {
    o.on = align.cast<bool>();
    return o;
  }
  if(!PyFloat_Check(align.ptr()) && !PyIndex_Check(align.ptr()) &&
     !(py::hasattr(align, "__float__") && !py::isinstance<py::str>(align)))
    throw py::type_error("align_features must be True, False, None or a threshold in degrees, got " +
                         std::string(py::repr(align)));
  o.on = true;
  o.threshold = align.cast<double>();
  // checked here, before the solver is built (the library's message and code: invalid_argument)
  TC::internal::features::check_threshold(o.threshold);
  return o;
}


// DEFAULT_FEATURE_ANGLE, DEFAULT_FEATURE_SMOOTHING, feature_aligned_faces(), feature_curves()
void bind_features(py::module_& m)
{
  m.attr("DEFAULT_FEATURE_ANGLE") = TC::default_feature_angle_degrees;
  m.attr("DEFAULT_FEATURE_SMOOTHING") = TC::default_feature_smoothing;
  m.def(
    "feature_aligned_faces",
    [](const py::object& V, const py::object& F, double threshold, const py::object& n_in, int smoothing) {
      const int n = symmetry_order_of(n_in, "n");
      Mesh_of_arrays mesh = mesh_of_arrays(V, F);
      Feature_pins p;
      {
        py::gil_scoped_release unlocked;
        mesh.wait_for_mesh();
        p = feature_pins_of(*mesh.mesh, threshold, n, smoothing);
      }
      std::vector<std::int64_t> faces(p.faces.begin(), p.faces.end());
      const py::ssize_t k = py::ssize_t(faces.size());
      return py::make_tuple(owning_array(std::move(faces), {k}), owning_array(std::move(p.directions), {k, 3}),
                            feature_report_dict(p.report));
    },
    py::arg("V"), py::arg("F"), py::arg("threshold") = TC::default_feature_angle_degrees, py::kw_only(),
    py::arg("n") = 4, py::arg("smoothing") = TC::default_feature_smoothing,
    R"(Pins for a feature-aligned field: the faces beside the mesh's sharp feature curves and the curves' directions.

Returns (faces, directions, report): faces a (k,) int64 array in increasing face number, directions a (k, 3)
float64 array of unit vectors tangent to their faces, report a dict. An interior edge is sharp when the normals of
its two faces make an angle over `threshold` degrees (default DEFAULT_FEATURE_ANGLE, 30); sharp edges are joined
into feature curves through the vertices that are not corners, and isolated short curves are dropped (see
feature_curves()). Every face with an edge on a kept curve is pinned to the curve's direction there: the
least-squares line through the curve's vertices within `smoothing` sharp edges (default
DEFAULT_FEATURE_SMOOTHING, 3; 0: each edge its own direction), so that a jagged crease gives pins that agree.
A face beside several curve edges takes their mean modulo 2 pi / n (for n = 4 perpendicular edges agree).
Give faces as constrained_faces and directions as solve(directions={face: vector}) (or use
Solver(align_features=...), which does it, as the program's --align-features). Faces on the boundary are included:
drop them when the solver aligns with the boundary (it refuses targets there).
report: threshold_degrees, number_of_sharp_edges, number_of_curves, dropped_curves, dropped_edges,
number_of_pinned_faces, faces_with_several_edges, number_of_cusps and sector_rule_faces (n = 4: a crease turning
back, and the faces pinned there to put one quad corner between its arms), neighbouring_pairs (pinned faces sharing an edge),
disagreeing_pairs (those whose directions, moved across the edge, differ by more than 5 degrees modulo 2 pi / n)
and max_disagreement_degrees. A mesh without sharp edges gives no face and a report of zeros.
Raises InvalidInput (a ValueError): invalid_argument for a threshold that is negative, over 180 or NaN or
smoothing < 0, invalid_symmetry_order for n outside 1 to MAX_SYMMETRY_ORDER, and for a mesh the package refuses,
as Solver().)");
  m.def(
    "feature_curves",
    [](const py::object& V, const py::object& F, double threshold) {
      Mesh_of_arrays mesh = mesh_of_arrays(V, F);
      TC::Feature_curves<Mesh> c;
      {
        py::gil_scoped_release unlocked;
        mesh.wait_for_mesh();
        c = TC::feature_curves(*mesh.mesh, threshold);
      }
      py::list curves, lengths;
      for(const auto& curve : c.curves) {
        std::vector<std::int64_t> pairs;
        pairs.reserve(2 * curve.halfedges.size());
        for(halfedge_descriptor h : curve.halfedges) {
          pairs.push_back(std::int64_t(mesh.mesh->source(h)));
          pairs.push_back(std::int64_t(mesh.mesh->target(h)));
        }
        curves.append(owning_array(std::move(pairs), {py::ssize_t(curve.halfedges.size()), 2}));
        lengths.append(curve.length);
      }
      py::dict report;
      report["threshold_degrees"] = threshold;
      report["number_of_sharp_edges"] = c.number_of_sharp_edges;
      report["number_of_curves"] = c.curves.size();
      report["dropped_curves"] = c.dropped_curves;
      report["dropped_edges"] = c.dropped_edges;
      report["lengths"] = lengths;
      return py::make_tuple(curves, report);
    },
    py::arg("V"), py::arg("F"), py::arg("threshold") = TC::default_feature_angle_degrees,
    R"(The feature curves of a triangle mesh: (curves, report).

curves: one (k, 2) int64 array per kept curve, the (source, target) vertices of its sharp edges (breadth-first
from one of them; which one and each edge's orientation depend on the numbering). An interior edge is sharp when
the normals of its two faces make an angle over `threshold` degrees (default DEFAULT_FEATURE_ANGLE, 30; border
edges never are). A curve is a set of sharp edges connected through vertices that are not corners (a corner: where
three creases meet, or a crease turns by more than about 60 degrees). An isolated curve (touching no corner) with
fewer than 2 edges and shorter than 3 mean edge lengths is dropped. report: threshold_degrees,
number_of_sharp_edges (of kept and dropped curves), number_of_curves, dropped_curves, dropped_edges and lengths
(of the kept curves, in their order). Raises InvalidInput as feature_aligned_faces().)");
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_FEATURES_H
