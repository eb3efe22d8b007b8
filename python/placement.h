// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Placement: automatic placement of singularities, their refinement, curvature guides and guided faces
// (Solver_of and Python_solver methods declared in solver_backend.h and solver_state.h).
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_PLACEMENT_H
#define TRIVIAL_CONNECTIONS_PYTHON_PLACEMENT_H

namespace {

template <class SolverTraits>
TC::Placement_report
Solver_of<SolverTraits>::place(int n, bool align_boundary, const std::vector<Kernel::Vector_3>* guide, double strength,
                               const Singularities& fixed, const Loop_periods* periods,
                               const std::vector<Kernel::Vector_3>* directions, Singularities& placed,
                               const TC::Progress_callback& progress) const
{
  namespace P = TC::parameters;
  const auto kept = descriptors(fixed);
  std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> out;
  const Loop_periods none(m_solver->loops().size()); // every integer chosen, as without the parameter
  const auto np = P::progress(
    progress, P::symmetry_order(n, P::align_with_boundary(align_boundary, P::fixed_singularities(
                                                            kept, P::loop_periods(periods ? *periods : none)))));
  TC::Placement_report report;
  auto place_with = [&](const auto& with) {
    if(guide != nullptr) {
      auto guide_map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
        [guide](face_descriptor f) { return (*guide)[std::size_t(f)]; });
      return TC::place_singularities(*m_solver, std::back_inserter(out),
                                     P::alignment_guide(guide_map, P::alignment_strength(strength, with)));
    }
    return TC::place_singularities(*m_solver, std::back_inserter(out), with);
  };
  // the constrained faces' directions, held in the smooth field (without them, a solver with constrained faces
  // refuses as solve() does)
  if(directions != nullptr) {
    auto target_map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
      [directions](face_descriptor f) { return (*directions)[std::size_t(f)]; });
    report = place_with(P::face_directions(target_map, np));
  } else
    report = place_with(np);
  for(const auto& [v, k] : out)
    placed.emplace_back(std::size_t(v), k);
  return report;
}

template <class SolverTraits>
std::vector<Kernel::Vector_3>
Solver_of<SolverTraits>::curvature_guide(std::vector<std::pair<double, double>>& curvatures) const
{
  std::vector<Kernel::Vector_3> guide(m_mesh.number_of_faces(), CGAL::NULL_VECTOR);
  auto map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3&>(
    [&guide](face_descriptor f) -> Kernel::Vector_3& { return guide[std::size_t(f)]; });
  TC::principal_curvature_guide(*m_solver, map, &curvatures);
  return guide;
}

template <class SolverTraits>
std::vector<std::size_t>
Solver_of<SolverTraits>::spread(const std::vector<Kernel::Vector_3>& guide, std::size_t count) const
{
  auto map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
    [&guide](face_descriptor f) { return guide[std::size_t(f)]; });
  std::vector<std::size_t> faces;
  for(face_descriptor f : TC::spread_guided_faces(*m_solver, map, count))
    faces.push_back(std::size_t(f));
  return faces;
}

template <class SolverTraits>
TC::Refinement_report<vertex_descriptor>
Solver_of<SolverTraits>::refine(const Singularities& start, int n, const std::vector<Kernel::Vector_3>* directions,
                                const Loop_periods* periods, const std::vector<std::size_t>& fixed, bool cancel_pairs,
                                std::size_t trials, const TC::Progress_callback& progress)
{
  namespace P = TC::parameters;
  std::vector<double> x(m_mesh.number_of_halfedges(), 0.);
  auto halfedge_x = boost::make_function_property_map<halfedge_descriptor, double&>(
    [&x](halfedge_descriptor h) -> double& { return x[std::size_t(h)]; });
  // directions_of() gives one per face
  const auto target_map = face_direction_map(directions);
  std::vector<vertex_descriptor> fixed_vertices;
  for(std::size_t v : fixed)
    fixed_vertices.push_back(vertex_of(m_mesh, v));
  const Loop_periods none(m_solver->loops().size()); // every integer chosen, as without the parameter
  return TC::refine_singularities(
    *m_solver, descriptors(start), halfedge_x,
    P::symmetry_order(n, P::face_directions(target_map, P::loop_periods(periods ? *periods : none,
      P::fixed_vertices(fixed_vertices,
                        P::cancel_pairs(cancel_pairs, P::maximum_trials(trials, P::progress(progress))))))));
}

py::tuple Python_solver::place_singularities(const py::object& n_in, bool align_boundary,
                                             const py::object& alignment_guide, double strength,
                                             const py::object& fixed, const py::object& loop_periods,
                                             const py::object& directions, const py::object& progress)
{
  const int n = symmetry_order_of(n_in, "n");
  check_directions_are_read(directions, "place_singularities()");
  const Singularities kept = singularities_of(fixed);
  const Optional_inputs in = optional_inputs(alignment_guide, loop_periods);
  const Optional_inputs targets = optional_inputs(directions, py::none());
  Singularities placed;
  Progress_context context("place_singularities()", progress);
  const TC::Placement_report report =
    reading_with_targets(targets.directions, [&](const std::vector<Kernel::Vector_3>* pinned) {
      return m_solver->place(n, align_boundary, in.directions_or_null(), strength, kept, in.periods_or_null(), pinned,
                             placed, context.callback());
    });
  py::dict d;
  d["n"] = report.symmetry_order;
  d["aligned"] = report.aligned;
  d["field_energy"] = report.field_energy;
  d["rayleigh_quotients"] = report.rayleigh_quotients;
  d["iterations"] = report.iterations;
  d["max_rounding"] = report.max_rounding;
  py::dict per_index;
  for(const auto& [k, count] : report.singularities_per_index)
    per_index[fraction(k)] = count;
  d["singularities_per_index"] = per_index;
  d["fixed"] = report.fixed;
  d["units_removed"] = report.units_removed;
  d["units_added"] = report.units_added;
  d["pinned"] = report.pinned;
  return py::make_tuple(singularity_dict(placed), d);
}

py::tuple Python_solver::principal_curvature_guide() const
{
  std::vector<std::pair<double, double>> c;
  std::vector<Kernel::Vector_3> guide;
  guide = reading([&] { return m_solver->curvature_guide(c); }); // beside solves, never during set_constraints()
  std::vector<double> g, k;
  for(const auto& v : guide)
    for(int i = 0; i < 3; ++i)
      g.push_back(CGAL::to_double(v[i]));
  for(const auto& [a, b] : c) {
    k.push_back(a);
    k.push_back(b);
  }
  const py::ssize_t nf = py::ssize_t(guide.size());
  return py::make_tuple(owning_array(std::move(g), {nf, 3}), owning_array(std::move(k), {nf, 2}));
}

std::vector<std::size_t> Python_solver::spread_guided_faces(const py::object& guide, std::size_t count) const
{
  const std::vector<Kernel::Vector_3> g = directions_of(guide);
  return reading([&] { return m_solver->spread(g, count); });
}

py::tuple Python_solver::refine_singularities(const py::object& start, const py::object& n_in,
                                              const py::object& directions, const py::object& loop_periods,
                                              const py::object& fixed_vertices, bool cancel_pairs,
                                              const py::object& maximum_trials_or_none, const py::object& progress)
{
  const int n = symmetry_order_of(n_in, "n");
  check_directions_are_read(directions, "refine_singularities()");
  // None: no budget, to a local minimum
  const std::size_t maximum_trials = maximum_trials_or_none.is_none()
                                       ? (std::numeric_limits<std::size_t>::max)()
                                       : maximum_trials_or_none.cast<std::size_t>();
  const Singularities s = singularities_of(start);
  const Optional_inputs in = optional_inputs(directions, loop_periods);
  std::vector<std::size_t> fixed;
  if(!fixed_vertices.is_none())
    for(const py::handle v : py::iter(fixed_vertices))
      fixed.push_back(vertex_number(v));
  // it solves again and again on the solver: as a solve, beside other solves
  Progress_context context("refine_singularities()", progress);
  const TC::Refinement_report<vertex_descriptor> r =
    reading_with_targets(in.directions, [&](const std::vector<Kernel::Vector_3>* targets) {
      return m_solver->refine(s, n, targets, in.periods_or_null(), fixed, cancel_pairs, maximum_trials,
                              context.callback());
    });
  Singularities refined;
  for(const auto& [v, k] : r.singularities)
    refined.emplace_back(std::size_t(v), k);
  py::list moves;
  for(const auto& m : r.moves) {
    py::dict d;
    d["from"] = std::size_t(m.from);
    d["to"] = std::size_t(m.to);
    d["index"] = fraction(m.index);
    d["energy"] = m.energy;
    moves.append(d);
  }
  py::dict d;
  d["energy_before"] = r.energy_before;
  d["energy_after"] = r.energy_after;
  d["moves"] = moves;
  d["trials"] = r.trials;
  d["rounds"] = r.rounds;
  d["cancellations"] = r.cancellations;
  d["singularities_before"] = r.singularities_before;
  d["local_minimum"] = r.local_minimum;
  d["stop"] = r.stop == TC::Refinement_stop::local_minimum    ? "local_minimum"
              : r.stop == TC::Refinement_stop::maximum_trials ? "maximum_trials"
                                                              : "rejected_moves";
  return py::make_tuple(singularity_dict(refined), d);
}

void bind_placement(py::class_<Python_solver>& solver)
{
  solver
    .def("place_singularities", &Python_solver::place_singularities, py::kw_only(), py::arg("n") = 1,
         py::arg("align_boundary") = false, py::arg("alignment_guide") = py::none(),
         py::arg("alignment_strength") = 100.0, py::arg("fixed_singularities") = py::none(),
         py::arg("loop_periods") = py::none(), py::arg("directions") = py::none(), py::arg("progress") = py::none(),
         R"(Automatic placement: the singularities of the globally smoothest n-direction field (Knoeppel et al. 2013).

Returns (singularities, report): {vertex: Fraction}, which satisfies Poincare-Hopf on every closed component and
can be given to solve() as it is, and a dict (field_energy, singularities_per_index, ...). alignment_guide: an
(m, 3) array (or {face: vector}) of guide directions whose length weighs them (principal_curvature_guide()), for
Knoeppel's aligned field, with alignment_strength. fixed_singularities: kept as they are, the automatic ones nearest
give way. align_boundary, loop_periods: as for the solver and solve(). directions: as for solve(), required when
the solver has constrained faces: the field is held at their directions (report["pinned"] counts them); a
ValueError when it has none. n: as for solve(). progress: as for solve() (phase "placement", with fractions in
between for the eigensolver's iterations); Ctrl-C is honoured there.)")
    .def("principal_curvature_guide", &Python_solver::principal_curvature_guide,
         "Per face, the direction of largest principal curvature times the anisotropy |k1 - k2| ((m, 3) array), "
         "and the two principal curvatures ((m, 2) array, larger absolute value first): a guide for n = 2 or 4.")
    .def("spread_guided_faces", &Python_solver::spread_guided_faces, py::arg("guide"), py::arg("count"),
         "Up to count faces spread over the mesh, strongest guide first: guided_faces for set_constraints().")
    .def("refine_singularities", &Python_solver::refine_singularities, py::arg("singularities"), py::kw_only(),
         py::arg("n") = 1, py::arg("directions") = py::none(), py::arg("loop_periods") = py::none(),
         py::arg("fixed_vertices") = py::none(), py::arg("cancel_pairs") = false, py::arg("maximum_trials") = py::none(),
         py::arg("progress") = py::none(),
         "Moves singularities to neighbouring vertices (and, with cancel_pairs, cancels opposite pairs) until no "
         "single move or cancellation lowers the trivial connection's energy: a local minimum (maximum_trials: a "
         "budget of solves; None: none). Returns (singularities, report) with energy_before, energy_after, moves, "
         "cancellations, rounds, trials, singularities_before, local_minimum and stop ('local_minimum', "
         "'maximum_trials' or 'rejected_moves'). n, directions: as for solve(). progress: as for solve(), called in "
         "every trial solve; Ctrl-C is honoured between them (the refinement is abandoned, the solver stays "
         "usable).");
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_PLACEMENT_H
