// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEGMENT_WALK_3_CELL_ARRAY_WALK_H
#define CGAL_EXT_INTERNAL_SEGMENT_WALK_3_CELL_ARRAY_WALK_H

// The generic step again, on the cell array, with each vertex turned once
// into Pluecker-style data relative to the segment line L = q + t D:
//   w = v - q,  u = D x w,  rho = (v - p) . D.
// Then pi(a, b) = u_a . (b - a) = det[D, a - q, b - q] has the sign of
// orientation(q, p, a, b), so the exit facet costs three dot products
// (and one cross product per new vertex, off the critical path). The
// edge b - a is taken from the coordinates, not as w_b - w_a: far from q,
// u_a . w_b loses about (|w| / edge length)^2 of relative precision to
// cancellation, u_a . (b - a) only |w| / edge length, which keeps the
// parameters below accurate to a few ulps. For a facet (g0, g1, g2) with the cell
// on its positive side crossed outwards, mu_i = -pi(g_{i+1}, g_{i+2}) are
// the barycentric weights of the crossing point X (S = sum mu_i > 0), and
//   G = sum mu_i rho_i = |D|^2 det[g1 - g0, g2 - g0, p - g0]
// (a polynomial identity), so sign(G) = orientation(g0, g1, g2, p) tells
// whether p was reached, and t = 1 + G / (S |D|^2). Every sign is
// certified by a static error bound for the whole segment (E, Er, derived
// like CGAL's static filters from bounds on the coordinate differences,
// with a safety factor of about 2), else the exact predicate decides.
// Each weight also carries a bound on its own error, for the exit
// parameter (see array_exit_t).
// The weights need no new products: entering a cell through facet
// (f0, f1, f2) with weights mu_f, the new vertex d and the signs
// v_i = pi(d, f_i) choose the exit facet, say (d, f_a, f_b), whose weights
// are |v_b| for f_a, |v_a| for f_b and, for d, the old weight of the vertex
// left behind (each the |pi| of the edge opposite the vertex). Each value
// is still within E of its exact counterpart.
//
// Member definitions of Segment_walk_3, included at the end of
// <CGAL_ext/Segment_walk_3.h>; not a header of its own.

namespace CGAL_ext {

// Sets x.fast and the error bounds; false if the bounds cannot be used
// (no cell array, or coordinates so small or large that products could
// underflow or overflow).
template <class Triangulation, class Domain_predicate>
inline bool Segment_walk_3<Triangulation, Domain_predicate>::prepare_fast(Ctx& x) const {
  x.fast = false;
  if (!cells_) return false;
  const double q[3] = {x.qx, x.qy, x.qz}, p[3] = {x.px, x.py, x.pz}, d[3] = {x.dx, x.dy, x.dz};
  double m[3], mp[3];
  for (int i = 0; i < 3; ++i) {
    // Rounding is monotone: |fl(v - q)| <= max(fl(hi - q), fl(q - lo)) for every vertex v.
    m[i] = std::max(std::max(cells_->hi[i] - q[i], q[i] - cells_->lo[i]), std::fabs(d[i]));
    mp[i] = std::max(cells_->hi[i] - p[i], p[i] - cells_->lo[i]);
    if (!(m[i] >= 1e-50 && m[i] <= 1e50 && mp[i] <= 1e50)) return false;
    mp[i] = std::max(mp[i], 1e-50);
  }
  // t = 1 + G / (S |D|^2) has S |D|^2 of the order of |D|^3 |v - q|^2: a
  // segment shorter than 1e-50 is left to the general path, whose
  // parameters do not underflow.
  if (!(x.dd >= 1e-100)) return false;
  // det of three rows of rounded differences: 6 terms of at most m0 m1 m2,
  // about 8 roundings each: < 5.4e-15 m0 m1 m2. pi(a, b): at most 8
  // roundings per term, sum_i (|d_j| |w_k| + |d_k| |w_j|) |e_i| with
  // |e_i| <= 2 m_i: < 8.1 u 12 m0 m1 m2 < 1.08e-14 m0 m1 m2. A dot of a
  // rounded difference with D: < 5.1 u sum mp_i |d_i|.
  x.E = 2e-14 * m[0] * m[1] * m[2];
  x.emu = 8.1 * 0x1p-53 * x.dinf;
  x.Er = 1e-15 * (mp[0] * std::fabs(d[0]) + mp[1] * std::fabs(d[1]) + mp[2] * std::fabs(d[2]));
  x.fast = true;
  return true;
}

// x and w = x - q of a vertex at a.
template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::set_position(const Ctx& x, const double* a, Vertex_data& v) {
  v.x[0] = a[0];
  v.x[1] = a[1];
  v.x[2] = a[2];
  v.w[0] = a[0] - x.qx;
  v.w[1] = a[1] - x.qy;
  v.w[2] = a[2] - x.qz;
}

template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::
    load_vertex(const Ctx& x, const double* a, Vertex_data& v) {
  set_position(x, a, v);
  finish_vertex(x, a, v);
}

// u, rho and n1 from w.
template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::
    finish_vertex(const Ctx& x, const double* a, Vertex_data& v) {
  v.n1 = std::fabs(v.w[0]) + std::fabs(v.w[1]) + std::fabs(v.w[2]);
  v.u[0] = x.dy * v.w[2] - x.dz * v.w[1];
  v.u[1] = x.dz * v.w[0] - x.dx * v.w[2];
  v.u[2] = x.dx * v.w[1] - x.dy * v.w[0];
  v.rho = (a[0] - x.px) * x.dx + (a[1] - x.py) * x.dy + (a[2] - x.pz) * x.dz;
}

// det[D, a - q, b - q] in double, as u_a . (b - a); within
// x.emu |a - q|_1 |b - a|_1 of its exact value.
template <class Triangulation, class Domain_predicate>
inline double Segment_walk_3<Triangulation, Domain_predicate>::pi(const Vertex_data& a, const Vertex_data& b) {
  return a.u[0] * (b.x[0] - a.x[0]) + a.u[1] * (b.x[1] - a.x[1]) + a.u[2] * (b.x[2] - a.x[2]);
}

template <class Triangulation, class Domain_predicate>
inline double Segment_walk_3<Triangulation, Domain_predicate>::edge_l1(const Vertex_data& a, const Vertex_data& b) {
  return std::fabs(b.x[0] - a.x[0]) + std::fabs(b.x[1] - a.x[1]) + std::fabs(b.x[2] - a.x[2]);
}

// Sign of orientation(q, p, a, b), given its value v in double.
template <class Triangulation, class Domain_predicate>
inline CGAL::
    Orientation Segment_walk_3<Triangulation, Domain_predicate>::side(const Ctx& x, double v, std::int32_t a,
        std::int32_t b) const {
  if (v > x.E) return CGAL::POSITIVE;
  if (v < -x.E) return CGAL::NEGATIVE;
  return orient4(x.q, x.p, array_point(a), array_point(b));
}

// Starts in record ci if q is certified strictly inside it and the line
// certified to leave it through the interior of a facet; otherwise
// returns false without output (the general path then starts over).
// The vertices are read through the cell handle c (the cell of record
// ci), so that loading them overlaps with the look-up of the record.
template <class Triangulation, class Domain_predicate>
template <class S>
inline bool Segment_walk_3<Triangulation, Domain_predicate>::
    array_start(Ctx& x, Cell_handle c, std::uint32_t ci, Next& nx, S& sink) const {
  Array_state st;
  int k;
  if (!array_enter(x, c, ci, st, k)) return false;
  nx = array_loop(x, st, ci, k, true, 0.0, sink);
  return true;
}

// The set-up of array_start: the vertex data and the exit facet k.
// The vertices come from the triangulation's cell c, or (if c is null)
// from the record.
template <class Triangulation, class Domain_predicate>
inline bool Segment_walk_3<Triangulation, Domain_predicate>::
    array_enter(Ctx& x, Cell_handle c, std::uint32_t ci, Array_state& st, int& k) const {
  if (c != Cell_handle()) {
#if defined(__GNUC__)
    __builtin_prefetch(&cells_->records[ci]);
#endif
    for (int l = 0; l < 4; ++l) {
      const Point& a = pt(c, l);
      const double xyz[3] = {CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z())};
      load_vertex(x, xyz, st.pool[l]);
    }
  } else {
    for (int l = 0; l < 4; ++l) load_vertex(x, cells_->records[ci].v[l], st.pool[l]);
  }
  const Vertex_data* P = st.pool;
  // q strictly inside: orientation(g0, g1, g2, q) = -sign det[g0 - q, g1 - q, g2 - q] > 0.
  for (int i = 0; i < 4; ++i) {
    const std::array<int, 3>& g = internal::walk_inner_facet(i);
    const double* a = P[g[0]].w;
    const double *b = P[g[1]].w, *c = P[g[2]].w;
    const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    if (!(det < -x.E)) return false;
  }
  k = -1;
  for (int i = 0; i < 4 && k < 0; ++i) {
    const std::array<int, 3>& g = internal::walk_inner_facet(i);
    const double m0 = -pi(P[g[1]], P[g[2]]), m1 = -pi(P[g[2]], P[g[0]]), m2 = -pi(P[g[0]], P[g[1]]);
    if (m0 > x.E && m1 > x.E && m2 > x.E) {
      k = i;
      st.pool[g[0]].mu = m0;
      st.pool[g[1]].mu = m1;
      st.pool[g[2]].mu = m2;
      st.pool[g[0]].el = edge_l1(P[g[1]], P[g[2]]);
      st.pool[g[1]].el = edge_l1(P[g[2]], P[g[0]]);
      st.pool[g[2]].el = edge_l1(P[g[0]], P[g[1]]);
    }
  }
  return k >= 0;
}

// Entered record ci through the interior of its facet j at t_in.
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    array_cells(Ctx& x, std::uint32_t ci, int j, double t_in, S& sink) const -> Next {
  const typename Cell_array::Record& r = cells_->records[ci];
  Array_state st;
  for (int l = 0; l < 4; ++l) {
    if (l != j) load_vertex(x, r.v[l], st.pool[l]);
  }
  // Weights of the entry crossing (the cell on the positive side of the
  // inner facet, entered from its negative side: the pi are >= 0).
  const std::array<int, 3>& f = internal::walk_inner_facet(j);
  Vertex_data* P = st.pool;
  P[f[0]].mu = std::fabs(pi(P[f[1]], P[f[2]]));
  P[f[1]].mu = std::fabs(pi(P[f[2]], P[f[0]]));
  P[f[2]].mu = std::fabs(pi(P[f[0]], P[f[1]]));
  P[f[0]].el = edge_l1(P[f[1]], P[f[2]]);
  P[f[1]].el = edge_l1(P[f[2]], P[f[0]]);
  P[f[2]].el = edge_l1(P[f[0]], P[f[1]]);
  return array_loop(x, st, ci, j, false, t_in, sink);
}

// The loop, one segment at a time.
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    array_loop(Ctx& x, Array_state& st, std::uint32_t ci, int j, bool have_exit, double t_in, S& sink) const -> Next {
  Array_position cur{&cells_->records[ci], ci, j, have_exit, t_in};
  Next nx;
  while (array_step(x, st, cur, nx, sink)) {
  }
  return nx;
}

// One step of the loop: the pieces of the current cell, then either the
// move to the next record (true) or the end of the loop, with nx (false).
template <class Triangulation, class Domain_predicate>
template <class S>
inline bool Segment_walk_3<Triangulation, Domain_predicate>::
    array_step(Ctx& x, Array_state& st, Array_position& cur, Next& nx, S& sink) const {
  const typename Cell_array::Record* r = cur.r;
  const std::uint32_t ci = cur.ci;
  const double t_in = cur.t_in;
  x.tick();
  int k = cur.j;
  Exit_sums e;
  if (!cur.have_exit) {
    if (!array_choose_exit(x, st, cur, k, e, nx, sink)) return false;
  } else {
    exit_sums(st, k, e);
  }
  // Exit facet (g0, g1, g2), the cell on its positive side.
  const std::array<int, 3>& g = internal::walk_inner_facet(k);
  // |G~ - G| <= sum E |rho~| + (|mu~| + E) Er + 3.5 u |mu~ rho~| (see above), plus a floor for underflow.
  const double err = 1.01 * (x.E * e.sum_rho + x.Er * (e.sum_mu + 3 * x.E) + 4e-16 * e.sum_mu_rho) + 1e-300;
  int op = e.G > err ? 1 : e.G < -err ? -1 : 2;
  if (op == 2) op = int(orient4(array_point(r->v[g[0]]), array_point(r->v[g[1]]), array_point(r->v[g[2]]), x.p));
  if (op >= 0) {
    sink(ci, 15u, t_in, 1.0, false);
    if (op == 0) sink(ci, 15u & ~(1u << k), 1.0, 1.0, true);
    nx = Next();
    return false;
  }
  double t_out = 1.0 + e.G / (e.sum_mu * x.dd);
  if (!array_exit_certified(x, t_out, e.sum_mu, e.sum_mu_rho, e.rho_range, e.max_n1, e.sum_el))
    t_out = array_exit_t(x, ci, k);
  t_out = internal::walk_exit_parameter(t_out, t_in);
  sink(ci, 15u, t_in, t_out, false);
  if (r->n[k] == Cell_array::outside) {
    nx = Next{false, Simplex{cells_->cell_handles[ci], 15u & ~(1u << k)}, t_out, true};
    return false;
  }
  sink(ci, 15u & ~(1u << k), t_out, t_out, true);
  array_move(st, cur, k, t_out);
  return true;
}

// The first part of a step entered through facet j = cur.j: the new vertex
// d, the exit facet k and the sums over it. False if the segment leaves
// through an edge or a vertex: the exact traversal then took over (nx).
template <class Triangulation, class Domain_predicate>
template <class S>
CGAL_EXT_WALK_INLINE bool Segment_walk_3<Triangulation, Domain_predicate>::
    array_choose_exit(Ctx& x, Array_state& st, const Array_position& cur, int& k, Exit_sums& sums, Next& nx,
                      S& sink) const {
  const typename Cell_array::Record* r = cur.r;
  const int j = cur.j;
  const std::array<int, 3>& f = internal::walk_inner_facet(j);
  Vertex_data& d = st.at(j);
  const Vertex_data& A = st.at(f[0]);
  const Vertex_data& B = st.at(f[1]);
  const Vertex_data& C = st.at(f[2]);
  const double* xyz = cells_->point(r->v[j]);
  set_position(x, xyz, d);
  // v_i = pi(d, f_i) = -pi(f_i, d): the u of the entry vertices are
  // known, so the cross product of d is off the critical path.
  const double v[3] = {-pi(A, d), -pi(B, d), -pi(C, d)};
  const double el_new[3] = {edge_l1(A, d), edge_l1(B, d), edge_l1(C, d)};
  finish_vertex(x, xyz, d);
  // The segment enters through facet (f0, f1, f2) from its negative
  // side; the plane (q, p, d) separates its vertices. With the three
  // signs certified, the exit is chosen without a branch (the choice
  // is random for the branch predictor); otherwise exact signs decide.
  int e = -1; // position in f of the vertex left behind
  if (std::min(std::fabs(v[0]), std::min(std::fabs(v[1]), std::fabs(v[2]))) > x.E) {
    // v0 > 0: v1 < 0 -> f2, v1 > 0 -> f0; v0 < 0: v2 > 0 -> f1, v2 < 0 -> f0
    const unsigned code = unsigned(v[0] > 0) | unsigned(v[1] > 0) << 1 | unsigned(v[2] > 0) << 2;
    e = int((0x01210020u >> (4 * code)) & 3u);
  } else {
    const CGAL::Orientation sa = side(x, v[0], r->v[j], r->v[f[0]]);
    if (sa == CGAL::POSITIVE) {
      const CGAL::Orientation sb = side(x, v[1], r->v[j], r->v[f[1]]);
      if (sb == CGAL::NEGATIVE) e = 2;
      else if (sb == CGAL::POSITIVE) e = 0;
    } else if (sa == CGAL::NEGATIVE) {
      const CGAL::Orientation sc = side(x, v[2], r->v[j], r->v[f[2]]);
      if (sc == CGAL::POSITIVE) e = 1;
      else if (sc == CGAL::NEGATIVE) e = 0;
    }
    if (e < 0) { // through an edge or a vertex
      nx = traverse_cell(x, cells_->cell_handles[cur.ci], cur.t_in, sink);
      return false;
    }
  }
  // Selections by index arithmetic: compilers turn conditional
  // expressions here into branches, which the random exit mispredicts.
  k = f[e];
  const int ia = int(e == 0), ib = 2 - int(e == 2); // positions of the two vertices kept
  const int pos[3] = {st.slot(f[0]), st.slot(f[1]), st.slot(f[2])};
  // The exit facet is d and the two entry vertices kept, the kept ones
  // with the weights |v| of each other's positions: the sums for each
  // of the three possible exits are formed while the exit is being
  // chosen, and the exit picks one (reading them back from the pool,
  // just written at positions that depend on the exit, would wait).
  const double av[3] = {std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])};
  const double rh[3] = {A.rho, B.rho, C.rho}, ar[3] = {std::fabs(A.rho), std::fabs(B.rho), std::fabs(C.rho)};
  const double mu_in[3] = {A.mu, B.mu, C.mu};
  const double kept_g[3] = {av[2] * rh[1] + av[1] * rh[2], av[2] * rh[0] + av[0] * rh[2], av[1] * rh[0] + av[0] * rh[1]};
  const double kept_mu[3] = {av[1] + av[2], av[0] + av[2], av[0] + av[1]};
  const double kept_rho[3] = {ar[1] + ar[2], ar[0] + ar[2], ar[0] + ar[1]};
  const double kept_mu_rho[3] = {av[2] * ar[1] + av[1] * ar[2], av[2] * ar[0] + av[0] * ar[2], av[1] * ar[0] + av[0] * ar[1]};
  const double md = mu_in[e];
  sums.G = md * d.rho + kept_g[e];
  sums.sum_mu = md + kept_mu[e];
  sums.sum_rho = std::fabs(d.rho) + kept_rho[e];
  sums.sum_mu_rho = md * std::fabs(d.rho) + kept_mu_rho[e];
  sums.rho_range = std::max(d.rho, std::max(rh[ia], rh[ib])) - std::min(d.rho, std::min(rh[ia], rh[ib]));
  const double n1_in[3] = {A.n1, B.n1, C.n1}, el_in[3] = {A.el, B.el, C.el};
  sums.max_n1 = std::max(d.n1, std::max(n1_in[ia], n1_in[ib]));
  sums.sum_el = el_in[e] + el_new[ia] + el_new[ib];
  d.mu = md;
  d.el = el_in[e];
  st.pool[pos[ia]].mu = av[ib];
  st.pool[pos[ib]].mu = av[ia];
  st.pool[pos[ia]].el = el_new[ib];
  st.pool[pos[ib]].el = el_new[ia];
  return true;
}

// The sums over the exit facet k when it was chosen before the step (at the
// start of a query): every weight is in the pool already.
template <class Triangulation, class Domain_predicate>
CGAL_EXT_WALK_INLINE void Segment_walk_3<Triangulation, Domain_predicate>::exit_sums(const Array_state& st, int k, Exit_sums& e) {
  const std::array<int, 3>& g = internal::walk_inner_facet(k);
  const Vertex_data &a = st.pool[st.slot(g[0])], &b = st.pool[st.slot(g[1])], &c = st.pool[st.slot(g[2])];
  e.G = a.mu * a.rho + b.mu * b.rho + c.mu * c.rho;
  e.sum_mu = a.mu + b.mu + c.mu;
  e.sum_rho = std::fabs(a.rho) + std::fabs(b.rho) + std::fabs(c.rho);
  e.sum_mu_rho = a.mu * std::fabs(a.rho) + b.mu * std::fabs(b.rho) + c.mu * std::fabs(c.rho);
  e.rho_range = std::max(a.rho, std::max(b.rho, c.rho)) - std::min(a.rho, std::min(b.rho, c.rho));
  e.max_n1 = std::max(a.n1, std::max(b.n1, c.n1));
  e.sum_el = a.el + b.el + c.el;
}

// The move across the exit facet k, at t_out, to the neighbour n; its vertex
// opposite the shared facet takes the pool entry of the vertex k left behind.
template <class Triangulation, class Domain_predicate>
CGAL_EXT_WALK_INLINE void Segment_walk_3<Triangulation, Domain_predicate>::
    array_move(Array_state& st, Array_position& cur, int k, double t_out) const {
  const auto& recs = cells_->records;
  const typename Cell_array::Record* r = cur.r;
  const std::array<int, 3>& g = internal::walk_inner_facet(k);
  const std::uint32_t link = r->n[k];
  const std::uint32_t ni = link >> 2;
  const int m = int(link & 3u);
  const typename Cell_array::Record* rn = &recs[ni];
  // One comparison finds how the shared facet is rotated between the two
  // cells (see walk_facet_map); without a branch, for the same reason.
  const std::int32_t id0 = rn->v[internal::walk_inner_facet(m)[0]];
  const unsigned rho = unsigned(r->v[g[1]] == id0) + 2u * unsigned(r->v[g[2]] == id0);
  const unsigned map = internal::walk_facet_map[std::size_t((4 * k + m) * 3) + rho];
  unsigned slots = 0;
  for (int i = 0; i < 4; ++i) slots |= ((st.slots >> (2 * ((map >> (2 * i)) & 3u))) & 3u) << (2 * i);
  st.slots = slots;
#if defined(__GNUC__)
  // Start loading the possible next records while this one is processed
  // (all four, without a branch: the one back is in cache anyway).
  for (int i = 0; i < 4; ++i) __builtin_prefetch(&recs[rn->n[i] == Cell_array::outside ? ni : rn->n[i] >> 2]);
  // and the new vertex of the next step (a batch walk comes back to this
  // segment only after steps of the others: it is loaded by then)
  __builtin_prefetch(cells_->point(rn->v[m]));
#endif
  cur.r = rn;
  cur.ci = ni;
  cur.j = m;
  cur.have_exit = false;
  cur.t_in = t_out;
}

// Whether t = 1 + G / (S |D|^2), the exit parameter from the weights, is
// certified within the tolerance. With r_i = rho_i / |D|^2,
// t - 1 = sum lambda_i r_i, lambda_i = mu_i / S. Weights off by delta_i
// (sum |delta_i| <= Delta) give lambda~ with sum |lambda~_i - lambda_i| <=
// 2 Delta / S~ and sum (lambda~ - lambda) = 0, so an error of at most
// 2 Delta / S~ (max r - min r); each rho is off by at most
// 5.1 u |v - p|_1 |D|_inf <= 5.1 u (|w|_1 + |D|_1) |D|_inf; G's own rounding
// is below 3.1 u sum mu |rho|, and S, |D|^2, the division and the sum with
// 1 add below 10 u. Multiplied by S |D|^2 (with Delta <= S / 100, so that
// the range of the rounded rho serves):
//   2.02 Delta range + 5.5 u (max |w|_1 + |D|_1) |D|_inf S + 3.1 u sum mu|rho| + 10 u S |D|^2
// against 1.9e-13 S |D|^2. Each weight pi(a, b) is within emu |w_a|_1 |b - a|_1
// of its exact value, so Delta <= emu max |w|_1 sum |b - a|_1 over the
// facet (the sums of absolute values within (1 + 2 u)).
template <class Triangulation, class Domain_predicate>
inline bool Segment_walk_3<Triangulation, Domain_predicate>::
    array_exit_certified(const Ctx& x, double t, double sum_mu, double sum_mu_rho, double rho_range, double max_n1,
        double sum_el) {
  constexpr double u = 0x1p-53;
  const double den = sum_mu * x.dd;
  const double Delta = x.emu * (1 + 5 * u) * max_n1 * sum_el;
  return certified_before_end(std::isnormal(den) && Delta <= 0.01 * sum_mu &&
                                  2.02 * Delta * rho_range + 5.5 * u * (max_n1 + x.d1) * x.dinf * sum_mu +
                                          3.1 * u * sum_mu_rho + 10 * u * den <=
                                      1.9e-13 * den,
                              t);
}

// Otherwise (a segment nearly in the facet's plane, or much shorter than
// the cell): the normal form, then interval and exact arithmetic. Out of
// line, since rarely needed.
template <class Triangulation, class Domain_predicate>
double Segment_walk_3<Triangulation, Domain_predicate>::array_exit_t(const Ctx& x, std::uint32_t ci, int k) const {
  const std::array<int, 3>& g = internal::walk_inner_facet(k);
  const typename Cell_array::Record& r = cells_->records[ci];
  const double q[3] = {x.qx, x.qy, x.qz}, d[3] = {x.dx, x.dy, x.dz};
  double t2 = 0;
  if (certified_before_end(internal::walk_plane_parameter(q, d, cells_->point(r.v[g[0]]), cells_->point(r.v[g[1]]),
                                                          cells_->point(r.v[g[2]]), t2), t2))
    return t2;
  return crossing_t(x, Simplex{cells_->cell_handles[ci], 15u & ~(1u << k)});
}

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEGMENT_WALK_3_CELL_ARRAY_WALK_H
