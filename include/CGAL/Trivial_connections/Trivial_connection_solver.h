// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_SOLVER_H
#define CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_SOLVER_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/Dual_loop.h>
#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/solver_traits.h>
#include <CGAL/Trivial_connections/internal/concurrency.h>
#include <CGAL/Trivial_connections/internal/solver_parameters.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>
#include <CGAL/Trivial_connections/internal/topology/loop_holonomy.h>
#include <CGAL/Trivial_connections/internal/system/constraint_links.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>
#include <CGAL/Trivial_connections/internal/system/system_assembly.h>
#include <CGAL/Trivial_connections/internal/factorization/concurrent_node_order.h>
#include <CGAL/Trivial_connections/internal/factorization/prefactored_system.h>
#include <CGAL/Trivial_connections/internal/integers/decided_links.h>
#include <CGAL/Trivial_connections/internal/integers/integer_solve.h>
#include <CGAL/Trivial_connections/internal/integers/loop_periods.h>
#include <CGAL/Trivial_connections/internal/field/field_propagation.h>
#include <CGAL/Trivial_connections/internal/field/report.h>

#include <CGAL/Default.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <future>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

namespace internal {

template <class TriangleMesh, class GeomTraits, class SolverTraits>
struct Trivial_connection_solver_types
{
  using Vertex_point_map = typename CGAL::GetVertexPointMap<TriangleMesh>::const_type;
  using Point = typename boost::property_traits<Vertex_point_map>::value_type;
  using Geom_traits = typename CGAL::Default::Get<GeomTraits, typename CGAL::Kernel_traits<Point>::Kernel>::type;
#ifdef CGAL_EIGEN3_ENABLED
  using Default_solver = Default_solver_traits;
#else
  using Default_solver = void;
#endif
  using Solver_traits = typename CGAL::Default::Get<SolverTraits, Default_solver>::type;
  static_assert(!std::is_same<Solver_traits, void>::value,
                "Trivial_connection_solver needs a sparse solver: link CGAL::Eigen3_support (which defines "
                "CGAL_EIGEN3_ENABLED) or pass a model of SparseLinearAlgebraWithFactorTraits_d as SolverTraits");
};

// read-only access to the solver's layers for the placement functions (placement/), which build on them
template <class Solver>
struct Solver_access;

} // namespace internal

/*!
\ingroup PkgTrivialConnectionsRef

Computes trivial connections closest to Levi-Civita and the direction fields they define on a triangle
mesh. Everything that depends only on the mesh (flat arrays, angles, weights, tree-cotree loops, the
sparse factorization) is done once in the constructor; each `solve()` then costs back-substitutions only.

The unknown is one angle `x_e` per interior edge. The constraints are one row per node of the surface in
which every boundary loop is collapsed to a point (each interior vertex, each boundary loop) and one row
per homology generator; in every connected component the node rows sum to zero, so the row of one node
(the last boundary loop, or on a closed component its first vertex) is dropped: its constraint follows
from the others and Poincare-Hopf, which is checked exactly beforehand. The minimiser of
`sum_e w_e x_e^2` is `x = W^-1 A^T lambda` with `(A W^-1 A^T) lambda = b`, factored once.

\tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph` with triangle faces
\tparam GeomTraits a kernel with `Point_3`, `Vector_3`, `Compute_x_3` (y, z), `Collinear_3`,
        `Construct_vector_3`. The default is the kernel of the vertex point map's value type.
\tparam SolverTraits a model of `TrivialConnectionSolverTraits`: `SparseLinearAlgebraWithFactorTraits_d` whose
        `Matrix` is constructible from `Eigen::SparseMatrix<double>` and has `eigen_object()` (as
        `CGAL::Eigen_sparse_matrix`). The default is
        `Default_solver_traits` (Eigen's `SimplicialLDLT`); `Cholmod_solver_traits` is faster on large meshes.
        The matrix handed to the backend is already in a fill-reducing order with the rows of the loop
        integers last; with these two traits the metric of the loop integers is read from the factor, with
        any other it costs one back-substitution per free loop (see the user manual).

\warning Computations use `double`, whatever the kernel.
*/
template <class TriangleMesh, class GeomTraits = CGAL::Default, class SolverTraits = CGAL::Default>
class Trivial_connection_solver
{
  using Types = internal::Trivial_connection_solver_types<TriangleMesh, GeomTraits, SolverTraits>;
  using Graph_traits = boost::graph_traits<TriangleMesh>;
  using Mesh = internal::Mesh_arrays<TriangleMesh>;
  using Sparse = Eigen::SparseMatrix<double>;

public:
  /// \name Types
  /// @{
  using Geom_traits = typename Types::Geom_traits;     ///< `GeomTraits`, or the point type's kernel
  using Solver_traits = typename Types::Solver_traits; ///< `SolverTraits`, or `Default_solver_traits`
  using Vector_3 = typename Geom_traits::Vector_3;     ///< the kernel's vector type (field directions)
  /// the mesh's vertex type
  using vertex_descriptor = typename Graph_traits::vertex_descriptor;
  /// the mesh's halfedge type
  using halfedge_descriptor = typename Graph_traits::halfedge_descriptor;
  /// the mesh's edge type
  using edge_descriptor = typename Graph_traits::edge_descriptor;
  /// the mesh's face type
  using face_descriptor = typename Graph_traits::face_descriptor;
  using Loop = Dual_loop<halfedge_descriptor>;         ///< a loop of `loops()`
  /// @}

  /*!
  Prepares everything that depends on the mesh only. `tm` is never modified and must outlive the solver.
  \param tm the triangle mesh
  \param np an optional sequence of named parameters among the ones listed below
  \cgalNamedParamsBegin
    \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
    \cgalParamNBegin{geom_traits} \cgalParamDefault{a default-constructed `Geom_traits`} \cgalParamNEnd
    \cgalParamNBegin{weighting} \cgalParamType{`Weighting`} \cgalParamDefault{`Weighting::hodge_star`} \cgalParamNEnd
    \cgalParamNBegin{progress} \cgalParamType{`Progress_callback`} \cgalParamDefault{none} \cgalParamNEnd
    \cgalParamNBegin{constrained_faces}
      \cgalParamDescription{faces on which the field must point in a direction given to each `solve()`
        (`face_directions`). Faces that touch (share an edge or a vertex) form clusters: within a cluster each
        link turns the short way between its two faces (its integer is the rounding, and it costs nothing: no
        dense block grows with the number of pins); the clusters of a component are linked by dual paths, one
        row each with a free integer chosen with the loop integers (see the user manual).
        `Solve_report::integers_proven_optimal` and `energy_lower_bound` cover every choice of both. Changing
        the directions costs back-substitutions only; `set_constraints()` changes the set of faces}
      \cgalParamType{a range of `face_descriptor`} \cgalParamDefault{none}
    \cgalParamNEnd
    \cgalParamNBegin{face_directions}
      \cgalParamDescription{optional, with `symmetry_order` (default 1): the targets of the constrained faces when
        they are known already (as for `solve()`). Touching faces whose targets then disagree by more than a
        quarter of 2 pi / n along their link are not linked the short way: their turn is left to the
        closest-vector search, with the loop integers. A zero vector means not known yet (that face is linked the
        short way). Each `solve()` still takes its own directions}
    \cgalParamNEnd
    \cgalParamNBegin{symmetry_order}
      \cgalParamDescription{the n the solves will use, for `face_directions` above and `align_with_boundary`}
      \cgalParamType{`int`} \cgalParamDefault{1 (the boundary's turns left free)}
    \cgalParamNEnd
    \cgalParamNBegin{align_with_boundary}
      \cgalParamDescription{every boundary face gets the direction of its border edge as its target (of its
        longer border edge when it has two): vectors along the boundary for n = 1, tangent lines for n = 2,
        crosses tangent and normal to it for n = 4. The targets of a boundary loop are linked through the fans of
        its vertices: the turn the field makes at each boundary vertex is an integer. With `symmetry_order` n >= 2
        given here, a turn within a quarter of 2 pi / n of a multiple of it is decided by rounding (the field turns the
        least at that vertex, as for touching pins; no dense block grows with the length of the boundary), the
        others are free integers chosen with the loop integers; otherwise every turn is free}
      \cgalParamType{`bool`} \cgalParamDefault{`false`}
    \cgalParamNEnd
    \cgalParamNBegin{guided_faces}
      \cgalParamDescription{soft guidance: faces on which the field is drawn towards a direction given to each
        `solve()` (`face_directions`). The solve then minimises `sum_e w_e x_e^2 + mu sum_g d_g^2`, with d_g the
        angle between the field and the guide on face g (modulo 2 pi / n), still with exactly the prescribed
        singularities; new guides cost back-substitutions only (see the user manual)}
      \cgalParamType{a range of `face_descriptor`} \cgalParamDefault{none}
    \cgalParamNEnd
    \cgalParamNBegin{guidance_weight}
      \cgalParamDescription{mu, positive and finite}
      \cgalParamType{`double`} \cgalParamDefault{1}
    \cgalParamNEnd
  \cgalNamedParamsEnd
  \throws Invalid_input `empty_mesh`, `not_triangle_mesh`, `non_manifold`, `non_finite_point`, `degenerate_face`,
          `invalid_constraint` (a constrained or guided face not of the mesh, listed twice, both constrained and
          guided, or on an aligned boundary; a direction given that is zero, not finite or normal to its face),
          `invalid_argument` (a guidance weight not positive and finite), `invalid_symmetry_order`, `solver_failure`
  */
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Trivial_connection_solver(const TriangleMesh& tm,
                                     const NamedParameters& np = parameters::default_values())
    : Trivial_connection_solver(tm,
                                [&] {
                                  notify(internal::progress_of(np), Phase::mesh_setup, 0);
                                  return Mesh(tm);
                                }(),
                                np)
  {
  }

  /// not copyable: it holds the factorization and refers to the mesh
  Trivial_connection_solver(const Trivial_connection_solver&) = delete;
  /// not copyable
  Trivial_connection_solver& operator=(const Trivial_connection_solver&) = delete;

private:
  // From the mesh's arrays, made already: by the constructor above, or from the validated connectivity a mesh
  // is built from (internal::Solver_access::make()), which spares deriving them from the mesh again. With such
  // arrays and a vertex point map in np, it reads nothing of tm (which may then still be under construction).
  template <class NamedParameters>
  Trivial_connection_solver(const TriangleMesh& tm, Mesh&& mesh, const NamedParameters& np)
    : m_tm(tm),
      m_traits(CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits),
                                                  Geom_traits())),
      m_weighting(CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::weighting),
                                                     Weighting::hodge_star)),
      m_progress(internal::progress_of(np)),
      m_mesh(std::move(mesh))
  {
    std::vector<int> user_faces, guided;
    internal::read_face_sets(m_mesh, np, user_faces, guided);
    const double mu = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::guidance_weight), 1.);
    if(!(mu > 0) || !std::isfinite(mu))
      throw Invalid_input(Error_code::invalid_argument,
                          "the guidance weight must be positive and finite (got " + std::to_string(mu) + ")");
    m_align = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::align_with_boundary), false);
    // The fill-reducing order of the node rows needs only the connectivity: it runs on a second thread while
    // the rest of the set-up (points, degenerate faces), the geometry and the trees are computed, and the
    // corner angles (not needed by the system) run beside the factorization.
    m_topology = internal::Mesh_topology(m_mesh);
    internal::Concurrent_node_order<Solver_traits> node_order(m_mesh, m_topology);
    m_mesh.check_and_read_points(internal::vertex_point_map_of(tm, np), m_traits);
    notify(Phase::mesh_setup, 1);
    notify(Phase::geometry, 0);
    m_geometry = internal::Mesh_geometry(m_mesh, m_weighting);
    notify(Phase::geometry, 1);
    notify(Phase::trees, 0);
    m_topology.build_trees(m_mesh, m_geometry.edge_of_corner, m_geometry.edge_corner);
    m_components = internal::component_reports(m_topology);
    build_loops();
    {
      std::vector<double> angles;
      const int n = internal::read_link_targets(m_mesh, m_traits, np, user_faces, angles);
      // the boundary's turns are decided for the symmetry order given here, from 2 on (and kept for
      // set_constraints()); 1 is also what a caller passes that does not know n yet (the Python module)
      if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::symmetry_order_t>::value)
        m_boundary_turn_order = n >= 2 ? n : 0;
      m_links = internal::Constraint_links(m_mesh, m_topology, user_faces, guided, m_align, mu, angles, n,
                                           m_boundary_turn_order);
    }
    notify(Phase::trees, 1);
    notify(Phase::assembly, 0);
    m_rows = internal::Constraint_rows(m_mesh, m_geometry, m_topology, m_links);
    node_order.wait_for_pattern();
    {
      Sparse M = internal::system_in_row_order(m_mesh, m_rows, node_order.node_start(), node_order.node_rows());
      std::vector<int> order = node_order.order();
      m_system.load(m_rows, M, order);
    }
    notify(Phase::assembly, 1);
    // beside the factorization rather than the assembly, which is more sensitive to a shared cache: the
    // corner angles (for the holonomies and the field) and the nodes of every edge (for the solves)
    std::future<int> angles = internal::concurrently([this] {
      m_geometry.compute_angles(m_mesh);
      m_rows.compute_edge_nodes(m_mesh);
      return 0;
    });
    notify(Phase::factorization, 0);
    m_system.factor(m_rows);
    notify(Phase::factorization, 1);
    angles.get();
    m_loop_holonomy = internal::levi_civita_holonomies(m_mesh, m_geometry, m_topology);
    m_gauss_bonnet_shares = internal::gauss_bonnet_rounding_shares(m_rows, m_loop_holonomy);
    notify(Phase::loop_metric, 0);
    m_system.compute_metrics(m_rows, m_links, m_components.size());
    m_lattices = internal::reduced_loop_lattices(m_system.metrics());
    notify(Phase::loop_metric, 1);
    m_progress = nullptr; // the callback may not outlive the constructor call
  }

public:

  /// \name Mesh information
  /// @{

  /// per component: its boundary loops, then its 2g generators; the order of `Solve_report::loops`
  /// \returns the non-contractible dual loops whose integers are free, components in the order of `components()`
  const std::vector<Loop>& loops() const { return m_loops; }
  /// topology of each connected component (`vertex_index_sum` is 0 here)
  /// \returns one report per connected component, in the order of the component indices of `component()`
  const std::vector<Component_report>& components() const { return m_components; }
  /// the component of a face
  /// \param f a face of the mesh
  /// \returns the 0-based index of its connected component, a position in `components()`
  std::size_t component(face_descriptor f) const
  {
    return std::size_t(m_topology.component_of_face[get(m_mesh.face_index, f)]);
  }
  /// `true` iff `e` has a face on both sides (only interior edges carry an angle `x_e`)
  /// \param e an edge of the mesh
  /// \returns whether `e` is an interior edge
  bool is_interior(edge_descriptor e) const { return !is_border(e, m_tm); }
  /// `w_e` of an interior edge. \pre `is_interior(e)`
  /// \param e an interior edge of the mesh
  /// \returns the weight `w_e` of `e` in the energy, for the `weighting()` of the solver
  double weight(edge_descriptor e) const
  {
    CGAL_precondition(is_interior(e));
    return m_geometry.weight[m_geometry.edge_of_corner[m_mesh.corner_of_edge(e, m_tm)]];
  }
  /// interior vertex: `2 pi - sum of its corner angles`; boundary vertex: `pi - sum`; isolated vertex: 0
  /// \param v a vertex of the mesh
  /// \returns the angle defect of `v`, in radians
  double angle_defect(vertex_descriptor v) const
  {
    const int i = int(get(m_mesh.vertex_index, v));
    return m_mesh.faces_at_vertex[i] > 0 ? m_geometry.angle_defect(i) : 0.;
  }
  /*!
  The change of frame angle of Levi-Civita transport from `face(h)` to `face(opposite(h))`, in
  `(-pi, pi]`: a direction at angle `t` (counter-clockwise from `halfedge(face(h))`) arrives at angle
  `t + transport_angle(h)` (counter-clockwise from `halfedge(face(opposite(h)))`), before the rotation by
  the connection. \pre `h` is a halfedge of an interior edge
  \param h a halfedge of an interior edge of the mesh
  \returns the transport angle of `h`, in radians, in `(-pi, pi]`
  */
  double transport_angle(halfedge_descriptor h) const
  {
    const int i = m_mesh.corner_of(h, m_tm);
    CGAL_precondition(i >= 0 && m_mesh.opposite_corner[i] >= 0);
    return m_geometry.transport_angle(i);
  }
  /// the position in `loops()` of the boundary loop through `v`; empty when `v` is not a boundary vertex of
  /// the mesh (an interior vertex, an isolated one, or not a vertex of the mesh)
  /// \param v a vertex descriptor
  /// \returns the 0-based index in `loops()` of the boundary loop through `v`, or `std::nullopt`
  std::optional<std::size_t> boundary_loop_of(vertex_descriptor v) const
  {
    const std::size_t i = std::size_t(get(m_mesh.vertex_index, v));
    if(i >= std::size_t(m_mesh.nv) || m_mesh.vertex_descriptors[i] != v)
      return std::nullopt;
    return m_topology.boundary_loop_of_node(m_topology.node_of_vertex[i]);
  }
  /// Levi-Civita holonomy `H_L` of `loops()[l]`: the exact geodesic curvature of a boundary loop, the
  /// holonomy wrapped to `(-pi, pi]` for a generator
  /// \param l the 0-based position of the loop in `loops()`, `l < loops().size()`
  /// \returns `H_L`, in radians
  double levi_civita_holonomy(std::size_t l) const { return m_loop_holonomy[l]; }
  /// the weights of the energy (the `weighting` named parameter of the constructor)
  /// \returns the weighting the solver was built with
  Weighting weighting() const { return m_weighting; }
  /// the kernel instance the geometry was computed with
  /// \returns the geometric traits given as `geom_traits` to the constructor, or the default-constructed one
  const Geom_traits& geom_traits() const { return m_traits; }
  /// the sparse solver holding the factorization of the constraint system, for example to ask
  /// `Cost_based_solver_traits::backend()` which backend it chose
  /// \returns the solver traits object the constructor (or the last `set_constraints()`) factored with
  const Solver_traits& solver_traits() const { return m_system.solver_traits(); }
  /// @}

  /*!
  Replaces the constrained and the guided faces by those of the named parameters `constrained_faces` and
  `guided_faces` (as for the constructor; an absent one means none). The boundary alignment and the guidance
  weight stay those given to the constructor. The mesh set-up, the geometry, the trees and the fill-reducing
  order are kept. With the default backend and with CHOLMOD, and when neither the old nor the new constrained
  faces touch one another, the factorization is kept too: the links that were factored by the constructor (or by
  the last full rebuild) and are still there keep their rows, the others are dropped from the dense block of the
  integers, and each new link costs one forward substitution through the factor (see the user manual).
  Otherwise (touching faces change the system itself, or other backends) the system is assembled and factored
  again, in the kept order: about the cost of the constructor's factorization, whatever the number of faces.
  \throws Invalid_input as the constructor for these parameters: the solver is then unchanged; and
  `solver_failure`, after which the solver is left without constrained or guided faces (but aligned if it was)
  \tparam NamedParameters a sequence of named parameters
  \param np a sequence of named parameters: `constrained_faces` and `guided_faces` are read (ranges of
         `face_descriptor`, as for the constructor), and `face_directions` with `symmetry_order` as for the
         constructor; any other is ignored
  \returns whether the system was factored again, and the number of links and forward substitutions
  */
  template <class NamedParameters = parameters::Default_named_parameters>
  Constraint_update set_constraints(const NamedParameters& np = parameters::default_values())
  {
    std::vector<int> user_faces, guided;
    internal::read_face_sets(m_mesh, np, user_faces, guided);
    Constraint_update update;
    try {
      std::vector<double> angles;
      const int n = internal::read_link_targets(m_mesh, m_traits, np, user_faces, angles);
      internal::Constraint_links links(m_mesh, m_topology, user_faces, guided, m_align, m_links.guidance_weight,
                                       angles, n, m_boundary_turn_order);
      // touching pins fix edges, which changes M: only links without them go outside a kept factor
      if(m_system.loop_rows_in_factor() && m_rows.decided_slots.empty() && !links.has_decided_links()) {
        m_links = std::move(links);
        update = m_system.set_links(m_links, m_rows);
        m_bordered_request = {std::move(user_faces), std::move(guided), std::move(angles), n};
      } else {
        rebuild(user_faces, guided, angles, n);
        update.refactored = true;
        update.links = m_links.links.size();
      }
      m_lattices = internal::reduced_loop_lattices(m_system.metrics());
    } catch(...) {
      rebuild({}, {}, {}, 1);
      m_lattices = internal::reduced_loop_lattices(m_system.metrics());
      throw;
    }
    return update;
  }

  /*!
  Computes the trivial connection closest to Levi-Civita with the given singularities and writes it.
  \param singularities a range whose value type has `first` (a `vertex_descriptor`) and `second`
         (a `Singularity_index`); vertices not listed have index 0
  \param x a writable property map `halfedge_descriptor -> double`: receives `x(h)` for both halfedges of
         every interior edge (`x(opposite(h)) = -x(h)`), and 0 for the halfedges of border edges
  \param np an optional sequence of named parameters among the ones listed below
  \cgalNamedParamsBegin
    \cgalParamNBegin{symmetry_order} \cgalParamType{`int`} \cgalParamDefault{1} \cgalParamNEnd
    \cgalParamNBegin{loop_periods}
      \cgalParamDescription{the integer of every loop of `loops()`: `period` with `H_L + sum_L x = 2 pi period / n`.
        With `std::optional` entries, the empty ones are chosen by the solver (minimising the energy with the
        others fixed); the boundary loops of a component are prescribed all or none}
      \cgalParamType{`std::vector<std::int64_t>` or `std::vector<std::optional<std::int64_t>>`}
      \cgalParamDefault{the integers minimising the energy}
    \cgalParamNEnd
    \cgalParamNBegin{face_directions}
      \cgalParamDescription{a readable property map `face_descriptor -> Vector_3`, read at the faces given as
        `constrained_faces` (the direction the field must have there, as one of its n directions) and as
        `guided_faces` (the guide), projected onto the face. Required when the solver has such faces}
    \cgalParamNEnd
    \cgalParamNBegin{energy_gradient}
      \cgalParamDescription{a writable property map `vertex_descriptor -> double` that receives, at every interior
        vertex v, g_v = dE / dk_v: the derivative of the minimised energy E (`energy + guidance_energy`) with
        respect to the index of v, the integers kept, the change balanced by the node whose row is dropped
        (see the class description; g is 0 there and at boundary and isolated vertices). Moving a part d of an
        index from v to w changes E by d (g_w - g_v) to first order, plus a positive second-order term. It is
        4 pi times v's Lagrange multiplier, so it costs nothing more than the solve}
    \cgalParamNEnd
  \cgalNamedParamsEnd
  \throws Invalid_input `invalid_symmetry_order`, `invalid_vertex`, `singularity_on_boundary`,
          `duplicate_singularity`, `index_not_multiple`, `poincare_hopf_violated`, `invalid_loop_periods`,
          `invalid_constraint` (directions missing, or zero, not finite or normal to their face),
          `solver_failure`
  \returns the energy, the residuals, the integer of every loop and link (chosen or prescribed) and the
           topology of every component (with the sum of its vertex indices)
  */
  template <class SingularityRange, class HalfedgeAngleMap,
            class NamedParameters = parameters::Default_named_parameters>
  Solve_report solve(const SingularityRange& singularities, HalfedgeAngleMap x,
                     const NamedParameters& np = parameters::default_values())
  {
    const int n = internal::symmetry_order_of(np);
    Solve_report report;
    report.symmetry_order = n;
    report.components = m_components;
    const std::vector<std::int64_t> k =
      internal::checked_vertex_indices(m_mesh, m_geometry, m_topology, singularities, n, report.components);
    // per slot (loops, then links): H with H + sum x = 2 pi period / n
    const std::vector<double> holonomy =
      internal::slot_holonomies(m_rows, m_loop_holonomy, internal::target_angles(m_mesh, m_traits, m_links, np));
    std::vector<std::int64_t> periods(holonomy.size(), 0);
    std::vector<char> prescribed(holonomy.size(), 0);
    if(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::loop_periods_t>::value)
      internal::read_prescribed_periods(internal::optional_periods(CGAL::parameters::choose_parameter(
                                          CGAL::parameters::get_parameter(np, tc_np::loop_periods),
                                          std::vector<std::int64_t>())),
                                        m_topology, report.components, n, periods, prescribed);

    const Progress_callback progress = internal::progress_of(np);
    const double unit = 2 * CGAL_PI / n;
    notify(progress, Phase::solve, 0);
    // the links between touching pins are decided by rounding; the edges they fix move to the right-hand side
    const bool decided = !m_rows.decided_slots.empty();
    Eigen::VectorXd x_fixed;
    if(decided)
      x_fixed = internal::decided_connection(m_rows, holonomy, unit, periods);
    Eigen::VectorXd b = internal::right_hand_side(m_rows, k, periods, holonomy, n, m_gauss_bonnet_shares);
    if(decided) {
      internal::Constraint_sums fixed_sums;
      m_rows.sums_of(x_fixed, std::vector<double>(m_links.number_of_guided_faces(), 0.), fixed_sums);
      b -= m_rows.row_sums(fixed_sums);
    }
    bool choose_periods = false; // a slot with a row whose integer is not prescribed
    for(const std::vector<int>& free : m_rows.free_slots)
      for(int l : free)
        choose_periods = choose_periods || !prescribed[l];
    Eigen::VectorXd lambda;
    internal::Integer_choice_energies energies;
    energies.want_relaxed = decided && m_bound_decided_choices;
    std::vector<std::int64_t> hint; // the refinement's, for this solve alone
    {
      std::lock_guard<std::mutex> lock(m_last_solve_mutex);
      hint.swap(m_period_hint);
    }
    if(choose_periods)
      lambda = internal::solve_choosing_integers(
        m_system, m_rows, m_lattices, b, unit, prescribed, holonomy, periods, energies,
        [&](double fraction) { notify(progress, Phase::loop_integers, fraction); }, hint.empty() ? nullptr : &hint);
    else
      lambda = m_system.solve(m_rows, b);

    constexpr bool wants_gradient =
      !CGAL::parameters::is_default_parameter<NamedParameters, tc_np::energy_gradient_t>::value;
    if constexpr(wants_gradient)
      write_energy_gradient(lambda, CGAL::parameters::get_parameter(np, tc_np::energy_gradient));
    {
      std::lock_guard<std::mutex> lock(m_last_solve_mutex); // solves may run concurrently
      if constexpr(wants_gradient)
        m_multipliers = lambda;
      m_last_periods = periods;
      m_free_integers_proven = energies.proven;
    }
    // the connection and its sums in vectors the solver keeps for later solves (see Connection_workspace)
    Workspace_lease workspace(*this);
    internal::Constraint_sums& sums = workspace->sums;
    Eigen::VectorXd& xe = workspace->connection;
    internal::checked_connection(
      m_rows, [&](const Eigen::VectorXd& r) { return m_system.solve(m_rows, r); }, b, lambda, sums, xe,
      workspace->checked, m_refine_residuals_above);
    if(decided) {
      xe += x_fixed;
      internal::Constraint_sums with_fixed;
      m_rows.sums_of(xe, sums.slack, with_fixed);
      sums = std::move(with_fixed);
    }
    internal::write_connection(m_tm, m_mesh, m_rows, xe, x);
    internal::fill_report(m_rows, sums, m_loop_holonomy, k, periods, prescribed, holonomy, n, report);
    const double minimised = report.energy + report.guidance_energy;
    const double fixed_energy = decided ? internal::decided_energy(m_rows, x_fixed) : 0.;
    report.rounding_energy = choose_periods ? energies.rounding_energy + fixed_energy : minimised;
    // the bound is exact arithmetic on the enumeration's costs: rounding may put it a hair above the energy
    report.energy_lower_bound =
      energies.proven ? minimised : (std::min)(energies.lower_bound + fixed_energy, minimised);
    if(decided && !m_bound_decided_choices) {
      energies.proven = false; // the decided integers' other choices not bounded: nothing claimed for them
      report.energy_lower_bound = 0;
    } else if(decided) {
      // the choices where a decided integer differs from its rounding (see decided_links_bound())
      double relaxed_energy = minimised;
      Eigen::VectorXd relaxed_lambda = lambda;
      if(choose_periods) {
        relaxed_lambda = m_system.solve(m_rows, energies.relaxed_rhs);
        relaxed_energy = energies.relaxed_rhs.dot(relaxed_lambda) + fixed_energy;
      }
      const double others =
        internal::decided_links_bound(m_rows, relaxed_lambda, relaxed_energy, x_fixed, holonomy, periods, unit);
      energies.proven = energies.proven && others >= minimised * (1 - 1e-12);
      report.energy_lower_bound = (std::min)(report.energy_lower_bound, others);
    }
    report.integers_proven_optimal = energies.proven;
    notify(progress, Phase::solve, 1);
    return report;
  }

  /*!
  Writes the direction field defined by a trivial connection: starting from the seed face, a unit
  tangent vector is moved along a breadth-first dual spanning tree of each component by Levi-Civita
  transport followed by the rotation `x(h)`. For an n-direction field it is one of the n directions.
  \param x a readable property map `halfedge_descriptor -> double` holding a connection (from `solve()`)
  \param field a writable property map `face_descriptor -> Vector_3`
  \param np an optional sequence of named parameters among the ones listed below
  \cgalNamedParamsBegin
    \cgalParamNBegin{seed_face} \cgalParamType{`face_descriptor`} \cgalParamDefault{the first face} \cgalParamNEnd
    \cgalParamNBegin{seed_angle}
      \cgalParamDescription{angle of the field in the seed face, counter-clockwise from the direction of `halfedge(seed_face)`}
      \cgalParamType{`double`} \cgalParamDefault{0}
    \cgalParamNEnd
    \cgalParamNBegin{face_directions}
      \cgalParamDescription{as for `solve()`: required when the solver has constrained or guided faces. A
        component with constrained faces starts from the target of one of them, so that the field meets every
        target; a component with guided faces only is rotated to minimise `sum_g d_g^2`}
    \cgalParamNEnd
    \cgalParamNBegin{symmetry_order}
      \cgalParamDescription{the n of the solve; required when a component has guided faces only (the mismatches
        are taken modulo 2 pi / n)}
      \cgalParamType{`int`}
    \cgalParamNEnd
  \cgalNamedParamsEnd
  Other components start with angle 0 in their first face (in face-index order).
  \throws Invalid_input `invalid_argument` (a seed face not of the mesh, or in a component with constrained
          faces), `invalid_constraint` (as `solve()`)
  */
  template <class HalfedgeAngleMap, class FaceVectorMap,
            class NamedParameters = parameters::Default_named_parameters>
  void compute_field(HalfedgeAngleMap x, FaceVectorMap field,
                     const NamedParameters& np = parameters::default_values()) const
  {
    const int seed = internal::seed_face_of(m_mesh, np);
    const double seed_angle = internal::seed_angle_of(np);
    const Progress_callback progress = internal::progress_of(np);
    notify(progress, Phase::field, 0);
    const std::vector<double> target =
      m_links.faces.empty() ? std::vector<double>() : internal::target_angles(m_mesh, m_traits, m_links, np);
    const std::vector<double> angle = internal::field_angles(m_mesh, m_geometry, m_topology, m_links, x, target,
                                                             internal::field_symmetry_order_of(np), seed, seed_angle);
    internal::write_field(m_mesh, angle, m_traits, field);
    notify(progress, Phase::field, 1);
  }

private:
  template <class S>
  friend struct internal::Solver_access;

  // E = b^T lambda with M lambda = b, so dE/db = 2 lambda, and a vertex's b is 2 pi k_v - K_v
  template <class VertexDoubleMap>
  void write_energy_gradient(const Eigen::VectorXd& lambda, VertexDoubleMap gradient) const
  {
    for(int v = 0; v < m_mesh.nv; ++v) {
      const int node = m_topology.node_of_vertex[v];
      const int r = node >= 0 && !m_geometry.on_boundary[v] ? m_rows.row_of_node[node] : -1;
      put(gradient, m_mesh.vertex_descriptors[v], r >= 0 ? 4 * CGAL_PI * lambda[r] : 0.);
    }
  }

  static void notify(const Progress_callback& progress, Phase p, double fraction)
  {
    if(progress)
      progress(p, fraction);
  }

  // the constructor's phases
  void notify(Phase p, double fraction) const { notify(m_progress, p, fraction); }

  // the loops of the topology as halfedges
  void build_loops()
  {
    for(const internal::Mesh_topology::Loop& l : m_topology.loops) {
      Loop loop;
      loop.kind = l.kind;
      loop.component = std::size_t(l.component);
      loop.halfedges.reserve(l.crossings.size());
      for(int i : l.crossings)
        loop.halfedges.push_back(m_mesh.halfedges[i]);
      m_loops.push_back(std::move(loop));
    }
  }

  // The links bordered outside the factor by set_constraints() factored in: the same faces, the system assembled
  // and factored again (the refinement reads M^-1 from the factor). Nothing when no row is bordered.
  void factor_bordered_links()
  {
    if(!m_system.has_bordered_rows())
      return;
    try {
      rebuild(m_bordered_request.user_faces, m_bordered_request.guided, m_bordered_request.angles, m_bordered_request.n);
      m_lattices = internal::reduced_loop_lattices(m_system.metrics());
    } catch(...) { // as set_constraints()
      rebuild({}, {}, {}, 1);
      m_lattices = internal::reduced_loop_lattices(m_system.metrics());
      throw;
    }
  }

  // The system again for new constrained and guided faces, on the same mesh data and node order.
  void rebuild(const std::vector<int>& user_faces, const std::vector<int>& guided, const std::vector<double>& angles,
               int n)
  {
    std::vector<int> order = m_system.node_order(m_rows, m_topology.number_of_nodes);
    m_links = internal::Constraint_links(m_mesh, m_topology, user_faces, guided, m_align, m_links.guidance_weight,
                                         angles, n, m_boundary_turn_order);
    std::vector<std::array<int, 2>> edge_nodes = std::move(m_rows.edge_nodes);
    m_rows = internal::Constraint_rows(m_mesh, m_geometry, m_topology, m_links);
    m_rows.edge_nodes = std::move(edge_nodes);
    m_system.refactor(m_mesh, m_rows, m_links, order, m_components.size());
  }

  // The parts, one per layer, declared in the order they are built: each is made from the ones before it and
  // keeps at most const references to them; none knows the coordinator, which alone sequences them and is
  // the only one to read named parameters (internal/solver_parameters.h: n, the weights and mu enter here and are
  // passed down as values).
  const TriangleMesh& m_tm;                  // the user's mesh, read only
  Geom_traits m_traits;
  Weighting m_weighting;
  Progress_callback m_progress;              // only during the constructor
  Mesh m_mesh;                               // mesh/: the flat arrays
  internal::Mesh_geometry m_geometry;        // mesh/: angles, transport, weights
  internal::Mesh_topology m_topology;        // topology/: trees, loops
  std::vector<Loop> m_loops;                 // the loops and components as loops() and components() give them
  std::vector<Component_report> m_components;
  std::vector<double> m_loop_holonomy;       // topology/: per loop, H_L
  std::vector<double> m_gauss_bonnet_shares; // system/: per component, the rounding each node row takes
  bool m_align = false;                      // align_with_boundary
  internal::Constraint_links m_links;        // system/: constrained and guided faces, links, mu
  internal::Constraint_rows m_rows;          // system/: the rows of A x = b
  internal::Prefactored_system<Solver_traits> m_system; // factorization/: M factored, its solves
  std::vector<internal::Reduced_lattice> m_lattices;    // integers/: per component, the reduced lattice of its integers
  Eigen::VectorXd m_multipliers; // of the last solve that gave its energy gradient (the refinement reads them)
  // solve()'s connection, its constraint sums and scratch vectors, kept for later solves: one set per solve running
  // at once (solves may run concurrently), taken and given back under a lock
  struct Solve_workspace
  {
    Eigen::VectorXd connection;
    internal::Constraint_sums sums;
    internal::Connection_workspace checked;
  };
  class Workspace_lease
  {
  public:
    explicit Workspace_lease(Trivial_connection_solver& s) : m_solver(s)
    {
      std::lock_guard<std::mutex> lock(s.m_workspaces_mutex);
      if(!s.m_workspaces.empty()) {
        m_workspace = std::move(s.m_workspaces.back());
        s.m_workspaces.pop_back();
      }
      if(!m_workspace)
        m_workspace.reset(new Solve_workspace());
    }
    ~Workspace_lease()
    {
      std::lock_guard<std::mutex> lock(m_solver.m_workspaces_mutex);
      m_solver.m_workspaces.push_back(std::move(m_workspace));
    }
    Workspace_lease(const Workspace_lease&) = delete;
    Workspace_lease& operator=(const Workspace_lease&) = delete;
    Solve_workspace* operator->() { return m_workspace.get(); }

  private:
    Trivial_connection_solver& m_solver;
    std::unique_ptr<Solve_workspace> m_workspace;
  };
  std::mutex m_workspaces_mutex;
  std::vector<std::unique_ptr<Solve_workspace>> m_workspaces; // given back, free
  double m_refine_residuals_above = internal::refine_residuals_above; // see checked_connection()
  // whether solve() bounds the other choices of the decided links (a solve more, for the report alone: the
  // refinement's trial solves skip it), and whether the last solve proved its free integers optimal (loops and
  // links not decided, the decided ones held: what the refinement's moves can change)
  bool m_bound_decided_choices = true;
  bool m_free_integers_proven = false;
  // the integers of every slot of the last solve, and those the next solve alone tries too (the refinement's)
  std::vector<std::int64_t> m_last_periods, m_period_hint;
  std::mutex m_last_solve_mutex; // over these, m_multipliers and m_free_integers_proven: solves run concurrently
  struct Face_sets
  {
    std::vector<int> user_faces, guided;
    std::vector<double> angles;
    int n = 1;
  } m_bordered_request; // what the last set_constraints() that kept the factorization was given
  int m_boundary_turn_order = 0; // the constructor's symmetry_order, when given (see Constraint_links)
};

} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/Trivial_connections/internal/solver_access.h>

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_SOLVER_H
