// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_BACKEND_VIEW_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_BACKEND_VIEW_H

// The backend of the last factorization of Automatic_solver_traits, seen as one-backend solver traits, so that
// the specializations for one backend serve the automatic choice.

#include <CGAL/Trivial_connections/solver_traits.h>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
// the views of one backend of Automatic_solver_traits that the specializations for that backend read (solver())
template <class Backend>
struct Backend_view
{
  Backend& backend;
  Backend& solver() { return backend; }
  const Backend& solver() const { return backend; }
};

using Automatic_simplicial_traits = CGAL::Eigen_solver_traits<Automatic_solver_traits::Simplicial>;
using Automatic_simplicial_view = Backend_view<Automatic_solver_traits::Simplicial>;
using Automatic_cholmod_view = Backend_view<Cholmod_supernodal_factorization>;
using Automatic_backend = Factorization_backend;

// `on_simplicial(view)` or `on_supernodal(view)` for the backend of the last factorization, `none` without one
template <class Traits, class OnSimplicial, class OnSupernodal, class Result>
Result on_backend(Traits& traits, OnSimplicial on_simplicial, OnSupernodal on_supernodal, Result none)
{
  switch(traits.backend()) {
  case Automatic_backend::simplicial_ldlt: {
    Automatic_simplicial_view view{traits.simplicial()};
    return on_simplicial(view);
  }
  case Automatic_backend::cholmod_supernodal: {
    Automatic_cholmod_view view{traits.cholmod()};
    return on_supernodal(view);
  }
  default:
    return none;
  }
}
#endif

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_BACKEND_VIEW_H
