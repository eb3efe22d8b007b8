// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_EXCEPTIONS_H
#define CGAL_TRIVIAL_CONNECTIONS_EXCEPTIONS_H

#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
What is wrong with the data given to the package. Every value names one documented failure; the
exception carrying it also says where (a vertex, face or loop index) when that makes sense.
*/
enum class Error_code {
  empty_mesh,                 ///< the mesh has no face
  not_triangle_mesh,          ///< a face is not a triangle
  non_manifold,               ///< a non-manifold vertex or edge
  inconsistent_orientation,   ///< two faces that share an edge do not traverse it in opposite directions
  degenerate_face,            ///< a face has zero area, or is so nearly collinear (every angle within 1e-12 rad of 0
                              ///< or pi) that its plane is not determined in double precision
  invalid_vertex,             ///< a vertex that does not exist, or that belongs to no face
  singularity_on_boundary,    ///< a singularity placed on a boundary vertex
  duplicate_singularity,      ///< a vertex listed twice
  index_not_multiple,         ///< an index that is not a multiple of 1/n
  poincare_hopf_violated,     ///< indices of a component do not sum to its Euler characteristic
  invalid_symmetry_order,     ///< n < 1
  invalid_loop_periods,       ///< prescribed loop integers of the wrong size or violating Poincare-Hopf
  invalid_index,              ///< a malformed index (zero denominator, overflow)
  invalid_constraint,         ///< a constrained face listed twice, a zero or normal target direction, a target
                              ///< missing, a constrained face on an aligned boundary
  invalid_argument,           ///< any other malformed argument (seed face, face out of range, ...)
  io_error,                   ///< a file could not be read or written
  parse_error,                ///< a file could not be parsed
  solver_failure,             ///< the sparse factorization or a solve failed
  non_finite_point            ///< a vertex's point has a coordinate that is not a finite number (NaN, infinite);
                              ///< the file readers report it as a `parse_error` of the file, with the same message
};

/*!
\ingroup PkgTrivialConnectionsRef
Short, stable name of an error code, e.g. `"poincare_hopf_violated"`.
\param c the error code
\returns the name of the enumerator `c` (a string literal), or `"unknown"` for a value that is not one of
         the enumerators
*/
inline const char* error_code_name(Error_code c)
{
  switch(c) {
    case Error_code::empty_mesh: return "empty_mesh";
    case Error_code::not_triangle_mesh: return "not_triangle_mesh";
    case Error_code::non_manifold: return "non_manifold";
    case Error_code::inconsistent_orientation: return "inconsistent_orientation";
    case Error_code::degenerate_face: return "degenerate_face";
    case Error_code::invalid_vertex: return "invalid_vertex";
    case Error_code::singularity_on_boundary: return "singularity_on_boundary";
    case Error_code::duplicate_singularity: return "duplicate_singularity";
    case Error_code::index_not_multiple: return "index_not_multiple";
    case Error_code::poincare_hopf_violated: return "poincare_hopf_violated";
    case Error_code::invalid_symmetry_order: return "invalid_symmetry_order";
    case Error_code::invalid_loop_periods: return "invalid_loop_periods";
    case Error_code::invalid_index: return "invalid_index";
    case Error_code::invalid_constraint: return "invalid_constraint";
    case Error_code::invalid_argument: return "invalid_argument";
    case Error_code::io_error: return "io_error";
    case Error_code::parse_error: return "parse_error";
    case Error_code::solver_failure: return "solver_failure";
    case Error_code::non_finite_point: return "non_finite_point";
  }
  return "unknown";
}

/*!
\ingroup PkgTrivialConnectionsRef
The exception thrown for every error in user data (and for a failed factorization). `what()` is a
one-line, human-readable message saying what is wrong and where; `code()` says which error it is and
`where()` the vertex, face or loop index concerned (`no_location` when there is none).
Programmer errors (violated preconditions) are `CGAL_precondition`s instead.
*/
class Invalid_input : public std::runtime_error
{
public:
  /// `where()` of an error that concerns no particular vertex, face or loop
  static constexpr std::size_t no_location = (std::numeric_limits<std::size_t>::max)();

  /// an error of kind `code`, described by `message`, at index `where`
  /// \param code which error it is
  /// \param message the one-line message returned by `what()`
  /// \param where the 0-based index of the vertex, face or loop concerned, or `no_location`
  Invalid_input(Error_code code, const std::string& message, std::size_t where = no_location)
    : std::runtime_error(message), m_code(code), m_where(where)
  {}

  /// which error it is
  /// \returns the `code` given to the constructor
  Error_code code() const { return m_code; }
  /// the index of the vertex, face or loop concerned (in the mesh's iteration order), or `no_location`
  /// \returns the `where` given to the constructor
  std::size_t where() const { return m_where; }

private:
  Error_code m_code;
  std::size_t m_where;
};

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_EXCEPTIONS_H
