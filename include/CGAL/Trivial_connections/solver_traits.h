// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H
#define CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H

#include <CGAL/Eigen_solver_traits.h>

#include <Eigen/SparseCholesky>
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
The default sparse solver of `Trivial_connection_solver`: Eigen's header-only `SimplicialLDLT`.
*/
using Default_solver_traits = CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>;

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
/*!
\ingroup PkgTrivialConnectionsRef
SuiteSparse's supernodal CHOLMOD through Eigen's `CholmodSupport`. Available when
`CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD` is defined and CHOLMOD is linked (CMake option
`TRIVIAL_CONNECTIONS_WITH_CHOLMOD`).
*/
using Cholmod_solver_traits = CGAL::Eigen_solver_traits<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>>;
/// the solver the command-line program uses: CHOLMOD when it is available
using Recommended_solver_traits = Cholmod_solver_traits;
#else
/// the solver the command-line program uses: CHOLMOD when it is available
using Recommended_solver_traits = Default_solver_traits;
#endif

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SOLVER_TRAITS_H
