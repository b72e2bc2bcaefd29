// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_FRAME_FIELD_3_REFINEMENT_H
#define CGAL_EXT_INTERNAL_FRAME_FIELD_3_REFINEMENT_H

// The refinement of Frame_field_3: L-BFGS on local rotations (over all the
// tetrahedra, or over the active set of a local re-optimisation), its energy
// and gradient, and the starts of reoptimize() (propagation, relaxation).
//
// Member definitions of Frame_field_3, included at the end of
// <CGAL_ext/Frame_field_3.h>; not a header of its own.

namespace CGAL_ext {

// The `propagated` start of reoptimize(): breadth-first from the fixed
// neighbours, each frame transported from the tetrahedron that reached it
// (its first facet towards one). False, with nothing changed, if no fixed
// neighbour reaches some of the tetrahedra.
// `local` gives the position of a tetrahedron in `tets`, or size_t(-1).
template <class Metric_field>
inline bool Frame_field_3<Metric_field>::
    propagate(const std::vector<std::size_t>& tets, const std::vector<std::size_t>& local) {
  const std::size_t none = std::size_t(-1);
  std::vector<std::size_t> queue;
  std::vector<char> done(tets.size(), 0);
  std::vector<Eigen::Quaterniond> q(tets.size());
  auto reach = [&](std::size_t k, std::size_t i, int f, const Eigen::Quaterniond& from) {
    q[k] = e_.links[i].identity[f] ? from : (e_.transport_in[i][f] * from).normalized();
    done[k] = 1;
    queue.push_back(k);
  };
  for (std::size_t k = 0; k < tets.size(); ++k)
    for (int f = 0; f < 4; ++f) {
      const std::int64_t j = e_.links[tets[k]].nb[f];
      if (j >= 0 && local[j] == none) {
        reach(k, tets[k], f, q_[j]);
        break;
      }
    }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t i = tets[queue[head]];
    for (int f = 0; f < 4; ++f) {
      const std::int64_t j = e_.links[i].nb[f];
      if (j < 0 || local[j] == none || done[local[j]]) continue;
      const int fj = e_.cells[j]->index(e_.cells[i]);
      reach(local[j], std::size_t(j), fj, q[queue[head]]);
    }
  }
  if (queue.size() < tets.size()) return false;
  for (std::size_t k = 0; k < tets.size(); ++k) q_[tets[k]] = q[k];
  return true;
}

// The `relaxed` start of reoptimize(): the linear initialisation on the
// list (H x = b with the frames outside on the right-hand side), projected
// onto rotations. `local` as in propagate().
template <class Metric_field>
inline void Frame_field_3<Metric_field>::
    relax(const std::vector<std::size_t>& tets, const Active_set& set, const std::vector<std::size_t>& local) {
  const std::size_t m = tets.size();
  std::vector<Sh_vector> x(m, Sh_vector::Zero()), b(m, Sh_vector::Zero());
  internal::parallel_for_each_index(m, [&](std::size_t k) {
    const std::size_t i = tets[k];
    if (e_.constraint_of[i] >= 0) b[k] = e_.constraints[e_.constraint_of[i]].b;
    for (int f = 0; f < 4; ++f)
      if (e_.links[i].nb[f] >= 0 && !set.active(e_.links[i].nb[f])) b[k] += e_.links[i].w[f] * e_.neighbour_sh(i, f, s_);
  });
  auto apply = [&](const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) {
    internal::parallel_for_each_index(m, [&](std::size_t k) {
      const std::size_t i = tets[k];
      const auto& L = e_.links[i];
      Sh_vector r = e_.diagonal[i] * v[k];
      const Sh_vector* from[4];
      Sh_vector t[4];
      for (int f = 0; f < 4; ++f) from[f] = L.nb[f] >= 0 && set.active(L.nb[f]) ? &v[local[L.nb[f]]] : nullptr;
      e_.transported(i, from, t);
      for (int f = 0; f < 4; ++f)
        if (from[f]) r -= L.w[f] * t[f];
      if (e_.constraint_of[i] >= 0) r += e_.constraints[e_.constraint_of[i]].B * v[k];
      y[k] = r;
    });
  };
  double residual = 0;
  pcg(x, b, apply, [&](std::size_t k, const Sh_vector& r) { return e_.precondition(tets[k], r); }, 1e-8, nullptr,
      residual);
  internal::parallel_for_each_index(m, [&](std::size_t k) {
    if (x[k].norm() > 1e-9) q_[tets[k]] = Eigen::Quaterniond(rotation_from_octahedral_sh(x[k]).rotation);
  });
}

// The refinement energy (smoothness + soft boundary terms) of the active
// tetrahedra and its gradient in their left-trivialised rotation
// increments, projected on the free axes; the frames are s_.
template <class Metric_field>
inline double Frame_field_3<Metric_field>::
    energy_and_gradient(const Active_set& set, std::vector<Eigen::Vector3d>* g) const {
  // Per tetrahedron: its four faces' terms, then its boundary term.
  return internal::deterministic_sum_of_terms<5>(set.n, [&](std::size_t k, std::array<double, 5>& e) {
    const std::size_t i = set.tet(k);
    const auto& L = e_.links[i];
#if defined(__GNUC__)
    // The neighbours' frames are scattered in memory: fetch those of a
    // tetrahedron a few ahead while this one computes.
    constexpr std::size_t ahead = 8;
    if (k + ahead < set.n) {
      const auto& La = e_.links[set.tet(k + ahead)];
      for (int f = 0; f < 4; ++f)
        if (La.nb[f] >= 0) {
          const char* p = reinterpret_cast<const char*>(&s_[std::size_t(La.nb[f])]);
          __builtin_prefetch(p), __builtin_prefetch(p + sizeof(Sh_vector) - 1);
        }
    }
#endif
    Sh_vector grad = Sh_vector::Zero(), t[4];
    e_.neighbour_shs(i, s_, t);
    for (int f = 0; f < 4; ++f) {
      if (L.nb[f] < 0) continue;
      const Sh_vector r = s_[i] - t[f];
      // A face between two active tetrahedra is seen from both sides.
      e[f] = (set.active(L.nb[f]) ? 0.5 : 1.0) * L.w[f] * r.squaredNorm();
      grad += (2 * L.w[f]) * r;
    }
    const std::int64_t c = e_.constraint_of[i];
    if (c >= 0) {
      const auto& C = e_.constraints[c];
      const Sh_vector Bs = C.B * s_[i];
      e[4] = s_[i].dot(Bs) - 2 * C.b.dot(s_[i]) + C.c;
      grad += 2 * (Bs - C.b);
    }
    if (g) {
      Eigen::Vector3d gi = sh_rotation_jacobian(s_[i]).transpose() * grad;
      if (c >= 0 && hard_constraint_held(i)) {
        const auto& C = e_.constraints[c];
        gi = C.axes == 2 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(gi.dot(C.d1) * C.d1);
      }
      (*g)[k] = gi;
    }
  });
}

template <class Metric_field>
inline void Frame_field_3<Metric_field>::refine() {
  Active_set all;
  all.n = size();
  int evaluations = 0;
  stats_.refinement_iterations =
      lbfgs(all, evaluations, stats_.refinement_iteration_limit_reached, "refinement", opt_.lbfgs_memory);
  stats_.energy_evaluations = evaluations;
}

// L-BFGS on the rotations of the active tetrahedra, until the energy
// converges (see `energy_tolerance`). Returns the iterations; `evaluations`
// gets the energy evaluations, `limit` whether the iteration bound stopped
// it. `stage` names the iterations for the progress callback (or null);
// `memory` is the number of pairs kept.
template <class Metric_field>
inline int Frame_field_3<Metric_field>::
    lbfgs(const Active_set& set, int& evaluations, bool& limit, const char* stage, int memory) {
  const std::size_t n = set.n;
  evaluations = 0;
  limit = false;
  if (opt_.max_refinement_iterations <= 0 || n == 0) return 0;
  const Sh_vector s0 = octahedral_reference_sh();
  // d^2 E / dw_i^2 ~ 2 (sum of the weights of i) J^T J, and J^T J = (20/3) I.
  std::vector<double> inverse_diagonal(n);
  for (std::size_t k = 0; k < n; ++k) {
    double sum = 0;
    for (int f = 0; f < 4; ++f) sum += e_.links[set.tet(k)].w[f];
    inverse_diagonal[k] = sum > 0 ? 3 / (40 * sum) : 1;
  }
  // The accepted rotations; trial steps are written into q_ and s_.
  std::vector<Eigen::Quaterniond> q_old(n);
  for (std::size_t k = 0; k < n; ++k) q_old[k] = q_[set.tet(k)];
  internal::Lbfgs_settings settings;
  settings.max_iterations = opt_.max_refinement_iterations;
  settings.memory = memory;
  settings.energy_tolerance = opt_.energy_tolerance;
  settings.floor_energy = 1e-14 * std::max(e_.total_weight, 1e-300);
  const internal::Lbfgs_outcome out = internal::lbfgs_on_rotations(
      inverse_diagonal, [&](std::vector<Eigen::Vector3d>& g) { return energy_and_gradient(set, &g); },
      [&](const std::vector<Eigen::Vector3d>& p, double step) {
        // By fours, so that their SH vectors are turned together (oct_apply_lanes()).
        internal::parallel_for_each_index((n + 3) / 4, [&](std::size_t g) {
          internal::Oct_euler_angles a[4];
          const internal::Oct_euler_angles* pa[4];
          const Sh_vector* from[4];
          Sh_vector* to[4];
          int m = 0;
          for (std::size_t k = 4 * g; k < std::min(4 * g + 4, n); ++k, ++m) {
            const std::size_t i = set.tet(k);
            q_[i] = step == 0 ? q_old[k] : (internal::oct_quaternion_exp(step * p[k]) * q_old[k]).normalized();
            a[m] = internal::oct_euler_angles(q_[i]), pa[m] = &a[m], from[m] = &s0, to[m] = &s_[i];
          }
          internal::oct_apply_lanes(m, pa, from, to);
        });
      },
      [&] { internal::parallel_for_each_index(n, [&](std::size_t k) { q_old[k] = q_[set.tet(k)]; }); },
      [&](int it, double E) {
        if (stage && opt_.iteration_progress) opt_.iteration_progress(stage, it, std::ldexp(E, e_.weight_exponent));
      },
      settings);
  evaluations = out.evaluations;
  limit = out.limit;
  if (opt_.hard_boundary) // undo the rounding drift of the constrained axes
    internal::parallel_for_each_index(n, [&](std::size_t k) {
      const std::size_t i = set.tet(k);
      if (e_.constraint_of[i] >= 0 && hard_constraint_held(i)) constrain(i);
    });
  return out.iterations;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_FRAME_FIELD_3_REFINEMENT_H
