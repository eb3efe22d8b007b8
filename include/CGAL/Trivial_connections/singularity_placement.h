// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_PLACEMENT_H
#define CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_PLACEMENT_H

#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/internal/placement/face_curvature.h>
#include <CGAL/Trivial_connections/internal/placement/field_singularities.h>
#include <CGAL/Trivial_connections/internal/placement/smoothest_field.h>
#include <CGAL/Trivial_connections/internal/integers/loop_periods.h>
#include <CGAL/Trivial_connections/internal/system/constraint_targets.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>

#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
What `place_singularities()` found.
*/
struct Placement_report
{
  int symmetry_order = 1;           ///< n
  bool aligned = false;             ///< the field was aligned with a guide (`alignment_guide`)
  /// the energy `sum_e w_e (d_e / n)^2` of the connection that makes the smooth field parallel (d_e: the change of
  /// n times its angle across e beyond n times the transport, wrapped): a trivial connection with exactly the
  /// placed singularities, so the optimal one's `Solve_report::energy` is at most this when its integers are optimal
  double field_energy = 0;
  /// per component, the smooth field's Rayleigh quotient `u^H A u / u^H B u` (its smallest eigenvalue
  /// unless aligned, with an aligned boundary or with constrained faces)
  std::vector<double> rayleigh_quotients;
  int iterations = 0;               ///< eigensolver iterations, one solve each (0 when only linear solves were needed)
  double max_rounding = 0;          ///< largest distance of a vertex's `n k_v` from the integer taken (about 1e-12)
  /// the number of singularities of each index, by increasing index
  std::vector<std::pair<Singularity_index, std::size_t>> singularities_per_index;
  std::size_t pinned = 0;           ///< faces held at their constrained direction (the solver's `constrained_faces`)
  std::size_t number_of_singularities = 0; ///< vertices written
  std::size_t fixed = 0;            ///< of which given as `fixed_singularities`
  std::size_t units_removed = 0;    ///< units of 1/n taken from automatic singularities near the fixed ones or holes
  std::size_t units_added = 0;      ///< units of 1/n added to balance a component (see the user manual)
};

namespace internal {

// guide vectors as the n-th powers of their directions in the face frames, times their lengths
template <class Mesh, class Traits, class GuideMap>
std::vector<std::complex<double>> guide_powers(const Mesh& m, const Traits& traits, GuideMap guide, int n)
{
  typename Traits::Compute_x_3 x = traits.compute_x_3_object();
  typename Traits::Compute_y_3 y = traits.compute_y_3_object();
  typename Traits::Compute_z_3 z = traits.compute_z_3_object();
  std::vector<std::complex<double>> q(std::size_t(m.nf));
  for(int f = 0; f < m.nf; ++f) {
    const auto& g = get(guide, m.face_descriptors[f]);
    const Vec3 v = {{CGAL::to_double(x(g)), CGAL::to_double(y(g)), CGAL::to_double(z(g))}};
    if(!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw Invalid_input(Error_code::invalid_argument, "the alignment guide of face " + std::to_string(f) +
                                                          " is not finite", std::size_t(f));
    Vec3 ex, ey;
    Mesh_geometry::frame(m, f, ex, ey);
    const double a = dot(v, ex), b = dot(v, ey), l = std::hypot(a, b);
    q[f] = l > 0 ? std::polar(l, n * std::atan2(b, a)) : std::complex<double>(0., 0.);
  }
  return q;
}

// the n-th power of the direction of every aligned boundary face (its border edge: the longer one on a face with
// two), as the boundary alignment of the solver defines it
template <class Mesh>
void boundary_powers(const Mesh& m, const Mesh_geometry& g, int n, std::vector<char>& fixed,
                     std::vector<std::complex<double>>& value)
{
  fixed.assign(std::size_t(m.nf), 0);
  value.assign(std::size_t(m.nf), std::complex<double>(0., 0.));
  std::vector<double> longest(std::size_t(m.nf), -1.);
  for(int i = 0; i < 3 * m.nf; ++i) {
    if(g.edge_of_corner[i] >= 0)
      continue;
    const int f = Mesh::face_of(i);
    const Vec3 e = sub(m.points[m.target_of(i)], m.points[m.source_of(i)]);
    const double l = norm(e);
    if(l <= longest[f])
      continue;
    longest[f] = l;
    Vec3 ex, ey;
    Mesh_geometry::frame(m, f, ex, ey);
    fixed[f] = 1;
    value[f] = std::polar(1., n * std::atan2(dot(e, ey), dot(e, ex)));
  }
}

// The n-th power of the direction of every constrained face of the solver (a user target, not a guided face nor
// an aligned boundary face of the solver), its vector in `directions` projected onto the face as solve() reads
// it (set_user_target_angles(), which also checks the guided faces' vectors as solve() does), marked in `fixed`
// and written in `value` over what is there (the boundary's); returns the number of such faces.
template <class Mesh, class Traits, class DirectionMap>
std::size_t pin_powers(const Mesh& m, const Constraint_links& links, const Traits& traits, const DirectionMap& directions,
                       int n, std::vector<char>& fixed, std::vector<std::complex<double>>& value)
{
  std::vector<double> angle(links.faces.size(), 0.);
  set_user_target_angles(m, links, traits, directions, angle);
  fixed.assign(std::size_t(m.nf), 0);
  value.assign(std::size_t(m.nf), std::complex<double>(0., 0.));
  std::size_t count = 0;
  for(std::size_t a = 0; a < links.faces.size(); ++a) {
    const Constraint_links::Constrained_face& c = links.faces[a];
    if(c.border_corner >= 0 || c.soft)
      continue;
    fixed[c.face] = 1;
    value[c.face] = std::polar(1., n * angle[a]);
    ++count;
  }
  return count;
}

inline bool has_pins(const Constraint_links& links)
{
  return std::any_of(links.faces.begin(), links.faces.end(),
                     [](const Constraint_links::Constrained_face& c) { return c.border_corner < 0 && !c.soft; });
}

} // namespace internal

/*!
\ingroup PkgTrivialConnectionsRef

Places the singularities of an n-direction field automatically: they are those of the globally smoothest
n-direction field on the faces (Knoeppel, Crane, Pinkall, Schroeder, "Globally Optimal Direction Fields",
SIGGRAPH 2013), or of the field aligned with a guide, read at the vertices; they satisfy Poincare-Hopf on every
closed component by construction. `solver.solve()` then gives the trivial connection with exactly these
singularities. The smooth field is the smallest eigenvector of the pencil (A, B) of its face-based Dirichlet
energy (`sum_e w_e |u_g - r_e^n u_f|^2`, with the solver's weights and transport) and the face areas, computed
per component by LOBPCG preconditioned with one sparse Cholesky factor; see the user manual for the stopping rule,
the aligned field and the boundary. When the solver has constrained faces (`constrained_faces`), the field is
held at their directions (`face_directions`): on each component with such faces it is the minimiser of the same
energy with these faces fixed, one linear solve, as Directional's constrained power field, so that the trivial
connection with its singularities can meet the constraints without twisting between them. Guided faces
(`guided_faces`) do not enter the placement.

\tparam Solver a `Trivial_connection_solver`
\tparam OutputIterator an output iterator accepting `std::pair<vertex_descriptor, Singularity_index>`
\param solver the solver of the mesh (its mesh, weights and transport are used; it is not modified)
\param out receives every singular vertex with its index, by increasing vertex index
\param np an optional sequence of named parameters among the ones listed below
\cgalNamedParamsBegin
  \cgalParamNBegin{symmetry_order} \cgalParamType{`int`} \cgalParamDefault{1} \cgalParamNEnd
  \cgalParamNBegin{align_with_boundary}
    \cgalParamDescription{the smooth field is prescribed on the boundary faces (along their border edge, as the
      solver's boundary alignment) instead of free there; with `alignment_guide`, the boundary directions are
      guides of the aligned field instead, as strong as the strongest guide of their component}
    \cgalParamType{`bool`} \cgalParamDefault{`false`}
  \cgalParamNEnd
  \cgalParamNBegin{alignment_guide}
    \cgalParamDescription{a readable property map `face_descriptor -> Vector_3`: the field is Knoeppel's aligned
      field, the minimiser of its smoothness energy plus `s |u - q|_B^2`, q the n-th power of each face's guide
      direction times the guide's length (its weight), s = `alignment_strength` / the area of the component.
      A component whose guide is zero everywhere gets the smoothest field}
  \cgalParamNEnd
  \cgalParamNBegin{alignment_strength} \cgalParamType{`double`} \cgalParamDefault{100} \cgalParamNEnd
  \cgalParamNBegin{face_directions}
    \cgalParamDescription{as for `solve()`: a readable property map `face_descriptor -> Vector_3`, required when the
      solver has constrained faces. The smooth field is held at each constrained face's direction (projected onto
      the face, one of its n directions: u_f = exp(i n theta_f) in the face's frame), whatever the other
      parameters: over the boundary's direction where `align_with_boundary` also prescribes the face, and with
      `alignment_guide` the aligned field is minimised with these faces held. The vectors at guided faces are
      checked as `solve()` checks them and are otherwise not used}
    \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{progress}
    \cgalParamDescription{called with `Phase::placement`: 0 at the start, after each eigensolver iteration 0.99
      times the iterations done over their budget (100), and 1 at the end; an exception it throws ends the
      placement}
    \cgalParamType{`Progress_callback`} \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{fixed_singularities}
    \cgalParamDescription{a range of pairs (vertex, index) kept as they are: the automatic singularities nearest
      to them give way, one unit of 1/n at a time, until each component's index sum is that of the automatic
      placement again (see the user manual)}
  \cgalParamNEnd
  \cgalParamNBegin{loop_periods}
    \cgalParamDescription{as for `solve()`: on a component whose boundary loops all have an index, the vertex
      indices must sum to its Euler characteristic minus theirs; the automatic singularities nearest to its boundary
      give way (or units are added nearest to it) until they do. Other entries are ignored, but every entry is
      checked as `solve()` checks it}
    \cgalParamType{`std::vector<std::int64_t>` or `std::vector<std::optional<std::int64_t>>`}
  \cgalParamNEnd
\cgalNamedParamsEnd
\throws Invalid_input `invalid_symmetry_order`, `invalid_argument` (a guide not finite, a strength not positive
        and finite), `invalid_constraint` (as `solve()`: `face_directions` missing while the solver has constrained
        faces, or a direction zero, not finite or normal to its face), those of `solve()` for the fixed singularities (except Poincare-Hopf, which the placement
        completes), `poincare_hopf_violated` (fixed singularities that cannot be completed), `solver_failure`
\returns the energies and the count of singularities per index
*/
template <class Solver, class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
Placement_report place_singularities(const Solver& solver, OutputIterator out,
                                     const NamedParameters& np = parameters::default_values())
{
  using Access = internal::Solver_access<Solver>;
  const auto& m = Access::mesh(solver);
  const internal::Mesh_geometry& g = Access::geometry(solver);
  const internal::Mesh_topology& t = Access::topology(solver);
  const int n = internal::checked_symmetry_order(
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1));
  const bool align_boundary =
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::align_with_boundary), false);
  const double strength =
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::alignment_strength), 100.);
  if(!(strength > 0) || !std::isfinite(strength))
    throw Invalid_input(Error_code::invalid_argument,
                        "the alignment strength must be positive and finite (got " + std::to_string(strength) + ")");

  const Progress_callback progress(
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::progress), Progress_callback()));
  auto notify = [&progress](double fraction) {
    if(progress)
      progress(Phase::placement, fraction);
  };
  // below 1 even at the last iteration of the budget: 1 is the end of the phase
  const std::function<void(int, int)> on_iteration = [&notify](int done, int budget) {
    notify(0.99 * done / budget);
  };
  notify(0);

  Placement_report report;
  report.symmetry_order = n;
  const internal::Smoothest_field_problem problem(m, g, t, n);
  std::vector<char> fixed_faces;
  std::vector<std::complex<double>> fixed_values;
  if(align_boundary)
    internal::boundary_powers(m, g, n, fixed_faces, fixed_values);
  // the solver's constrained faces (pins) are held at their directions, over the boundary's where both are given
  std::vector<char> pinned;
  std::vector<std::complex<double>> pinned_values;
  if(internal::has_pins(Access::links(solver))) {
    if constexpr(CGAL::parameters::is_default_parameter<NamedParameters, tc_np::face_directions_t>::value) {
      throw Invalid_input(Error_code::invalid_constraint,
                          "the solver has constrained faces: their directions (face_directions) are missing");
    } else {
      report.pinned = internal::pin_powers(m, Access::links(solver), solver.geom_traits(),
                                           CGAL::parameters::get_parameter(np, tc_np::face_directions), n, pinned,
                                           pinned_values);
    }
    if(fixed_faces.empty()) {
      fixed_faces = pinned;
      fixed_values = pinned_values;
    } else {
      for(int f = 0; f < m.nf; ++f)
        if(pinned[f]) {
          fixed_faces[f] = 1;
          fixed_values[f] = pinned_values[f];
        }
    }
  }
  // what the eigensolver reads to know that its singularities are settled (Eigen vectors are contiguous)
  auto singularities_of = [&](const Eigen::VectorXcd& u) {
    return internal::read_field_singularities(m, g, std::vector<std::complex<double>>(u.data(), u.data() + u.size()), n).k;
  };
  internal::Smoothest_field field;
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::alignment_guide_t>::value) {
    std::vector<std::complex<double>> q =
      internal::guide_powers(m, solver.geom_traits(), CGAL::parameters::get_parameter(np, tc_np::alignment_guide), n);
    // an aligned boundary is one more guide, as strong as the strongest of its component (1 without one)
    if(align_boundary) {
      std::vector<double> strongest(t.components.size(), 0.);
      for(int f = 0; f < m.nf; ++f)
        strongest[t.component_of_face[f]] = (std::max)(strongest[t.component_of_face[f]], std::abs(q[f]));
      for(int f = 0; f < m.nf; ++f)
        if(!fixed_faces.empty() && fixed_faces[f] && (pinned.empty() || !pinned[f])) {
          const double s = strongest[t.component_of_face[f]];
          q[f] = fixed_values[f] * (s > 0 ? s : 1.);
        }
    }
    std::vector<double> weight(t.components.size(), 0.);
    for(int f = 0; f < m.nf; ++f)
      weight[t.component_of_face[f]] += std::abs(q[f]);
    std::vector<char> unguided(t.components.size(), 0);
    bool any_unguided = false;
    for(std::size_t c = 0; c < weight.size(); ++c)
      any_unguided = any_unguided || (unguided[c] = !(weight[c] > 0));
    field = internal::aligned_field(problem, q, strength, pinned, pinned_values);
    report.aligned = true;
    if(any_unguided) {
      // the components without a guide: the smoothest field
      const internal::Smoothest_field smooth =
        internal::smoothest_field(problem, fixed_faces, fixed_values, singularities_of, 100, on_iteration);
      for(int f = 0; f < m.nf; ++f)
        if(unguided[t.component_of_face[f]])
          field.u[f] = smooth.u[f];
      for(std::size_t c = 0; c < weight.size(); ++c)
        if(unguided[c])
          field.rayleigh_quotient[c] = smooth.rayleigh_quotient[c];
      field.iterations = smooth.iterations;
    }
  } else {
    field = internal::smoothest_field(problem, fixed_faces, fixed_values, singularities_of, 100, on_iteration);
  }
  report.rayleigh_quotients = field.rayleigh_quotient;
  report.iterations = field.iterations;

  const internal::Field_singularities read = internal::field_singularities(m, g, t, field.u, n);
  report.field_energy = read.connection_energy;
  report.max_rounding = read.max_rounding;
  std::vector<std::int64_t> k = read.k;

  // what the user prescribes: fixed singularities, and boundary indices (loop_periods), which fix the index sums
  std::vector<std::int64_t> fixed_k(std::size_t(m.nv), 0);
  std::vector<char> fixed(std::size_t(m.nv), 0);
  std::vector<std::optional<std::int64_t>> target(t.components.size());
  bool prescribed = false;
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::fixed_singularities_t>::value) {
    std::vector<Component_report> components = internal::component_reports(t);
    const auto& given = CGAL::parameters::get_parameter(np, tc_np::fixed_singularities);
    // checked as solve() checks them, except the sums
    try {
      fixed_k = internal::checked_vertex_indices(m, g, t, given, n, components);
    } catch(const Invalid_input& e) {
      if(e.code() != Error_code::poincare_hopf_violated)
        throw;
      std::vector<Component_report> ignored(components.size()); // no closed component: no sum is checked
      for(Component_report& c : ignored)
        c.number_of_boundary_loops = 1;
      fixed_k = internal::checked_vertex_indices(m, g, t, given, n, ignored);
    }
    for(const auto& s : given) {
      fixed[std::size_t(get(m.vertex_index, s.first))] = 1;
      ++report.fixed;
    }
    prescribed = true;
  }
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::loop_periods_t>::value) {
    // a copy: optional_periods() may return a reference into its argument, a temporary here
    const std::vector<std::optional<std::int64_t>> periods = internal::optional_periods(
      CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::loop_periods),
                                         std::vector<std::int64_t>()));
    if(periods.size() != t.loops.size())
      throw Invalid_input(Error_code::invalid_loop_periods,
                          "loop_periods has " + std::to_string(periods.size()) + " entries for " +
                            std::to_string(t.loops.size()) + " loops");
    // a component whose boundary loops all have an index: its vertex indices must sum to chi minus theirs
    std::vector<std::int64_t> sum(t.components.size(), 0);
    std::vector<char> complete(t.components.size(), 1);
    for(std::size_t l = 0; l < t.loops.size(); ++l)
      if(periods[l])
        internal::checked_loop_period(*periods[l], l, t, n);
    for(std::size_t l = 0; l < t.loops.size(); ++l)
      if(t.loops[l].kind == Loop_kind::boundary) {
        if(periods[l])
          sum[t.loops[l].component] += *periods[l];
        else
          complete[t.loops[l].component] = 0;
      }
    for(std::size_t c = 0; c < t.components.size(); ++c) {
      const internal::Mesh_topology::Component& comp = t.components[c];
      if(comp.boundary_loops > 0 && complete[c]) {
        target[c] = n * (std::int64_t(comp.vertices) - comp.edges + comp.faces) - sum[c];
        prescribed = true;
      }
    }
  }
  if(prescribed)
    k = internal::combine_with_prescribed(m, g, t, k, fixed_k, fixed, target, report.units_removed, report.units_added);

  std::vector<std::pair<std::int64_t, std::size_t>> counts;
  for(int v = 0; v < m.nv; ++v) {
    if(k[v] == 0)
      continue;
    *out++ = std::make_pair(m.vertex_descriptors[v], Singularity_index(k[v], n));
    ++report.number_of_singularities;
    bool found = false;
    for(auto& c : counts)
      if(c.first == k[v]) {
        ++c.second;
        found = true;
      }
    if(!found)
      counts.emplace_back(k[v], 1);
  }
  std::sort(counts.begin(), counts.end());
  for(const auto& c : counts)
    report.singularities_per_index.emplace_back(Singularity_index(c.first, n), c.second);
  notify(1);
  return report;
}

/*!
\ingroup PkgTrivialConnectionsRef

A guide for curvature-aligned fields: per face, the principal direction of larger absolute curvature times the
anisotropy `|kappa_1 - kappa_2|`, so that umbilic regions (where the directions are noise) carry no weight. The
curvatures are those of the per-face shape operator of Rusinkiewicz ("Estimating curvatures and their derivatives
on triangle meshes", 3DPVT 2004), from angle-weighted vertex normals. For n = 4 (any multiple of 4) the two
principal directions give the same cross; for n = 2 the lines follow the direction of larger absolute curvature
(around a cylinder, not along it). Pass it as `alignment_guide` to `place_singularities()` and, with its
faces as `guided_faces`, as `face_directions` to `solve()`.

\param solver the solver of the mesh
\param guide a writable property map `face_descriptor -> Vector_3`
\param curvatures optional: receives, per face index, the two principal curvatures (larger absolute value first)
*/
template <class Solver, class FaceVectorMap>
void principal_curvature_guide(const Solver& solver, FaceVectorMap guide,
                               std::vector<std::pair<double, double>>* curvatures = nullptr)
{
  using Access = internal::Solver_access<Solver>;
  const auto& m = Access::mesh(solver);
  const std::vector<internal::Face_curvature> c = internal::face_curvatures(m);
  typename Solver::Geom_traits::Construct_vector_3 vector = solver.geom_traits().construct_vector_3_object();
  if(curvatures)
    curvatures->resize(std::size_t(m.nf));
  for(int f = 0; f < m.nf; ++f) {
    const double a = std::abs(c[f].first - c[f].second);
    const internal::Vec3& d = c[f].first_direction;
    put(guide, m.face_descriptors[f], vector(a * d[0], a * d[1], a * d[2]));
    if(curvatures)
      (*curvatures)[f] = {c[f].first, c[f].second};
  }
}


/*!
\ingroup PkgTrivialConnectionsRef

Chooses faces to guide (soft guidance, `guided_faces`) towards a guide such as `principal_curvature_guide()`:
up to `count` faces, spread over the mesh, the strongest first: faces are taken by decreasing guide length and a
face is skipped when a face already taken is within `d` steps in the dual graph, d = max(1, sqrt(F / count) / 2)
with F the number of faces; faces with a zero guide are never taken.
\param solver the solver of the mesh
\param guide a readable property map `face_descriptor -> Vector_3`
\param count the number of faces wanted
\returns the faces, strongest guide first
*/
template <class Solver, class FaceVectorMap>
std::vector<typename Solver::face_descriptor> spread_guided_faces(const Solver& solver, FaceVectorMap guide,
                                                                  std::size_t count)
{
  using Access = internal::Solver_access<Solver>;
  const auto& m = Access::mesh(solver);
  const auto& traits = solver.geom_traits();
  typename Solver::Geom_traits::Compute_squared_length_3 length2 = traits.compute_squared_length_3_object();
  std::vector<double> strength(std::size_t(m.nf));
  std::vector<int> order;
  for(int f = 0; f < m.nf; ++f) {
    strength[f] = CGAL::to_double(length2(get(guide, m.face_descriptors[f])));
    if(strength[f] > 0 && std::isfinite(strength[f]))
      order.push_back(f);
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return strength[a] > strength[b]; });
  const int d = count == 0 ? 0 : (std::max)(1, int(std::sqrt(double(m.nf) / double(count)) / 2));
  std::vector<int> near(std::size_t(m.nf), -1); // steps from the nearest face taken, within d
  std::vector<typename Solver::face_descriptor> taken;
  std::vector<int> queue;
  for(int f : order) {
    if(taken.size() >= count)
      break;
    if(near[f] >= 0)
      continue;
    taken.push_back(m.face_descriptors[f]);
    // mark the faces within d steps
    queue.assign(1, f);
    near[f] = 0;
    for(std::size_t q = 0; q < queue.size(); ++q) {
      const int g = queue[q];
      if(near[g] >= d)
        continue;
      for(int k = 0; k < 3; ++k) {
        const int o = m.opposite_corner[3 * g + k];
        if(o < 0)
          continue;
        const int h = o / 3;
        if(near[h] < 0 || near[h] > near[g] + 1) {
          near[h] = near[g] + 1;
          queue.push_back(h);
        }
      }
    }
  }
  return taken;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_PLACEMENT_H
