// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_REFINEMENT_H
#define CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_REFINEMENT_H

#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/internal/concurrency.h>
#include <CGAL/Trivial_connections/internal/placement/move_energy.h>
#include <CGAL/Trivial_connections/internal/placement/move_integers.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>

#include <CGAL/assertions.h>

#include <boost/property_map/vector_property_map.hpp>

#include <algorithm>
#include <array>
#include <type_traits>
#include <cstdint>
#include <unordered_map>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

namespace internal {

/*
  The accuracy of the refinement's trial solves, set on `solver` for the lifetime of this object. They refine their
  connection only from a relative residual of 1e-11 (the promise is 1e-9): on a large mesh the first residual is
  barely above the rounding level that solve() refines down to (cheese_loop3: 1.0e-13 to 2.2e-13 of 1 + |b|), and
  that refinement is a second back-substitution per trial. Nor do they bound the other choices of the links decided
  by rounding (touching pins, an aligned boundary): a solve more per trial for the report alone (holes.off with its
  boundary aligned: a third of a trial). The connection returned is solved again at full accuracy, with its bound,
  as is the first (so energy_after <= energy_before). The placement benchmark times its trial solves with it.
*/
template <class Solver>
struct Trial_accuracy
{
  using Access = Solver_access<Solver>;
  Solver& s;
  explicit Trial_accuracy(Solver& solver) : s(solver)
  {
    Access::refine_residuals_above(s, 1e-11);
    Access::bound_decided_choices(s, false);
  }
  ~Trial_accuracy()
  {
    Access::refine_residuals_above(s, refine_residuals_above);
    Access::bound_decided_choices(s, true);
  }
  Trial_accuracy(const Trial_accuracy&) = delete;
  Trial_accuracy& operator=(const Trial_accuracy&) = delete;
};

} // namespace internal

/*!
\ingroup PkgTrivialConnectionsRef
One accepted move of `refine_singularities()`: `index` went from `from` to `to` (a whole singularity to a
neighbouring vertex, or one unit of 1/n of a positive singularity cancelling one of a negative singularity at `to`).
*/
template <class VertexDescriptor>
struct Singularity_move
{
  VertexDescriptor from;   ///< the vertex the index left
  VertexDescriptor to;     ///< the neighbour it went to, or the negative singularity it cancelled against
  Singularity_index index; ///< the index moved
  double energy = 0;       ///< the minimised energy after the move
};

/*!
\ingroup PkgTrivialConnectionsRef
Why `refine_singularities()` stopped.
*/
enum class Refinement_stop
{
  local_minimum,  ///< no single move or cancellation lowers the energy, its integers chosen again (kept in the
                  ///< components beyond the 64 free integers of loops and links searched, fewest first)
  maximum_trials, ///< the budget of solves (`maximum_trials`) was spent
  rejected_moves  ///< moves predicted to lower the energy did not once their integers were chosen again
};

/*!
\ingroup PkgTrivialConnectionsRef
What `refine_singularities()` did.
*/
template <class VertexDescriptor>
struct Refinement_report
{
  /// the refined singularities, by increasing vertex index
  std::vector<std::pair<VertexDescriptor, Singularity_index>> singularities;
  std::size_t singularities_before = 0; ///< the number of singularities of the starting set
  double energy_before = 0;  ///< minimised energy (`energy + guidance_energy`) of the starting set
  double energy_after = 0;   ///< and of the refined set (never more)
  std::vector<Singularity_move<VertexDescriptor>> moves; ///< in the order made (`energy`: after its round)
  std::size_t cancellations = 0; ///< the moves among them that cancelled a unit of a pair
  std::size_t rounds = 0;    ///< rounds of moves accepted together
  std::size_t trials = 0;    ///< solves tried (the first solve not counted)
  std::size_t column_solves = 0; ///< back-substitutions for entries of the inverse (see above)
  bool local_minimum = false; ///< `stop == Refinement_stop::local_minimum`
  Refinement_stop stop = Refinement_stop::local_minimum; ///< why it stopped
  Solve_report report;       ///< the solve of the refined set (its connection is the last one written)
};

/*!
\ingroup PkgTrivialConnectionsRef

Moves singularities to where they cost least: starting from a valid set (automatic or the user's), it moves
singularities to neighbouring interior vertices (or, with `cancel_pairs`, cancels a unit of a positive
singularity against one of a negative singularity) while that lowers the minimised energy of the trivial
connection (`energy + guidance_energy` of `solve()`), until no single move or cancellation lowers it: a local
minimum.

Every candidate is scored exactly from one solve: the energy is `b^T M^-1 b`, so moving `d = 2 pi u / n` of
index from `v` to `w` changes it, the integers of loops and links kept, by
`(u / n) (g_w - g_v) + d^2 (G_vv + G_ww - 2 G_vw)`, with `g` the energy gradient of the solve and `G = M^-1`.
The entries of `G` between neighbours are on the pattern of the sparse factor, so one selected inversion of
the factor gives all of them; with few singularities, their paths in the elimination tree give those wanted for
less (the cheaper of the two is predicted). A cancellation between distant vertices reads `G_vw` from the column
of `G` at one of them (a back-substitution, kept from round to round), or, with the entries from paths, from
the product of the two singularities' paths when all of a round's products cost less than one column. A move
may lower the energy only with some free integers of its component changed: the rounds price the moves with the
integers kept (each trial solve chooses them again) and, on components with few of them (64 in all, fewest
first), search the moves for the best change of the integers (a closest vector search in their metric), by
increasing lower bound of what it may give, until that bound reaches the best change found: a round takes one
such move at most, when it beats every move with the integers kept. Proven integers (loops; links decided by
rounding, under an aligned boundary or between touching pins, are held, and the report's weak bound of their other
choices does not count) are searched every round; unproven ones (links under guidance, whose bounds prune little)
only when no move pays with them kept.
A round applies the best-scored candidates that lie apart (no two within one ring of each other) in one
`solve()` that chooses the integers again, each cancellation's change corrected exactly for its interaction
with those taken before it; when that solve does not lower the energy, half of the moves are tried, down to a
single one. The energy decreases at every round, so the refinement ends, at a local minimum unless a budget of
solves is given. After `set_constraints()` on a kept factorization, the new links' rows live outside the factor:
the system is then factored again with them first (about the cost of the constructor's factorization), so that
each step costs what it costs without pins. Solvers whose backend does not expose its factor get the entries
from back-substitutions, a column per vertex (kept up to about 256 MB).
See the user manual, "Refinement by Moves", for the measurements.

Poincare-Hopf is kept: a move keeps every component's index sum.

\tparam Solver a `Trivial_connection_solver`
\tparam SingularityRange as for `solve()`
\param solver the prefactored solver
\param start the starting singularities (checked as by `solve()`)
\param x a writable property map `halfedge_descriptor -> double`: receives the connection of the refined set,
       solved again at the end with the residual refined as by `solve()` (the trial solves refine it only from
       1e-11, and leave out the bound of the decided links' other choices; the report has both) and with the integers the trials accepted as a candidate (its energy is `energy_after`). Its integers of loops and links are also a candidate of the solver's next
       `solve()` (once): when no solve can prove them optimal (many of them, e.g. under guidance), solving the
       refined set again chooses them or better ones, never the worse ones a fresh search might settle for.
\param np an optional sequence of named parameters: those of `solve()` (`symmetry_order`, `loop_periods`,
       `face_directions`), and
\cgalNamedParamsBegin
  \cgalParamNBegin{fixed_vertices}
    \cgalParamDescription{vertices whose singularity does not move and onto which none moves}
    \cgalParamType{a range of `vertex_descriptor`} \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{cancel_pairs}
    \cgalParamDescription{a pair of opposite singularities of a component may also cancel, one unit of 1/n each,
      whatever their distance; otherwise singularities never move onto each other}
    \cgalParamType{`bool`} \cgalParamDefault{`false`}
  \cgalParamNEnd
  \cgalParamNBegin{maximum_trials}
    \cgalParamDescription{a budget of solves after the first; the refinement otherwise runs to a local minimum.
      With 0, no round is priced: the starting set is solved and returned (`stop` is `maximum_trials`, the start
      not checked for a local minimum)}
    \cgalParamType{`std::size_t`} \cgalParamDefault{no budget}
  \cgalParamNEnd
\cgalNamedParamsEnd
\throws Invalid_input as `solve()` for the starting set
\returns the refined set, the energies before and after, the moves made and why it stopped
*/
template <class Solver, class SingularityRange, class HalfedgeAngleMap,
          class NamedParameters = parameters::Default_named_parameters>
Refinement_report<typename Solver::vertex_descriptor>
refine_singularities(Solver& solver, const SingularityRange& start, HalfedgeAngleMap x,
                     const NamedParameters& np = parameters::default_values())
{
  using vertex_descriptor = typename Solver::vertex_descriptor;
  using Access = internal::Solver_access<Solver>;
  const auto& m = Access::mesh(solver);
  const internal::Mesh_geometry& g = Access::geometry(solver);
  const internal::Mesh_topology& t = Access::topology(solver);
  const int n = internal::checked_symmetry_order(
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1));
  const bool cancel = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::cancel_pairs), false);
  const std::size_t budget = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, tc_np::maximum_trials), (std::numeric_limits<std::size_t>::max)());

  std::vector<char> fixed(std::size_t(m.nv), 0);
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::fixed_vertices_t>::value)
    for(const vertex_descriptor v : CGAL::parameters::get_parameter(np, tc_np::fixed_vertices)) {
      const std::size_t i = std::size_t(get(m.vertex_index, v));
      if(i >= std::size_t(m.nv) || m.vertex_descriptors[i] != v)
        throw Invalid_input(Error_code::invalid_vertex, "a fixed vertex is not a vertex of the mesh");
      fixed[i] = 1;
    }

  // n times the index per vertex; the set as solve() takes it
  std::vector<std::int64_t> k(std::size_t(m.nv), 0);
  auto as_set = [&](const std::vector<std::int64_t>& kk) {
    std::vector<std::pair<vertex_descriptor, Singularity_index>> s;
    for(int v = 0; v < m.nv; ++v)
      if(kk[v] != 0)
        s.emplace_back(m.vertex_descriptors[v], Singularity_index(kk[v], n));
    return s;
  };
  using Gradient = boost::vector_property_map<double, typename std::decay_t<decltype(m)>::Vertex_index_map>;
  std::vector<double> gradient(std::size_t(m.nv), 0.);
  Gradient map(std::size_t(m.nv), m.vertex_index); // written whole by each solve, kept (fresh pages are faults)
  auto solve = [&](const std::vector<std::pair<vertex_descriptor, Singularity_index>>& set,
                   std::vector<double>& gradient_out, Solve_report& report) {
    report = solver.solve(set, x, parameters::energy_gradient(map, np));
    for(int v = 0; v < m.nv; ++v)
      gradient_out[std::size_t(v)] = map[m.vertex_descriptors[v]];
    return report.energy + report.guidance_energy;
  };

  // rows bordered outside the factor (set_constraints() on a kept factorization) would leave the entries of M^-1
  // to one back-substitution per vertex: factored in first
  Access::factor_bordered_links(solver);

  std::optional<internal::Trial_accuracy<Solver>> trial_accuracy; // set after the first solve (see there)

  Refinement_report<vertex_descriptor> result;
  double energy = 0;
  {
    // the first solve checks the set (vertices, multiples of 1/n, Poincare-Hopf) before it is read
    std::vector<std::pair<vertex_descriptor, Singularity_index>> given;
    for(const auto& s : start)
      given.emplace_back(s.first, s.second);
    energy = solve(given, gradient, result.report);
    for(const auto& s : given)
      k[std::size_t(get(m.vertex_index, s.first))] = s.second.times(n);
    result.singularities_before = given.size();
  }
  result.energy_before = energy;
  // whether the accepted solve's free integers are optimal: the moves price changes of these only (the links
  // decided by rounding are held by every solve), so the weak bound of the decided ones' other choices, which
  // leaves the report unproven under an aligned boundary, does not make the rounds search them as unproven
  bool integers_proven = Access::free_integers_proven(solver);
  trial_accuracy.emplace(solver); // after the first solve, at full accuracy: energy_before is exact to rounding
  // each trial also tries the integers of the set it moves from: a move predicted with them kept is then never
  // rejected because a search that cannot prove the optimum (hundreds of integers) found worse ones
  std::vector<std::int64_t> accepted_periods = Access::last_periods(solver);

  // vertex neighbours (each interior edge once per direction; border edges from their one corner)
  std::vector<std::vector<int>> neighbours(std::size_t(m.nv));
  for(int i = 0; i < 3 * m.nf; ++i) {
    neighbours[m.source_of(i)].push_back(m.target_of(i));
    if(m.opposite_corner[i] < 0)
      neighbours[m.target_of(i)].push_back(m.source_of(i));
  }

  // the rows of the vertices, as the energy gradient reads them, and M^-1 between them
  const internal::Constraint_rows& rows = Access::rows(solver);
  auto& system = Access::system(solver);
  std::vector<int> row_of_vertex(std::size_t(m.nv), -1);
  for(int v = 0; v < m.nv; ++v) {
    const int node = t.node_of_vertex[v];
    if(node >= 0 && !g.on_boundary[v])
      row_of_vertex[std::size_t(v)] = rows.row_of_node[node];
  }
  // the rows of the system solved (those of the factor, the bordered ones factored in above)
  const Eigen::Index system_rows = Access::multipliers(solver).size();
  internal::Unit_lower_factor factor;
  if(!system.read_factor(rows, factor))
    factor = internal::Unit_lower_factor();
  // the vertices whose entries the first round reads: the singular ones and their neighbours
  auto singular_and_neighbours = [&] {
    std::vector<int> wanted;
    for(int v = 0; v < m.nv; ++v)
      if(k[std::size_t(v)] != 0 && !fixed[std::size_t(v)]) {
        wanted.push_back(v);
        wanted.insert(wanted.end(), neighbours[std::size_t(v)].begin(), neighbours[std::size_t(v)].end());
      }
    return wanted;
  };
  internal::Move_energy inverse(std::move(row_of_vertex),
                                rows.rows > 0 ? system.permutation().indices().data() : nullptr, system_rows,
                                std::move(factor), singular_and_neighbours(),
                                [&](const Eigen::VectorXd& e) { return system.solve(rows, e); },
                                internal::Move_energy::Entries::automatic,
                                internal::Move_energy::default_column_budget_bytes, [&] {
                                  internal::Unit_lower_factor again;
                                  return system.read_factor(rows, again) ? again : internal::Unit_lower_factor();
                                });

  // The free integers (loops, links) of each component, which the solves choose: see Move_integers. Only those of
  // components with a free singularity: nothing moves in the others, ever.
  const double unit = 2 * CGAL_PI / n;
  std::vector<char> moving(rows.free_slots.size(), 0);
  for(int v = 0; v < m.nv; ++v)
    if(k[std::size_t(v)] != 0 && !fixed[std::size_t(v)]) {
      const std::size_t c = std::size_t(t.component_of_node[t.node_of_vertex[v]]);
      if(c < moving.size())
        moving[c] = 1;
    }
  std::vector<std::vector<int>> free_rows(rows.free_slots.size()), free_row_slots(rows.free_slots.size());
  for(std::size_t c = 0; c < rows.free_slots.size(); ++c)
    for(int l : rows.free_slots[c]) {
      if(!moving[c])
        break;
      const bool prescribed = std::size_t(l) < result.report.loops.size() && result.report.loops[std::size_t(l)].prescribed;
      if(!prescribed && rows.row_of_slot[std::size_t(l)] >= 0) {
        free_rows[c].push_back(rows.row_of_slot[std::size_t(l)]);
        free_row_slots[c].push_back(l);
      }
    }
  internal::Move_integers integers(free_rows, system_rows, unit,
                                   [&](const Eigen::VectorXd& e) { return system.solve(rows, e); },
                                   [&](const std::vector<int>& at, auto& out) { return inverse.full_columns(at, out); });
  auto component = [&](int v) { return std::size_t(t.component_of_node[t.node_of_vertex[v]]); };

  struct Candidate
  {
    int from, to;
    std::int64_t units;
    double change; // of the energy
    bool cancels;  // onto an opposite singularity
    bool integers; // priced with some integers changed
  };
  const double two_pi = 2 * CGAL_PI;
  auto score = [&](int v, int w, std::int64_t units, double resistance) {
    const double d = two_pi * double(units) / n;
    return double(units) / n * (gradient[std::size_t(w)] - gradient[std::size_t(v)]) + d * d * resistance;
  };
  std::vector<double> trial_gradient(std::size_t(m.nv), 0.);
  Solve_report trial_report;
  std::vector<int> blocked(std::size_t(m.nv), -1); // the round that last blocked a vertex
  internal::Second_thread second_thread;          // half of each round's pair pricing
  const std::size_t unlimited = (std::numeric_limits<std::size_t>::max)();
  std::size_t round_size = unlimited; // the most moves a round tries at once
  // with no trial to follow, a round's pricing would be spent for nothing (the start is not checked for a minimum)
  result.stop = budget == 0 ? Refinement_stop::maximum_trials : Refinement_stop::local_minimum;
  for(int round = 0; budget > 0; ++round) {
    // changes below this are rounding: no cycling on ties
    const double tolerance = 1e-10 * (std::max)(energy, 1e-300);
    // the rows this round reads (singular vertices, where they may move): paths, and the columns kept on them
    const std::vector<int> wanted = singular_and_neighbours();
    if(inverse.paths())
      inverse.prefetch_paths(wanted);
    inverse.watch(wanted);
    std::vector<std::int64_t> changed_periods; // the integers of the move found with them changed
    // The candidates that lower the energy with the integers kept; and (`search`) the one that lowers it most with
    // the best of them, when it beats them all: a round can take only one move that changes integers, first (its
    // integers would interact with the others'), so the moves are searched by increasing lower bound of what they
    // may give, until that bound reaches the best change found.
    struct Hope
    {
      double hoped, kept; // the lower bound, and the change with the integers kept
      int from, to;
      std::int64_t units;
      bool cancels;
    };
    bool pairs_by_paths = false; // this round's cancellations priced from paths, not columns (collect())
    auto collect = [&](const bool search) {
      std::vector<Candidate> candidates;
      std::vector<Hope> hopes;
      for(int v = 0; v < m.nv; ++v) {
        if(k[v] == 0 || fixed[v])
          continue;
        for(int w : neighbours[v]) {
          if(fixed[w] || g.on_boundary[w] || w == v || k[w] != 0)
            continue;
          const double kept = score(v, w, k[v], inverse.resistance(v, w));
          if(kept < -tolerance)
            candidates.push_back({v, w, k[v], kept, false, false});
          if(!search)
            continue;
          const double hoped =
            kept + integers.bound(component(v), inverse.row_of(v), inverse.row_of(w), two_pi * double(k[v]) / n);
          if(hoped < -tolerance)
            hopes.push_back({hoped, kept, v, w, k[v], false});
        }
      }
      if(cancel) {
        // one unit of a positive singularity onto a negative one of its component, at any distance: both lose a unit
        std::vector<int> positive, negative;
        for(int v = 0; v < m.nv; ++v)
          if(k[v] != 0 && !fixed[v])
            (k[v] > 0 ? positive : negative).push_back(v);
        // The exact change of every pair, from the columns of G at the singularities of one sign (kept from round
        // to round: most of them stay), the integers priced as for moves.
        std::vector<double> diagonal(std::size_t(m.nv), 0.);
        for(int v = 0; v < m.nv; ++v)
          if(k[v] != 0 && !fixed[v])
            diagonal[std::size_t(v)] = inverse.diagonal(v);
        // the columns of the smaller side; what a pair reads of the other, gathered once (tens of thousands of
        // pairs a round); the integers searched only for the pairs their quick bound leaves
        const bool by_positive = positive.size() <= negative.size();
        const std::vector<int>& columns = by_positive ? positive : negative;
        const std::vector<int>& others = by_positive ? negative : positive;
        // With the entries from paths, a pair's G_vw is also the product of the two singularities' paths over the
        // part they share (Move_energy::path_entry()). Singularities that move make new columns every round
        // (bunny00_loop1, N = 4, under guidance: 53 columns for 89 moves, most of a step); but a column is kept
        // while the products are made again every round, so they are taken only when all of them (bounded by the
        // shorter path of each pair) cost less than one column.
        pairs_by_paths = false;
        if(inverse.paths()) { // the paths of the singular vertices are made (prefetch_paths() above)
          bool missing = false; // a column to make: else the columns kept serve
          for(int s : columns)
            missing = missing || !inverse.has_column(s);
          if(missing) {
            std::vector<double> length_o;
            for(int o : others)
              length_o.push_back(double(inverse.path_length(inverse.row_of(o))));
            double work = 0;
            for(int s : columns) {
              const double length = double(inverse.path_length(inverse.row_of(s)));
              for(double lo : length_o)
                work += (std::min)(length, lo);
            }
            pairs_by_paths = work < inverse.column_work();
          }
        }
        if(!pairs_by_paths)
          inverse.prefetch(columns);
        struct End
        {
          int vertex, row, entry; // entry: where the columns hold row's (see Move_energy::entry_of_row())
          std::size_t component;
          double gradient, diagonal;
          internal::Move_integers::Row_terms terms;
        };
        auto end_of = [&](int v) {
          const std::size_t c = component(v);
          const int r = inverse.row_of(v);
          return End{v, r, r >= 0 ? inverse.entry_of_row(r) : -1, c, gradient[std::size_t(v)], diagonal[std::size_t(v)],
                     search ? integers.terms(c, inverse.row_of(v)) : internal::Move_integers::Row_terms()};
        };
        std::vector<End> column_ends, other_ends;
        std::vector<const double*> column_values; // null: no row, G_s. = 0
        for(int s : columns) {
          column_ends.push_back(end_of(s));
          column_values.push_back(pairs_by_paths ? nullptr : inverse.column_of(s));
        }
        for(int o : others)
          other_ends.push_back(end_of(o));
        const double unit2 = unit * unit;
        // The pairs of a range of columns, in order: those that lower the energy with the integers kept, and those
        // whose integers are to be searched (the search is not thread-safe: it runs after, in the same order).
        struct Pair_price
        {
          std::uint32_t column, other;
          double kept, hoped; // the change with the integers kept, and at best with them changed (quick_bound())
          bool search;
        };
        auto price = [&](std::size_t begin, std::size_t end) {
          std::vector<Pair_price> found;
          for(std::size_t i = begin; i < end; ++i) {
            const End& a = column_ends[i];
            const double* column = column_values[i];
            for(std::size_t o = 0; o < other_ends.size(); ++o) {
              const End& b = other_ends[o];
              if(a.component != b.component)
                continue;
              const End& v = by_positive ? a : b;
              const End& w = by_positive ? b : a;
              CGAL_assertion(pairs_by_paths || b.row < 0 || inverse.watched(b.row));
              const double g_vw = pairs_by_paths          ? inverse.path_entry(a.row, b.row)
                                  : column && b.row >= 0 ? column[b.entry]
                                                         : 0.;
              // score(v, w, 1, G_vv + G_ww - 2 G_vw)
              const double kept = 1. / n * (w.gradient - v.gradient) + unit2 * (v.diagonal + w.diagonal - 2 * g_vw);
              const double hoped = search ? kept + integers.quick_bound(a.component, v.terms, w.terms, unit) : kept;
              const bool searched = search && hoped < -tolerance;
              if(searched || kept < -tolerance)
                found.push_back({std::uint32_t(i), std::uint32_t(o), kept, hoped, searched});
            }
          }
          return found;
        };
        // hundreds of thousands of pairs a round on cheese_loop1 (N = 4): half on a second thread
        std::vector<Pair_price> priced;
        if(column_ends.size() >= 2 && column_ends.size() * other_ends.size() >= 20000) {
          auto halves = second_thread.on_two_halves(column_ends.size(), price);
          priced = std::move(halves.first);
          priced.insert(priced.end(), halves.second.begin(), halves.second.end());
        } else
          priced = price(0, column_ends.size()); // fewer: not worth a thread
        for(const Pair_price& q : priced) {
          const End& a = column_ends[q.column];
          const End& v = by_positive ? a : other_ends[q.other];
          const End& w = by_positive ? other_ends[q.other] : a;
          if(q.kept < -tolerance)
            candidates.push_back({v.vertex, w.vertex, 1, q.kept, true, false});
          if(q.search)
            hopes.push_back({q.hoped, q.kept, v.vertex, w.vertex, 1, true});
        }
      }
      if(search) {
        // Unproven integers: their bounds are heuristic and prune few searches, so at most this many a round
        // (ChineseDragon-10kv's curvature guidance, 64 link integers: 285k searches were 3.4 s of 3.7 s).
        const std::size_t unproven_searches = 2000;
        const bool proven = integers.proven();
        std::stable_sort(hopes.begin(), hopes.end(), [](const Hope& a, const Hope& b) { return a.hoped < b.hoped; });
        // only a move that changes integers and beats every move with them kept is taken (it must come first)
        double best = -tolerance;
        for(const Candidate& c : candidates)
          best = (std::min)(best, c.change);
        const Hope* found = nullptr;
        std::size_t change_component = 0;
        std::vector<std::int64_t> changed;
        auto units_of = [&](const Hope& h) { return two_pi * double(h.units) / n; };
        if(proven) {
          for(std::size_t i = 0; i < hopes.size() && hopes[i].hoped < best; ++i) {
            const Hope& h = hopes[i];
            const double change = integers.best(component(h.from), inverse.row_of(h.from), inverse.row_of(h.to),
                                                units_of(h), h.kept, best);
            if(change < best) {
              best = change;
              found = &h;
              change_component = integers.change_component();
              changed = integers.change();
            }
          }
        } else {
          // The same choice as the loop above, the searches priced ahead a chunk at a time on two threads (the
          // chunk bounds the searches made past the one that ends the loop).
          const std::size_t chunk = 256;
          const std::size_t searched = (std::min)(hopes.size(), unproven_searches);
          double best_before_found = best;
          bool ended = false;
          std::vector<internal::Move_integers::Unproven_search> searches;
          for(std::size_t begin = 0; begin < searched && !ended; begin += chunk) {
            const std::size_t end = (std::min)(begin + chunk, searched);
            searches.clear();
            for(std::size_t i = begin; i < end; ++i) {
              const Hope& h = hopes[i];
              searches.push_back(
                {component(h.from), inverse.row_of(h.from), inverse.row_of(h.to), units_of(h), h.kept});
            }
            integers.price_unproven(searches, best, [&](std::size_t count, const auto& f) {
              if(count >= 32)
                second_thread.on_two_halves(count, f);
              else
                f(std::size_t(0), count);
            });
            for(std::size_t i = begin; i < end; ++i) {
              const internal::Move_integers::Unproven_search& q = searches[i - begin];
              if(!(hopes[i].hoped < best)) {
                ended = true;
                break;
              }
              if(q.bounded >= best || !(q.change < best))
                continue; // best() would not search it at this threshold, or it does not beat the best
              best_before_found = best;
              best = q.change;
              found = &hopes[i];
            }
          }
          if(found) {
            // the integers behind it, searched again alone
            const double change = integers.best(component(found->from), inverse.row_of(found->from),
                                                inverse.row_of(found->to), units_of(*found), found->kept,
                                                best_before_found);
            CGAL_assertion(change == best);
            CGAL_USE(change);
            change_component = integers.change_component();
            changed = integers.change();
          }
        }
        if(found) {
          candidates.push_back({found->from, found->to, found->units, best, found->cancels, true});
          // its trial solve is given these integers (see Move_integers::change())
          changed_periods = accepted_periods;
          for(std::size_t a = 0; a < changed.size(); ++a)
            changed_periods[std::size_t(free_row_slots[change_component][a])] += changed[a];
        }
      }
      return candidates;
    };
    // Proven integers (loops of the mesh's topology) are searched every round: their bounds are exact, so few
    // searches, and a move that pays only with them changed is taken as soon as it is the best (femur, n = 4:
    // 7 trials, 13 when deferred). Unproven ones (links under guidance: about 1,700 searches a round on homer,
    // 1.5 to 2.9 ms on two threads, a solve 0.4 ms) only when no candidate lowers the energy with them kept,
    // before stopping, so that a step costs what it costs without; either way the local minimum is one with the
    // integers chosen again.
    const bool search_every_round = !integers.empty() && integers_proven;
    if(search_every_round)
      integers.start_round(Access::multipliers(solver), true);
    std::vector<Candidate> candidates = collect(search_every_round);
    if(candidates.empty() && !integers.empty() && !search_every_round) {
      integers.start_round(Access::multipliers(solver), integers_proven);
      candidates = collect(true);
    }
    if(candidates.empty())
      break;
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.change < b.change; });

    // The moves of a round: best first, none within a ring of another. Cancellations interact with everything
    // at any distance (long dipoles): each one taken has its change corrected by its interaction with those taken
    // before, exactly, from the columns of G at both its ends, and so has every later candidate (the interactions
    // of moves with moves, short dipoles a ring apart, are left to the solve). A move that changes integers goes
    // alone with moves (they would interact through the integers). In a first round on refined_elephant, 71
    // moves with 40 cancellations, predicted -59 without the interactions, gave +99.
    std::vector<Candidate> chosen;
    // a cancellation, G e_from, G e_to (null: no row); kept by `inverse` until its next prefetch()
    std::vector<std::pair<Candidate, std::array<const double*, 2>>> long_dipoles;
    bool integers_taken = false;
    auto free_here = [&](int v) { return blocked[std::size_t(v)] != round; };
    // G between a long dipole's end (its column, or its vertex when the pairs were priced from paths: every vertex
    // a candidate moves has its path) and v; the products kept, a candidate's ends recurring in many pairs
    std::unordered_map<std::uint64_t, double> products;
    auto at = [&](const double* column, int end, int v) {
      const int r = inverse.row_of(v);
      if(pairs_by_paths) {
        const int re = inverse.row_of(end);
        if(r < 0 || re < 0)
          return 0.;
        const std::uint64_t key = (std::uint64_t(std::uint32_t(re)) << 32) | std::uint32_t(r);
        auto known = products.find(key);
        return known != products.end() ? known->second : products.emplace(key, inverse.path_entry(re, r)).first->second;
      }
      CGAL_assertion(r < 0 || inverse.watched(r));
      return r >= 0 && column ? column[inverse.entry_of_row(r)] : 0.;
    };
    for(std::size_t i = 0; i < candidates.size(); ++i) {
      const Candidate& c = candidates[i];
      if(!free_here(c.from) || !free_here(c.to))
        continue;
      if(c.integers && (!chosen.empty()))
        continue;
      if(integers_taken && c.cancels)
        continue;
      // 2 db_c^T G db_x, db = d (e_to - e_from), for each long dipole x taken
      const double dc = two_pi * double(c.units) / n;
      double change = c.change;
      for(const auto& x : long_dipoles) {
        const double dx = two_pi * double(x.first.units) / n;
        const int from = x.first.from, to = x.first.to;
        change += 2 * dc * dx *
                  ((at(x.second[1], to, c.to) - at(x.second[1], to, c.from)) -
                   (at(x.second[0], from, c.to) - at(x.second[0], from, c.from)));
      }
      if(change >= -tolerance)
        continue;
      chosen.push_back(c);
      chosen.back().change = change;
      integers_taken = integers_taken || c.integers;
      if(c.cancels && !c.integers && pairs_by_paths) {
        long_dipoles.emplace_back(c, std::array<const double*, 2>{{nullptr, nullptr}});
      } else if(c.cancels && !c.integers) {
        // its columns (one end's is kept from the pricing), with those of the next cancellations still free: eight
        // substitutions cost about one (the factor is read once), and the best-scored are mostly taken next
        // (cheese_loop1, N = 4: 88 columns made one at a time were a fifth of the refinement)
        if(!inverse.has_column(c.from) || !inverse.has_column(c.to)) {
          std::vector<int> ends;
          for(std::size_t j = i; j < candidates.size() && ends.size() < 8; ++j) {
            const Candidate& d = candidates[j];
            if(j == i || (d.cancels && !d.integers && free_here(d.from) && free_here(d.to)))
              for(int v : {d.from, d.to})
                if(!inverse.has_column(v) && std::find(ends.begin(), ends.end(), v) == ends.end())
                  ends.push_back(v);
          }
          inverse.prefetch(ends, false); // the columns of long_dipoles stay
        }
        long_dipoles.emplace_back(c, std::array<const double*, 2>{{inverse.column_of(c.from), inverse.column_of(c.to)}});
      }
      for(int v : {c.from, c.to}) {
        blocked[std::size_t(v)] = round;
        for(int w : neighbours[v])
          blocked[std::size_t(w)] = round;
      }
    }
    bool accepted = false;
    for(std::size_t size = (std::min)(chosen.size(), round_size); size > 0 && !accepted; size /= 2) {
      if(result.trials >= budget)
        break;
      std::vector<std::int64_t> kk(k);
      for(std::size_t i = 0; i < size; ++i) {
        kk[std::size_t(chosen[i].from)] -= chosen[i].units;
        kk[std::size_t(chosen[i].to)] += chosen[i].units;
      }
      ++result.trials;
      // a move priced with changed integers is alone (see above): its trial starts from them
      Access::hint_periods(solver, size == 1 && chosen[0].integers && !changed_periods.empty() ? changed_periods
                                                                                              : accepted_periods);
      const double e = solve(as_set(kk), trial_gradient, trial_report);
      accepted = e < energy * (1 - 1e-12);
      if(!accepted)
        continue;
      // after a halving, the next round starts at twice the size that was accepted (fewer solves rejected where
      // moves interact more than predicted), and grows back when its first solve is accepted
      round_size = size < (std::min)(chosen.size(), round_size) ? 2 * size
                   : round_size > unlimited / 2               ? unlimited
                                                              : 2 * round_size;
      k.swap(kk);
      accepted_periods = Access::last_periods(solver);
      gradient.swap(trial_gradient);
      result.report = trial_report;
      integers_proven = Access::free_integers_proven(solver);
      energy = e;
      ++result.rounds;
      for(std::size_t i = 0; i < size; ++i) {
        const Candidate& c = chosen[i];
        result.moves.push_back({m.vertex_descriptors[c.from], m.vertex_descriptors[c.to], Singularity_index(c.units, n), e});
        result.cancellations += c.cancels ? 1 : 0;
      }
    }
    if(!accepted) {
      result.stop = result.trials >= budget ? Refinement_stop::maximum_trials : Refinement_stop::rejected_moves;
      break;
    }
  }
  result.local_minimum = result.stop == Refinement_stop::local_minimum;
  result.column_solves = inverse.column_solves() + integers.column_solves();
  result.energy_after = energy;
  result.singularities = as_set(k);
  // x holds the last trial's connection (of a rejected set, or refined only from 1e-11): solved again at full
  // accuracy, from the integers accepted
  trial_accuracy.reset();
  Access::hint_periods(solver, accepted_periods);
  result.report = solver.solve(result.singularities, x, np);
  accepted_periods = Access::last_periods(solver);
  result.energy_after = result.report.energy + result.report.guidance_energy;
  // and the next solve, of the refined set as a rule, starts from them (ChineseDragon-10kv with --align-curvature:
  // the refinement reached 175.51, a fresh solve of its singularities 177.94)
  Access::hint_periods(solver, accepted_periods);
  return result;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_REFINEMENT_H
