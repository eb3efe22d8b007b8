/*!
\ingroup PkgTrivialConnectionsConcepts
\cgalConcept

The sparse linear algebra `Trivial_connection_solver` factors its constraint system with (its template
parameter `SolverTraits`). It is CGAL's `SparseLinearAlgebraWithFactorTraits_d` on Eigen matrices: the
solver assembles the symmetric positive definite matrix \f$ A W^{-1} A^T \f$ as an
`Eigen::SparseMatrix<double>`, already in a fill-reducing order with the rows of the loop integers last, hands
it over without a copy, factors it once in the constructor, and then solves by back-substitutions.

With the two models of the package the solver also reads the factor itself (the Schur complement of the loop
rows, and partial substitutions for `set_constraints()`); with any other model these cost one
back-substitution per loop, and `set_constraints()` factors again.

\cgalRefines{`SparseLinearAlgebraWithFactorTraits_d`}

\cgalHasModel{`CGAL::Trivial_connections::Default_solver_traits` (Eigen's `SimplicialLDLT`, natural
ordering), `CGAL::Trivial_connections::Cholmod_solver_traits` (CHOLMOD, supernodal), and any
`CGAL::Eigen_solver_traits<S>` with an Eigen sparse solver `S` of symmetric positive definite matrices}
*/
class TrivialConnectionSolverTraits
{
public:
  /// \name Types
  /// @{

  /// a sparse matrix type constructible from an `Eigen::SparseMatrix<double>`, with
  /// `Eigen::SparseMatrix<double>& eigen_object()` (as `CGAL::Eigen_sparse_matrix<double>`)
  typedef unspecified_type Matrix;

  /// a dense vector type constructible with a size, assignable from an Eigen expression and convertible
  /// to `Eigen::VectorXd` (as `CGAL::Eigen_vector<double>`)
  typedef unspecified_type Vector;

  /// @}

  /// \name Operations
  /// @{

  /// factors `M`, symmetric positive definite (both triangles are filled for a model the package does not
  /// know; for its own models, only the triangle they read).
  /// \param M the matrix, in the order it must be factored in (the solver orders it)
  /// \param d the scaling factor of the solution; the solver assumes 1, which `CGAL::Eigen_solver_traits`
  ///        sets
  /// \returns `false` when the factorization fails
  bool factor(const Matrix& M, double& d);

  /// solves with the last factorization.
  /// \param b the right-hand side
  /// \param x receives the solution of `M x = b`
  /// \returns `false` when the solve fails
  bool linear_solver(const Vector& b, Vector& x);

  /// @}
};
