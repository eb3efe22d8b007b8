// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Solver.solve() and Solver.set_constraints() (Python_solver methods declared in solver_state.h), and the
// arguments of the solver's calls read and checked: directions=, loop_periods=, the size of Result.directions.
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_SOLVING_H
#define TRIVIAL_CONNECTIONS_PYTHON_SOLVING_H

namespace {

Result Python_solver::solve(const py::object& singularities, const py::object& n_in, const py::object& directions,
                            const py::object& loop_periods, bool all_directions, const py::object& progress)
{
  const int n = symmetry_order_of(n_in, "n");
  const auto s = singularities_of(singularities);
  check_directions_are_read(directions, "solve()");
  const Optional_inputs in = optional_inputs(directions, loop_periods);
  if(all_directions && n > 1)
    check_directions_fit(n);
  Progress_context context("solve()", progress);
  Solve_output out = reading_with_targets(in.directions, [&](const std::vector<Kernel::Vector_3>* targets) {
    return m_solver->solve(s, n, targets, in.periods_or_null(), all_directions, context.callback());
  });
  m_last_n = n;
  return result_of(std::move(out), n);
}

py::dict Python_solver::set_constraints(const py::object& constrained, const py::object& guided)
{
  auto c = faces_of(constrained, m_mesh->number_of_faces(), "constrained_faces");
  const auto g = faces_of(guided, m_mesh->number_of_faces(), "guided_faces");
  const std::size_t user_pins = c.size() + g.size();
  const TC::Constraint_update u = writing([&] {
    TC::Constraint_update update;
    if(m_features) { // merged again with the new faces; kept as they were when the solver refuses them
      Features merged = *m_features;
      c = merge_feature_pins(*m_mesh, c, g, merged);
      Options known;
      known_feature_directions(*m_mesh, merged, m_feature_n, known);
      update = m_solver->set_constraints(c, g, known.known_directions, known.known_n);
      m_features = std::move(merged);
    } else
      update = m_solver->set_constraints(c, g, {}, 1);
    m_user_pins = user_pins; // after the solver took them (it may refuse them)
    return update;
  });
  py::dict d;
  d["refactored"] = u.refactored;
  d["links"] = u.links;
  d["links_outside_the_factor"] = u.links_outside_the_factor;
  d["new_forward_substitutions"] = u.new_forward_substitutions;
  return d;
}

// ---- the arguments of the calls ------------------------------------------------------------------------

// directions= of a call is read only for the user's constrained and guided faces: given (not None, not empty)
// to a solver without any, it would be ignored; a ValueError says so rather than a field that ignores it
void Python_solver::check_directions_are_read(const py::object& directions, const char* call) const
{
  if(directions.is_none() || m_user_pins > 0)
    return;
  if(py::isinstance<py::dict>(directions) && py::len(directions) == 0)
    return;
  throw py::value_error(std::string(call) + ": directions= is given but this solver has no constrained or guided "
                        "face, so it would be ignored: give the faces it is for as constrained_faces= or "
                        "guided_faces= (to Solver() or set_constraints()), or leave directions=None" +
                        (m_align_features ? std::string(" (the feature pins of align_features take their directions "
                                                        "themselves)")
                                          : std::string()));
}

// Result.directions holds 3 n numbers per face: refused, before the solve, when it could not fit in the
// machine's memory (n = 10^6 on a mesh of 10^4 faces would be 240 GB), with the way out
void Python_solver::check_directions_fit(int n) const
{
  const double bytes = 3. * double(n) * double(m_mesh->number_of_faces()) * sizeof(double);
  double memory = std::numeric_limits<double>::infinity(); // MemAvailable, else the physical memory
#ifdef __linux__
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if(pages > 0 && page > 0)
    memory = double(pages) * double(page);
  if(std::FILE* meminfo = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    double kb = 0;
    while(std::fgets(line, sizeof line, meminfo))
      if(std::sscanf(line, "MemAvailable: %lf kB", &kb) == 1) {
        memory = kb * 1024;
        break;
      }
    std::fclose(meminfo);
  }
#endif
  if(bytes > memory || bytes > double((std::numeric_limits<py::ssize_t>::max)())) {
    const std::string text = "Result.directions for n = " + std::to_string(n) + " on " +
                             std::to_string(m_mesh->number_of_faces()) + " faces would take " +
                             std::to_string(std::llround(bytes / 1e9)) + " GB (3 n numbers per face), more than " +
                             "the memory available: pass all_directions=False (Result.field alone)";
    PyErr_SetString(PyExc_MemoryError, text.c_str());
    throw py::error_already_set();
  }
}

// directions= and loop_periods= of a call (None: not given)
Python_solver::Optional_inputs Python_solver::optional_inputs(const py::object& directions,
                                                              const py::object& loop_periods) const
{
  Optional_inputs in;
  if(!directions.is_none())
    in.directions = directions_of(directions);
  in.periods = periods_of(loop_periods);
  return in;
}

// one integer or None per loop, or None (all chosen by the solver)
std::optional<Loop_periods> Python_solver::periods_of(const py::object& loop_periods)
{
  if(loop_periods.is_none())
    return std::nullopt;
  Loop_periods periods;
  for(const py::handle p : py::iter(loop_periods)) {
    if(p.is_none())
      periods.emplace_back();
    else if(py::isinstance<py::bool_>(p) || !PyIndex_Check(p.ptr()))
      throw py::type_error("loop_periods must hold integers or None, got " + std::string(py::repr(p)));
    else
      periods.emplace_back(int64_of(p, TC::Error_code::invalid_loop_periods, "the loop period"));
  }
  return periods;
}

// one target per face (rows of the faces that are neither constrained nor guided are not read), or a dict
// {face: vector}
std::vector<Kernel::Vector_3> Python_solver::directions_of(const py::object& directions) const
{
  const std::size_t nf = m_mesh->number_of_faces();
  std::vector<Kernel::Vector_3> targets(nf, CGAL::NULL_VECTOR);
  if(py::isinstance<py::dict>(directions)) {
    py::list keys;
    for(const auto& item : py::reinterpret_borrow<py::dict>(directions))
      keys.append(item.first);
    const std::vector<face_descriptor> faces = faces_of(keys, nf, "directions");
    std::size_t i = 0;
    for(const auto& item : py::reinterpret_borrow<py::dict>(directions))
      targets[std::size_t(faces[i++])] = vector_at(direction_of(item.second).data(), 0);
    return targets;
  }
  const py::array a = as_array(directions, "directions");
  check_rows_of_three(a, "directions", "fiu", "real numbers");
  if(std::size_t(a.shape(0)) != nf)
    throw py::value_error("directions must have one row per face (" + std::to_string(nf) + "), got " +
                          std::to_string(a.shape(0)));
  const auto d = Doubles::ensure(a);
  for(std::size_t f = 0; f < nf; ++f)
    targets[f] = vector_at(d.data(), f);
  return targets;
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_SOLVING_H
