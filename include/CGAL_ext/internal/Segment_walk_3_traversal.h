// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEGMENT_WALK_3_TRAVERSAL_H
#define CGAL_EXT_INTERNAL_SEGMENT_WALK_3_TRAVERSAL_H

// The exact general traversal of Segment_walk_3: the walk from simplex to
// simplex through cells, facets, edges and vertices, decided by exact
// predicates only, and the stars of edges and vertices it searches.
//
// Member definitions of Segment_walk_3, included at the end of
// <CGAL_ext/Segment_walk_3.h>; not a header of its own.

namespace CGAL_ext {

// ------------------------------------------------------------------ walk
template <class Triangulation, class Domain_predicate>
template <class S>
inline void Segment_walk_3<Triangulation, Domain_predicate>::
    walk(const Point& q, const Point& p, Simplex start, S& sink) const {
  Ctx x(q, p, max_steps_);
  prepare_fast(x);
  finish(x, start_at(x, start, sink), sink);
}

// The state at q, in the simplex start (or in a gap if start is invalid).
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    start_at(Ctx& x, const Simplex& start, S& sink) const -> Next {
  if (!start.valid()) return gap(x, Simplex(), 0.0, sink);
  Next nx;
  nx.done = false;
  nx.s = start;
  nx.t = 0.0;
  return nx;
}

template <class Triangulation, class Domain_predicate>
template <class S>
inline void Segment_walk_3<Triangulation, Domain_predicate>::finish(Ctx& x, Next nx, S& sink) const {
  while (!nx.done) {
    x.tick();
    nx = from_point(x, nx, sink);
  }
}

// The walk is at x(t) in the relative interior of nx.s (t < 1): emit that
// zero-length piece (unless the segment goes on inside nx.s, which happens
// only at q), find the simplex the segment enters next and traverse it.
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::from_point(Ctx& x, const Next& nx, S& sink) const -> Next {
  const Simplex& s = nx.s;
  const double t = nx.t;
  if (nx.crossed) {
    sink(s, t, t, true);
    int k = 0;
    while (s.mask & (1u << k)) ++k;
    const Cell_handle n = s.c->neighbor(k);
    if (!is_domain_cell(n)) return gap(x, s, t, sink);
    if (x.fast) {
      const std::uint32_t ni = cells_->index(n);
      if (ni != Cell_array::outside) return array_cells(x, ni, n->index(s.c), t, sink);
    }
    return fast_cells(x, n, n->index(s.c), t, sink);
  }
  const Simplex tt = enter(x, s);
  if (!tt.valid()) {
    sink(s, t, t, true);
    return gap(x, s, t, sink);
  }
  if (tt.dimension() != s.dimension()) sink(s, t, t, true);
  switch (tt.dimension()) {
  case 3: return traverse_cell(x, tt.c, t, sink);
  case 2: return traverse_facet(x, tt, t, sink);
  default: return traverse_edge(x, tt, t, sink);
  }
}

// The classic straight walk through cells entered by the interior of a
// facet: two orientation tests choose the exit facet, a third tells
// whether p was reached. A zero falls back on the exact general step.
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    fast_cells(Ctx& x, Cell_handle c, int j, double t_in, S& sink) const -> Next {
  const Point& p = x.p;
  for (;;) {
    x.tick();
    const std::array<int, 3>& f = internal::walk_inner_facet(j);
#if defined(__GNUC__)
    // The walk is bound by memory latency on large meshes: start loading the
    // three possible next cells while the new vertex is loaded and tested.
    __builtin_prefetch(&*c->neighbor(f[0]));
    __builtin_prefetch(&*c->neighbor(f[1]));
    __builtin_prefetch(&*c->neighbor(f[2]));
#endif
    const Point& d = pt(c, j);
    double dq[3];
    diff(d, x.qx, x.qy, x.qz, dq);
    // The segment enters through facet (a, b, cc), which it crosses from the
    // negative to the positive side; the plane (q, p, d) separates its vertices.
    int k = -1;
    const CGAL::Orientation sa = orient_qp(x, dq, d, pt(c, f[0]));
    if (sa == CGAL::POSITIVE) {
      const CGAL::Orientation sb = orient_qp(x, dq, d, pt(c, f[1]));
      if (sb == CGAL::NEGATIVE) k = f[2];
      else if (sb == CGAL::POSITIVE) k = f[0];
    } else if (sa == CGAL::NEGATIVE) {
      const CGAL::Orientation sc = orient_qp(x, dq, d, pt(c, f[2]));
      if (sc == CGAL::POSITIVE) k = f[1];
      else if (sc == CGAL::NEGATIVE) k = f[0];
    }
    if (k < 0) return traverse_cell(x, c, t_in, sink); // through an edge or a vertex
    // Exit facet (a, b, e), ordered so that the cell is on its positive side:
    // p is reached iff orientation(a, b, e, p) >= 0. Its normal also gives t.
    const std::array<int, 3>& g = internal::walk_inner_facet(k);
    const Point &a = pt(c, g[0]), &b = pt(c, g[1]), &e = pt(c, g[2]);
    const double ax = CGAL::to_double(a.x()), ay = CGAL::to_double(a.y()), az = CGAL::to_double(a.z());
    double ba[3], ea[3], pa[3];
    diff(b, ax, ay, az, ba);
    diff(e, ax, ay, az, ea);
    diff(p, ax, ay, az, pa);
    int op = 2;
    if (double_coordinates) op = filtered_det_sign(ba, ea, pa);
    if (op == 2) op = int(orient_(a, b, e, p));
    if (op >= 0) {
      sink(Simplex{c, 15u}, t_in, 1.0, false);
      if (op == 0) sink(Simplex{c, 15u & ~(1u << k)}, 1.0, 1.0, true);
      return Next();
    }
    const Simplex fct{c, 15u & ~(1u << k)};
    double xa[3], xb[3], xe[3];
    coords(a, xa);
    coords(b, xb);
    coords(e, xe);
    const double t_out = internal::walk_exit_parameter(facet_crossing_t(x, fct, xa, xb, xe), t_in);
    sink(Simplex{c, 15u}, t_in, t_out, false);
    const Cell_handle n = c->neighbor(k);
    if (!is_domain_cell(n)) return Next{false, fct, t_out, true};
    sink(fct, t_out, t_out, true);
    j = n->index(c);
    c = n;
    t_in = t_out;
  }
}

// Exact general traversal of the open cell c, entered at parameter t_in.
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    traverse_cell(Ctx& x, Cell_handle c, double t_in, S& sink) const -> Next {
  CGAL::Orientation o[4];
  bool inside = true, closed = true;
  for (int i = 0; i < 4; ++i) {
    o[i] = orient_x(c, i, x.p);
    if (o[i] != CGAL::POSITIVE) inside = false;
    if (o[i] == CGAL::NEGATIVE) closed = false;
  }
  if (closed) {
    sink(Simplex{c, 15u}, t_in, 1.0, false);
    if (!inside) {
      unsigned m = 0;
      for (int i = 0; i < 4; ++i)
        if (o[i] == CGAL::POSITIVE) m |= 1u << i;
      sink(Simplex{c, m}, 1.0, 1.0, true);
    }
    return Next();
  }
  // p is beyond the exit point B. The facets through B are those beyond
  // which p lies and that the line meets; the line meets the facet at the
  // entry point only if p is on its inner side.
  unsigned exits = 0, negative = 0;
  for (int i = 0; i < 4; ++i)
    if (o[i] == CGAL::NEGATIVE) negative |= 1u << i;
  // B lies on at least one facet beyond which p lies: if there is only one,
  // it is the exit facet and B is in its interior.
  if (internal::walk_popcount(negative) == 1) {
    exits = negative;
  } else {
    // Otherwise B is on the facets of negative that the line meets.
    for (int i = 0; i < 4; ++i) {
      if (o[i] != CGAL::NEGATIVE) continue;
      const std::array<int, 3>& f = internal::walk_inner_facet(i);
      const CGAL::Orientation s1 = orient4(x.q, x.p, pt(c, f[0]), pt(c, f[1]));
      const CGAL::Orientation s2 = orient4(x.q, x.p, pt(c, f[1]), pt(c, f[2]));
      const CGAL::Orientation s3 = orient4(x.q, x.p, pt(c, f[2]), pt(c, f[0]));
      const bool nonneg = s1 != CGAL::NEGATIVE && s2 != CGAL::NEGATIVE && s3 != CGAL::NEGATIVE;
      const bool nonpos = s1 != CGAL::POSITIVE && s2 != CGAL::POSITIVE && s3 != CGAL::POSITIVE;
      if ((nonneg || nonpos) && !(nonneg && nonpos)) exits |= 1u << i;
    }
  }
  if (exits == 0 || exits == 15u) throw_inconsistent(x, "no exit from a cell");
  const Simplex f{c, 15u & ~exits};
  const double t_out = t_of(x, f, t_in);
  sink(Simplex{c, 15u}, t_in, t_out, false);
  return Next{false, f, t_out, internal::walk_popcount(exits) == 1};
}

// Traversal of the open facet s (the segment lies in its plane).
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    traverse_facet(Ctx& x, const Simplex& s, double t_in, S& sink) const -> Next {
  int v[3];
  s.vertices(v);
  const Cell_handle c = s.c;
  // w[i] > 0 iff p is strictly on the side of vertex v[i] of the opposite edge
  CGAL::Orientation w[3];
  bool inside = true, closed = true;
  for (int i = 0; i < 3; ++i) {
    w[i] = coplanar_orient_(pt(c, v[(i + 1) % 3]), pt(c, v[(i + 2) % 3]), pt(c, v[i]), x.p);
    if (w[i] != CGAL::POSITIVE) inside = false;
    if (w[i] == CGAL::NEGATIVE) closed = false;
  }
  if (closed) {
    sink(s, t_in, 1.0, false);
    if (!inside) {
      unsigned m = 0;
      for (int i = 0; i < 3; ++i)
        if (w[i] == CGAL::POSITIVE) m |= 1u << v[i];
      sink(Simplex{c, m}, 1.0, 1.0, true);
    }
    return Next();
  }
  unsigned m = s.mask;
  CGAL::Orientation side[3];
  for (int i = 0; i < 3; ++i) side[i] = coplanar_orient_(x.q, x.p, pt(c, v[i]));
  for (int i = 0; i < 3; ++i) {
    if (w[i] != CGAL::NEGATIVE) continue;
    const CGAL::Orientation a = side[(i + 1) % 3], b = side[(i + 2) % 3];
    if (a == CGAL::ZERO || b == CGAL::ZERO || a != b) m &= ~(1u << v[i]);
  }
  if (m == s.mask || m == 0) throw_inconsistent(x, "no exit from a facet");
  const Simplex f{c, m};
  const double t_out = t_of(x, f, t_in);
  sink(s, t_in, t_out, false);
  return Next{false, f, t_out, false};
}

// Traversal of the open edge s (the segment runs along it).
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    traverse_edge(Ctx& x, const Simplex& s, double t_in, S& sink) const -> Next {
  int v[2];
  s.vertices(v);
  const Point &a = pt(s.c, v[0]), &b = pt(s.c, v[1]);
  if (strictly_ordered_(a, x.p, b)) {
    sink(s, t_in, 1.0, false);
    return Next();
  }
  if (x.p == a || x.p == b) {
    sink(s, t_in, 1.0, false);
    sink(Simplex{s.c, 1u << (x.p == a ? v[0] : v[1])}, 1.0, 1.0, true);
    return Next();
  }
  const int e = strictly_ordered_(b, a, x.p) ? v[0] : v[1];
  const Simplex f{s.c, 1u << e};
  const double t_out = t_of(x, f, t_in);
  sink(s, t_in, t_out, false);
  return Next{false, f, t_out, false};
}

template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::throw_inconsistent(const Ctx& x, const char* what) const {
  std::ostringstream os;
  os.precision(17);
  os << "Segment_walk_3: inconsistent predicates (" << what << ") on the segment (" << x.q << ") -> (" << x.p
     << "); the triangulation is probably not valid";
  throw std::logic_error(os.str());
}

// ------------------------------------------------------------------ star
// The simplex the segment enters just after x(t), a point of the relative
// interior of s (x(t) != p): for each domain cell C around s, the facets of
// C through s on which p lies contain the simplex entered, and p strictly
// inside the others means the segment enters C's face spanned by s and
// their opposite vertices. Invalid if the segment leaves the domain.
template <class Triangulation, class Domain_predicate>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::enter(Ctx& x, const Simplex& s) const -> Simplex {
  if (s.mask == 15u) return s;
  Vertex_handle sv[3];
  int ns = 0;
  for (int i = 0; i < 4; ++i)
    if (s.mask & (1u << i)) sv[ns++] = s.c->vertex(i);
  Simplex result;
  auto try_cell = [&](Cell_handle cc) -> bool {
    x.tick();
    if (!is_domain_cell(cc)) return false;
    unsigned m = 0;
    for (int k = 0; k < ns; ++k) m |= 1u << cc->index(sv[k]);
    unsigned tm = m;
    for (int i = 0; i < 4; ++i) {
      if (m & (1u << i)) continue;
      const CGAL::Orientation o = orient_x(cc, i, x.p);
      if (o == CGAL::NEGATIVE) return false;
      if (o == CGAL::POSITIVE) tm |= 1u << i;
    }
    result = Simplex{cc, tm};
    return true;
  };
  if (ns == 3) {
    int k = 0;
    while (s.mask & (1u << k)) ++k;
    if (!try_cell(s.c)) try_cell(s.c->neighbor(k));
  } else if (ns == 2) {
    for_each_edge_cell(x, s.c, sv[0], sv[1], try_cell);
  } else {
    for_each_vertex_cell(x, s.c, sv[0], try_cell);
  }
  return result;
}

// Cells around the edge (a, b) of c, by circulation (stops when f returns true).
template <class Triangulation, class Domain_predicate>
template <class F>
inline void Segment_walk_3<Triangulation, Domain_predicate>::
    for_each_edge_cell(Ctx& x, Cell_handle c, Vertex_handle a, Vertex_handle b, F& f) const {
  if (f(c)) return;
  const int ia = c->index(a), ib = c->index(b);
  int k = 0;
  while (k == ia || k == ib) ++k;
  Cell_handle prev = c, cur = c->neighbor(k);
  while (cur != c) {
    x.tick();
    if (f(cur)) return;
    const int ja = cur->index(a), jb = cur->index(b), jp = cur->index(prev);
    const int l = 6 - ja - jb - jp;
    prev = cur;
    cur = cur->neighbor(l);
  }
}

// Cells around the vertex v of c: search through the facets containing v,
// from c and from one cell of every other component of the star.
template <class Triangulation, class Domain_predicate>
template <class F>
inline void Segment_walk_3<Triangulation, Domain_predicate>::
    for_each_vertex_cell(Ctx& x, Cell_handle c, Vertex_handle v, F& f) const {
  ensure_boundary();
  x.visited.clear();
  x.stack.clear();
  auto push = [&](Cell_handle cc) {
    if (std::find(x.visited.begin(), x.visited.end(), cc) != x.visited.end()) return;
    x.visited.push_back(cc);
    x.stack.push_back(cc);
  };
  push(c);
  const auto seeds = shared_->vertex_seeds.find(&*v);
  if (seeds != shared_->vertex_seeds.end())
    for (Cell_handle sc : seeds->second) push(sc);
  while (!x.stack.empty()) {
    const Cell_handle cur = x.stack.back();
    x.stack.pop_back();
    if (f(cur)) return;
    const int iv = cur->index(v);
    for (int i = 0; i < 4; ++i)
      if (i != iv) push(cur->neighbor(i));
  }
}

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEGMENT_WALK_3_TRAVERSAL_H
