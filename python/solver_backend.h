// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The C++ solver of either backend behind one interface (Solver_interface, Solver_of, make_solver()): what the
// Python class Solver (solver_state.h) holds. Its placement methods are in placement.h.
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_SOLVER_BACKEND_H
#define TRIVIAL_CONNECTIONS_PYTHON_SOLVER_BACKEND_H

namespace {

// Seconds of steady clock since `start` (build_timings, Result.timings)
double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

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

    auto start = std::chrono::steady_clock::now();
    const auto np = TC::parameters::symmetry_order(
      n, TC::parameters::face_directions(target_map, TC::parameters::progress(progress)));
    out.report = loop_periods != nullptr ? m_solver->solve(s, halfedge_x, TC::parameters::loop_periods(*loop_periods, np))
                                         : m_solver->solve(s, halfedge_x, np);
    out.solve_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    m_solver->compute_field(halfedge_x, face_field, np);
    out.field_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();

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

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_SOLVER_BACKEND_H
