// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Internal to the integer-grid map: the untangling of a map in a linear
// space x = E y + c (the equalities and the rounded integers held), by the
// foldover-free energy of Garanzha, Kaporin, Kudryavtseva, Protais, Ray and
// Sokolov, "Foldover-free maps in 50 lines of code" (ACM ToG 2021).
#ifndef CGAL_EXT_SRC_HEX_FOLDOVER_FREE_MAP_H
#define CGAL_EXT_SRC_HEX_FOLDOVER_FREE_MAP_H

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <cstddef>
#include <vector>

namespace CGAL_ext::internal {

// A map of tetrahedra into parameter space, each corner at three entries of x.
struct Foldover_free_problem {
  std::vector<std::array<std::size_t, 4>> corner; // the index of each corner's first entry in x
  std::vector<Eigen::Matrix<double, 3, 4>> B;     // grad u = U B^T (U: the corners' parameters as columns)
  std::vector<Eigen::Matrix3d> M;                 // the inverse of the target Jacobian: K = J M is I at best
  std::vector<double> volume;                     // physical volumes (the weights)
  const Eigen::SparseMatrix<double>* E = nullptr;
  const Eigen::VectorXd* c = nullptr;
  std::vector<char> fixed; // per entry of y: held
};

struct Foldover_free_settings {
  int max_rounds = 40;           // of the barrier's epsilon
  int max_iterations = 300;      // L-BFGS iterations per round
  int memory = 8;                // L-BFGS pairs
  double volume_weight = 0.5;    // theta: (1 - theta) shape + theta volume
  double energy_tolerance = 1e-5;
  int stall_rounds = 5;          // rounds without a higher least determinant, while negative, that stop it
};

struct Foldover_free_outcome {
  int rounds = 0, iterations = 0;
  double min_det_before = 0, min_det_after = 0; // of K = J M
};

// The least det(J M) over the tetrahedra for x = E y + c.
double min_relative_det(const Foldover_free_problem& pb, const Eigen::VectorXd& y);

// Moves the entries of y that are not fixed to minimise the foldover-free
// energy with a vanishing regularisation, until every det(J M) is positive
// and the energy settles (or the rounds run out). Serial, deterministic.
Foldover_free_outcome untangle(const Foldover_free_problem& pb, Eigen::VectorXd& y, const Foldover_free_settings& s);

} // namespace CGAL_ext::internal

#endif
