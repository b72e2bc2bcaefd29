// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEGMENT_WALK_3_GAP_SEARCH_H
#define CGAL_EXT_INTERNAL_SEGMENT_WALK_3_GAP_SEARCH_H

// The gap search of Segment_walk_3: where a segment that left the domain
// re-enters it, from the boundary facets (an AABB tree, built lazily) and
// exact rational parameters.
//
// Member definitions of Segment_walk_3, included at the end of
// <CGAL_ext/Segment_walk_3.h>; not a header of its own.

namespace CGAL_ext {

// ------------------------------------------------------------------- gap
template <class Triangulation, class Domain_predicate>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::ek(const Point& a) const -> EPoint {
  return EPoint(CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z()));
}

// Exact parameter of the point where the segment meets face s (not along it).
template <class Triangulation, class Domain_predicate>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::exact_t(const Ctx& x, const Simplex& s) const -> EFT {
  if (!s.valid()) return EFT(0);
  const EPoint Q = ek(x.q);
  const EVector D = ek(x.p) - Q;
  EPoint v[3];
  int k = 0;
  for (int i = 0; i < 4 && k < 3; ++i)
    if (s.mask & (1u << i)) v[k++] = ek(pt(s.c, i));
  if (k == 1) return ((v[0] - Q) * D) / (D * D);
  if (k == 2) return exact_t_line(Q, D, v[0], v[1]);
  const EVector n = CGAL::cross_product(v[1] - v[0], v[2] - v[0]);
  return (n * (v[0] - Q)) / (n * D);
}

// Parameter of the intersection of the line Q + t D with the coplanar, non-parallel line (a, b).
template <class Triangulation, class Domain_predicate>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    exact_t_line(const EPoint& Q, const EVector& D, const EPoint& a, const EPoint& b) -> EFT {
  const EVector e = b - a;
  const EVector c2 = CGAL::cross_product(D, e);
  return (CGAL::cross_product(a - Q, e) * c2) / (c2 * c2);
}

// Exact parameter of the first point of the line (q, p) in boundary
// triangle i (it may be < 0); false if the line misses it.
template <class Triangulation, class Domain_predicate>
inline bool Segment_walk_3<Triangulation, Domain_predicate>::
    first_t_in_triangle(const Ctx& x, std::size_t i, EFT& t) const {
  const Cell_handle c = shared_->triangle_facets[i].first;
  const std::array<int, 3>& f = internal::walk_inner_facet(shared_->triangle_facets[i].second);
  const Point &a = pt(c, f[0]), &b = pt(c, f[1]), &cc = pt(c, f[2]);
  const EPoint Q = ek(x.q), A = ek(a), B = ek(b), C = ek(cc);
  const EVector D = ek(x.p) - Q;
  const EVector n = CGAL::cross_product(B - A, C - A);
  const EFT nd = n * D;
  if (nd != 0) {
    const CGAL::Orientation s1 = orient_(x.q, x.p, a, b), s2 = orient_(x.q, x.p, b, cc), s3 = orient_(x.q, x.p, cc, a);
    const bool nonneg = s1 != CGAL::NEGATIVE && s2 != CGAL::NEGATIVE && s3 != CGAL::NEGATIVE;
    const bool nonpos = s1 != CGAL::POSITIVE && s2 != CGAL::POSITIVE && s3 != CGAL::POSITIVE;
    if (!nonneg && !nonpos) return false;
    t = (n * (A - Q)) / nd;
    return true;
  }
  if (orient_(a, b, cc, x.q) != CGAL::ZERO) return false;
  // The line lies in the plane of the triangle: smallest parameter over the edges it meets.
  const Point* P[3] = {&a, &b, &cc};
  const EPoint E[3] = {A, B, C};
  CGAL::Orientation sd[3];
  for (int j = 0; j < 3; ++j) sd[j] = coplanar_orient_(x.q, x.p, *P[j]);
  bool found = false;
  auto consider = [&](const EFT& u) {
    if (!found || u < t) t = u;
    found = true;
  };
  for (int j = 0; j < 3; ++j) {
    const int l = (j + 1) % 3;
    if (sd[j] != CGAL::ZERO && sd[j] == sd[l]) continue;
    if (sd[j] == CGAL::ZERO && sd[l] == CGAL::ZERO) {
      consider(((E[j] - Q) * D) / (D * D));
      consider(((E[l] - Q) * D) / (D * D));
    } else {
      consider(exact_t_line(Q, D, E[j], E[l]));
    }
  }
  return found;
}

// The segment leaves the closed domain just after x(t) (t == 0 and s
// invalid: q is outside). Emit the gap up to the next point of the closed
// domain, found among the boundary facets the segment meets.
template <class Triangulation, class Domain_predicate>
template <class S>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    gap(Ctx& x, const Simplex& s, double t, S& sink) const -> Next {
  ensure_boundary();
  if (!x.candidates_ready) {
    x.candidates_ready = true;
    if (!shared_->triangles.empty()) {
      std::vector<Tri_iterator> ids;
      shared_->tree->all_intersected_primitives(typename Kernel::Segment_3(x.q, x.p), std::back_inserter(ids));
      for (const Tri_iterator& it : ids) {
        const std::size_t i = static_cast<std::size_t>(it - shared_->triangles.begin());
        EFT u;
        if (first_t_in_triangle(x, i, u)) x.candidates.emplace_back(u, i);
      }
      std::sort(x.candidates.begin(), x.candidates.end(),
                [](const std::pair<EFT, std::size_t>& a, const std::pair<EFT, std::size_t>& b) { return a.first < b.first; });
    }
  }
  const EFT ts = exact_t(x, s);
  auto it = std::upper_bound(x.candidates.begin(), x.candidates.end(), ts,
                             [](const EFT& v, const std::pair<EFT, std::size_t>& e) { return v < e.first; });
  if (it == x.candidates.end() || it->first > 1) {
    sink(Simplex(), t, 1.0, false);
    return Next();
  }
  const EFT ty = it->first;
  const std::size_t i = it->second;
  // The simplex of the re-entry point: the lowest face of the triangle containing it.
  const Cell_handle c = shared_->triangle_facets[i].first;
  const std::array<int, 3>& f = internal::walk_inner_facet(shared_->triangle_facets[i].second);
  const EPoint Q = ek(x.q);
  const EPoint Y = Q + (ek(x.p) - Q) * ty;
  EPoint V[3];
  for (int j = 0; j < 3; ++j) V[j] = ek(pt(c, f[j]));
  unsigned m = 0;
  for (int j = 0; j < 3 && m == 0; ++j)
    if (Y == V[j]) m = 1u << f[j];
  for (int j = 0; j < 3 && m == 0; ++j)
    if (CGAL::collinear(V[j], V[(j + 1) % 3], Y)) m = (1u << f[j]) | (1u << f[(j + 1) % 3]);
  if (m == 0) m = (1u << f[0]) | (1u << f[1]) | (1u << f[2]);
  const Simplex ns{c, m};
  if (ty == 1) {
    sink(Simplex(), t, 1.0, false);
    sink(ns, 1.0, 1.0, true);
    return Next();
  }
  const double td = internal::walk_exit_parameter(CGAL::to_double(ty), t);
  sink(Simplex(), t, td, false);
  return Next{false, ns, td, false};
}

// Boundary facets, their AABB tree, and the extra seeds of vertex stars.
template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::ensure_boundary() const {
  std::call_once(shared_->boundary_once, [this] {
    Shared& sh = *shared_;
    std::unordered_map<const void*, std::size_t> bindex; // boundary vertex -> slot
    std::vector<Vertex_handle> bverts;
    for (auto c : tr_->finite_cell_handles()) {
      if (!is_domain_cell(c)) continue;
      for (int i = 0; i < 4; ++i) {
        if (is_domain_cell(c->neighbor(i))) continue;
        const std::array<int, 3>& f = internal::walk_inner_facet(i);
        sh.triangles.emplace_back(pt(c, f[0]), pt(c, f[1]), pt(c, f[2]));
        sh.triangle_facets.emplace_back(c, i);
        for (int j : f)
          if (bindex.emplace(&*c->vertex(j), bverts.size()).second) bverts.push_back(c->vertex(j));
      }
    }
    if (!sh.triangles.empty()) {
      sh.tree = std::make_unique<AABB>(sh.triangles.begin(), sh.triangles.end());
      sh.tree->build();
    }
    // Domain cells around each boundary vertex, then their components
    // through facets containing the vertex.
    std::vector<std::vector<Cell_handle>> around(bverts.size());
    for (auto c : tr_->finite_cell_handles()) {
      if (!is_domain_cell(c)) continue;
      for (int i = 0; i < 4; ++i) {
        const auto b = bindex.find(&*c->vertex(i));
        if (b != bindex.end()) around[b->second].push_back(c);
      }
    }
    std::vector<Cell_handle> visited, stack;
    for (std::size_t k = 0; k < bverts.size(); ++k) {
      const Vertex_handle v = bverts[k];
      visited.clear();
      std::vector<Cell_handle> seeds;
      for (Cell_handle start : around[k]) {
        if (std::find(visited.begin(), visited.end(), start) != visited.end()) continue;
        seeds.push_back(start); // one cell per component, the first one included
        visited.push_back(start);
        stack.assign(1, start);
        while (!stack.empty()) {
          const Cell_handle cur = stack.back();
          stack.pop_back();
          const int iv = cur->index(v);
          for (int i = 0; i < 4; ++i) {
            if (i == iv) continue;
            const Cell_handle n = cur->neighbor(i);
            if (std::find(visited.begin(), visited.end(), n) != visited.end()) continue;
            visited.push_back(n);
            stack.push_back(n);
          }
        }
      }
      if (seeds.size() > 1) sh.vertex_seeds.emplace(&*v, std::move(seeds));
    }
  });
}

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEGMENT_WALK_3_GAP_SEARCH_H
