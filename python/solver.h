// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The solver: the C++ solver of either backend behind one interface (Solver_of), the Python class Solver
// (Python_solver) and its Result; construction, solve(), set_constraints(), topology and the mesh's arrays.
// Its placement, streamlines and files are in placement.h, streamlines.h and files.h.
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_SOLVER_H
#define TRIVIAL_CONNECTIONS_PYTHON_SOLVER_H

namespace {

// ---- the solver, whatever its backend ------------------------------------------------------------------

struct Solve_output
{
  TC::Solve_report report;
  double solve_seconds = 0, field_seconds = 0, output_seconds = 0; // the C++ calls, and the outputs' vectors
  std::vector<double> connection; // per interior edge, in the order of `edges`
  std::vector<double> field;      // 3 per face
  std::vector<double> directions; // 3 n per face (n > 1)
};

class Solver_interface
{
public:
  virtual ~Solver_interface() = default;
  // all_directions: also the n directions per face (Solve_output::directions), for n > 1
  virtual Solve_output solve(const std::vector<std::pair<std::size_t, TC::Singularity_index>>& singularities,
                             int n, const std::vector<Kernel::Vector_3>* directions,
                             const Loop_periods* loop_periods, bool all_directions,
                             const TC::Progress_callback& progress) = 0;
  virtual std::size_t number_of_loops() const = 0;
  virtual std::vector<double> weights() const = 0; // w_e per interior edge, in edges() order
  // per loop of the solver: a boundary loop?, its component, the halfedges it crosses
  virtual std::vector<std::tuple<bool, std::size_t, std::vector<halfedge_descriptor>>> loops() const = 0;
  virtual TC::Placement_report place(int n, bool align_boundary, const std::vector<Kernel::Vector_3>* guide,
                                     double strength, const Singularities& fixed, const Loop_periods* periods,
                                     const std::vector<Kernel::Vector_3>* directions, Singularities& placed,
                                     const TC::Progress_callback& progress) const = 0;
  virtual std::vector<Kernel::Vector_3> curvature_guide(std::vector<std::pair<double, double>>& curvatures) const = 0;
  virtual std::vector<std::size_t> spread(const std::vector<Kernel::Vector_3>& guide, std::size_t count) const = 0;
  virtual TC::Refinement_report<vertex_descriptor> refine(const Singularities& start, int n,
                                                          const std::vector<Kernel::Vector_3>* directions,
                                                          const Loop_periods* periods,
                                                          const std::vector<std::size_t>& fixed, bool cancel_pairs,
                                                          std::size_t trials, const TC::Progress_callback& progress) = 0;
  // `known`: the targets known already (per face, zero where not known; empty: none), with their n
  virtual TC::Constraint_update set_constraints(const std::vector<face_descriptor>& constrained,
                                                const std::vector<face_descriptor>& guided,
                                                const std::vector<Kernel::Vector_3>& known, int known_n) = 0;
  virtual const char* backend() const = 0;
  // the topology of each connected component, and the component of each face (Trivial_connection_solver's)
  virtual std::vector<TC::Component_report> components() const = 0;
  virtual std::vector<std::size_t> face_components() const = 0;
  // the vertices of each interior edge, two per edge (smaller first), in the order of Result.connection
  virtual const std::vector<std::int64_t>& edge_vertices() const = 0;
};

// Vertex v of `mesh` (vertex i is the i-th of the arrays or the file); a vertex out of range is the user's error.
vertex_descriptor vertex_of(const Mesh& mesh, std::size_t v)
{
  if(v >= mesh.number_of_vertices())
    throw TC::Invalid_input(TC::Error_code::invalid_vertex,
                            "vertex " + std::to_string(v) + " does not exist (the mesh has " +
                              std::to_string(mesh.number_of_vertices()) + " vertices)",
                            v);
  return vertex_descriptor(Mesh::size_type(v));
}

// The vertices of `s` in `mesh`, each checked by vertex_of()
std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> vertex_descriptors(const Mesh& mesh,
                                                                                    const Singularities& s)
{
  std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> out;
  out.reserve(s.size());
  for(const auto& [v, k] : s)
    out.emplace_back(vertex_of(mesh, v), k);
  return out;
}

// x(h) kept straight in the per-edge output array: x of the halfedge from the smaller vertex index to the larger
// one, its opposite's the negative (nothing on the border)
struct Edge_connection_map
{
  using key_type = halfedge_descriptor;
  using value_type = double;
  using reference = double;
  using category = boost::read_write_property_map_tag;
  const Mesh* mesh;
  const std::vector<std::int64_t>* slot; // per edge: its entry, -1 on the border
  double* x;
  friend double get(const Edge_connection_map& m, halfedge_descriptor h)
  {
    const std::int64_t i = (*m.slot)[std::size_t(m.mesh->edge(h))];
    if(i < 0)
      return 0.;
    return m.mesh->source(h) < m.mesh->target(h) ? m.x[i] : -m.x[i];
  }
  friend void put(const Edge_connection_map& m, halfedge_descriptor h, double value)
  {
    const std::int64_t i = (*m.slot)[std::size_t(m.mesh->edge(h))];
    if(i >= 0)
      m.x[i] = m.mesh->source(h) < m.mesh->target(h) ? value : -value;
  }
};

// The points the solver reads while it is built: V's rows (Solver(V, F): the mesh may still be under
// construction), else the mesh's own
struct Point_source
{
  using key_type = vertex_descriptor;
  using value_type = Kernel::Point_3;
  using reference = Kernel::Point_3;
  using category = boost::readable_property_map_tag;
  const double* xyz;
  const Mesh* mesh;

  friend Kernel::Point_3 get(const Point_source& m, vertex_descriptor v)
  {
    if(m.xyz == nullptr)
      return m.mesh->point(v);
    const double* p = m.xyz + 3 * std::size_t(v);
    return Kernel::Point_3(p[0], p[1], p[2]);
  }
};

struct Options
{
  TC::Weighting weighting = TC::Weighting::hodge_star;
  std::vector<face_descriptor> constrained, guided;
  double guidance_weight = 1;
  bool align_boundary = false;
  // the targets known when the solver is built (per face, zero where not known) and their n: touching pins that
  // disagree are then left to the lattice rather than rounded
  std::vector<Kernel::Vector_3> known_directions;
  int known_n = 1;
  TC::Progress_callback progress; // the constructor's phases (empty: none)
};

// Per face, the direction of `directions` (one per face), or the zero vector everywhere without them
inline auto face_direction_map(const std::vector<Kernel::Vector_3>* directions)
{
  return boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
    [directions](face_descriptor f) { return directions ? (*directions)[std::size_t(f)] : CGAL::NULL_VECTOR; });
}

template <class SolverTraits>
class Solver_of : public Solver_interface
{
  using Solver = TC::Trivial_connection_solver<Mesh, Kernel, SolverTraits>;

public:
  // From `source`: its arrays when it has them (mesh_of_arrays(); the mesh may then still be under construction,
  // and is waited for once the solver is built), else from its mesh
  Solver_of(Mesh_of_arrays& source, const Options& o, const char* name)
    : m_mesh(*source.mesh), m_name(name)
  {
    const Mesh& mesh = *source.mesh;
    const auto known_map = face_direction_map(o.known_directions.empty() ? nullptr : &o.known_directions);
    const auto np = TC::parameters::progress(o.progress, TC::parameters::weighting(
      o.weighting,
      TC::parameters::constrained_faces(
        o.constrained,
        TC::parameters::guided_faces(
          o.guided, TC::parameters::guidance_weight(
                      o.guidance_weight, TC::parameters::align_with_boundary(
                                           o.align_boundary,
                                           TC::parameters::face_directions(
                                             known_map, TC::parameters::symmetry_order(
                                                          o.known_n, CGAL::parameters::vertex_point_map(
                                                                       Point_source{source.points, &mesh})))))))));
    if(source.arrays)
      m_solver = TC::internal::Solver_access<Solver>::make(mesh, std::move(*source.arrays), np);
    else
      m_solver = std::make_unique<Solver>(mesh, np);
    source.wait_for_mesh();
    m_edge_slot.assign(mesh.number_of_edges(), -1);
    for(auto e : mesh.edges())
      if(!mesh.is_border(e)) {
        m_edge_slot[std::size_t(e)] = m_interior_edges++;
        const auto h = mesh.halfedge(e);
        const std::int64_t a = std::int64_t(mesh.source(h)), b = std::int64_t(mesh.target(h));
        m_edge_vertices.push_back((std::min)(a, b));
        m_edge_vertices.push_back((std::max)(a, b));
      }
  }

  Solve_output solve(const std::vector<std::pair<std::size_t, TC::Singularity_index>>& singularities, int n,
                     const std::vector<Kernel::Vector_3>* directions, const Loop_periods* loop_periods,
                     bool all_directions, const TC::Progress_callback& progress) override
  {
    const auto s = vertex_descriptors(m_mesh, singularities);
    Solve_output out;
    out.connection.assign(std::size_t(m_interior_edges), 0.);
    out.field.assign(3 * m_mesh.number_of_faces(), 0.);
    const Edge_connection_map halfedge_x{&m_mesh, &m_edge_slot, out.connection.data()};
    const Face_vector_map face_field{out.field.data()};
    // directions_of() gives one per face
    const auto target_map = face_direction_map(directions);

    using Clock = std::chrono::steady_clock;
    const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
    Clock::time_point start = Clock::now();
    const auto np = TC::parameters::symmetry_order(
      n, TC::parameters::face_directions(target_map, TC::parameters::progress(progress)));
    out.report = loop_periods != nullptr ? m_solver->solve(s, halfedge_x, TC::parameters::loop_periods(*loop_periods, np))
                                         : m_solver->solve(s, halfedge_x, np);
    out.solve_seconds = seconds_since(start);
    start = Clock::now();
    m_solver->compute_field(halfedge_x, face_field, np);
    out.field_seconds = seconds_since(start);
    start = Clock::now();

    if(n > 1 && all_directions) { // the n directions: the field turned by 2 pi j / n about the face's normal
      std::vector<double> cosine(static_cast<std::size_t>(n)), sine(static_cast<std::size_t>(n));
      for(int j = 0; j < n; ++j) { // once, not per face (the trigonometry was most of this loop's time)
        const double t = 2 * CGAL_PI * j / n;
        cosine[std::size_t(j)] = std::cos(t);
        sine[std::size_t(j)] = std::sin(t);
      }
      out.directions.resize(3 * std::size_t(n) * m_mesh.number_of_faces());
      double* d = out.directions.data();
      for(auto f : m_mesh.faces()) {
        const auto h = m_mesh.halfedge(f);
        const auto& a = m_mesh.point(m_mesh.source(h));
        const auto& b = m_mesh.point(m_mesh.target(h));
        const auto& c = m_mesh.point(m_mesh.target(m_mesh.next(h)));
        Kernel::Vector_3 normal = CGAL::cross_product(b - a, c - a);
        normal = normal / std::sqrt(CGAL::to_double(normal.squared_length()));
        const Kernel::Vector_3 u = get(face_field, f);
        const Kernel::Vector_3 w = CGAL::cross_product(normal, u);
        for(std::size_t j = 0; j < std::size_t(n); ++j, d += 3) { // cos(t) u + sin(t) w, as before, in place
          d[0] = cosine[j] * CGAL::to_double(u.x()) + sine[j] * CGAL::to_double(w.x());
          d[1] = cosine[j] * CGAL::to_double(u.y()) + sine[j] * CGAL::to_double(w.y());
          d[2] = cosine[j] * CGAL::to_double(u.z()) + sine[j] * CGAL::to_double(w.z());
        }
      }
    }
    out.output_seconds = seconds_since(start);
    return out;
  }

  std::size_t number_of_loops() const override { return m_solver->loops().size(); }

  // defined in placement.h
  TC::Placement_report place(int n, bool align_boundary, const std::vector<Kernel::Vector_3>* guide, double strength,
                             const Singularities& fixed, const Loop_periods* periods,
                             const std::vector<Kernel::Vector_3>* directions, Singularities& placed,
                             const TC::Progress_callback& progress) const override;
  std::vector<Kernel::Vector_3> curvature_guide(std::vector<std::pair<double, double>>& curvatures) const override;
  std::vector<std::size_t> spread(const std::vector<Kernel::Vector_3>& guide, std::size_t count) const override;
  TC::Refinement_report<vertex_descriptor> refine(const Singularities& start, int n,
                                                  const std::vector<Kernel::Vector_3>* directions,
                                                  const Loop_periods* periods, const std::vector<std::size_t>& fixed,
                                                  bool cancel_pairs, std::size_t trials,
                                                  const TC::Progress_callback& progress) override;

  std::vector<std::tuple<bool, std::size_t, std::vector<halfedge_descriptor>>> loops() const override
  {
    std::vector<std::tuple<bool, std::size_t, std::vector<halfedge_descriptor>>> out;
    for(const auto& l : m_solver->loops())
      out.emplace_back(l.kind == TC::Loop_kind::boundary, l.component, l.halfedges);
    return out;
  }

  std::vector<double> weights() const override
  {
    std::vector<double> w;
    for(auto e : m_mesh.edges())
      if(!m_mesh.is_border(e))
        w.push_back(m_solver->weight(e));
    return w;
  }

  TC::Constraint_update set_constraints(const std::vector<face_descriptor>& constrained,
                                        const std::vector<face_descriptor>& guided,
                                        const std::vector<Kernel::Vector_3>& known, int known_n) override
  {
    const auto known_map = face_direction_map(known.empty() ? nullptr : &known);
    return m_solver->set_constraints(TC::parameters::constrained_faces(
      constrained, TC::parameters::guided_faces(
                     guided, TC::parameters::face_directions(known_map, TC::parameters::symmetry_order(known_n)))));
  }

  const char* backend() const override { return m_name; }

  std::vector<TC::Component_report> components() const override { return m_solver->components(); }
  std::vector<std::size_t> face_components() const override
  {
    std::vector<std::size_t> c;
    c.reserve(m_mesh.number_of_faces());
    for(auto f : m_mesh.faces())
      c.push_back(m_solver->component(f));
    return c;
  }

  const std::vector<std::int64_t>& edge_vertices() const override { return m_edge_vertices; }

private:
  std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> descriptors(const Singularities& s) const
  {
    return vertex_descriptors(m_mesh, s);
  }

  const Mesh& m_mesh;
  const char* m_name;
  std::unique_ptr<Solver> m_solver; // not movable: made in place
  std::vector<std::int64_t> m_edge_slot; // per edge, its entry in Result.connection (-1: border)
  std::int64_t m_interior_edges = 0;
  std::vector<std::int64_t> m_edge_vertices; // per interior edge in that order, its vertices (smaller first)
};

// ---- the Python classes ---------------------------------------------------------------------------------

struct Result
{
  py::object connection, edges, field, directions, energy, guidance_energy, max_residual, max_loop_residual,
    loop_periods, boundary_indices, integers_proven_optimal, energy_lower_bound, rounding_energy, constraints,
    guidance, n, timings;
};

void check_backend(const std::string& backend)
{
  if(backend != "auto" && backend != "ldlt" && backend != "cholmod")
    throw py::value_error("backend must be \"auto\", \"ldlt\" or \"cholmod\", got \"" + backend + "\"");
#ifndef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  if(backend == "cholmod")
    throw py::value_error("backend \"cholmod\": this build of the module has no CHOLMOD (libsuitesparse-dev)");
#endif
}

// The solver of `source` (as for Solver_of) with the backend named (checked by check_backend())
std::unique_ptr<Solver_interface> make_solver(Mesh_of_arrays& source, const Options& o, const std::string& backend)
{
  if(backend == "ldlt")
    return std::make_unique<Solver_of<TC::Default_solver_traits>>(source, o, "ldlt");
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  if(backend == "cholmod")
    return std::make_unique<Solver_of<TC::Cholmod_solver_traits>>(source, o, "cholmod");
  return std::make_unique<Solver_of<TC::Automatic_solver_traits>>(source, o, "auto");
#else
  return std::make_unique<Solver_of<TC::Default_solver_traits>>(source, o, "auto");
#endif
}

class Python_solver
{
public:
  // `mesh` keeps its mesh until the solver is built and the mesh complete: on an error before, its destructor waits
  // for the mesh's construction before freeing it
  Python_solver(Mesh_of_arrays mesh, const std::string& weights, const std::string& backend,
                const py::object& constrained, const py::object& guided, double guidance_weight, bool align_boundary,
                const Feature_options& features, const TC::Progress_callback& progress)
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
    m_solver_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m_mesh = std::move(mesh.mesh);
  }

  Result solve(const py::object& singularities, const py::object& n_in, const py::object& directions,
               const py::object& loop_periods, bool all_directions, const py::object& progress)
  {
    const int n = symmetry_order_of(n_in, "n");
    const auto s = singularities_of(singularities);
    check_directions_are_read(directions, "solve()");
    const Optional_inputs in = optional_inputs(directions, loop_periods);
    if(all_directions && n > 1)
      check_directions_fit(n);
    Progress_context context("solve()", progress);
    Solve_output out = reading([&] {
      const auto targets = with_feature_targets(in.directions);
      return m_solver->solve(s, n, targets ? &*targets : nullptr, in.periods_or_null(), all_directions,
                             context.callback());
    });
    m_last_n = n;
    return result_of(std::move(out), n);
  }

  py::dict set_constraints(const py::object& constrained, const py::object& guided)
  {
    auto c = faces_of(constrained, m_mesh->number_of_faces(), "constrained_faces");
    const auto g = faces_of(guided, m_mesh->number_of_faces(), "guided_faces");
    const std::size_t user_pins = c.size() + g.size();
    TC::Constraint_update u;
    {
      py::gil_scoped_release unlocked;
      std::unique_lock<std::shared_mutex> writing(m_mutex);
      if(m_features) { // merged again with the new faces; kept as they were when the solver refuses them
        Features merged = *m_features;
        c = merge_feature_pins(*m_mesh, c, g, merged);
        Options known;
        known_feature_directions(*m_mesh, merged, m_feature_n, known);
        u = m_solver->set_constraints(c, g, known.known_directions, known.known_n);
        m_features = std::move(merged);
      } else
        u = m_solver->set_constraints(c, g, {}, 1);
      m_user_pins = user_pins; // after the solver took them (it may refuse them)
    }
    py::dict d;
    d["refactored"] = u.refactored;
    d["links"] = u.links;
    d["links_outside_the_factor"] = u.links_outside_the_factor;
    d["new_forward_substitutions"] = u.new_forward_substitutions;
    return d;
  }

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

  // defined in files.h
  // the field of `result` as a field file (.txt), or the mesh with it and the singularities as a VTK (.vtk) or PLY
  // (.ply) file, written completely or not at all
  void write_field(const py::object& path_in, const Result& result, const py::object& singularities) const;

  // the loops of loop_periods: boundary loops and homology generators, each with the halfedges it crosses as
  // (source, target) vertex pairs, crossed from the face on their left to the other one
  py::list loops() const
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
  py::list topology() const
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

  std::string repr() const
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

  std::size_t number_of_vertices() const { return m_mesh->number_of_vertices(); }
  std::size_t number_of_faces() const { return m_mesh->number_of_faces(); }
  std::size_t number_of_loops() const { return m_solver->number_of_loops(); }
  std::string backend() const { return m_solver->backend(); }
  py::array_t<double> vertices() const
  {
    std::vector<double> p;
    p.reserve(3 * m_mesh->number_of_vertices());
    for(auto v : m_mesh->vertices())
      for(int i = 0; i < 3; ++i)
        p.push_back(CGAL::to_double(m_mesh->point(v)[i]));
    return owning_array(std::move(p), {py::ssize_t(m_mesh->number_of_vertices()), 3});
  }
  py::array_t<std::int64_t> faces() const
  {
    std::vector<std::int64_t> t = corners_in_input_order(*m_mesh);
    return owning_array(std::move(t), {py::ssize_t(m_mesh->number_of_faces()), 3});
  }
  py::array_t<double> weights() const
  {
    std::vector<double> w = m_solver->weights();
    const py::ssize_t ne = py::ssize_t(w.size());
    return owning_array(std::move(w), {ne});
  }
  // one read-only array for the solver and all its results
  py::object edges() const
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
  py::object feature_pins() const
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
  py::object feature_alignment() const
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

private:
  // The feature pins of Solver(align_features=...): all the faces beside the feature curves, and which of them the
  // solver holds (the others are named by the user's constrained or guided faces, or on an aligned boundary)
  struct Features
  {
    Feature_pins all;
    std::vector<std::size_t> pinned; // entries of all.faces given to the solver
    std::size_t named_by_user = 0, on_guided_faces = 0, on_aligned_boundary = 0;
  };

  // The constrained faces of the solver: the user's `constrained`, then the feature pins on the faces that are
  // neither constrained nor guided by the user (the user wins, as the program's --constraints), and, with
  // align_boundary, not on the boundary (the solver refuses targets there; the field follows the boundary).
  // `features.pinned` and its counts are set.
  std::vector<face_descriptor> merge_feature_pins(const Mesh& mesh, const std::vector<face_descriptor>& constrained,
                                                  const std::vector<face_descriptor>& guided, Features& features) const
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

  // The feature pins' directions (zero elsewhere: the user's come with each solve) and their n, for the solver's
  // constructor: touching feature pins that disagree are then left to the lattice, as in the program
  static void known_feature_directions(const Mesh& mesh, const Features& features, int n, Options& o)
  {
    o.known_directions.assign(mesh.number_of_faces(), CGAL::NULL_VECTOR);
    const std::vector<double>& d = features.all.directions;
    for(std::size_t i : features.pinned)
      o.known_directions[features.all.faces[i]] = Kernel::Vector_3(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
    o.known_n = n;
  }

  // The targets of a call (the user's directions, or none) with the feature pins' directions on their faces
  // (those faces are not the user's: their rows are not read otherwise). Under the solver's lock.
  std::optional<std::vector<Kernel::Vector_3>> with_feature_targets(
    const std::optional<std::vector<Kernel::Vector_3>>& user) const
  {
    std::optional<std::vector<Kernel::Vector_3>> out = user;
    if(!m_features || m_features->pinned.empty())
      return out;
    if(!out)
      out.emplace(m_mesh->number_of_faces(), CGAL::NULL_VECTOR);
    const std::vector<double>& d = m_features->all.directions;
    for(std::size_t i : m_features->pinned)
      (*out)[m_features->all.faces[i]] = Kernel::Vector_3(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
    return out;
  }

  // directions= of a call is read only for the user's constrained and guided faces: given (not None, not empty)
  // to a solver without any, it would be ignored; a ValueError says so rather than a field that ignores it
  void check_directions_are_read(const py::object& directions, const char* call) const
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
  void check_directions_fit(int n) const
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

  // x per halfedge from a Result of this solver (its edges are the mesh's interior edges, in order)
  std::vector<double> halfedge_angles(const Result& result) const
  {
    const auto connection = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(result.connection);
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
  std::vector<Kernel::Vector_3> field_of(const Result& result) const
  {
    const auto f = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(result.field);
    if(!f || f.ndim() != 2 || std::size_t(f.shape(0)) != m_mesh->number_of_faces() || f.shape(1) != 3)
      throw py::value_error("the result is not one of this solver (its number of faces differs)");
    std::vector<Kernel::Vector_3> field(m_mesh->number_of_faces());
    for(std::size_t i = 0; i < field.size(); ++i)
      field[i] = Kernel::Vector_3(f.data()[3 * i], f.data()[3 * i + 1], f.data()[3 * i + 2]);
    return field;
  }

  static py::dict singularity_dict(const Singularities& s)
  {
    py::dict d;
    for(const auto& [v, k] : s)
      d[py::int_(v)] = fraction(k);
    return d;
  }

  // The optional per-face directions and loop periods of a call, read with the GIL
  struct Optional_inputs
  {
    std::optional<std::vector<Kernel::Vector_3>> directions;
    std::optional<Loop_periods> periods;
    const std::vector<Kernel::Vector_3>* directions_or_null() const { return directions ? &*directions : nullptr; }
    const Loop_periods* periods_or_null() const { return periods ? &*periods : nullptr; }
  };

  Optional_inputs optional_inputs(const py::object& directions, const py::object& loop_periods) const
  {
    Optional_inputs in;
    if(!directions.is_none())
      in.directions = directions_of(directions);
    in.periods = periods_of(loop_periods);
    return in;
  }

  // f() without the GIL, beside the solver's other readers (solves, placement), never during set_constraints()
  template <class F>
  auto reading(F&& f) const -> decltype(f())
  {
    py::gil_scoped_release unlocked;
    std::shared_lock<std::shared_mutex> lock(m_mutex);
    return f();
  }

  static std::optional<Loop_periods> periods_of(const py::object& loop_periods)
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
  std::vector<Kernel::Vector_3> directions_of(const py::object& directions) const
  {
    const std::size_t nf = m_mesh->number_of_faces();
    std::vector<Kernel::Vector_3> targets(nf, CGAL::NULL_VECTOR);
    auto vector_of = [](const py::handle& h) {
      const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
      if(!a || a.ndim() != 1 || a.shape(0) != 3)
        throw py::value_error("a direction must be three numbers, got " + std::string(py::repr(h)));
      return Kernel::Vector_3(a.data()[0], a.data()[1], a.data()[2]);
    };
    if(py::isinstance<py::dict>(directions)) {
      py::list keys;
      for(const auto& item : py::reinterpret_borrow<py::dict>(directions))
        keys.append(item.first);
      const std::vector<face_descriptor> faces = faces_of(keys, nf, "directions");
      std::size_t i = 0;
      for(const auto& item : py::reinterpret_borrow<py::dict>(directions))
        targets[std::size_t(faces[i++])] = vector_of(item.second);
      return targets;
    }
    const py::array a = as_array(directions, "directions");
    check_rows_of_three(a, "directions", "fiu", "real numbers");
    if(std::size_t(a.shape(0)) != nf)
      throw py::value_error("directions must have one row per face (" + std::to_string(nf) + "), got " +
                            std::to_string(a.shape(0)));
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    for(std::size_t f = 0; f < nf; ++f)
      targets[f] = Kernel::Vector_3(d.data()[3 * f], d.data()[3 * f + 1], d.data()[3 * f + 2]);
    return targets;
  }

  Result result_of(Solve_output&& out, int n) const
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


// Result, Solver (all but the methods of placement.h, streamlines.h and files.h) and _reference_build()
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
  solver
    .def(py::init([](const py::object& V, const py::object& F, const std::string& weights, const std::string& backend,
                     const py::object& constrained, const py::object& guided, double mu, bool align,
                     const py::object& align_features, int feature_smoothing, const py::object& feature_n,
                     const py::object& progress) {
           const Feature_options features =
             feature_options_of(align_features, symmetry_order_of(feature_n, "feature_n"), feature_smoothing);
           Progress_context context("Solver()", progress);
           const auto start = std::chrono::steady_clock::now();
           Mesh_of_arrays mesh = mesh_of_arrays(V, F);
           const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
           auto solver = std::make_unique<Python_solver>(std::move(mesh), weights, backend, constrained, guided, mu,
                                                         align, features, context.callback());
           solver->m_mesh_seconds = seconds;
           return solver;
         }),
         py::arg("V"), py::arg("F"), py::kw_only(), py::arg("weights") = "hodge", py::arg("backend") = "auto",
         py::arg("constrained_faces") = py::none(), py::arg("guided_faces") = py::none(),
         py::arg("guidance_weight") = 1.0, py::arg("align_boundary") = false, py::arg("align_features") = py::none(),
         py::arg("feature_smoothing") = TC::default_feature_smoothing, py::arg("feature_n") = 4,
         py::arg("progress") = py::none())
    .def_static(
      "from_file",
      [](const py::object& path, bool triangulate, const std::string& weights, const std::string& backend,
         const py::object& constrained, const py::object& guided, double mu, bool align,
         const py::object& align_features, int feature_smoothing, const py::object& feature_n,
         const py::object& progress) {
        const Feature_options features =
          feature_options_of(align_features, symmetry_order_of(feature_n, "feature_n"), feature_smoothing);
        Progress_context context("Solver.from_file()", progress);
        const auto start = std::chrono::steady_clock::now();
        Mesh_of_arrays mesh;
        mesh.mesh = mesh_of_file(path_of(path), triangulate);
        mesh.number_of_faces = mesh.mesh->number_of_faces();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        auto solver = std::make_unique<Python_solver>(std::move(mesh), weights, backend, constrained, guided, mu,
                                                      align, features, context.callback());
        solver->m_mesh_seconds = seconds;
        return solver;
      },
      py::arg("path"), py::arg("triangulate") = false, py::kw_only(), py::arg("weights") = "hodge",
      py::arg("backend") = "auto", py::arg("constrained_faces") = py::none(), py::arg("guided_faces") = py::none(),
      py::arg("guidance_weight") = 1.0, py::arg("align_boundary") = false, py::arg("align_features") = py::none(),
      py::arg("feature_smoothing") = TC::default_feature_smoothing, py::arg("feature_n") = 4,
      py::arg("progress") = py::none(),
      "A solver for the mesh of an OFF, OBJ, PLY, STL or GOCAD file (path: str, bytes or os.PathLike; the "
      "package's validating reader, as read_mesh(); triangulate=True splits polygons). Options as Solver(), "
      "align_features and progress included (the program's --align-features [DEGREES]).")
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

#endif // TRIVIAL_CONNECTIONS_PYTHON_SOLVER_H
