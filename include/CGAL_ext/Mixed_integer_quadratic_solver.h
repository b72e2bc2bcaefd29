// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_MIXED_INTEGER_QUADRATIC_SOLVER_H
#define CGAL_EXT_MIXED_INTEGER_QUADRATIC_SOLVER_H

/// \file Mixed_integer_quadratic_solver.h
/// A convex quadratic minimised under sparse linear equality constraints,
/// some variables integer: the equalities are eliminated exactly, then the
/// integer variables are rounded in batches with a re-solve after each batch
/// (the scheme of CoMISo's constrained solver, Bommes et al. 2009/2013).
/// The integer-grid map (`Integer_grid_map_3.h`) is its user.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cstddef>
#include <utility>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtHex
/// One linear equality `sum_i a_i x_i = rhs`.
struct Linear_equality {
  /// The terms `(i, a_i)`; an index may appear more than once (the
  /// coefficients add up).
  std::vector<std::pair<std::size_t, double>> terms;
  /// The right-hand side.
  double rhs = 0;
};

/// \ingroup PkgCGALExtHex
/// The problem: minimise `x^T H x - 2 b^T x` subject to the equalities, with
/// the integer variables in Z.
struct Mixed_integer_quadratic_problem {
  /// `H`, symmetric positive semi-definite (both triangles stored), `n x n`.
  Eigen::SparseMatrix<double> H;
  /// `b`, of size `n`.
  Eigen::VectorXd b;
  /// The equalities. Redundant ones are allowed (they are recognised and
  /// counted); inconsistent ones are an error.
  std::vector<Linear_equality> equalities;
  /// The indices of the integer variables, each once.
  std::vector<std::size_t> integer_variables;
};

/// \ingroup PkgCGALExtHex
/// How the integer variables are rounded.
struct Mixed_integer_quadratic_options {
  /// Whether to round at all: `false` gives the relaxed minimiser, with the
  /// equalities held and the integer variables real.
  bool round = true;
  /// Whether the rounding takes the integer variables by the cost of their
  /// rounding (the rise of the objective when one is fixed at its nearest
  /// integer and the others re-optimised, `d^2 / (K^-1)_kk` for a distance
  /// `d`, from the columns of `K^-1` computed once), cheapest first; else by
  /// their distance to their nearest integer, closest first.
  bool least_cost_first = true;
  /// Each round fixes, in the order above, the leading variables whose
  /// distance to their nearest integer is below this (at least the first), ...
  double rounding_threshold = 0.1;
  /// ... at most this share of those still free (at least one per round),
  /// then re-solves. 0 rounds one variable per solve.
  double rounding_batch_share = 0.2;
  /// Relative weight of the diagonal added to the reduced system
  /// (`epsilon * mean diagonal`), so that variables the objective does not
  /// see take 0 instead of making the system singular.
  double regularization = 1e-12;
};

/// \ingroup PkgCGALExtHex
/// What the solver did.
struct Mixed_integer_quadratic_report {
  /// The number of variables.
  std::size_t variables = 0;
  /** @{ */
  /// The equalities given, those that were redundant (a combination of the
  /// others), and the variables left free after eliminating the rest.
  std::size_t equalities = 0, redundant_equalities = 0, free_variables = 0;
  /** @} */
  /** @{ */
  /// The integer variables given, and those among the free variables (the
  /// others are integer combinations of these).
  std::size_t integer_variables = 0, free_integer_variables = 0;
  /** @} */
  /// Eliminated integer variables that are not an integer combination of
  /// integer free ones (their final expression) and were found non-integral
  /// after the rounding (0 when every equality among integer variables has
  /// a unit coefficient to pivot on).
  std::size_t non_integral_eliminated = 0;
  /// The solves of the reduced system: the first factorises it, the others
  /// (one per rounding round) are low-rank updates of that solution.
  std::size_t solves = 0;
  /** @{ */
  /// The objective `x^T H x - 2 b^T x` of the relaxed and of the rounded solution.
  double objective_relaxed = 0, objective_rounded = 0;
  /** @} */
};

/// \ingroup PkgCGALExtHex
/// The solution.
struct Mixed_integer_quadratic_solution {
  /// The minimiser, of size `n`; the integer variables hold exact integers
  /// when `options.round` is set.
  Eigen::VectorXd x;
  /// What the solver did.
  Mixed_integer_quadratic_report report;
  /** @{ */
  /// The reduced space: every `x = E y + c` meets the equalities; `y` is
  /// the solution's, one entry per free variable.
  Eigen::SparseMatrix<double> E;
  Eigen::VectorXd c, y;
  /** @} */
  /// Per entry of `y`: whether it is an integer variable (then an integer,
  /// when rounded), so that a later step can move the others only.
  std::vector<char> integer_column;
};

/// \ingroup PkgCGALExtHex
/// Minimises `x^T H x - 2 b^T x` under the linear equalities with the integer
/// variables in Z (see `Mixed_integer_quadratic_problem`).
///
/// **Elimination.** The equalities are taken in order; each, with the
/// variables eliminated so far substituted, eliminates one of its variables:
/// a real one if it has any, else an integer one with a unit coefficient
/// whose other coefficients are integers (the eliminated variable is then an
/// integer combination of the others), else the largest coefficient's
/// (`non_integral_eliminated` counts such variables left non-integral). Among those, the variable that the
/// fewest eliminated expressions use, which keeps the expressions short. The
/// equalities hold exactly up to rounding of the coefficients' arithmetic.
///
/// **Rounding.** The reduced system is factorised once (a sparse Cholesky
/// factorisation, `Eigen::SimplicialLDLT`) and solved, with one more solve
/// per integer variable for its column of the inverse. Then the integer
/// variables cheapest to round are fixed (see
/// `Mixed_integer_quadratic_options`) and the system solved again with them
/// fixed, until every integer variable is: each re-solve is a dense system
/// of the fixed variables' size (the Schur complement of the first
/// factorisation), not a factorisation. Greedy: the result is not the
/// integer optimum.
///
/// Serial and deterministic: the same problem gives the same bits.
/// \param problem the problem
/// \param options the rounding's options
/// \returns the minimiser and the report
/// \throws std::invalid_argument for sizes that do not match, an index out of
///   range, or a value that is not finite
/// \throws std::runtime_error for inconsistent equalities, or a reduced
///   system that is not positive definite
Mixed_integer_quadratic_solution solve_mixed_integer_quadratic(const Mixed_integer_quadratic_problem& problem,
                                                               const Mixed_integer_quadratic_options& options = {});

} // namespace CGAL_ext

#endif // CGAL_EXT_MIXED_INTEGER_QUADRATIC_SOLVER_H
