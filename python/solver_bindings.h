// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The binding of Result and Solver (all but the methods of placement.h, streamlines.h and files.h), with their
// docstrings, and of _reference_build().
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_SOLVER_BINDINGS_H
#define TRIVIAL_CONNECTIONS_PYTHON_SOLVER_BINDINGS_H

namespace {

// The meshes of Solver(V, F) and of Solver.from_file(path, triangulate)
Mesh_of_arrays mesh_of_V_F(const py::object& V, const py::object& F) { return mesh_of_arrays(V, F); }

Mesh_of_arrays mesh_of_path(const py::object& path, bool triangulate)
{
  Mesh_of_arrays mesh;
  mesh.mesh = mesh_of_file(path_of(path), triangulate);
  mesh.number_of_faces = mesh.mesh->number_of_faces();
  return mesh;
}

// The factory of Solver() and Solver.from_file(): `make_mesh` of the call's own arguments (timed as
// build_timings["mesh"]), then the solver with the options both take. One body and one list of the options' types,
// so that the two stay the same.
template <class... Leading>
auto solver_constructor(const char* call, Mesh_of_arrays (*make_mesh)(Leading...))
{
  return [call, make_mesh](Leading... leading, const std::string& weights, const std::string& backend,
                           const py::object& constrained, const py::object& guided, double mu, bool align,
                           const py::object& align_features, int feature_smoothing, const py::object& feature_n,
                           const py::object& progress) {
    const Feature_options features =
      feature_options_of(align_features, symmetry_order_of(feature_n, "feature_n"), feature_smoothing);
    Progress_context context(call, progress);
    const auto start = std::chrono::steady_clock::now();
    Mesh_of_arrays mesh = make_mesh(leading...);
    const double seconds = seconds_since(start);
    auto solver = std::make_unique<Python_solver>(std::move(mesh), weights, backend, constrained, guided, mu, align,
                                                  features, context.callback());
    solver->m_mesh_seconds = seconds;
    return solver;
  };
}

py::class_<Python_solver> bind_solver(py::module_& m)
{
  m.def(
    "_reference_build",
    [](const py::object& V, const py::object& F, const std::string& backend) {
      check_backend(backend);
      const auto [points, faces] = checked_arrays(V, F);
      // the arrays a C++ program holds (not timed)
      std::vector<Kernel::Point_3> p;
      for(py::ssize_t i = 0; i < points.shape(0); ++i)
        p.emplace_back(points.at(i, 0), points.at(i, 1), points.at(i, 2));
      std::vector<std::array<std::size_t, 3>> t;
      for(py::ssize_t i = 0; i < faces.shape(0); ++i)
        t.push_back({std::size_t(faces.at(i, 0)), std::size_t(faces.at(i, 1)), std::size_t(faces.at(i, 2))});
      double to_mesh = 0, solver = 0;
      {
        py::gil_scoped_release unlocked;
        const auto t0 = std::chrono::steady_clock::now();
        Mesh_of_arrays mesh;
        mesh.mesh = std::make_unique<Mesh>();
        TC::triangle_soup_to_mesh(p, t, *mesh.mesh);
        const auto t1 = std::chrono::steady_clock::now();
        std::unique_ptr<Solver_interface> s = make_solver(mesh, Options(), backend);
        const auto t2 = std::chrono::steady_clock::now();
        to_mesh = std::chrono::duration<double>(t1 - t0).count();
        solver = std::chrono::duration<double>(t2 - t1).count();
      }
      py::dict d;
      d["soup_to_mesh"] = to_mesh;
      d["solver"] = solver;
      return d;
    },
    py::arg("V"), py::arg("F"), py::arg("backend") = "auto",
    R"(The benchmark's reference (benchmark/python/binding_overhead.py), not part of the API: what a C++ program
holding V and F does, triangle_soup_to_mesh() into a Surface_mesh, then the Trivial_connection_solver
constructor on it, with default options. Returns the seconds of each: {"soup_to_mesh": s, "solver": s}.)");

  py::class_<Result>(m, "Result", "What Solver.solve() returns: the connection, the field and the report.")
    .def_readonly("connection", &Result::connection,
                  "(e,) float64: x of each interior edge, for the halfedge from edges[i, 0] to edges[i, 1]")
    .def_readonly("edges", &Result::edges, "(e, 2) int64: the interior edges (i < j), in the mesh's edge order")
    .def_readonly("field", &Result::field, "(m, 3) float64: a unit tangent vector per face (one of the n directions)")
    .def_readonly("directions", &Result::directions, "(m, n, 3) float64 for n > 1: the n directions per face; else None (and with "
                  "solve(all_directions=False))")
    .def_readonly("n", &Result::n, "n of the n-direction field")
    .def_readonly("energy", &Result::energy, "sum over interior edges of w_e x_e^2")
    .def_readonly("guidance_energy", &Result::guidance_energy, "mu sum_g d_g^2 over the guided faces")
    .def_readonly("max_residual", &Result::max_residual, "max over interior vertices of |K_v + sum x - 2 pi k_v|")
    .def_readonly("max_loop_residual", &Result::max_loop_residual, "max residual over the loops")
    .def_readonly("loop_periods", &Result::loop_periods, "the integer of every loop (Solver.number_of_loops)")
    .def_readonly("boundary_indices", &Result::boundary_indices, "{loop: Fraction}: the index of every boundary loop")
    .def_readonly("integers_proven_optimal", &Result::integers_proven_optimal,
                  "True when the loop integers were proven energy-optimal")
    .def_readonly("energy_lower_bound", &Result::energy_lower_bound,
                  "no choice of the free integers gives less energy than this")
    .def_readonly("rounding_energy", &Result::rounding_energy, "the energy with the integers rounded one by one")
    .def_readonly("constraints", &Result::constraints,
                  "one dict per link joining two constrained (or guided) faces: component, from_face, to_face, "
                  "length (edges crossed), period (its integer), residual, decided (True for a link between two "
                  "faces that touch, whose integer is the rounding, the short way from one target to the other, "
                  "rather than a free integer of the lattice problem)")
    .def_readonly("guidance", &Result::guidance, "one dict per guided face: face, mismatch")
    .def_readonly("timings", &Result::timings,
                  "seconds in C++: solve (Trivial_connection_solver::solve), field (compute_field) and outputs "
                  "(the arrays filled); the rest of a call's time is the binding's")
    .def("__repr__", [](const Result& r) {
      return "<trivial_connections.Result n=" + std::string(py::str(r.n)) +
             " energy=" + std::string(py::str(r.energy)) + " max_residual=" + std::string(py::str(r.max_residual)) +
             ">";
    });

  py::class_<Python_solver> solver(m, "Solver", R"(A prefactored trivial-connection solver for one triangle mesh.

Solver(V, F, weights="hodge", backend="auto", constrained_faces=None, guided_faces=None,
       guidance_weight=1.0, align_boundary=False, align_features=None, feature_smoothing=3, feature_n=4)

V: (n, 3) array of real numbers (any float or integer dtype, any layout); F: (m, 3) array of vertex indices
(any integer dtype). The mesh must be an oriented 2-manifold of triangles (boundaries allowed). Building the
solver factors the system once; every solve() after that costs back-substitutions only.
weights: "hodge" (w_e = |e| / |e*|) or "unit". backend: "auto" (SimplicialLDLT or CHOLMOD by predicted cost,
as the program), "ldlt" or "cholmod". constrained_faces / guided_faces: face numbers whose direction
solve() prescribes (exactly) or draws the field towards (with weight guidance_weight).
align_boundary: the field follows the boundary.
align_features: True (threshold 30 degrees) or a threshold in degrees in [0, 180]: the faces beside the mesh's
sharp feature curves are pinned to the curves' directions (feature_aligned_faces() with n=feature_n and
smoothing=feature_smoothing), as the program's --align-features: the user's constrained_faces and guided_faces
win on the faces they name, and with align_boundary the boundary faces are left to the boundary alignment.
solve(), place_singularities() and refine_singularities() then take the feature pins' directions themselves
(directions= is needed only for the user's own constrained and guided faces); set_constraints() merges the
feature pins again with its new faces. feature_pins and feature_alignment say what was pinned. A mesh with no
sharp edge pins nothing (feature_alignment["number_of_sharp_edges"] == 0), which is not an error.
progress: None or a callable progress(phase, fraction) for the constructor's phases ("mesh setup", "geometry",
"trees", "assembly", "factorization", "loop metric"; fraction 0 at a phase's start, 1 at its end; from arrays,
whose mesh setup the binding does, only the end of "mesh setup"), also logged to the logger "trivial_connections";
Ctrl-C (KeyboardInterrupt) is honoured between them, and an exception of progress stops there too (no solver is
made). A single phase (the factorization of a large mesh) is not interrupted: Ctrl-C waits for its end.
Raises InvalidInput for a mesh the package refuses (code and where say why), and (invalid_argument) for a
threshold that is negative, over 180 or NaN or feature_smoothing < 0, and (invalid_symmetry_order) for feature_n
outside 1 to MAX_SYMMETRY_ORDER.)");
  // Solver() and Solver.from_file() take the same options after their own arguments
  const auto options = std::make_tuple(
    py::arg("weights") = "hodge", py::arg("backend") = "auto", py::arg("constrained_faces") = py::none(),
    py::arg("guided_faces") = py::none(), py::arg("guidance_weight") = 1.0, py::arg("align_boundary") = false,
    py::arg("align_features") = py::none(), py::arg("feature_smoothing") = TC::default_feature_smoothing,
    py::arg("feature_n") = 4, py::arg("progress") = py::none());
  std::apply(
    [&](const auto&... option) {
      solver.def(py::init(solver_constructor("Solver()", &mesh_of_V_F)), py::arg("V"), py::arg("F"), py::kw_only(),
                 option...);
      solver.def_static(
        "from_file", solver_constructor("Solver.from_file()", &mesh_of_path), py::arg("path"),
        py::arg("triangulate") = false, py::kw_only(), option...,
        "A solver for the mesh of an OFF, OBJ, PLY, STL or GOCAD file (path: str, bytes or os.PathLike; the "
        "package's validating reader, as read_mesh(); triangulate=True splits polygons). Options as Solver(), "
        "align_features and progress included (the program's --align-features [DEGREES]).");
    },
    options);
  solver
    .def("solve", &Python_solver::solve, py::arg("singularities"), py::arg("n") = 1, py::arg("directions") = py::none(),
         py::arg("loop_periods") = py::none(), py::kw_only(), py::arg("all_directions") = true,
         py::arg("progress") = py::none(),
         R"(The trivial connection with exactly these singularities, and its field.

singularities: {vertex: index} or a sequence of (vertex, index) pairs (e.g. a (k, 2) integer array); an index
is an int, a fractions.Fraction or a string "p/q", a multiple of 1/n. On every closed component the indices
must sum to its Euler characteristic (Poincare-Hopf; see Solver.topology). n: 1 vectors, 2 lines, 4 crosses,
..., an integer from 1 to MAX_SYMMETRY_ORDER (else InvalidInput invalid_symmetry_order, a ValueError).
directions: for constrained or guided faces, an (m, 3) array (one row per face; the other rows are not read)
or {face: (3,) vector}; a ValueError when the solver has no constrained or guided face (it would be ignored).
loop_periods: one int (or None: chosen by the solver) per loop.
all_directions: False leaves Result.directions None (Result.field alone), which saves 3 n numbers per face and
their time (most of a solve's for large n); with True, a MemoryError before the solve when those numbers would
not fit in the memory available.
progress: None or a callable progress(phase, fraction), called between the phases ("solve", "loop integers",
"field") with fraction 0 at a phase's start, 1 at its end; the phases are also logged to the logger
"trivial_connections" (INFO, DEBUG in between). Ctrl-C (KeyboardInterrupt) is honoured between phases: the call
is abandoned and the solver stays usable; an exception raised by progress abandons it too.
Returns a Result. Releases the GIL: solves from several threads run concurrently.)")
    .def("set_constraints", &Python_solver::set_constraints, py::arg("constrained_faces") = py::none(),
         py::arg("guided_faces") = py::none(),
         "Changes the constrained and guided faces (as the constructor's options); returns what it did. With "
         "align_features, the feature pins are merged again with the new faces (the user's win).")
    .def_property_readonly("feature_pins", &Python_solver::feature_pins,
                           "With align_features: (faces, directions), a (k,) int64 and a (k, 3) float64 array, the "
                           "feature pins the solver holds besides the user's constrained faces (increasing face "
                           "number; unit vectors tangent to their faces). None without align_features.")
    .def_property_readonly("feature_alignment", &Python_solver::feature_alignment,
                           "With align_features: the report of feature_aligned_faces() (see there) and pinned (the "
                           "faces in feature_pins), named_by_user (left to constrained_faces), on_guided_faces (left "
                           "to guided_faces) and on_aligned_boundary (left to align_boundary). None without "
                           "align_features.")
    .def_property_readonly("loops", &Python_solver::loops,
                           "The loops whose integers loop_periods gives, in that order: dicts with kind (\"boundary\" "
                           "or \"generator\": the 2g homology generators of each component), component and "
                           "halfedges, a (k, 2) array of the (source, target) vertices of the halfedges crossed, each "
                           "from the face on its left to the face on its right.")
    .def_property_readonly(
      "build_timings",
      [](const Python_solver& s) {
        py::dict d;
        d["mesh"] = s.m_mesh_seconds;
        d["solver"] = s.m_solver_seconds;
        return d;
      },
      "seconds in C++ while the solver was built: mesh (the arrays validated and made into a Surface_mesh and the "
      "solver's arrays, or the file read into a validated Surface_mesh) and solver (the C++ constructor: from "
      "those arrays, or from the Surface_mesh of the file)")
    .def_property_readonly("number_of_vertices", &Python_solver::number_of_vertices,
                           "the mesh's vertices: the rows of V (and of Solver.vertices)")
    .def_property_readonly("number_of_faces", &Python_solver::number_of_faces,
                           "the mesh's triangles: the rows of F (and of Solver.faces, Result.field)")
    .def_property_readonly("topology", &Python_solver::topology,
                           "One dict per connected component, in the order of the components of Result and loops: "
                           "number_of_faces, euler_characteristic (V - E + F), genus ((2 - chi - b) / 2), "
                           "number_of_boundary_loops (b), closed (b == 0) and faces ((k,) int64, its face numbers). "
                           "On a closed component the singularity indices of solve() must sum to "
                           "euler_characteristic (2 on a sphere, 0 on a torus); the program prints the same lines.")
    .def("__repr__", &Python_solver::repr)
    .def_property_readonly("number_of_loops", &Python_solver::number_of_loops,
                           "boundary loops and homology generators: the entries of loop_periods")
    .def_property_readonly("backend", &Python_solver::backend, "\"ldlt\", \"cholmod\" or \"auto\"")
    .def_property_readonly("edges", &Python_solver::edges, "(e, 2) int64: the interior edges, as in Result.edges")
    .def_property_readonly("vertices", &Python_solver::vertices, "(n, 3) float64: the mesh's points (V)")
    .def_property_readonly("faces", &Python_solver::faces,
                           "(m, 3) int64: the mesh's triangles, each row as in F or the file (its corners in their order; the "
                           "triangles of a face split by from_file(triangulate=True) in their order)")
    .def_property_readonly("weights", &Python_solver::weights,
                           "(e,) float64: the weight w_e of each interior edge in the energy, as in Result.edges");
  return solver;
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_SOLVER_BINDINGS_H
