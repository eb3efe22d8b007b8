// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// What Solver gives out (Python_solver methods declared in solver_state.h): the Result of a solve, the loops,
// the topology, repr() and the mesh's arrays; and a Result read back (streamlines.h, files.h).
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_SOLVER_OUTPUTS_H
#define TRIVIAL_CONNECTIONS_PYTHON_SOLVER_OUTPUTS_H

namespace {

// Result of the solve's output: its vectors become the arrays, without a copy
Result Python_solver::result_of(Solve_output&& out, int n) const
{
  Result r;
  const TC::Solve_report& report = out.report;
  const py::ssize_t ne = py::ssize_t(out.connection.size()), nf = py::ssize_t(m_mesh->number_of_faces());
  r.connection = owning_array(std::move(out.connection), {ne});
  r.edges = edges();
  r.field = owning_array(std::move(out.field), {nf, 3});
  r.directions = n > 1 && !out.directions.empty()
                   ? py::object(owning_array(std::move(out.directions), {nf, py::ssize_t(n), 3}))
                   : py::none();
  r.n = py::int_(n);
  r.energy = py::float_(report.energy);
  r.guidance_energy = py::float_(report.guidance_energy);
  r.max_residual = py::float_(report.max_vertex_residual);
  r.max_loop_residual = py::float_(report.max_loop_residual);
  r.integers_proven_optimal = py::bool_(report.integers_proven_optimal);
  r.energy_lower_bound = py::float_(report.energy_lower_bound);
  r.rounding_energy = py::float_(report.rounding_energy);
  py::list periods;
  py::dict boundary;
  for(std::size_t l = 0; l < report.loops.size(); ++l) {
    periods.append(report.loops[l].period);
    if(report.loops[l].kind == TC::Loop_kind::boundary)
      boundary[py::int_(l)] = fraction(report.loops[l].index);
  }
  r.loop_periods = periods;
  r.boundary_indices = boundary;
  py::list constraints;
  for(const auto& c : report.constraints) {
    py::dict d;
    d["component"] = c.component;
    d["from_face"] = c.from_face;
    d["to_face"] = c.to_face;
    d["length"] = c.length;
    d["period"] = c.period;
    d["residual"] = c.residual;
    d["decided"] = c.decided;
    constraints.append(d);
  }
  r.constraints = constraints;
  py::list guidance;
  for(const auto& g : report.guidance) {
    py::dict d;
    d["face"] = g.face;
    d["mismatch"] = g.mismatch;
    guidance.append(d);
  }
  r.guidance = guidance;
  py::dict timings;
  timings["solve"] = out.solve_seconds;
  timings["field"] = out.field_seconds;
  timings["outputs"] = out.output_seconds;
  r.timings = timings;
  return r;
}

// the loops of loop_periods: boundary loops and homology generators, each with the halfedges it crosses as
// (source, target) vertex pairs, crossed from the face on their left to the other one
py::list Python_solver::loops() const
{
  py::list out;
  for(const auto& [boundary, component, halfedges] : m_solver->loops()) {
    std::vector<std::int64_t> pairs;
    for(halfedge_descriptor h : halfedges) {
      pairs.push_back(std::int64_t(m_mesh->source(h)));
      pairs.push_back(std::int64_t(m_mesh->target(h)));
    }
    py::dict d;
    d["kind"] = boundary ? "boundary" : "generator";
    d["component"] = component;
    d["halfedges"] = owning_array(std::move(pairs), {py::ssize_t(halfedges.size()), 2});
    out.append(d);
  }
  return out;
}

// per connected component: its faces, Euler characteristic, genus and boundary loops (as the program prints them)
py::list Python_solver::topology() const
{
  const std::vector<TC::Component_report> reports = m_solver->components();
  const std::vector<std::size_t> of_face = m_solver->face_components();
  std::vector<std::vector<std::int64_t>> faces(reports.size());
  for(std::size_t f = 0; f < of_face.size(); ++f)
    faces[of_face[f]].push_back(std::int64_t(f));
  py::list out;
  for(std::size_t c = 0; c < reports.size(); ++c) {
    py::dict d;
    d["number_of_faces"] = reports[c].number_of_faces;
    d["euler_characteristic"] = reports[c].euler_characteristic;
    d["genus"] = reports[c].genus;
    d["number_of_boundary_loops"] = reports[c].number_of_boundary_loops;
    d["closed"] = reports[c].number_of_boundary_loops == 0;
    const py::ssize_t k = py::ssize_t(faces[c].size());
    d["faces"] = owning_array(std::move(faces[c]), {k});
    out.append(d);
  }
  return out;
}

// repr(Solver): the mesh, its components, the loops, the backend and what the solver holds
std::string Python_solver::repr() const
{
  const std::vector<TC::Component_report> reports = m_solver->components();
  std::string chi;
  for(std::size_t c = 0; c < reports.size() && c < 4; ++c)
    chi += (c ? ", " : "") + std::to_string(reports[c].euler_characteristic);
  if(reports.size() > 4)
    chi += ", ...";
  const auto plural = [](std::size_t k, const char* word) {
    return std::to_string(k) + " " + word + (k == 1 ? "" : "s");
  };
  std::string out = "<trivial_connections.Solver: " + std::to_string(m_mesh->number_of_vertices()) +
        (m_mesh->number_of_vertices() == 1 ? " vertex, " : " vertices, ") + plural(m_mesh->number_of_faces(), "face") +
        ", " + plural(reports.size(), "component") + " (chi " + chi + "), " +
        plural(m_solver->number_of_loops(), "loop") + ", backend \"" + m_solver->backend() + "\"";
  if(m_user_pins > 0)
    out += ", " + std::to_string(m_user_pins.load()) + " constrained or guided faces";
  const std::optional<std::size_t> feature_pins =
    reading([&] { return m_features ? std::optional<std::size_t>(m_features->pinned.size()) : std::nullopt; });
  if(feature_pins)
    out += ", " + std::to_string(*feature_pins) + " feature pins";
  const int last = m_last_n;
  if(last > 0)
    out += ", last solve n=" + std::to_string(last);
  return out + ">";
}

py::array_t<double> Python_solver::vertices() const
{
  std::vector<double> p;
  p.reserve(3 * m_mesh->number_of_vertices());
  for(auto v : m_mesh->vertices())
    for(int i = 0; i < 3; ++i)
      p.push_back(CGAL::to_double(m_mesh->point(v)[i]));
  return owning_array(std::move(p), {py::ssize_t(m_mesh->number_of_vertices()), 3});
}

py::array_t<std::int64_t> Python_solver::faces() const
{
  std::vector<std::int64_t> t = corners_in_input_order(*m_mesh);
  return owning_array(std::move(t), {py::ssize_t(m_mesh->number_of_faces()), 3});
}

py::array_t<double> Python_solver::weights() const
{
  std::vector<double> w = m_solver->weights();
  const py::ssize_t ne = py::ssize_t(w.size());
  return owning_array(std::move(w), {ne});
}

// one read-only array for the solver and all its results
py::object Python_solver::edges() const
{
  if(!m_edges_array) {
    std::vector<std::int64_t> copy = m_solver->edge_vertices();
    const py::ssize_t ne = py::ssize_t(copy.size() / 2);
    py::array_t<std::int64_t> a = owning_array(std::move(copy), {ne, 2});
    a.attr("setflags")(py::arg("write") = false);
    m_edges_array = a;
  }
  return m_edges_array;
}

// Solver.feature_pins: (faces, directions) of the feature pins the solver holds, or None
py::object Python_solver::feature_pins() const
{
  std::vector<std::int64_t> faces;
  std::vector<double> xyz;
  const bool on = reading([&] {
    if(!m_features)
      return false;
    for(std::size_t i : m_features->pinned) {
      faces.push_back(std::int64_t(m_features->all.faces[i]));
      xyz.insert(xyz.end(), m_features->all.directions.begin() + 3 * std::ptrdiff_t(i),
                 m_features->all.directions.begin() + 3 * std::ptrdiff_t(i) + 3);
    }
    return true;
  });
  if(!on)
    return py::none();
  const py::ssize_t k = py::ssize_t(faces.size());
  return py::make_tuple(owning_array(std::move(faces), {k}), owning_array(std::move(xyz), {k, 3}));
}

// Solver.feature_alignment: the report of feature_aligned_faces() and what the merge did, or None
py::object Python_solver::feature_alignment() const
{
  std::optional<Features> f = reading([&] { return m_features; });
  if(!f)
    return py::none();
  py::dict d = feature_report_dict(f->all.report);
  d["pinned"] = f->pinned.size();
  d["named_by_user"] = f->named_by_user;
  d["on_guided_faces"] = f->on_guided_faces;
  d["on_aligned_boundary"] = f->on_aligned_boundary;
  return d;
}

// ---- a Result read back --------------------------------------------------------------------------------

// x per halfedge from a Result of this solver (its edges are the mesh's interior edges, in order)
std::vector<double> Python_solver::halfedge_angles(const Result& result) const
{
  const auto connection = Doubles::ensure(result.connection);
  std::vector<double> x(m_mesh->number_of_halfedges(), 0.);
  if(!connection || std::size_t(connection.size()) != m_solver->edge_vertices().size() / 2)
    throw py::value_error("the result is not one of this solver (its number of edges differs)");
  std::size_t i = 0;
  for(auto e : m_mesh->edges()) {
    if(m_mesh->is_border(e))
      continue;
    halfedge_descriptor h = m_mesh->halfedge(e);
    if(std::size_t(m_mesh->source(h)) > std::size_t(m_mesh->target(h)))
      h = m_mesh->opposite(h);
    x[std::size_t(h)] = connection.data()[i];
    x[std::size_t(m_mesh->opposite(h))] = -connection.data()[i];
    ++i;
  }
  return x;
}

// the field per face from a Result of this solver
std::vector<Kernel::Vector_3> Python_solver::field_of(const Result& result) const
{
  const auto f = Doubles::ensure(result.field);
  if(!f || f.ndim() != 2 || std::size_t(f.shape(0)) != m_mesh->number_of_faces() || f.shape(1) != 3)
    throw py::value_error("the result is not one of this solver (its number of faces differs)");
  std::vector<Kernel::Vector_3> field(m_mesh->number_of_faces());
  for(std::size_t i = 0; i < field.size(); ++i)
    field[i] = vector_at(f.data(), i);
  return field;
}

// {vertex: Fraction}, as the placement and refinement return the singularities
py::dict Python_solver::singularity_dict(const Singularities& s)
{
  py::dict d;
  for(const auto& [v, k] : s)
    d[py::int_(v)] = fraction(k);
  return d;
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_SOLVER_OUTPUTS_H
