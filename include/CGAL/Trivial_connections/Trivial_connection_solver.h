// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_SOLVER_H
#define CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_SOLVER_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/internal/concurrency.h>
#include <CGAL/Trivial_connections/internal/geometry.h>
#include <CGAL/Trivial_connections/internal/integer_periods.h>
#include <CGAL/Trivial_connections/internal/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology.h>

#include <CGAL/Default.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <CGAL/Trivial_connections/solver_traits.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <future>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
A closed dual loop given by the halfedges it crosses: `halfedges[i]` is crossed from `face(halfedges[i])`
to `face(opposite(halfedges[i]))`, and `face(opposite(halfedges[i])) == face(halfedges[i+1])` cyclically.
A boundary loop crosses, vertex after vertex of the boundary, every interior edge of each vertex's open
fan counter-clockwise (an interior edge joining two of its vertices is crossed twice, once each way).
*/
template <class HalfedgeDescriptor>
struct Dual_loop
{
  Loop_kind kind = Loop_kind::generator;     ///< boundary loop or homology generator
  std::size_t component = 0;                 ///< index of the loop's component
  std::vector<HalfedgeDescriptor> halfedges; ///< the halfedges crossed, in order (see above)
};

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
        (`face_directions`). Per component, the constrained faces are linked by dual paths, one row each with a
        free integer chosen with the loop integers (see the user manual). Changing the directions costs
        back-substitutions only; `set_constraints()` changes the set of faces}
      \cgalParamType{a range of `face_descriptor`} \cgalParamDefault{none}
    \cgalParamNEnd
    \cgalParamNBegin{align_with_boundary}
      \cgalParamDescription{every boundary face gets the direction of its border edge as its target (of its
        longer border edge when it has two): vectors along the boundary for n = 1, tangent lines for n = 2,
        crosses tangent and normal to it for n = 4. The targets of a boundary loop are linked through the fans of
        its vertices, so the turn the field makes at each boundary vertex is one of the free integers}
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
  \throws Invalid_input `empty_mesh`, `not_triangle_mesh`, `non_manifold`, `degenerate_face`,
          `invalid_constraint` (a constrained or guided face not of the mesh, listed twice, both constrained and
          guided, or on an aligned boundary), `invalid_argument` (a guidance weight not positive and finite),
          `solver_failure`
  */
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Trivial_connection_solver(const TriangleMesh& tm,
                                     const NamedParameters& np = parameters::default_values())
    : m_tm(tm),
      m_traits(CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits),
                                                  Geom_traits())),
      m_weighting(CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::weighting),
                                                     Weighting::hodge_star)),
      m_progress(progress_of(np)),
      m_mesh([&] {
        notify(Phase::mesh_setup, 0);
        return Mesh(tm);
      }()),
      m_geometry(),
      m_topology()
  {
    std::vector<int> user_faces, guided;
    read_face_sets(np, user_faces, guided);
    m_guidance_weight = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::guidance_weight), 1.);
    if(!(m_guidance_weight > 0) || !std::isfinite(m_guidance_weight))
      throw Invalid_input(Error_code::invalid_argument, "the guidance weight must be positive and finite (got " +
                                                          std::to_string(m_guidance_weight) + ")");
    m_align = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::align_with_boundary), false);
    // The fill-reducing order of the node rows needs only the connectivity: it runs on a second thread
    // while the rest of the set-up (points, degenerate faces), the geometry and the trees are computed, and
    // the corner angles (not needed by the system) run beside the factorization. The other thread never
    // calls user code (property maps, the callback) and never reads what the main thread writes meanwhile;
    // when the main thread throws, the future's destructor waits for it.
    m_topology = internal::Mesh_topology(m_mesh);
    // The pattern of the node rows, made by the other thread: it orders the pattern, this thread fills in
    // M's values on it (read-only for both once `pattern_ready`).
    std::vector<int> node_start, node_rows;
    std::promise<void> pattern_made;
    std::future<void> pattern_ready = pattern_made.get_future();
    std::future<std::vector<int>> node_order =
      internal::concurrently([this, &node_start, &node_rows, &pattern_made] {
        try {
          m_topology.node_adjacency(m_mesh, node_start, node_rows);
        } catch(...) {
          pattern_made.set_exception(std::current_exception());
          throw;
        }
        pattern_made.set_value();
        std::vector<int> order;
        internal::Fill_reducing_ordering<Solver_traits>::compute(m_topology.number_of_nodes, node_start, node_rows,
                                                                 order);
        return order;
      });
    m_mesh.check_and_read_points(CGAL::parameters::choose_parameter(
                                   CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                   get_const_property_map(CGAL::vertex_point, tm)),
                                 m_traits);
    notify(Phase::mesh_setup, 1);
    notify(Phase::geometry, 0);
    m_geometry = internal::Mesh_geometry(m_mesh, m_weighting);
    notify(Phase::geometry, 1);
    notify(Phase::trees, 0);
    m_topology.build_trees(m_mesh, m_geometry.edge_of_corner, m_geometry.edge_corner);
    build_loops();
    build_constraint_paths(user_faces, guided, m_align);
    notify(Phase::trees, 1);
    notify(Phase::assembly, 0);
    build_constraints();
    {
      std::vector<int> order;
      const bool deferred = node_order.wait_for(std::chrono::seconds(0)) == std::future_status::deferred;
      if(deferred)
        order = node_order.get(); // no second thread: the task runs here, now
      else
        pattern_ready.get();
      Sparse M = system_in_row_order(node_start, node_rows);
      if(!deferred)
        order = node_order.get(); // the other thread is done with the pattern
      std::vector<int>().swap(node_start);
      std::vector<int>().swap(node_rows);
      assemble_system(M, order); // ends the assembly phase
    }
    // beside the factorization rather than the assembly, which is more sensitive to a shared cache: the
    // corner angles (for the holonomies and the field) and the nodes of every edge (for the solves)
    std::future<int> angles = internal::concurrently([this] {
      m_geometry.compute_angles(m_mesh);
      m_edge_nodes.resize(std::size_t(m_geometry.number_of_interior_edges()));
      for(int e = 0; e < m_geometry.number_of_interior_edges(); ++e)
        m_edge_nodes[e] = nodes_of_edge(e);
      return 0;
    });
    factor();
    angles.get();
    compute_loop_holonomies();
    in_phase(Phase::loop_metric, [&] { compute_loop_metric(); return 0; });
    keep_factored_links();
    m_progress = nullptr; // the callback may not outlive the constructor call
  }

  /// not copyable: it holds the factorization and refers to the mesh
  Trivial_connection_solver(const Trivial_connection_solver&) = delete;
  /// not copyable
  Trivial_connection_solver& operator=(const Trivial_connection_solver&) = delete;

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
    const int node = m_topology.node_of_vertex[i];
    if(node < m_topology.number_of_interior_nodes)
      return std::nullopt;
    for(std::size_t l = 0; l < m_topology.loops.size(); ++l)
      if(m_topology.loops[l].kind == Loop_kind::boundary && m_topology.loops[l].node == node)
        return l;
    return std::nullopt;
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
  /// @}

  /*!
  Replaces the constrained and the guided faces by those of the named parameters `constrained_faces` and
  `guided_faces` (as for the constructor; an absent one means none). The boundary alignment and the guidance
  weight stay those given to the constructor. The mesh set-up, the geometry, the trees and the fill-reducing
  order are kept. With the default backend and with CHOLMOD the factorization is kept too: the links that were
  factored by the constructor (or by the last full rebuild) and are still there keep their rows, the others
  are dropped from the dense block of the integers, and each new link costs one forward substitution through
  the factor (see the user manual). With other backends the system is assembled and factored again.
  \throws Invalid_input as the constructor for these parameters: the solver is then unchanged; and
  `solver_failure`, after which the solver is left without constrained or guided faces (but aligned if it was)
  \tparam NamedParameters a sequence of named parameters
  \param np a sequence of named parameters: `constrained_faces` and `guided_faces` are read (ranges of
         `face_descriptor`, as for the constructor), any other is ignored
  \returns whether the system was factored again, and the number of links and forward substitutions
  */
  template <class NamedParameters = parameters::Default_named_parameters>
  Constraint_update set_constraints(const NamedParameters& np = parameters::default_values())
  {
    std::vector<int> user_faces, guided;
    read_face_sets(np, user_faces, guided);
    Constraint_update update;
    try {
      if(m_loop_rows_in_factor) {
        update = border_constraints(user_faces, guided);
      } else {
        rebuild_constraints(user_faces, guided);
        update.refactored = true;
        update.links = m_paths.size();
      }
    } catch(...) {
      rebuild_constraints({}, {});
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
    const int n = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1);
    if(n < 1)
      throw Invalid_input(Error_code::invalid_symmetry_order,
                          "the symmetry order n must be at least 1 (got " + std::to_string(n) + ")");
    Solve_report report;
    report.symmetry_order = n;
    report.components = m_components;

    const std::vector<std::int64_t> k = vertex_indices(singularities, n, report);
    // per slot (loops, then constraint paths): H with H + sum x = 2 pi period / n
    const std::vector<double> holonomy = slot_holonomies(constraint_angles(np));

    std::vector<std::int64_t> periods(holonomy.size(), 0);
    std::vector<char> prescribed(holonomy.size(), 0);
    const bool user_periods =
      !CGAL::parameters::is_default_parameter<NamedParameters, tc_np::loop_periods_t>::value;
    if(user_periods)
      read_periods(optional_periods(CGAL::parameters::choose_parameter(
                     CGAL::parameters::get_parameter(np, tc_np::loop_periods), std::vector<std::int64_t>())),
                   k, n, periods, prescribed);

    const Progress_callback progress = progress_of(np);
    const double unit = 2 * CGAL_PI / n;
    notify(progress, Phase::solve, 0);
    Eigen::VectorXd b = right_hand_side(k, periods, holonomy, n);
    Eigen::VectorXd lambda;
    double rounding_energy = 0;
    // the loops with a row whose integer is not prescribed
    bool choose_periods = false;
    for(const std::vector<int>& free : m_free_loops)
      for(int l : free)
        choose_periods = choose_periods || !prescribed[l];
    if(choose_periods && m_bordered_mode) {
      Bordered_forward forward = bordered_forward(b);
      notify(progress, Phase::loop_integers, 0);
      const double loop_energy = choose_loop_periods(forward.y, unit, prescribed, holonomy, periods, report);
      notify(progress, Phase::loop_integers, 1);
      std::vector<Eigen::VectorXd> blocks(m_components.size());
      for(std::size_t c = 0; c < m_components.size(); ++c) {
        Eigen::VectorXd t = forward.y[c];
        for(Eigen::Index a = 0; a < t.size(); ++a)
          if(!prescribed[m_free_loops[c][a]])
            t[a] += unit * double(periods[m_free_loops[c][a]]);
        blocks[c] = t.size() > 0 ? Eigen::VectorXd(m_loop_metric[c].system.solve(t)) : t;
      }
      rounding_energy = forward.node_part + loop_energy;
      lambda = bordered_backward(forward, blocks);
      add_loop_periods(periods, prescribed, unit, b);
    } else if(choose_periods && m_loop_rows_in_factor) {
      // One forward and one backward substitution in all, the free loop rows F last. The forward
      // substitution through the node columns N leaves on the rows F y = b_F - M_FN M_NN^-1 b_N, the
      // right-hand side of their Schur complement S = L_FF D_F L_FF^T (the trailing block of the factor):
      // lambda_F = S^-1 (y + unit m) for the loop integers m. So the continuous optimum is m = -y / unit,
      // and the integers change y only.
      using Substitutions = internal::Factor_substitutions<Solver_traits>;
      const Eigen::Index first = m_rows - Eigen::Index(m_free_rows.size());
      Eigen::VectorXd z = m_permutation * b;
      if constexpr(Substitutions::leading_columns)
        Substitutions::forward(m_solver, z, first);
      else
        Substitutions::forward(m_solver, z);
      std::vector<Eigen::VectorXd> y(m_components.size());
      for(std::size_t c = 0; c < m_components.size(); ++c) {
        const Loop_metric& metric = m_loop_metric[c];
        y[c].resize(Eigen::Index(metric.block.size()));
        for(Eigen::Index a = 0; a < y[c].size(); ++a)
          y[c][a] = z[first + metric.block[a]];
        if constexpr(!Substitutions::leading_columns) // the whole forward substitution gave L_FF^-1 y
          y[c] = metric.schur_factor.template triangularView<Eigen::Lower>() * y[c];
      }
      notify(progress, Phase::loop_integers, 0);
      const double loop_energy = choose_loop_periods(y, unit, prescribed, holonomy, periods, report);
      notify(progress, Phase::loop_integers, 1);
      for(std::size_t c = 0; c < m_components.size(); ++c) {
        const Loop_metric& metric = m_loop_metric[c];
        Eigen::VectorXd& t = y[c];
        for(Eigen::Index a = 0; a < t.size(); ++a)
          if(!prescribed[m_free_loops[c][a]]) // the prescribed ones are in b already
            t[a] += unit * double(periods[m_free_loops[c][a]]);
        metric.schur_factor.template triangularView<Eigen::Lower>().solveInPlace(t);
        for(Eigen::Index a = 0; a < t.size(); ++a)
          z[first + metric.block[a]] = t[a];
      }
      const Eigen::VectorXd z_nodes = z.head(first);
      Substitutions::scale(m_solver, z);
      rounding_energy = z_nodes.dot(z.head(first)) + loop_energy; // b_N^T M_NN^-1 b_N + the loop part
      if constexpr(Substitutions::leading_columns) {
        for(std::size_t c = 0; c < m_components.size(); ++c) {
          const Loop_metric& metric = m_loop_metric[c];
          Eigen::VectorXd t(Eigen::Index(metric.block.size()));
          for(Eigen::Index a = 0; a < t.size(); ++a)
            t[a] = z[first + metric.block[a]];
          metric.schur_factor.template triangularView<Eigen::Lower>().transpose().solveInPlace(t);
          for(Eigen::Index a = 0; a < t.size(); ++a)
            z[first + metric.block[a]] = t[a];
        }
        Substitutions::backward(m_solver, z, first);
      } else {
        Substitutions::backward(m_solver, z);
      }
      add_loop_periods(periods, prescribed, unit, b);
      lambda = m_permutation.transpose() * z;
    } else {
      if(choose_periods) {
        // checked here already: its loop multipliers choose the integers
        lambda = solve_system(b);
        std::vector<Eigen::VectorXd> y(m_components.size());
        double loop_part = 0; // y^T S^-1 y = lambda_F . y
        for(std::size_t c = 0; c < m_components.size(); ++c) {
          const Loop_metric& metric = m_loop_metric[c];
          Eigen::VectorXd lf(Eigen::Index(m_free_loops[c].size()));
          for(std::size_t a = 0; a < m_free_loops[c].size(); ++a)
            lf[Eigen::Index(a)] = lambda[m_row_of_loop[m_free_loops[c][a]]];
          const auto L = metric.schur_factor.template triangularView<Eigen::Lower>();
          y[c] = L * (metric.schur_diagonal.asDiagonal() * (L.transpose() * lf)); // S lambda_F
          loop_part += lf.dot(y[c]);
        }
        notify(progress, Phase::loop_integers, 0);
        rounding_energy = b.dot(lambda) - loop_part + choose_loop_periods(y, unit, prescribed, holonomy, periods, report);
        notify(progress, Phase::loop_integers, 1);
        add_loop_periods(periods, prescribed, unit, b);
      }
      lambda = unchecked_solve(b);
    }

    Constraint_sums sums;
    const Eigen::VectorXd xe = checked_connection(b, lambda, sums);
    write_connection(xe, x);

    fill_report(sums, k, periods, prescribed, holonomy, n, report);
    report.rounding_energy = choose_periods ? rounding_energy : report.energy + report.guidance_energy;
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
    const double seed_angle =
      CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::seed_angle), 0.);
    int seed = -1;
    if(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::seed_face_t>::value) {
      const face_descriptor f = CGAL::parameters::choose_parameter(
        CGAL::parameters::get_parameter(np, tc_np::seed_face), face_descriptor());
      seed = f == Graph_traits::null_face() ? -1 : int(get(m_mesh.face_index, f));
      if(seed < 0 || seed >= m_mesh.nf || m_mesh.face_descriptors[seed] != f)
        throw Invalid_input(Error_code::invalid_argument, "the seed face is not a face of the mesh");
    }
    if(!std::isfinite(seed_angle))
      throw Invalid_input(Error_code::invalid_argument, "the seed angle is not finite");
    const Progress_callback progress = progress_of(np);
    notify(progress, Phase::field, 0);

    std::vector<double> angle(m_mesh.nf, 0.);
    for(int f : m_topology.face_order) {
      const int i = m_topology.parent_corner[f];
      if(i >= 0)
        angle[f] = internal::wrap_angle(angle[Mesh::face_of(i)] + m_geometry.transport_angle(i) +
                                        get(x, m_mesh.halfedges[i]));
    }
    // per component, the rotation that puts the field on its seed's angle, or on the target of its first
    // constrained face (the connection carries it to the others)
    std::vector<double> shift(m_components.size(), 0.);
    std::vector<char> shifted(m_components.size(), 0);
    if(!m_constrained.empty()) {
      const std::vector<double> target = constraint_angles(np);
      for(std::size_t c = 0; c < m_components.size(); ++c)
        if(m_seed_constraint[c] >= 0) {
          shift[c] = target[m_seed_constraint[c]] - angle[m_constrained[m_seed_constraint[c]].face];
          shifted[c] = 1;
        }
      // a component with guided faces only: the rotation minimising sum_g d_g^2, the mismatches d_g wrapped to
      // a period of the n-field
      std::vector<std::vector<double>> offsets(m_components.size());
      for(std::size_t a = std::size_t(m_first_guided); a < m_constrained.size(); ++a) {
        const int f = m_constrained[a].face, c = m_topology.component_of_face[f];
        if(m_seed_constraint[c] < 0)
          offsets[c].push_back(angle[f] - target[a]);
      }
      const bool has_guided_only = std::any_of(offsets.begin(), offsets.end(),
                                               [](const std::vector<double>& o) { return !o.empty(); });
      if(has_guided_only) {
        if(CGAL::parameters::is_default_parameter<NamedParameters, tc_np::symmetry_order_t>::value)
          throw Invalid_input(Error_code::invalid_argument,
                              "a component has guided faces only: compute_field() needs the symmetry_order of the "
                              "solve to rotate the field towards the guides");
        const int n = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1);
        if(n < 1)
          throw Invalid_input(Error_code::invalid_symmetry_order,
                              "the symmetry order n must be at least 1 (got " + std::to_string(n) + ")");
        for(std::size_t c = 0; c < m_components.size(); ++c)
          if(!offsets[c].empty()) {
            shift[c] = best_rotation(offsets[c], 2 * CGAL_PI / n);
            shifted[c] = 1;
          }
      }
    }
    if(seed >= 0) {
      const int c = m_topology.component_of_face[seed];
      if(shifted[c])
        throw Invalid_input(Error_code::invalid_argument,
                            "the seed face is in a component with constrained or guided faces, which set the field there",
                            std::size_t(seed));
      shift[c] = seed_angle - angle[seed];
      shifted[c] = 1;
    }
    for(int f = 0; f < m_mesh.nf; ++f)
      if(shifted[m_topology.component_of_face[f]])
        angle[f] = internal::wrap_angle(angle[f] + shift[m_topology.component_of_face[f]]);
    typename Geom_traits::Construct_vector_3 vector = m_traits.construct_vector_3_object();
    for(int f = 0; f < m_mesh.nf; ++f) {
      const double c = std::cos(angle[f]), s = std::sin(angle[f]);
      internal::Vec3 ex, ey;
      internal::Mesh_geometry::frame(m_mesh, f, ex, ey);
      put(field, m_mesh.face_descriptors[f],
          vector(c * ex[0] + s * ey[0], c * ex[1] + s * ey[1], c * ex[2] + s * ey[2]));
    }
    notify(progress, Phase::field, 1);
  }

private:
  template <class NamedParameters>
  static Progress_callback progress_of(const NamedParameters& np)
  {
    return Progress_callback(
      CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::progress), Progress_callback()));
  }

  static void notify(const Progress_callback& progress, Phase p, double fraction)
  {
    if(progress)
      progress(p, fraction);
  }

  // the constructor's phases
  void notify(Phase p, double fraction) const { notify(m_progress, p, fraction); }

  template <class Make>
  auto in_phase(Phase p, Make&& make) -> decltype(make())
  {
    notify(p, 0);
    auto result = make();
    notify(p, 1);
    return result;
  }

  void build_loops()
  {
    const std::vector<internal::Mesh_topology::Component>& comps = m_topology.components;
    m_components.resize(comps.size());
    for(std::size_t c = 0; c < comps.size(); ++c) {
      m_components[c].number_of_faces = std::size_t(comps[c].faces);
      m_components[c].euler_characteristic = comps[c].euler_characteristic;
      m_components[c].genus = comps[c].genus;
      m_components[c].number_of_boundary_loops = std::size_t(comps[c].boundary_loops);
    }
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

  // `constrained_faces` and `guided_faces` as face indices, checked
  template <class NamedParameters>
  void read_face_sets(const NamedParameters& np, std::vector<int>& user_faces, std::vector<int>& guided) const
  {
    if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::constrained_faces_t>::value)
      user_faces = face_indices(CGAL::parameters::get_parameter(np, tc_np::constrained_faces), "constrained");
    if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::guided_faces_t>::value)
      guided = face_indices(CGAL::parameters::get_parameter(np, tc_np::guided_faces), "guided");
    std::vector<char> constrained(std::size_t(m_mesh.nf), 0);
    for(int f : user_faces)
      constrained[f] = 1;
    for(int f : guided)
      if(constrained[f])
        throw Invalid_input(Error_code::invalid_constraint,
                            "face " + std::to_string(f) + " is both constrained and guided", std::size_t(f));
  }

  // A range of faces given to the constructor, as face indices (checked: faces of the mesh, once each)
  template <class FaceRange>
  std::vector<int> face_indices(const FaceRange& range, const std::string& what) const
  {
    std::vector<int> faces;
    std::vector<char> listed(std::size_t(m_mesh.nf), 0);
    for(const face_descriptor f : range) {
      const std::size_t i = f == Graph_traits::null_face() ? std::size_t(m_mesh.nf) : std::size_t(get(m_mesh.face_index, f));
      if(i >= std::size_t(m_mesh.nf) || m_mesh.face_descriptors[i] != f)
        throw Invalid_input(Error_code::invalid_constraint, "a " + what + " face is not a face of the mesh");
      if(listed[i])
        throw Invalid_input(Error_code::invalid_constraint, "face " + std::to_string(i) + " is " + what + " twice", i);
      listed[i] = 1;
      faces.push_back(int(i));
    }
    return faces;
  }

  // The rows of the directional constraints: per component, the constrained faces are chained and each link
  // is a dual path, whose row says that the connection carries the target of one end to the target of the
  // other, up to a free multiple of 2 pi / n. With the boundary aligned, the boundary faces of each loop are
  // chained along the loop, each link being the open fan of the boundary vertex between them; the chains
  // and the faces the user constrains are then linked in the order of a depth-first traversal of the dual
  // spanning tree, by their paths in that tree (the tree paths between consecutive faces of a depth-first
  // order cross each tree edge at most twice in all). The links of a component form a tree on its
  // constrained faces, so the rows are independent of each other and of the cycle rows.
  // Guided faces (soft guidance) are linked like constrained ones; each has a slack, its mismatch d_g, which
  // enters its links' rows (see the user manual).
  void build_constraint_paths(const std::vector<int>& user_faces, const std::vector<int>& guided, bool align)
  {
    const internal::Mesh_topology& t = m_topology;
    const int nf = m_mesh.nf;
    std::vector<int> constraint_of_face(std::size_t(nf), -1);
    std::vector<std::vector<int>> units(t.components.size()); // per component: a constrained face of each chain
    auto add_face = [&](int f, int border_corner, bool soft = false) {
      CGAL_assertion(constraint_of_face[f] < 0);
      constraint_of_face[f] = int(m_constrained.size());
      m_constrained.push_back({f, border_corner, soft});
      return int(m_constrained.size()) - 1;
    };
    auto border_length = [&](int i) { return internal::norm(internal::sub(m_mesh.points[m_mesh.target_of(i)],
                                                                          m_mesh.points[m_mesh.source_of(i)])); };
    if(align) {
      for(const internal::Mesh_topology::Loop& loop : t.loops) {
        if(loop.kind != Loop_kind::boundary)
          continue;
        const std::vector<int>& corners = loop.border_corners;
        const int m = int(corners.size());
        // start where the face changes, so that a face with two border edges is one link of the chain
        int start = 0;
        while(start < m && Mesh::face_of(corners[start]) == Mesh::face_of(corners[(start + m - 1) % m]))
          ++start;
        start %= m;
        int previous = -1;
        for(int a = 0; a < m; ++a) {
          const int i = (start + a) % m, corner = corners[i], f = Mesh::face_of(corner);
          if(previous >= 0 && m_constrained[previous].face == f) {
            // the same face again (two border edges): it follows the longer one
            if(border_length(corner) > border_length(m_constrained[previous].border_corner))
              m_constrained[previous].border_corner = corner;
          } else {
            const int current = add_face(f, corner);
            if(previous >= 0) {
              // the fan of the vertex between them: from the previous border corner's face to this one
              const int j = (i + m - 1) % m;
              const int end = j + 1 < m ? loop.fan_start[j + 1] : int(loop.crossings.size());
              m_paths.push_back({previous, current, loop.component,
                                 std::vector<int>(loop.crossings.begin() + loop.fan_start[j],
                                                  loop.crossings.begin() + end)});
            } else {
              units[loop.component].push_back(current);
            }
            previous = current;
          }
        }
      }
    }
    // user targets, then guides: each face a chain of its own
    auto add_user_faces = [&](const std::vector<int>& faces, bool soft) {
      for(int f : faces) {
        if(constraint_of_face[f] >= 0)
          throw Invalid_input(Error_code::invalid_constraint,
                              "face " + std::to_string(f) + " is on the boundary, which the field is aligned with: " +
                                (soft ? "it cannot be guided too" : "it cannot have a target too"),
                              std::size_t(f));
        units[t.component_of_face[f]].push_back(add_face(f, -1, soft));
      }
    };
    add_user_faces(user_faces, false);
    m_first_guided = int(m_constrained.size());
    add_user_faces(guided, true);
    m_has_user_constraints = !user_faces.empty() || !guided.empty();
    m_seed_constraint.assign(t.components.size(), -1);
    if(m_constrained.empty())
      return;

    // depth-first preorder of the dual spanning tree, and depths, for the tree paths
    std::vector<int> child_start(std::size_t(nf) + 1, 0), children(std::size_t(nf), 0), depth(std::size_t(nf), 0);
    for(int f = 0; f < nf; ++f)
      if(t.parent_corner[f] >= 0)
        ++child_start[std::size_t(Mesh::face_of(t.parent_corner[f])) + 1];
    for(int f = 0; f < nf; ++f)
      child_start[f + 1] += child_start[f];
    {
      std::vector<int> next(child_start.begin(), child_start.end() - 1);
      for(int f : t.face_order) // parents first
        if(t.parent_corner[f] >= 0) {
          const int p = Mesh::face_of(t.parent_corner[f]);
          children[next[p]++] = f;
          depth[f] = depth[p] + 1;
        }
    }
    std::vector<int> preorder(std::size_t(nf), 0);
    {
      int count = 0;
      std::vector<int> stack;
      for(int f : t.face_order)
        if(t.parent_corner[f] < 0) {
          stack.push_back(f);
          while(!stack.empty()) {
            const int g = stack.back();
            stack.pop_back();
            preorder[g] = count++;
            for(int p = child_start[g + 1]; p-- > child_start[g];)
              stack.push_back(children[p]);
          }
        }
    }
    for(std::size_t c = 0; c < units.size(); ++c) {
      std::vector<int>& u = units[c];
      if(u.empty())
        continue;
      std::sort(u.begin(), u.end(), [&](int a, int b) {
        return preorder[m_constrained[a].face] < preorder[m_constrained[b].face];
      });
      // the field starts from a constrained face (its target is exact); a component with guided faces only
      // is rotated by compute_field()
      for(int a : u)
        if(!m_constrained[a].soft) {
          m_seed_constraint[c] = a;
          break;
        }
      for(std::size_t k = 1; k < u.size(); ++k) {
        // up from a to the common ancestor, then down to b
        int a = m_constrained[u[k - 1]].face, b = m_constrained[u[k]].face;
        std::vector<int> crossings, down;
        while(a != b) {
          if(depth[a] >= depth[b]) {
            crossings.push_back(m_mesh.opposite_corner[t.parent_corner[a]]);
            a = Mesh::face_of(t.parent_corner[a]);
          } else {
            down.push_back(t.parent_corner[b]);
            b = Mesh::face_of(t.parent_corner[b]);
          }
        }
        crossings.insert(crossings.end(), down.rbegin(), down.rend());
        m_paths.push_back({u[k - 1], u[k], int(c), std::move(crossings)});
      }
    }
    // per guided face, the links at it: the slack s_g enters +1 in a link from it, -1 in a link to it
    m_slack_start.assign(m_constrained.size() - std::size_t(m_first_guided) + 1, 0);
    for(const Constraint_path& path : m_paths)
      for(int end : {path.from, path.to})
        if(m_constrained[end].soft)
          ++m_slack_start[std::size_t(end - m_first_guided) + 1];
    for(std::size_t g = 1; g < m_slack_start.size(); ++g)
      m_slack_start[g] += m_slack_start[g - 1];
    m_slack_links.resize(std::size_t(m_slack_start.back()));
    std::vector<int> next(m_slack_start.begin(), m_slack_start.end() - 1);
    for(std::size_t j = 0; j < m_paths.size(); ++j)
      for(int end : {m_paths[j].from, m_paths[j].to})
        if(m_constrained[end].soft)
          m_slack_links[std::size_t(next[std::size_t(end - m_first_guided)]++)] =
            end == m_paths[j].from ? int(j) : ~int(j);
  }

  // The constraint rows again for new constrained and guided faces, on the same mesh data and node order.
  void rebuild_constraints(const std::vector<int>& user_faces, const std::vector<int>& guided)
  {
    // the nodes in their current order (positions of their rows), for the same fill-reducing order
    const internal::Mesh_topology& t = m_topology;
    std::vector<int> order(std::size_t(t.number_of_nodes));
    for(int node = 0; node < t.number_of_nodes; ++node)
      order[std::size_t(node)] = node;
    if(m_rows > 0)
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        const int ra = m_row_of_node[a], rb = m_row_of_node[b];
        return (ra < 0 ? -1 : m_permutation.indices()[ra]) < (rb < 0 ? -1 : m_permutation.indices()[rb]);
      });
    m_constrained.clear();
    m_paths.clear();
    m_slack_start.clear();
    m_slack_links.clear();
    m_free_rows.clear();
    m_border_corners.clear();
    build_constraint_paths(user_faces, guided, m_align);
    build_constraints();
    std::vector<int> node_start, node_rows;
    m_topology.node_adjacency(m_mesh, node_start, node_rows);
    Sparse M = system_in_row_order(node_start, node_rows);
    std::vector<int>().swap(node_start);
    std::vector<int>().swap(node_rows);
    assemble_system(M, order);
    factor();
    compute_loop_metric();
    keep_factored_links();
  }

  // ---- Constraint links outside the factorization (set_constraints() with a backend that exposes its factor)
  //
  // The factor is that of the constructor: node rows N, then the free rows F (loops and the links made then).
  // After set_constraints(), a link that is still there keeps its row in F, a link that is gone is dropped
  // from the dense block (its multiplier is 0: the Schur complement of the remaining rows is the principal
  // submatrix), and a new link e is a "bordered" row outside the factor: with its column K_e of the full
  // system, z_e = L_NN^-1 K_e,N (a forward substitution through the node columns, sparse) gives its Schur
  // complement entries S_Fe and S_ee' = M_ee' - z_e^T D_N^-1 z_e'. The integers then live on a dense block per
  // component over its free rows and its bordered rows, factored by a dense Cholesky.

  struct Link_key
  {
    int from_face, to_face;
    bool soft_from, soft_to;
    bool operator<(const Link_key& o) const
    {
      return std::tie(from_face, to_face, soft_from, soft_to) < std::tie(o.from_face, o.to_face, o.soft_from, o.soft_to);
    }
  };
  struct Factored_link
  {
    Link_key key;
    int row;
    std::vector<int> codes; // crossings, as in m_loop_edges
  };
  struct Bordered_row
  {
    Link_key key;
    int component = 0;
    std::vector<int> codes;
    std::vector<int> z_index;    // z_e = L_NN^-1 K_e,N: positions (< first) ...
    std::vector<double> z_value; // ... and values
    Eigen::VectorXd schur_free;  // S_Fe, over the positions of F
  };

  Link_key key_of(std::size_t j) const // of link j of m_paths
  {
    const int from = m_paths[j].from, to = m_paths[j].to;
    return {m_constrained[from].face, m_constrained[to].face, m_constrained[from].soft, m_constrained[to].soft};
  }

  // after a factorization: the links in the factor, and the metric of its free rows
  void keep_factored_links()
  {
    m_factored_links.clear();
    m_bordered.clear();
    m_bordered_mode = false;
    m_factor_metric = m_loop_metric;
    const std::size_t nl = m_topology.loops.size();
    for(std::size_t j = 0; j < m_paths.size(); ++j) {
      const std::size_t l = nl + j;
      m_factored_links.push_back({key_of(j), m_row_of_loop[l],
                                  std::vector<int>(m_loop_edges.begin() + m_loop_edge_start[l],
                                                   m_loop_edges.begin() + m_loop_edge_start[l + 1])});
    }
  }

  Eigen::Index system_size() const { return m_rows + Eigen::Index(m_bordered.size()); }

  Constraint_update border_constraints(const std::vector<int>& user_faces, const std::vector<int>& guided)
  {
    Constraint_update update;
    using Substitutions = internal::Factor_substitutions<Solver_traits>;
    const internal::Mesh_topology& t = m_topology;
    const std::size_t nl = t.loops.size();
    const Eigen::Index k = Eigen::Index(m_free_rows.size()), first = m_rows - k;
    m_constrained.clear();
    m_paths.clear();
    m_slack_start.clear();
    m_slack_links.clear();
    build_constraint_paths(user_faces, guided, m_align);

    // the row of every new link: in the factor, or bordered (computed before, or now)
    std::map<Link_key, int> factored;
    for(const Factored_link& link : m_factored_links)
      factored[link.key] = link.row;
    std::map<Link_key, std::size_t> previous;
    for(std::size_t e = 0; e < m_bordered.size(); ++e)
      previous[m_bordered[e].key] = e;
    std::vector<Bordered_row> bordered;
    std::vector<char> fresh;
    m_row_of_loop.resize(nl + m_paths.size());
    for(std::size_t j = 0; j < m_paths.size(); ++j) {
      const Link_key key = key_of(j);
      const auto f = factored.find(key);
      if(f != factored.end()) {
        m_row_of_loop[nl + j] = f->second;
        continue;
      }
      m_row_of_loop[nl + j] = int(m_rows) + int(bordered.size());
      const auto p = previous.find(key);
      if(p != previous.end()) {
        bordered.push_back(std::move(m_bordered[p->second]));
        fresh.push_back(0);
      } else {
        Bordered_row row;
        row.key = key;
        row.component = m_paths[j].component;
        for(int i : m_paths[j].crossings) {
          const int e = m_geometry.edge_of_corner[i];
          row.codes.push_back(m_geometry.edge_corner[e] == i ? e : ~e);
        }
        bordered.push_back(std::move(row));
        fresh.push_back(1);
      }
    }
    m_bordered = std::move(bordered);
    // the slots: loops as before, then the links; the free slots per component
    m_free_loops.assign(m_components.size(), {});
    for(std::size_t l = 0; l < m_row_of_loop.size(); ++l)
      if(m_row_of_loop[l] >= 0)
        m_free_loops[l < nl ? std::size_t(t.loops[l].component) : std::size_t(m_paths[l - nl].component)].push_back(int(l));
    m_loop_edge_start.resize(nl + 1);
    m_loop_edges.resize(std::size_t(m_loop_edge_start[nl]));
    for(auto& path : m_paths) {
      for(int i : path.crossings) {
        const int e = m_geometry.edge_of_corner[i];
        m_loop_edges.push_back(m_geometry.edge_corner[e] == i ? e : ~e);
      }
      m_loop_edge_start.push_back(int(m_loop_edges.size()));
      path.length = path.crossings.size();
      std::vector<int>().swap(path.crossings);
    }

    // K_e of the new bordered rows on the factor's rows: its nodes, the factor's crossing rows (generators and
    // links) through shared edges, and the slacks it shares with the factor's links
    std::unordered_map<int, std::vector<std::pair<int, double>>> crossers; // edge -> (factor row, sign)
    for(std::size_t e = 0; e < m_bordered.size(); ++e)
      if(fresh[e])
        for(int code : m_bordered[e].codes)
          crossers.emplace(edge_of_code(code), std::vector<std::pair<int, double>>());
    auto note_crossings = [&](int row, const int* begin, const int* end) {
      for(const int* c = begin; c != end; ++c) {
        const auto it = crossers.find(edge_of_code(*c));
        if(it != crossers.end())
          it->second.push_back({row, sign_of_code(*c)});
      }
    };
    for(std::size_t l = 0; l < nl; ++l)
      if(t.loops[l].kind == Loop_kind::generator)
        note_crossings(m_row_of_loop[l], m_loop_edges.data() + m_loop_edge_start[l],
                       m_loop_edges.data() + m_loop_edge_start[l + 1]);
    for(const Factored_link& link : m_factored_links)
      note_crossings(link.row, link.codes.data(), link.codes.data() + link.codes.size());
    for(std::size_t e = 0; e < m_bordered.size(); ++e) {
      if(!fresh[e])
        continue;
      Bordered_row& row = m_bordered[e];
      Eigen::VectorXd column = Eigen::VectorXd::Zero(m_rows);
      for(int code : row.codes) {
        const int edge = edge_of_code(code);
        const double v = sign_of_code(code) / m_geometry.weight[edge];
        const std::array<int, 2> ends = m_edge_nodes[edge];
        if(ends[0] != ends[1]) {
          if(m_row_of_node[ends[1]] >= 0) column[m_row_of_node[ends[1]]] += v;
          if(m_row_of_node[ends[0]] >= 0) column[m_row_of_node[ends[0]]] -= v;
        }
        for(const auto& c : crossers[edge])
          column[c.first] += v * c.second;
      }
      for(const Factored_link& link : m_factored_links)
        column[link.row] += slack_coupling(row.key, link.key);
      Eigen::VectorXd z = m_permutation * column;
      Eigen::VectorXd trailing;
      if constexpr(Substitutions::leading_columns) {
        Substitutions::forward(m_solver, z, first);
        trailing = z.tail(k);
      } else {
        Substitutions::forward(m_solver, z);
        trailing = trailing_times_lower(z.tail(k), false);
      }
      row.z_index.clear();
      row.z_value.clear();
      for(Eigen::Index i = 0; i < first; ++i)
        if(z[i] != 0) {
          row.z_index.push_back(int(i));
          row.z_value.push_back(z[i]);
        }
      row.schur_free = trailing;
    }
    bordered_metric();
    m_bordered_mode = true;
    update.links = m_paths.size();
    update.links_outside_the_factor = m_bordered.size();
    for(char f : fresh)
      update.new_forward_substitutions += std::size_t(f);
    return update;
  }

  // C C^T / mu between two links: the guided faces they share, +1 at the face a link leaves, -1 where it arrives
  double slack_coupling(const Link_key& a, const Link_key& b) const
  {
    double sum = 0;
    for(int i = 0; i < 2; ++i)
      for(int j = 0; j < 2; ++j) {
        const int fa = i == 0 ? a.from_face : a.to_face, fb = j == 0 ? b.from_face : b.to_face;
        const bool sa = i == 0 ? a.soft_from : a.soft_to, sb = j == 0 ? b.soft_from : b.soft_to;
        if(fa == fb && sa && sb)
          sum += (i == 0 ? 1. : -1.) * (j == 0 ? 1. : -1.);
      }
    return sum / m_guidance_weight;
  }

  // L_FF v (or L_FF^T v) over the positions of F, component by component (L_FF: the factor's trailing block)
  Eigen::VectorXd trailing_times_lower(const Eigen::VectorXd& v, bool transposed) const
  {
    Eigen::VectorXd out = Eigen::VectorXd::Zero(v.size());
    for(std::size_t c = 0; c < m_factor_metric.size(); ++c) {
      const std::vector<Eigen::Index>& block = m_factor_metric[c].block;
      if(block.empty())
        continue;
      Eigen::VectorXd t(Eigen::Index(block.size()));
      for(Eigen::Index a = 0; a < t.size(); ++a)
        t[a] = v[block[a]];
      const auto L = m_factor_metric[c].schur_factor.template triangularView<Eigen::Lower>();
      t = transposed ? Eigen::VectorXd(L.transpose() * t) : Eigen::VectorXd(L * t);
      for(Eigen::Index a = 0; a < t.size(); ++a)
        out[block[a]] = t[a];
    }
    return out;
  }

  // The dense block of the integers per component over its free rows (loops, links in the factor) and its
  // bordered rows, in the order of m_free_loops, and its Cholesky factorization
  void bordered_metric()
  {
    using Substitutions = internal::Factor_substitutions<Solver_traits>;
    const Eigen::Index k = Eigen::Index(m_free_rows.size()), first = m_rows - k;
    // S over the positions of F, per component of the factor: L D L^T
    std::vector<Eigen::Index> component_at(std::size_t(k), 0), index_at(std::size_t(k), 0);
    std::vector<Eigen::MatrixXd> S(m_factor_metric.size());
    for(std::size_t c = 0; c < m_factor_metric.size(); ++c) {
      const Loop_metric& metric = m_factor_metric[c];
      for(std::size_t a = 0; a < metric.block.size(); ++a) {
        component_at[std::size_t(metric.block[a])] = Eigen::Index(c);
        index_at[std::size_t(metric.block[a])] = Eigen::Index(a);
      }
      if(!metric.block.empty())
        S[c] = metric.schur_factor * metric.schur_diagonal.asDiagonal() * metric.schur_factor.transpose();
    }
    Eigen::VectorXd d_inverse = Eigen::VectorXd::Ones(m_rows); // D^-1
    if(m_rows > 0)
      Substitutions::scale(m_solver, d_inverse);
    // shared edges between bordered rows
    std::unordered_map<int, std::vector<std::pair<int, double>>> on_edge;
    for(std::size_t e = 0; e < m_bordered.size(); ++e)
      for(int code : m_bordered[e].codes)
        on_edge[edge_of_code(code)].push_back({int(e), sign_of_code(code)});
    const Eigen::Index ne = Eigen::Index(m_bordered.size());
    Eigen::MatrixXd M_EE = Eigen::MatrixXd::Zero(ne, ne);
    for(const auto& edge : on_edge)
      for(const auto& a : edge.second)
        for(const auto& b : edge.second)
          M_EE(a.first, b.first) += a.second * b.second / m_geometry.weight[edge.first];
    for(Eigen::Index a = 0; a < ne; ++a)
      for(Eigen::Index b = 0; b < ne; ++b)
        M_EE(a, b) += slack_coupling(m_bordered[a].key, m_bordered[b].key);
    // z_e^T D^-1 z_e' through a dense scatter of z_e'
    Eigen::VectorXd scattered = Eigen::VectorXd::Zero(first);
    for(Eigen::Index b = 0; b < ne; ++b) {
      const Bordered_row& rb = m_bordered[b];
      for(std::size_t q = 0; q < rb.z_index.size(); ++q)
        scattered[rb.z_index[q]] = rb.z_value[q] * d_inverse[rb.z_index[q]];
      for(Eigen::Index a = 0; a < ne; ++a) {
        if(m_bordered[a].component != rb.component)
          continue;
        double dot = 0;
        const Bordered_row& ra = m_bordered[a];
        for(std::size_t q = 0; q < ra.z_index.size(); ++q)
          dot += ra.z_value[q] * scattered[ra.z_index[q]];
        M_EE(a, b) -= dot;
      }
      for(int i : rb.z_index)
        scattered[i] = 0;
    }
    m_loop_metric.assign(m_components.size(), Loop_metric());
    for(std::size_t c = 0; c < m_components.size(); ++c) {
      const std::vector<int>& free = m_free_loops[c];
      const Eigen::Index kc = Eigen::Index(free.size());
      if(kc == 0)
        continue;
      Loop_metric& metric = m_loop_metric[c];
      metric.place.resize(free.size());
      for(Eigen::Index a = 0; a < kc; ++a) {
        const int row = m_row_of_loop[free[a]];
        metric.place[a] = row < m_rows ? m_permutation.indices()[row] - first : -1 - (row - m_rows);
      }
      Eigen::MatrixXd system(kc, kc);
      for(Eigen::Index a = 0; a < kc; ++a)
        for(Eigen::Index b = 0; b < kc; ++b) {
          const Eigen::Index pa = metric.place[a], pb = metric.place[b];
          if(pa >= 0 && pb >= 0) {
            CGAL_assertion(component_at[pa] == component_at[pb]);
            system(a, b) = S[component_at[pa]](index_at[pa], index_at[pb]);
          } else if(pa >= 0) {
            system(a, b) = m_bordered[-1 - pb].schur_free[pa];
          } else if(pb >= 0) {
            system(a, b) = m_bordered[-1 - pa].schur_free[pb];
          } else {
            system(a, b) = M_EE(-1 - pa, -1 - pb);
          }
        }
      system = (system + system.transpose()) / 2;
      metric.system.compute(system);
      if(metric.system.info() != Eigen::Success || !system.allFinite())
        throw Invalid_input(Error_code::solver_failure, "the metric of the integers is not positive definite");
      metric.inverse = metric.system.solve(Eigen::MatrixXd::Identity(kc, kc));
      metric.inverse = (metric.inverse + metric.inverse.transpose()) / 2;
      Eigen::LLT<Eigen::MatrixXd> llt(metric.inverse);
      if(llt.info() != Eigen::Success)
        throw Invalid_input(Error_code::solver_failure, "the metric of the integers is not positive definite");
      metric.inverse_factor = llt.matrixU();
    }
  }

  // With bordered rows: the forward part of a solve of the full system for b (rows, then bordered rows): z after
  // the forward substitution, u = D^-1 z, per component the right-hand side y of its dense block (in the order
  // of m_free_loops), and b_N^T M_NN^-1 b_N
  struct Bordered_forward
  {
    Eigen::VectorXd z, u;
    std::vector<Eigen::VectorXd> y;
    double node_part = 0;
  };

  Bordered_forward bordered_forward(const Eigen::VectorXd& b)
  {
    using Substitutions = internal::Factor_substitutions<Solver_traits>;
    const Eigen::Index k = Eigen::Index(m_free_rows.size()), first = m_rows - k;
    Bordered_forward f;
    f.z = m_permutation * b.head(m_rows);
    Eigen::VectorXd trailing;
    if constexpr(Substitutions::leading_columns) {
      Substitutions::forward(m_solver, f.z, first);
      trailing = f.z.tail(k);
    } else {
      Substitutions::forward(m_solver, f.z);
      trailing = trailing_times_lower(f.z.tail(k), false);
    }
    f.u = f.z;
    Substitutions::scale(m_solver, f.u);
    f.node_part = f.z.head(first).dot(f.u.head(first));
    f.y.resize(m_components.size());
    for(std::size_t c = 0; c < m_components.size(); ++c) {
      const Loop_metric& metric = m_loop_metric[c];
      f.y[c].resize(Eigen::Index(metric.place.size()));
      for(Eigen::Index a = 0; a < f.y[c].size(); ++a) {
        const Eigen::Index p = metric.place[a];
        if(p >= 0) {
          f.y[c][a] = trailing[p];
        } else {
          const Bordered_row& row = m_bordered[-1 - p];
          double v = b[m_rows + (-1 - p)];
          for(std::size_t q = 0; q < row.z_index.size(); ++q)
            v -= row.z_value[q] * f.u[row.z_index[q]];
          f.y[c][a] = v;
        }
      }
    }
    return f;
  }

  // the multipliers (rows, then bordered rows) from the forward part and the dense blocks' solutions
  Eigen::VectorXd bordered_backward(Bordered_forward& f, const std::vector<Eigen::VectorXd>& lambda_blocks)
  {
    using Substitutions = internal::Factor_substitutions<Solver_traits>;
    const Eigen::Index k = Eigen::Index(m_free_rows.size()), first = m_rows - k;
    Eigen::VectorXd lambda_free = Eigen::VectorXd::Zero(k), lambda_bordered = Eigen::VectorXd::Zero(system_size() - m_rows);
    for(std::size_t c = 0; c < m_components.size(); ++c)
      for(std::size_t a = 0; a < m_loop_metric[c].place.size(); ++a) {
        const Eigen::Index p = m_loop_metric[c].place[a];
        (p >= 0 ? lambda_free[p] : lambda_bordered[-1 - p]) = lambda_blocks[c][Eigen::Index(a)];
      }
    Eigen::VectorXd& z = f.z;
    for(Eigen::Index e = 0; e < lambda_bordered.size(); ++e) {
      const Bordered_row& row = m_bordered[std::size_t(e)];
      for(std::size_t q = 0; q < row.z_index.size(); ++q)
        z[row.z_index[q]] -= row.z_value[q] * lambda_bordered[e];
    }
    Substitutions::scale(m_solver, z);
    if constexpr(Substitutions::leading_columns) {
      z.tail(k) = lambda_free;
      Substitutions::backward(m_solver, z, first);
    } else {
      z.tail(k) = trailing_times_lower(lambda_free, true);
      Substitutions::backward(m_solver, z);
    }
    Eigen::VectorXd lambda(system_size());
    lambda.head(m_rows) = m_permutation.transpose() * z;
    lambda.tail(lambda_bordered.size()) = lambda_bordered;
    return lambda;
  }

  // M^-1 b with bordered rows
  Eigen::VectorXd bordered_solve(const Eigen::VectorXd& b)
  {
    Bordered_forward f = bordered_forward(b);
    std::vector<Eigen::VectorXd> lambda(m_components.size());
    for(std::size_t c = 0; c < m_components.size(); ++c)
      lambda[c] = f.y[c].size() > 0 ? Eigen::VectorXd(m_loop_metric[c].system.solve(f.y[c])) : Eigen::VectorXd();
    return bordered_backward(f, lambda);
  }

  // needs the corner angles
  void compute_loop_holonomies()
  {
    // exact geodesic curvature of each boundary loop: sum over its vertices of pi - their angle sums
    std::vector<double> geodesic_curvature(m_topology.number_of_nodes - m_topology.number_of_interior_nodes, 0.);
    for(int v = 0; v < m_mesh.nv; ++v)
      if(m_mesh.faces_at_vertex[v] > 0 && m_geometry.on_boundary[v])
        geodesic_curvature[m_topology.node_of_vertex[v] - m_topology.number_of_interior_nodes] +=
          m_geometry.angle_defect(v);
    m_loop_holonomy.clear();
    for(const internal::Mesh_topology::Loop& l : m_topology.loops) {
      double holonomy = 0;
      if(l.kind == Loop_kind::boundary) {
        holonomy = geodesic_curvature[l.node - m_topology.number_of_interior_nodes];
      } else {
        for(int i : l.crossings)
          holonomy += m_geometry.transport_angle(i);
        holonomy = internal::wrap_angle(holonomy);
      }
      m_loop_holonomy.push_back(holonomy);
    }
  }

  // Rows: every node except the pinned one of its component, then every generator.
  void build_constraints()
  {
    const internal::Mesh_topology& t = m_topology;
    m_row_of_node.assign(t.number_of_nodes, -1);
    int rows = 0;
    std::vector<char> pinned(t.number_of_nodes, 0);
    for(const auto& c : t.components)
      pinned[c.pinned_node] = 1;
    for(int node = 0; node < t.number_of_nodes; ++node)
      if(!pinned[node])
        m_row_of_node[node] = rows++;
    const std::size_t nl = t.loops.size(), slots = nl + m_paths.size();
    m_row_of_loop.assign(slots, -1);
    m_free_loops.assign(t.components.size(), {});
    for(std::size_t l = 0; l < slots; ++l) {
      const int component = l < nl ? t.loops[l].component : m_paths[l - nl].component;
      m_row_of_loop[l] = l < nl && t.loops[l].kind == Loop_kind::boundary ? m_row_of_node[t.loops[l].node] : rows++;
      if(m_row_of_loop[l] >= 0) {
        m_free_loops[component].push_back(int(l));
        m_free_rows.push_back(m_row_of_loop[l]);
      }
    }
    for(int i = 0; i < 3 * m_mesh.nf; ++i)
      if(m_mesh.opposite_corner[i] < 0)
        m_border_corners.push_back(i);
    m_vertex_of_node.assign(t.number_of_interior_nodes, -1);
    for(int v = 0; v < m_mesh.nv; ++v) {
      const int node = t.node_of_vertex[v];
      if(node >= 0 && node < t.number_of_interior_nodes)
        m_vertex_of_node[node] = v;
    }

    // per slot, its crossings as oriented interior edges (e: x_e, ~e: -x_e), for the solves
    auto crossings_of = [&](std::size_t l) -> const std::vector<int>& {
      return l < nl ? t.loops[l].crossings : m_paths[l - nl].crossings;
    };
    m_loop_edge_start.assign(slots + 1, 0);
    for(std::size_t l = 0; l < slots; ++l)
      m_loop_edge_start[l + 1] = m_loop_edge_start[l] + int(crossings_of(l).size());
    m_loop_edges.resize(std::size_t(m_loop_edge_start.back()));
    for(std::size_t l = 0; l < slots; ++l) {
      int* out = m_loop_edges.data() + m_loop_edge_start[l];
      for(int i : crossings_of(l)) {
        const int e = m_geometry.edge_of_corner[i];
        *out++ = m_geometry.edge_corner[e] == i ? e : ~e;
      }
    }
    for(Constraint_path& path : m_paths) {
      path.length = path.crossings.size();
      std::vector<int>().swap(path.crossings);
    }

    m_rows = rows;
  }

  // M = A W^-1 A^T, both triangles, in the order of the rows (where mesh files usually have locality),
  // without forming A. The node rows are the weighted Laplacian of the node graph: its pattern is
  // `node_start`/`node_rows` (from node_adjacency(), which the fill-reducing order reads meanwhile on the
  // other thread) and every interior edge adds its 1/w_e to four entries. The generator rows (last)
  // gather their crossings, Gustavson-style. Needs no fill-reducing order, so it is formed while that
  // order is computed.
  Sparse system_in_row_order(const std::vector<int>& node_start, const std::vector<int>& node_rows) const
  {
    const internal::Mesh_topology& t = m_topology;
    const int rows = int(m_rows), ne = m_geometry.number_of_interior_edges();
    int node_row_count = 0;
    for(int node = 0; node < t.number_of_nodes; ++node)
      if(m_row_of_node[node] >= 0)
        ++node_row_count;

    // generator (and constraint path) crossings per edge (CSR): (its row, +-1)
    const std::size_t slots = m_row_of_loop.size();
    std::vector<int> crossing_start(std::size_t(ne) + 1, 0);
    for(std::size_t l = 0; l < slots; ++l)
      if(is_crossing_slot(l))
        for(int p = m_loop_edge_start[l]; p < m_loop_edge_start[l + 1]; ++p)
          ++crossing_start[std::size_t(edge_of_code(m_loop_edges[p])) + 1];
    for(int e = 0; e < ne; ++e)
      crossing_start[e + 1] += crossing_start[e];
    std::vector<std::pair<int, double>> crossings((std::size_t(crossing_start[ne]))); // not a declaration (clang)
    {
      std::vector<int> next(crossing_start.begin(), crossing_start.end() - 1);
      for(std::size_t l = 0; l < slots; ++l)
        if(is_crossing_slot(l))
          for(int p = m_loop_edge_start[l]; p < m_loop_edge_start[l + 1]; ++p) {
            const int code = m_loop_edges[p];
            crossings[next[edge_of_code(code)]++] = {m_row_of_loop[l], sign_of_code(code)};
          }
    }

    // the generator rows (all their entries, sorted), which are also the generator entries of the node columns
    std::vector<int> generator_start(1, 0), generator_row;
    std::vector<double> generator_value;
    {
      std::vector<int> pattern, mark(std::size_t(rows), -1);
      std::vector<double> sum(std::size_t(rows), 0.);
      auto add = [&](int r, double v, int g) {
        if(mark[r] != g) {
          mark[r] = g;
          sum[r] = 0;
          pattern.push_back(r);
        }
        sum[r] += v;
      };
      for(std::size_t l = 0; l < slots; ++l) {
        if(!is_crossing_slot(l))
          continue;
        const int g = m_row_of_loop[l];
        pattern.clear();
        for(int p = m_loop_edge_start[l]; p < m_loop_edge_start[l + 1]; ++p) {
          const int code = m_loop_edges[p], e = edge_of_code(code);
          const double v = sign_of_code(code) / m_geometry.weight[e];
          const std::array<int, 2> ends = nodes_of_edge(e);
          const int a = ends[0], b = ends[1];
          if(a != b) {
            if(m_row_of_node[b] >= 0) add(m_row_of_node[b], v, g);
            if(m_row_of_node[a] >= 0) add(m_row_of_node[a], -v, g);
          }
          for(int q = crossing_start[e]; q < crossing_start[e + 1]; ++q)
            add(crossings[q].first, v * crossings[q].second, g);
        }
        if(l >= t.loops.size()) // a link: its guided ends' slacks couple it with the other links there (C C^T / mu)
          for_each_slack_coupling(int(l - t.loops.size()), [&](int other, double value) {
            add(m_row_of_loop[t.loops.size() + std::size_t(other)], value, g);
          });
        std::sort(pattern.begin(), pattern.end());
        for(int r : pattern) {
          generator_row.push_back(r);
          generator_value.push_back(sum[r]);
        }
        generator_start.push_back(int(generator_row.size()));
      }
    }
    CGAL_assertion(int(generator_start.size()) - 1 == rows - node_row_count);

    // column sizes: the non-pinned nodes of the pattern, then the generator rows coupled to the column
    Sparse M(rows, rows);
    int* outer = M.outerIndexPtr();
    std::fill(outer, outer + rows + 1, 0);
    for(int node = 0; node < t.number_of_nodes; ++node) {
      const int c = m_row_of_node[node];
      if(c < 0)
        continue;
      for(int p = node_start[node]; p < node_start[node + 1]; ++p)
        if(m_row_of_node[node_rows[p]] >= 0)
          ++outer[c + 1];
    }
    for(int g = node_row_count; g < rows; ++g) {
      const int first = generator_start[g - node_row_count], last = generator_start[g - node_row_count + 1];
      outer[g + 1] = last - first;
      for(int p = first; p < last; ++p)
        if(generator_row[p] < node_row_count)
          ++outer[generator_row[p] + 1];
    }
    for(int c = 0; c < rows; ++c)
      outer[c + 1] += outer[c];
    M.resizeNonZeros(outer[rows]);
    int* inner = M.innerIndexPtr();
    double* value = M.valuePtr();
    std::fill(value, value + outer[rows], 0.);
    // the node part of a node column, in row order (rows grow with nodes); then its generator rows
    std::vector<int> next(outer, outer + rows);
    for(int node = 0; node < t.number_of_nodes; ++node) {
      const int c = m_row_of_node[node];
      if(c < 0)
        continue;
      for(int p = node_start[node]; p < node_start[node + 1]; ++p) {
        const int r = m_row_of_node[node_rows[p]];
        if(r >= 0)
          inner[next[c]++] = r;
      }
    }
    const std::vector<int> node_part_end(next); // end of each node column's node part
    for(int g = node_row_count; g < rows; ++g)
      for(int p = generator_start[g - node_row_count]; p < generator_start[g - node_row_count + 1]; ++p) {
        const int r = generator_row[p];
        if(r < node_row_count) { // (g, r) and its mirror (r, g), generator rows in increasing order
          inner[next[r]] = g;
          value[next[r]++] = generator_value[p];
        }
        inner[next[g]] = r;
        value[next[g]++] = generator_value[p];
      }
    // the weighted Laplacian of the node graph: a few entries per column, found by a short scan
    auto entry = [&](int c, int r) -> double& {
      int p = outer[c];
      while(inner[p] != r)
        ++p;
      CGAL_assertion(p < node_part_end[c]);
      return value[p];
    };
    for(int e = 0; e < ne; ++e) {
      const std::array<int, 2> ends = nodes_of_edge(e);
      const int a = ends[0], b = ends[1];
      if(a == b)
        continue;
      const double v = 1 / m_geometry.weight[e];
      const int ra = m_row_of_node[a], rb = m_row_of_node[b];
      if(ra >= 0) entry(ra, ra) += v;
      if(rb >= 0) entry(rb, rb) += v;
      if(ra >= 0 && rb >= 0) {
        entry(ra, rb) -= v;
        entry(rb, ra) -= v;
      }
    }
    return M;
  }

  // The triangle that the backend reads (or the whole matrix) of `M` (from system_in_row_order()) in the
  // order m_permutation, columns sorted (short: insertion sort).
  Sparse ordered_system(const Sparse& M) const
  {
    const int rows = int(M.rows());
    const int* position = m_permutation.indices().data();
    std::vector<int> row_at(std::size_t(rows), 0);
    for(int r = 0; r < rows; ++r)
      row_at[position[r]] = r;
    Sparse S(rows, rows);
    S.resizeNonZeros(stored_triangle == 0 ? M.nonZeros() : (M.nonZeros() + rows) / 2);
    int* outer = S.outerIndexPtr();
    int* inner = S.innerIndexPtr();
    double* value = S.valuePtr();
    const int* m_outer = M.outerIndexPtr();
    const int* m_inner = M.innerIndexPtr();
    const double* m_value = M.valuePtr();
    int nnz = 0;
    for(int c = 0; c < rows; ++c) {
      outer[c] = nnz;
      const int begin = nnz;
      const int row = row_at[c];
      for(int p = m_outer[row]; p < m_outer[row + 1]; ++p) {
        const int r = position[m_inner[p]];
        if((stored_triangle == Eigen::Lower && r < c) || (stored_triangle == Eigen::Upper && r > c))
          continue;
        int q = nnz++;
        for(; q > begin && inner[q - 1] > r; --q) {
          inner[q] = inner[q - 1];
          value[q] = value[q - 1];
        }
        inner[q] = r;
        value[q] = m_value[p];
      }
    }
    outer[rows] = nnz;
    S.resizeNonZeros(nnz);
    return S;
  }

  // M = A W^-1 A^T with its node rows in the backend's fill-reducing order (`node_order`, AMD for Eigen)
  // and the free loop rows last, so that the metric of the loop integers is a dense block of the factor
  // (see internal::Trailing_schur_complement). `M`: from system_in_row_order(). Both arguments are
  // released before the factorization, whose memory is the peak.
  void assemble_system(Sparse& M, std::vector<int>& node_order)
  {
    const Eigen::Index rows = m_rows;
    if(rows == 0) {
      notify(Phase::assembly, 1);
      return;
    }
    std::vector<char> is_loop_row(std::size_t(rows), 0);
    for(int r : m_free_rows)
      is_loop_row[r] = 1;
    m_permutation.resize(rows); // row -> position
    int position = 0;
    for(int node : node_order) {
      const int r = m_row_of_node[node];
      if(r >= 0 && !is_loop_row[r])
        m_permutation.indices()[r] = position++;
    }
    for(int r : m_free_rows)
      m_permutation.indices()[r] = position++;
    CGAL_assertion(position == rows);
    Sparse ordered = ordered_system(M);
    M = Sparse(); // returned before the factorization, whose memory is the peak
    std::vector<int>().swap(node_order);
    m_system.reset(new typename Solver_traits::Matrix(Sparse()));
    m_system->eigen_object().swap(ordered); // no copy
    notify(Phase::assembly, 1);
  }

  void factor()
  {
    notify(Phase::factorization, 0);
    m_substitutions_available = false;
    if(m_rows == 0) {
      notify(Phase::factorization, 1);
      return;
    }
    double d = 1;
    if(!m_solver.factor(*m_system, d))
      throw Invalid_input(Error_code::solver_failure,
                          "the sparse factorization of the constraint system failed");
    m_substitutions_available = internal::Factor_substitutions<Solver_traits>::available(m_solver);
    if(internal::Substitutions_need_only_the_factor<Solver_traits>::value)
      Sparse().swap(m_system->eigen_object()); // released: the solves read the factor alone
    notify(Phase::factorization, 1);
  }

  static constexpr int stored_triangle = internal::Stored_triangle<Solver_traits>::value;

  // The sums the constraints read from a connection: per node its star sum (collapsed for a boundary
  // loop; pinned nodes too), per loop the signed sum of its crossings (a boundary loop's is its node's).
  struct Constraint_sums
  {
    std::vector<double> node, loop; // a link's sum includes its guided ends' slacks
    double energy = 0; // sum of w_e x_e^2, read on the way
    std::vector<double> slack; // per guided face, its mismatch d_g
    double guidance_energy = 0; // mu sum_g d_g^2
  };

  // M^-1 b (rows in their own order), to be checked by the caller. Safe to run from several threads at once:
  // the substitutions of the package's backends read the factor only; another backend's solve may use
  // scratch memory of its own, so it runs under a lock.
  Eigen::VectorXd unchecked_solve(const Eigen::VectorXd& b)
  {
    if(b.size() == 0)
      return b;
    if(m_bordered_mode)
      return bordered_solve(b);
    if(m_substitutions_available) {
      using Substitutions = internal::Factor_substitutions<Solver_traits>;
      Eigen::VectorXd z = m_permutation * b;
      if constexpr(Substitutions::leading_columns) {
        Substitutions::forward(m_solver, z, z.size());
        Substitutions::scale(m_solver, z);
        Substitutions::backward(m_solver, z, z.size());
      } else {
        Substitutions::forward(m_solver, z);
        Substitutions::scale(m_solver, z);
        Substitutions::backward(m_solver, z);
      }
      return m_permutation.transpose() * z;
    }
    typename Solver_traits::Vector rhs(b.size()), sol(b.size());
    rhs = m_permutation * b;
    {
      std::lock_guard<std::mutex> lock(m_backend_mutex);
      if(!m_solver.linear_solver(rhs, sol))
        throw Invalid_input(Error_code::solver_failure, "a back-substitution failed");
    }
    return m_permutation.transpose() * Eigen::VectorXd(sol);
  }

  // The connection x = W^-1 A^T lambda, checked through the constraints it must satisfy: A x - b is
  // M lambda - b, computed from x at the cost of one pass over the edges (cheaper than a product with M,
  // and the sums are the ones the report needs). Refined once when the residual is not already at
  // rounding level.
  Eigen::VectorXd checked_connection(const Eigen::VectorXd& b, Eigen::VectorXd& lambda, Constraint_sums& sums)
  {
    const double scale = 1 + b.template lpNorm<Eigen::Infinity>();
    Eigen::VectorXd xe = connection_of(lambda);
    std::vector<double> slack = slacks(lambda);
    sums_of(xe, slack, sums);
    double res = (b - row_sums(sums)).template lpNorm<Eigen::Infinity>();
    // Refined in x itself: x += W^-1 A^T M^-1 (b - A x). Recomputing x from refined multipliers would divide
    // their rounding errors by the smallest weights again, which on needle triangles is the residual itself.
    for(int step = 0; step < 3 && std::isfinite(res) && res > 1e-13 * scale; ++step) {
      const Eigen::VectorXd delta = unchecked_solve(b - row_sums(sums));
      Eigen::VectorXd refined_x = xe + connection_of(delta);
      std::vector<double> refined_slack = slacks(delta);
      for(std::size_t g = 0; g < slack.size(); ++g)
        refined_slack[g] += slack[g];
      Constraint_sums refined;
      sums_of(refined_x, refined_slack, refined);
      const double refined_res = (b - row_sums(refined)).template lpNorm<Eigen::Infinity>();
      if(!(refined_res < res))
        break;
      lambda += delta;
      xe.swap(refined_x);
      slack.swap(refined_slack);
      sums = std::move(refined);
      res = refined_res;
    }
    // the package promises holonomy residuals below 1e-9 rad (plus the rounding of 2 pi k for huge indices): a
    // mesh whose geometry double precision cannot carry that far (coordinates spanning some 15 orders of
    // magnitude) is refused rather than half solved
    if(!std::isfinite(res) || !xe.allFinite() || res > 1e-9 + 1e-14 * (scale - 1)) {
      std::ostringstream message;
      message << "the linear solve is inaccurate: constraint residual " << std::scientific << std::setprecision(2)
              << res << " rad after refinement (more than 1e-9; the mesh's geometry is too ill-conditioned for "
              << "double precision)";
      throw Invalid_input(Error_code::solver_failure, message.str());
    }
    return xe;
  }

  // x = W^-1 A^T lambda, without A: each interior edge gets the multipliers of the stars it enters (+ at
  // its target's node, - at its source's; the difference vanishes when both are one boundary loop) and of
  // the generators that cross it.
  Eigen::VectorXd connection_of(const Eigen::VectorXd& lambda) const
  {
    const internal::Mesh_topology& t = m_topology;
    const int ne = m_geometry.number_of_interior_edges();
    std::vector<double> multiplier(std::size_t(t.number_of_nodes), 0.);
    for(int node = 0; node < t.number_of_nodes; ++node)
      if(m_row_of_node[node] >= 0)
        multiplier[node] = lambda[m_row_of_node[node]];
    const std::size_t slots = m_row_of_loop.size();
    Eigen::VectorXd xe = Eigen::VectorXd::Zero(ne); // first the generators' (and paths') part, then the stars'
    for(std::size_t l = 0; l < slots; ++l)
      if(is_crossing_slot(l)) {
        const double g = lambda[m_row_of_loop[l]];
        for(int p = m_loop_edge_start[l]; p < m_loop_edge_start[l + 1]; ++p)
          xe[edge_of_code(m_loop_edges[p])] += sign_of_code(m_loop_edges[p]) * g;
      }
    for(int e = 0; e < ne; ++e) {
      const int a = m_edge_nodes[e][0], c = m_edge_nodes[e][1];
      xe[e] = (xe[e] + multiplier[c] - multiplier[a]) / m_geometry.weight[e];
    }
    return xe;
  }

  // The sums the constraints read from a connection x and the guided faces' slacks, and the energies.
  void sums_of(const Eigen::VectorXd& xe, const std::vector<double>& slack, Constraint_sums& sums) const
  {
    const internal::Mesh_topology& t = m_topology;
    const int ne = m_geometry.number_of_interior_edges();
    const std::size_t slots = m_row_of_loop.size();
    // x(i) enters target(i)'s star, -x(i) = x(opposite(i)) enters source(i)'s star
    std::vector<double> node_sum(std::size_t(t.number_of_nodes), 0.);
    double energy = 0;
    for(int e = 0; e < ne; ++e) {
      const int a = m_edge_nodes[e][0], c = m_edge_nodes[e][1];
      const double x = xe[e];
      energy += m_geometry.weight[e] * x * x;
      if(a != c) {
        node_sum[c] += x;
        node_sum[a] -= x;
      }
    }
    sums.energy = energy;
    sums.loop.assign(slots, 0.);
    for(std::size_t l = 0; l < slots; ++l) {
      if(!is_crossing_slot(l)) {
        sums.loop[l] = node_sum[t.loops[l].node];
        continue;
      }
      double sum = 0;
      for(int p = m_loop_edge_start[l]; p < m_loop_edge_start[l + 1]; ++p)
        sum += sign_of_code(m_loop_edges[p]) * xe[edge_of_code(m_loop_edges[p])];
      sums.loop[l] = sum;
    }
    sums.node.swap(node_sum);
    // the guided faces' slacks: row j of the links reads sum x + s_from - s_to
    sums.slack = slack;
    sums.guidance_energy = 0;
    for(std::size_t g = 0; g < sums.slack.size(); ++g) {
      sums.guidance_energy += m_guidance_weight * sums.slack[g] * sums.slack[g];
      for(int p = m_slack_start[g]; p < m_slack_start[g + 1]; ++p) {
        const int code = m_slack_links[p];
        sums.loop[t.loops.size() + std::size_t(edge_of_code(code))] += sign_of_code(code) * sums.slack[g];
      }
    }
  }

  // For link j, calls visit(link, value) for the entries of C C^T / mu in its row: C has one column per guided
  // face, +1 in the links from it and -1 in the links to it
  template <class Visit>
  void for_each_slack_coupling(int j, Visit visit) const
  {
    for(int end : {m_paths[j].from, m_paths[j].to}) {
      if(!m_constrained[end].soft)
        continue;
      const double sign = end == m_paths[j].from ? 1. : -1.;
      const std::size_t g = std::size_t(end - m_first_guided);
      for(int p = m_slack_start[g]; p < m_slack_start[g + 1]; ++p) {
        const int code = m_slack_links[p];
        visit(edge_of_code(code), sign * sign_of_code(code) / m_guidance_weight);
      }
    }
  }

  // the slacks s = C^T lambda / mu of the guided faces (their mismatches d_g), from the multipliers
  std::vector<double> slacks(const Eigen::VectorXd& lambda) const
  {
    const std::size_t nl = m_topology.loops.size();
    std::vector<double> s(m_constrained.size() - std::size_t(m_first_guided), 0.);
    for(std::size_t g = 0; g < s.size(); ++g)
      for(int p = m_slack_start[g]; p < m_slack_start[g + 1]; ++p) {
        const int code = m_slack_links[p];
        s[g] += sign_of_code(code) * lambda[m_row_of_loop[nl + std::size_t(edge_of_code(code))]];
      }
    for(double& v : s)
      v /= m_guidance_weight;
    return s;
  }

  // The phi minimising sum_g (phi + o_g)^2 with each phi + o_g reduced to (-period/2, period/2]: the values
  // -o_g reduced to [0, period) are sorted; an optimal choice of representatives takes them as they are from
  // some point on and one period higher before it (a contiguous arc), and phi is their mean.
  static double best_rotation(const std::vector<double>& offsets, double period)
  {
    std::vector<double> u;
    u.reserve(offsets.size());
    for(double o : offsets) {
      double r = std::fmod(-o, period);
      if(r < 0)
        r += period;
      u.push_back(r);
    }
    std::sort(u.begin(), u.end());
    const double count = double(u.size());
    double s1 = 0, s2 = 0;
    for(double v : u) {
      s1 += v;
      s2 += v * v;
    }
    double best = s2 - s1 * s1 / count, phi = s1 / count;
    for(double v : u) { // move v up by a period
      s2 += 2 * period * v + period * period;
      s1 += period;
      const double cost = s2 - s1 * s1 / count;
      if(cost < best) {
        best = cost;
        phi = s1 / count;
      }
    }
    return phi;
  }

  // a generator or a constraint path: a row made of its crossings (a boundary loop's row is its node's)
  bool is_crossing_slot(std::size_t l) const
  {
    return l >= m_topology.loops.size() || m_topology.loops[l].kind == Loop_kind::generator;
  }

  // A crossing of a loop is coded e (x_e) or ~e (-x_e); decoded without branches, whose sign pattern is
  // random
  static int edge_of_code(int code) { return code ^ (code >> 31); }
  static double sign_of_code(int code) { return double(1 | (code >> 31)); }

  // the nodes of interior edge e's canonical corner: x_e enters the star of the second and, reversed, the
  // star of the first; both are the same node when the edge joins two vertices of one boundary loop
  std::array<int, 2> nodes_of_edge(int e) const
  {
    const int i = m_geometry.edge_corner[e];
    return {m_topology.node_of_vertex[m_mesh.source_of(i)], m_topology.node_of_vertex[m_mesh.target_of(i)]};
  }

  // A x, from its constraint sums
  Eigen::VectorXd row_sums(const Constraint_sums& sums) const
  {
    Eigen::VectorXd ax = Eigen::VectorXd::Zero(system_size());
    for(int node = 0; node < m_topology.number_of_nodes; ++node)
      if(m_row_of_node[node] >= 0)
        ax[m_row_of_node[node]] = sums.node[node];
    for(std::size_t l = 0; l < m_row_of_loop.size(); ++l)
      if(m_row_of_loop[l] >= 0)
        ax[m_row_of_loop[l]] = sums.loop[l];
    return ax;
  }

  // M^-1 b (rows in their own order), checked and refined like the solution of a solve (checked_connection())
  Eigen::VectorXd solve_system(const Eigen::VectorXd& b)
  {
    Eigen::VectorXd lambda = unchecked_solve(b);
    Constraint_sums sums;
    checked_connection(b, lambda, sums);
    return lambda;
  }

  // Per component, the Schur complement S of its free loop rows and S^-1 = (M^-1) on those rows: the
  // metric of the integer problem. Read from the factor when the backend allows it, otherwise one
  // back-substitution per free loop.
  void compute_loop_metric()
  {
    m_loop_metric.assign(m_components.size(), Loop_metric());
    const Eigen::Index k = Eigen::Index(m_free_rows.size());
    const Eigen::Index first = m_rows - k;
    Eigen::MatrixXd Lt;
    Eigen::VectorXd d;
    const bool from_factor = m_rows > 0 && internal::Trailing_schur_complement<Solver_traits>::read(m_solver, k, Lt, d);
    m_loop_rows_in_factor = from_factor && internal::Factor_substitutions<Solver_traits>::available(m_solver);
    if(k == 0)
      return;
    for(std::size_t c = 0; c < m_components.size(); ++c) {
      const std::vector<int>& free = m_free_loops[c];
      const Eigen::Index kc = Eigen::Index(free.size());
      if(kc == 0)
        continue;
      Loop_metric& metric = m_loop_metric[c];
      std::vector<Eigen::Index>& block = metric.block; // increasing: the loop rows are placed in this order
      block.resize(free.size());
      for(Eigen::Index a = 0; a < kc; ++a)
        block[a] = m_permutation.indices()[m_row_of_loop[free[a]]] - first;
      if(from_factor) {
        // M is block diagonal by component, so is the trailing factor: its block is this component's
        metric.schur_factor.resize(kc, kc);
        metric.schur_diagonal.resize(kc);
        for(Eigen::Index a = 0; a < kc; ++a) {
          metric.schur_diagonal[a] = d[block[a]];
          for(Eigen::Index r = 0; r < kc; ++r)
            metric.schur_factor(r, a) = r >= a ? Lt(block[r], block[a]) : 0.;
        }
        if(!(metric.schur_diagonal.minCoeff() > 0) || !metric.schur_factor.allFinite())
          throw Invalid_input(Error_code::solver_failure, "the metric of the loop integers is not positive definite");
        // S^-1 = Y^T Y with Y = D^-1/2 L^-1, lower triangular
        Eigen::MatrixXd Y = metric.schur_factor.template triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(kc, kc));
        Y = metric.schur_diagonal.cwiseSqrt().cwiseInverse().asDiagonal() * Y;
        metric.inverse.noalias() = Y.transpose().template triangularView<Eigen::Upper>() * Y;
        metric.inverse = (metric.inverse + metric.inverse.transpose()) / 2;
      } else {
        metric.inverse.resize(kc, kc);
        for(Eigen::Index a = 0; a < kc; ++a) {
          Eigen::VectorXd unit_rhs = Eigen::VectorXd::Zero(m_rows);
          unit_rhs[m_row_of_loop[free[a]]] = 1;
          const Eigen::VectorXd column = solve_system(unit_rhs);
          for(Eigen::Index r = 0; r < kc; ++r)
            metric.inverse(r, a) = column[m_row_of_loop[free[r]]];
        }
        metric.inverse = (metric.inverse + metric.inverse.transpose()) / 2;
        Eigen::LLT<Eigen::MatrixXd> schur(metric.inverse.llt().solve(Eigen::MatrixXd::Identity(kc, kc)));
        if(schur.info() != Eigen::Success)
          throw Invalid_input(Error_code::solver_failure, "the metric of the loop integers is not positive definite");
        metric.schur_factor = schur.matrixL();
        metric.schur_diagonal = Eigen::VectorXd::Ones(kc);
      }
      Eigen::LLT<Eigen::MatrixXd> llt(metric.inverse);
      if(llt.info() != Eigen::Success || !metric.inverse.allFinite())
        throw Invalid_input(Error_code::solver_failure, "the metric of the loop integers is not positive definite");
      metric.inverse_factor = llt.matrixU();
    }
  }

  template <class SingularityRange>
  std::vector<std::int64_t> vertex_indices(const SingularityRange& singularities, int n, Solve_report& report) const
  {
    std::vector<std::int64_t> k(m_mesh.nv, 0);
    std::vector<char> listed(m_mesh.nv, 0);
    std::vector<std::int64_t> sums(m_components.size(), 0); // n times the index sums
    for(const auto& s : singularities) {
      const vertex_descriptor vd = s.first;
      const Singularity_index& index = s.second;
      const std::size_t v = std::size_t(get(m_mesh.vertex_index, vd));
      if(v >= std::size_t(m_mesh.nv) || m_mesh.vertex_descriptors[v] != vd)
        throw Invalid_input(Error_code::invalid_vertex, "a singularity is placed on a vertex that is not in the mesh");
      if(m_mesh.faces_at_vertex[v] == 0)
        throw Invalid_input(Error_code::invalid_vertex,
                            "vertex " + std::to_string(v) + " carries a singularity but belongs to no face", v);
      if(listed[v])
        throw Invalid_input(Error_code::duplicate_singularity,
                            "vertex " + std::to_string(v) + " is given a singularity twice", v);
      listed[v] = 1;
      if(m_geometry.on_boundary[v])
        throw Invalid_input(Error_code::singularity_on_boundary,
                            "vertex " + std::to_string(v) + " is on the boundary: singularities must be interior "
                            "(boundary loops get their index from the solver or from loop_periods)", v);
      if(!index.is_multiple_of_one_over(n))
        throw Invalid_input(Error_code::index_not_multiple,
                            "the index " + index.to_string() + " of vertex " + std::to_string(v) +
                              " is not a multiple of 1/" + std::to_string(n), v);
      // bounded so that the sums over all vertices stay far from overflow
      if(std::abs(index.numerator()) > (std::int64_t(1) << 30) / (n / index.denominator()))
        throw Invalid_input(Error_code::invalid_index,
                            "the index " + index.to_string() + " of vertex " + std::to_string(v) + " is too large", v);
      k[v] = index.times(n);
      sums[m_topology.component_of_node[m_topology.node_of_vertex[v]]] += k[v];
    }
    std::string violations;
    std::size_t first_bad = Invalid_input::no_location, bad = 0;
    for(std::size_t c = 0; c < m_components.size(); ++c) {
      const Singularity_index sum(sums[c], n);
      report.components[c].vertex_index_sum = sum;
      if(m_components[c].number_of_boundary_loops == 0 && sums[c] != n * m_components[c].euler_characteristic &&
         ++bad <= 5) {
        violations += (violations.empty() ? "" : "; ") + std::string("component ") + std::to_string(c) +
                      " (closed, genus " + std::to_string(m_components[c].genus) + "): indices sum to " +
                      sum.to_string() + ", expected " + std::to_string(m_components[c].euler_characteristic);
        if(first_bad == Invalid_input::no_location)
          first_bad = c;
      }
    }
    if(bad > 5)
      violations += "; and " + std::to_string(bad - 5) + " more components";
    if(!violations.empty())
      throw Invalid_input(Error_code::poincare_hopf_violated,
                          "Poincare-Hopf violated: " + violations, first_bad);
    return k;
  }

  static std::vector<std::optional<std::int64_t>> optional_periods(const std::vector<std::int64_t>& given)
  {
    return std::vector<std::optional<std::int64_t>>(given.begin(), given.end());
  }
  static const std::vector<std::optional<std::int64_t>>&
  optional_periods(const std::vector<std::optional<std::int64_t>>& given)
  {
    return given;
  }

  // `loop_periods`: one entry per loop, empty where the solver chooses. The boundary loops of a component are
  // prescribed all or none (Poincare-Hopf ties their sum to the vertex indices).
  void read_periods(const std::vector<std::optional<std::int64_t>>& given, const std::vector<std::int64_t>& k, int n,
                    std::vector<std::int64_t>& periods, std::vector<char>& prescribed) const
  {
    if(given.size() != m_loops.size())
      throw Invalid_input(Error_code::invalid_loop_periods,
                          "loop_periods has " + std::to_string(given.size()) + " values, the mesh has " +
                            std::to_string(m_loops.size()) + " loops");
    std::vector<std::size_t> boundary_given(m_components.size(), 0);
    for(std::size_t l = 0; l < m_loops.size(); ++l) {
      prescribed[l] = given[l].has_value() ? 1 : 0;
      periods[l] = given[l].value_or(0);
      if(m_loops[l].kind == Loop_kind::boundary && given[l])
        ++boundary_given[m_loops[l].component];
    }
    std::vector<std::int64_t> total(m_components.size(), 0);
    for(int v = 0; v < m_mesh.nv; ++v)
      if(k[v] != 0)
        total[m_topology.component_of_node[m_topology.node_of_vertex[v]]] += k[v];
    for(std::size_t l = 0; l < m_loops.size(); ++l)
      if(m_loops[l].kind == Loop_kind::boundary)
        total[m_loops[l].component] += periods[l];
    for(std::size_t c = 0; c < m_components.size(); ++c) {
      const std::size_t b = m_components[c].number_of_boundary_loops;
      if(boundary_given[c] != 0 && boundary_given[c] != b)
        throw Invalid_input(Error_code::invalid_loop_periods,
                            std::to_string(boundary_given[c]) + " of the " + std::to_string(b) +
                              " boundary loops of component " + std::to_string(c) +
                              " are prescribed: prescribe all of them or none (Poincare-Hopf ties their sum)",
                            c);
      if(b > 0 && boundary_given[c] == b && total[c] != n * m_components[c].euler_characteristic)
        throw Invalid_input(Error_code::invalid_loop_periods,
                            "Poincare-Hopf violated by the prescribed boundary loop indices of component " +
                              std::to_string(c) + ": vertex and boundary indices sum to " +
                              Singularity_index(total[c], n).to_string() + ", expected " +
                              std::to_string(m_components[c].euler_characteristic),
                            c);
    }
  }

  // The integers of the free loops not prescribed, minimising the energy, per component, written into
  // `periods` (0 there on entry). `y[c]`: the right-hand side of the Schur complement S of component c's
  // free loop rows with those integers 0 (the prescribed ones are in it), so that the loop part of the
  // energy is t^T S^-1 t with t = y + unit m. Returns that part for the integers rounded one by one (for
  // Solve_report::rounding_energy).
  double choose_loop_periods(const std::vector<Eigen::VectorXd>& y, double unit, const std::vector<char>& prescribed,
                             const std::vector<double>& holonomy, std::vector<std::int64_t>& periods,
                             Solve_report& report) const
  {
    bool proven = true;
    double rounding_part = 0;
    for(std::size_t c = 0; c < m_components.size(); ++c) {
      const std::vector<int>& free = m_free_loops[c];
      if(free.empty())
        continue;
      const Loop_metric& metric = m_loop_metric[c];
      std::vector<Eigen::Index> chosen, fixed; // positions in the component's block
      for(std::size_t a = 0; a < free.size(); ++a)
        (prescribed[free[a]] ? fixed : chosen).push_back(Eigen::Index(a));
      const Eigen::Index kc = Eigen::Index(chosen.size());
      if(kc == 0) {
        rounding_part += y[c].dot(metric.inverse * y[c]);
        continue;
      }
      // With G = S^-1 and the prescribed part t_P = y_P fixed, t^T G t = (t_Q - t_Q*)^T G_QQ (t_Q - t_Q*) +
      // const with t_Q* = -G_QQ^-1 G_QP y_P: the minimiser of (m - center)^T G_QQ (m - center), with
      // center = (t_Q* - y_Q) / unit. Without prescribed loops G_QQ = G, whose factor is kept.
      Eigen::VectorXd center(kc);
      double constant = 0;
      Eigen::MatrixXd G_QQ, R_Q;
      const Eigen::MatrixXd* G = &metric.inverse;
      const Eigen::MatrixXd* R = &metric.inverse_factor;
      if(fixed.empty()) {
        center = -y[c] / unit;
      } else {
        G_QQ.resize(kc, kc);
        Eigen::MatrixXd G_QP(kc, Eigen::Index(fixed.size()));
        Eigen::VectorXd y_P(Eigen::Index(fixed.size()));
        for(Eigen::Index i = 0; i < kc; ++i) {
          for(Eigen::Index j = 0; j < kc; ++j)
            G_QQ(i, j) = metric.inverse(chosen[i], chosen[j]);
          for(Eigen::Index j = 0; j < Eigen::Index(fixed.size()); ++j)
            G_QP(i, j) = metric.inverse(chosen[i], fixed[j]);
        }
        for(Eigen::Index j = 0; j < Eigen::Index(fixed.size()); ++j)
          y_P[j] = y[c][fixed[j]];
        const Eigen::LLT<Eigen::MatrixXd> llt(G_QQ);
        if(llt.info() != Eigen::Success)
          throw Invalid_input(Error_code::solver_failure, "the metric of the loop integers is not positive definite");
        R_Q = llt.matrixU();
        const Eigen::VectorXd g = G_QP * y_P;
        const Eigen::VectorXd t_star = -llt.solve(g);
        for(Eigen::Index i = 0; i < kc; ++i)
          center[i] = (t_star[i] - y[c][chosen[i]]) / unit;
        double fixed_part = 0;
        for(Eigen::Index i = 0; i < Eigen::Index(fixed.size()); ++i)
          for(Eigen::Index j = 0; j < Eigen::Index(fixed.size()); ++j)
            fixed_part += y_P[i] * metric.inverse(fixed[i], fixed[j]) * y_P[j];
        constant = fixed_part + g.dot(t_star); // y_P^T (G_PP - G_PQ G_QQ^-1 G_QP) y_P
        G = &G_QQ;
        R = &R_Q;
      }
      std::vector<std::int64_t> rounded(kc), own(kc);
      for(Eigen::Index a = 0; a < kc; ++a) {
        rounded[a] = std::int64_t(std::llround(center[a]));
        // each loop on its own: the integer making its own connection sum smallest
        own[a] = std::int64_t(std::llround(holonomy[free[chosen[a]]] / unit));
      }
      const internal::Closest_vector_result best =
        internal::closest_vector(*G, *R, center, {rounded, own},
                                 // about the work of a few back-substitutions, so that a re-solve stays cheap
                                 (std::max)(2e5, 10. * double(m_rows)));
      proven = proven && best.proven;
      // t^T S^-1 t = unit^2 q(m) + constant
      rounding_part += unit * unit * best.candidate_values[0] + constant;
      for(Eigen::Index a = 0; a < kc; ++a)
        periods[free[chosen[a]]] = best.m[a];
    }
    report.integers_proven_optimal = proven;
    return rounding_part;
  }

  // angle of a vector in the frame of face f (counter-clockwise from the direction of its corner halfedge 3f)
  double angle_in_frame(int f, const internal::Vec3& v) const
  {
    internal::Vec3 ex, ey;
    internal::Mesh_geometry::frame(m_mesh, f, ex, ey);
    return std::atan2(internal::dot(v, ey), internal::dot(v, ex));
  }

  // per constrained face, its target angle in its frame: the direction of its border halfedge when the boundary
  // is aligned, otherwise the user's vector (`face_directions`) projected onto the face
  template <class NamedParameters>
  std::vector<double> constraint_angles(const NamedParameters& np) const
  {
    std::vector<double> angle(m_constrained.size(), 0.);
    for(std::size_t a = 0; a < m_constrained.size(); ++a) {
      const int i = m_constrained[a].border_corner;
      if(i >= 0)
        angle[a] = angle_in_frame(Mesh::face_of(i), internal::sub(m_mesh.points[m_mesh.target_of(i)],
                                                                  m_mesh.points[m_mesh.source_of(i)]));
    }
    if(!m_has_user_constraints)
      return angle;
    if constexpr(CGAL::parameters::is_default_parameter<NamedParameters, tc_np::face_directions_t>::value) {
      throw Invalid_input(Error_code::invalid_constraint,
                          "the solver has constrained or guided faces: their directions (face_directions) are missing");
    } else {
      const auto directions = CGAL::parameters::get_parameter(np, tc_np::face_directions);
      typename Geom_traits::Compute_x_3 x = m_traits.compute_x_3_object();
      typename Geom_traits::Compute_y_3 y = m_traits.compute_y_3_object();
      typename Geom_traits::Compute_z_3 z = m_traits.compute_z_3_object();
      for(std::size_t a = 0; a < m_constrained.size(); ++a) {
        if(m_constrained[a].border_corner >= 0)
          continue;
        const int f = m_constrained[a].face;
        const Vector_3 d = get(directions, m_mesh.face_descriptors[f]);
        const internal::Vec3 v = {{CGAL::to_double(x(d)), CGAL::to_double(y(d)), CGAL::to_double(z(d))}};
        internal::Vec3 ex, ey;
        internal::Mesh_geometry::frame(m_mesh, f, ex, ey);
        const double along_x = internal::dot(v, ex), along_y = internal::dot(v, ey), length = internal::norm(v);
        // a vector within 1e-9 rad of the normal has no meaningful tangent direction
        if(!std::isfinite(length) || !(std::hypot(along_x, along_y) > 1e-9 * length))
          throw Invalid_input(Error_code::invalid_constraint,
                              "the direction given for face " + std::to_string(f) +
                                (std::isfinite(length) && length > 0 ? " is normal to the face"
                                                                     : " is zero or not finite"),
                              std::size_t(f));
        angle[a] = std::atan2(along_y, along_x);
      }
      return angle;
    }
  }

  // per slot, H with H + sum x = 2 pi period / n: the loops' Levi-Civita holonomy, and for a constraint path
  // the transport along it plus the target angle it leaves minus the one it reaches (wrapped)
  std::vector<double> slot_holonomies(const std::vector<double>& target) const
  {
    std::vector<double> holonomy(m_loop_holonomy);
    holonomy.resize(m_row_of_loop.size(), 0.);
    for(std::size_t j = 0; j < m_paths.size(); ++j) {
      const std::size_t l = m_loops.size() + j;
      double h = target[m_paths[j].from] - target[m_paths[j].to];
      for(int p = m_loop_edge_start[l]; p < m_loop_edge_start[l + 1]; ++p)
        h += sign_of_code(m_loop_edges[p]) * m_geometry.transport[edge_of_code(m_loop_edges[p])];
      holonomy[l] = internal::wrap_angle(h);
    }
    return holonomy;
  }

  Eigen::VectorXd right_hand_side(const std::vector<std::int64_t>& k, const std::vector<std::int64_t>& periods,
                                  const std::vector<double>& holonomy, int n) const
  {
    const double unit = 2 * CGAL_PI / n;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(system_size());
    for(std::size_t node = 0; node < m_vertex_of_node.size(); ++node) {
      const int r = m_row_of_node[node];
      if(r >= 0) {
        const int v = m_vertex_of_node[node];
        b[r] = unit * double(k[v]) - m_geometry.angle_defect(v);
      }
    }
    for(std::size_t l = 0; l < holonomy.size(); ++l)
      if(m_row_of_loop[l] >= 0)
        b[m_row_of_loop[l]] = unit * double(periods[l]) - holonomy[l];
    return b;
  }

  // b for the chosen integers of the free loops not prescribed, from b for the integers 0 there
  void add_loop_periods(const std::vector<std::int64_t>& periods, const std::vector<char>& prescribed, double unit,
                        Eigen::VectorXd& b) const
  {
    for(const std::vector<int>& free : m_free_loops)
      for(int l : free)
        if(!prescribed[l])
          b[m_row_of_loop[l]] += unit * double(periods[l]);
  }

  template <class HalfedgeAngleMap>
  void write_connection(const Eigen::VectorXd& xe, HalfedgeAngleMap x) const
  {
    // by edges: both halfedges of an interior edge at once (much faster than corner by corner on some meshes)
    for(int e = 0; e < int(xe.size()); ++e) {
      const int i = m_geometry.edge_corner[e];
      put(x, m_mesh.halfedges[i], xe[e]);
      put(x, m_mesh.halfedges[m_mesh.opposite_corner[i]], -xe[e]);
    }
    for(int i : m_border_corners) {
      put(x, m_mesh.halfedges[i], 0.);
      put(x, opposite(m_mesh.halfedges[i], m_tm), 0.);
    }
  }

  void fill_report(const Constraint_sums& sums, const std::vector<std::int64_t>& k,
                   std::vector<std::int64_t>& periods, const std::vector<char>& prescribed,
                   const std::vector<double>& holonomy, int n, Solve_report& report) const
  {
    const double unit = 2 * CGAL_PI / n;
    report.energy = sums.energy;

    // every interior vertex, the pinned ones included
    report.max_vertex_residual = 0;
    for(int node = 0; node < m_topology.number_of_interior_nodes; ++node) {
      const int v = m_vertex_of_node[node];
      report.max_vertex_residual = (std::max)(
        report.max_vertex_residual, std::abs(m_geometry.angle_defect(v) + sums.node[node] - unit * double(k[v])));
    }

    // the pinned boundary loop's integer follows from Poincare-Hopf
    std::vector<std::int64_t> total(m_components.size(), 0);
    for(int v = 0; v < m_mesh.nv; ++v)
      if(k[v] != 0)
        total[m_topology.component_of_node[m_topology.node_of_vertex[v]]] += k[v];
    for(std::size_t l = 0; l < m_loops.size(); ++l)
      if(m_loops[l].kind == Loop_kind::boundary && m_row_of_loop[l] >= 0)
        total[m_loops[l].component] += periods[l];
    for(std::size_t l = 0; l < m_loops.size(); ++l)
      if(m_loops[l].kind == Loop_kind::boundary && m_row_of_loop[l] < 0 && !prescribed[l])
        periods[l] = n * m_components[m_loops[l].component].euler_characteristic - total[m_loops[l].component];

    report.max_loop_residual = 0;
    report.loops.resize(m_loops.size());
    for(std::size_t l = 0; l < m_loops.size(); ++l) {
      const double sum = sums.loop[l];
      Loop_report& r = report.loops[l];
      r.kind = m_loops[l].kind;
      r.component = m_loops[l].component;
      r.period = periods[l];
      r.index = Singularity_index(periods[l], n);
      r.prescribed = prescribed[l] != 0;
      r.residual = std::abs(m_loop_holonomy[l] + sum - unit * double(periods[l]));
      report.max_loop_residual = (std::max)(report.max_loop_residual, r.residual);
    }
    report.guidance_energy = sums.guidance_energy;
    report.guidance.resize(sums.slack.size());
    for(std::size_t g = 0; g < sums.slack.size(); ++g)
      report.guidance[g] = {std::size_t(m_constrained[std::size_t(m_first_guided) + g].face), sums.slack[g]};
    report.max_constraint_residual = 0;
    report.constraints.resize(m_paths.size());
    for(std::size_t j = 0; j < m_paths.size(); ++j) {
      const std::size_t l = m_loops.size() + j;
      Constraint_report& r = report.constraints[j];
      r.component = std::size_t(m_paths[j].component);
      r.from_face = std::size_t(m_constrained[m_paths[j].from].face);
      r.to_face = std::size_t(m_constrained[m_paths[j].to].face);
      r.length = m_paths[j].length;
      r.period = periods[l];
      r.residual = std::abs(holonomy[l] + sums.loop[l] - unit * double(periods[l]));
      report.max_constraint_residual = (std::max)(report.max_constraint_residual, r.residual);
    }
  }

  const TriangleMesh& m_tm;
  Geom_traits m_traits;
  Weighting m_weighting;
  Progress_callback m_progress; // only during the constructor
  Mesh m_mesh;
  internal::Mesh_geometry m_geometry;
  internal::Mesh_topology m_topology;
  std::vector<Loop> m_loops;
  std::vector<double> m_loop_holonomy;
  std::vector<Component_report> m_components;

  // Directional constraints: the constrained faces and the paths linking them (see build_constraint_paths())
  struct Constrained_face
  {
    int face;
    int border_corner; // the border corner halfedge it follows with the boundary aligned; -1: a user target
    bool soft;         // a guided face (its target is a guide)
  };
  struct Constraint_path
  {
    int from, to;      // in m_constrained
    int component;
    std::vector<int> crossings; // corner halfedges, as a loop's (released once coded in m_loop_edges)
    std::size_t length = 0;
  };
  std::vector<Constrained_face> m_constrained;
  std::vector<Constraint_path> m_paths;
  std::vector<int> m_seed_constraint; // per component: the constrained face the field starts from, or -1
  bool m_has_user_constraints = false; // user targets or guides (read from face_directions)
  bool m_align = false;                // align_with_boundary
  int m_first_guided = 0;              // the guided faces are the last of m_constrained
  double m_guidance_weight = 1;        // mu
  // per guided face (CSR): the links at it, j when it is their `from` end (+1), ~j when their `to` end (-1)
  std::vector<int> m_slack_start, m_slack_links;

  // Rows with an integer are numbered by "slots": the loops of loops(), then the constraint paths.
  std::vector<int> m_row_of_node, m_row_of_loop /* per slot */, m_vertex_of_node, m_free_rows;
  // per interior edge, the nodes of its canonical corner's source and target, for the solves (made during the
  // factorization, on the other thread)
  std::vector<std::array<int, 2>> m_edge_nodes;
  std::vector<int> m_border_corners;           // corner halfedges on a border edge
  std::vector<int> m_loop_edge_start, m_loop_edges; // per slot (CSR): e for x_e, ~e for -x_e, per crossing
  std::vector<std::vector<int>> m_free_loops;  // per component: slots whose integer is free (loops, then paths)
  Eigen::Index m_rows = 0;                     // of the constraint system
  // the solver keeps a pointer to it; empty after the factorization when the backend needs only its factor
  std::unique_ptr<typename Solver_traits::Matrix> m_system;
  Solver_traits m_solver;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> m_permutation; // row -> position in m_system
  struct Loop_metric
  {
    Eigen::MatrixXd schur_factor;   // S = schur_factor diag(schur_diagonal) schur_factor^T, lower triangular
    Eigen::VectorXd schur_diagonal;
    Eigen::MatrixXd inverse;        // S^-1 = (M^-1) on the free loop rows of one component
    Eigen::MatrixXd inverse_factor; // R upper triangular with R^T R = S^-1
    std::vector<Eigen::Index> block; // per free loop of the component: its position after the first loop row
    // with bordered rows (set_constraints()): per free slot, its position in F, or -1 - e for bordered row e;
    // and the Cholesky factorization of the dense block
    std::vector<Eigen::Index> place;
    Eigen::LLT<Eigen::MatrixXd> system;
  };
  std::vector<Loop_metric> m_loop_metric;
  bool m_loop_rows_in_factor = false; // the metric was read from the factor, whose substitutions are available
  bool m_substitutions_available = false; // Factor_substitutions read the factor (thread-safe solves)
  std::mutex m_backend_mutex; // serialises the solves of backends without Factor_substitutions
  std::vector<Factored_link> m_factored_links; // the links in the factor
  std::vector<Loop_metric> m_factor_metric;    // the metric of the factor's free rows
  std::vector<Bordered_row> m_bordered;        // links outside the factor (after set_constraints())
  bool m_bordered_mode = false;                // solves go through bordered_forward/backward
};

} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_SOLVER_H
