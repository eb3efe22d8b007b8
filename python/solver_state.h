// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The Python class Solver (Python_solver) and its Result: the class with its state, its construction and the
// feature pins it holds. Its methods are defined in solving.h (solve(), set_constraints() and their arguments),
// solver_outputs.h (Result, topology and the mesh's arrays), placement.h, streamlines.h and files.h; its binding
// in solver_bindings.h.
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_SOLVER_STATE_H
#define TRIVIAL_CONNECTIONS_PYTHON_SOLVER_STATE_H

namespace {

struct Result
{
  py::object connection, edges, field, directions, energy, guidance_energy, max_residual, max_loop_residual,
    loop_periods, boundary_indices, integers_proven_optimal, energy_lower_bound, rounding_energy, constraints,
    guidance, n, timings;
};

class Python_solver
{
public:
  // `mesh` keeps its mesh until the solver is built and the mesh complete: on an error before, its destructor waits
  // for the mesh's construction before freeing it
  Python_solver(Mesh_of_arrays mesh, const std::string& weights, const std::string& backend,
                const py::object& constrained, const py::object& guided, double guidance_weight, bool align_boundary,
                const Feature_options& features, const TC::Progress_callback& progress);

  // defined in solving.h
  Result solve(const py::object& singularities, const py::object& n_in, const py::object& directions,
               const py::object& loop_periods, bool all_directions, const py::object& progress);
  py::dict set_constraints(const py::object& constrained, const py::object& guided);

  // defined in placement.h
  py::tuple place_singularities(const py::object& n_in, bool align_boundary, const py::object& alignment_guide,
                                double strength, const py::object& fixed, const py::object& loop_periods,
                                const py::object& directions, const py::object& progress);
  py::tuple principal_curvature_guide() const;
  std::vector<std::size_t> spread_guided_faces(const py::object& guide, std::size_t count) const;
  py::tuple refine_singularities(const py::object& start, const py::object& n_in, const py::object& directions,
                                 const py::object& loop_periods, const py::object& fixed_vertices, bool cancel_pairs,
                                 const py::object& maximum_trials_or_none, const py::object& progress);

  // defined in streamlines.h
  // the polylines of the field of `result`, from the barycentres of `seed_faces` (default: every face)
  py::list trace_streamlines(const Result& result, const py::object& singularities, const py::object& seed_faces,
                             std::size_t maximum_faces_per_ray);

  // defined in quad_mesh.h
  // the quads of the cross field of `result`: (vertices, quads, report)
  py::tuple quad_mesh(const Result& result, const py::object& singularities, const py::object& quad_size,
                      const py::object& target_faces, const std::string& rounding, double max_quads,
                      const py::object& feature_edges, double scale_smoothness, bool untangle,
                      double cone_mode_weight);
  // the singularities closer than H to a feature edge moved H away: (singularities, report)
  py::tuple move_singularities_off_features(const py::object& singularities, const py::object& feature_edges,
                                            const py::object& quad_size, const py::object& target_faces,
                                            const py::object& fixed_vertices);

  // defined in files.h
  // the field of `result` as a field file (.txt), or the mesh with it and the singularities as a VTK (.vtk) or PLY
  // (.ply) file, written completely or not at all
  void write_field(const py::object& path_in, const Result& result, const py::object& singularities) const;

  // defined in solver_outputs.h
  // the loops of loop_periods: boundary loops and homology generators, each with the halfedges it crosses as
  // (source, target) vertex pairs, crossed from the face on their left to the other one
  py::list loops() const;
  // per connected component: its faces, Euler characteristic, genus and boundary loops (as the program prints them)
  py::list topology() const;
  std::string repr() const;
  std::size_t number_of_vertices() const { return m_mesh->number_of_vertices(); }
  std::size_t number_of_faces() const { return m_mesh->number_of_faces(); }
  std::size_t number_of_loops() const { return m_solver->number_of_loops(); }
  std::string backend() const { return m_solver->backend(); }
  py::array_t<double> vertices() const;
  py::array_t<std::int64_t> faces() const;
  py::array_t<double> weights() const;
  // one read-only array for the solver and all its results
  py::object edges() const;
  // Solver.feature_pins: (faces, directions) of the feature pins the solver holds, or None
  py::object feature_pins() const;
  // Solver.feature_alignment: the report of feature_aligned_faces() and what the merge did, or None
  py::object feature_alignment() const;

private:
  // The feature pins of Solver(align_features=...): all the faces beside the feature curves, and which of them the
  // solver holds (the others are named by the user's constrained or guided faces, or on an aligned boundary)
  struct Features
  {
    Feature_pins all;
    std::vector<std::size_t> pinned; // entries of all.faces given to the solver
    std::size_t named_by_user = 0, on_guided_faces = 0, on_aligned_boundary = 0;
  };

  // The optional per-face directions and loop periods of a call, read with the GIL
  struct Optional_inputs
  {
    std::optional<std::vector<Kernel::Vector_3>> directions;
    std::optional<Loop_periods> periods;
    const std::vector<Kernel::Vector_3>* directions_or_null() const { return directions ? &*directions : nullptr; }
    const Loop_periods* periods_or_null() const { return periods ? &*periods : nullptr; }
  };

  // f() without the GIL, beside the solver's other readers (solves, placement), never during set_constraints()
  template <class F>
  auto reading(F&& f) const -> decltype(f())
  {
    py::gil_scoped_release unlocked;
    std::shared_lock<std::shared_mutex> lock(m_mutex);
    return f();
  }

  // f(the call's targets: `user`'s directions with the feature pins', or null when neither) as reading() does
  template <class F>
  auto reading_with_targets(const std::optional<std::vector<Kernel::Vector_3>>& user, F&& f) const
  {
    return reading([&] {
      const auto targets = with_feature_targets(user);
      return f(targets ? &*targets : nullptr);
    });
  }

  // f() without the GIL, alone: set_constraints() waits for the readers and they for it
  template <class F>
  auto writing(F&& f) -> decltype(f())
  {
    py::gil_scoped_release unlocked;
    std::unique_lock<std::shared_mutex> lock(m_mutex);
    return f();
  }

  // the feature pins, below
  std::vector<face_descriptor> merge_feature_pins(const Mesh& mesh, const std::vector<face_descriptor>& constrained,
                                                  const std::vector<face_descriptor>& guided, Features& features) const;
  static void known_feature_directions(const Mesh& mesh, const Features& features, int n, Options& o);
  std::optional<std::vector<Kernel::Vector_3>> with_feature_targets(
    const std::optional<std::vector<Kernel::Vector_3>>& user) const;

  // the arguments of the calls, defined in solving.h
  void check_directions_are_read(const py::object& directions, const char* call) const;
  void check_directions_fit(int n) const;
  Optional_inputs optional_inputs(const py::object& directions, const py::object& loop_periods) const;
  static std::optional<Loop_periods> periods_of(const py::object& loop_periods);
  std::vector<Kernel::Vector_3> directions_of(const py::object& directions) const;

  // the outputs, and a Result read back, defined in solver_outputs.h
  Result result_of(Solve_output&& out, int n) const;
  std::vector<double> halfedge_angles(const Result& result) const;
  std::vector<Kernel::Vector_3> field_of(const Result& result) const;
  static py::dict singularity_dict(const Singularities& s);

public:
  double m_mesh_seconds = 0, m_solver_seconds = 0; // reading the arrays or the file into the mesh; the C++ solver

private:
  std::unique_ptr<Mesh> m_mesh; // before the solver, which refers to it
  std::unique_ptr<Solver_interface> m_solver;
  bool m_align_boundary = false;
  bool m_align_features = false;       // Solver(align_features=...) on (m_features is engaged for good)
  std::atomic<std::size_t> m_user_pins{0}; // the user's constrained and guided faces (not the feature pins)
  std::atomic<int> m_last_n{0};        // n of the last solve (0: none yet), for repr()
  std::optional<Features> m_features; // Solver(align_features=...); changed by set_constraints() under m_mutex
  int m_feature_n = 4;                 // the n of the feature pins (feature_n)
  mutable py::object m_edges_array; // made on first use, with the GIL
  mutable std::shared_mutex m_mutex;
};

Python_solver::Python_solver(Mesh_of_arrays mesh, const std::string& weights, const std::string& backend,
                             const py::object& constrained, const py::object& guided, double guidance_weight,
                             bool align_boundary, const Feature_options& features,
                             const TC::Progress_callback& progress)
{
  Options o;
  if(weights == "unit")
    o.weighting = TC::Weighting::unit;
  else if(weights != "hodge")
    throw py::value_error("weights must be \"hodge\" or \"unit\", got \"" + weights + "\"");
  o.constrained = faces_of(constrained, mesh.number_of_faces, "constrained_faces");
  o.guided = faces_of(guided, mesh.number_of_faces, "guided_faces");
  m_user_pins = o.constrained.size() + o.guided.size();
  o.progress = progress;
  o.guidance_weight = guidance_weight;
  o.align_boundary = align_boundary;
  check_backend(backend);
  m_align_boundary = align_boundary;
  py::gil_scoped_release unlocked;
  const auto start = std::chrono::steady_clock::now();
  if(features.on) { // the feature pins need the whole mesh (from arrays, it is still being built)
    mesh.wait_for_mesh();
    m_features.emplace();
    m_align_features = true;
    m_features->all = feature_pins_of(*mesh.mesh, features.threshold, features.n, features.smoothing);
    o.constrained = merge_feature_pins(*mesh.mesh, o.constrained, o.guided, *m_features);
    m_feature_n = features.n;
    known_feature_directions(*mesh.mesh, *m_features, features.n, o);
  }
  m_solver = make_solver(mesh, o, backend); // the mesh complete when it returns
  m_solver_seconds = seconds_since(start);
  m_mesh = std::move(mesh.mesh);
}

// ---- the feature pins ----------------------------------------------------------------------------------

// The constrained faces of the solver: the user's `constrained`, then the feature pins on the faces that are
// neither constrained nor guided by the user (the user wins, as the program's --constraints), and, with
// align_boundary, not on the boundary (the solver refuses targets there; the field follows the boundary).
// `features.pinned` and its counts are set.
std::vector<face_descriptor> Python_solver::merge_feature_pins(const Mesh& mesh,
                                                               const std::vector<face_descriptor>& constrained,
                                                               const std::vector<face_descriptor>& guided,
                                                               Features& features) const
{
  std::vector<char> taken(mesh.number_of_faces(), 0);
  for(face_descriptor f : constrained)
    taken[std::size_t(f)] = 1;
  for(face_descriptor f : guided)
    taken[std::size_t(f)] = 2;
  features.pinned.clear();
  features.named_by_user = features.on_guided_faces = features.on_aligned_boundary = 0;
  std::vector<face_descriptor> out = constrained;
  for(std::size_t i = 0; i < features.all.faces.size(); ++i) {
    const face_descriptor f(Mesh::size_type(features.all.faces[i]));
    if(taken[std::size_t(f)]) {
      ++(taken[std::size_t(f)] == 1 ? features.named_by_user : features.on_guided_faces);
      continue;
    }
    bool on_boundary = false;
    for(auto h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh))
      on_boundary = on_boundary || mesh.is_border(mesh.opposite(h));
    if(m_align_boundary && on_boundary) {
      ++features.on_aligned_boundary;
      continue;
    }
    features.pinned.push_back(i);
    out.push_back(f);
  }
  return out;
}

// The directions of the pinned feature faces written into `per_face` (one vector per face)
void put_feature_directions(const Feature_pins& all, const std::vector<std::size_t>& pinned,
                            std::vector<Kernel::Vector_3>& per_face)
{
  for(std::size_t i : pinned)
    per_face[all.faces[i]] = vector_at(all.directions.data(), i);
}

// The feature pins' directions (zero elsewhere: the user's come with each solve) and their n, for the solver's
// constructor: touching feature pins that disagree are then left to the lattice, as in the program
void Python_solver::known_feature_directions(const Mesh& mesh, const Features& features, int n, Options& o)
{
  o.known_directions.assign(mesh.number_of_faces(), CGAL::NULL_VECTOR);
  put_feature_directions(features.all, features.pinned, o.known_directions);
  o.known_n = n;
}

// The targets of a call (the user's directions, or none) with the feature pins' directions on their faces
// (those faces are not the user's: their rows are not read otherwise). Under the solver's lock.
std::optional<std::vector<Kernel::Vector_3>> Python_solver::with_feature_targets(
  const std::optional<std::vector<Kernel::Vector_3>>& user) const
{
  std::optional<std::vector<Kernel::Vector_3>> out = user;
  if(!m_features || m_features->pinned.empty())
    return out;
  if(!out)
    out.emplace(m_mesh->number_of_faces(), CGAL::NULL_VECTOR);
  put_feature_directions(m_features->all, m_features->pinned, *out);
  return out;
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_SOLVER_STATE_H
