// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEGMENT_WALK_3_PREDICATES_H
#define CGAL_EXT_INTERNAL_SEGMENT_WALK_3_PREDICATES_H

// The orientation tests of Segment_walk_3 (a semi-static filter in front of
// the kernel's exact predicates) and its crossing parameters, each within
// internal::walk_crossing_tolerance of its exact value.
//
// Member definitions of Segment_walk_3, included at the end of
// <CGAL_ext/Segment_walk_3.h>; not a header of its own.

namespace CGAL_ext {

// Orientation of cell c with vertex i replaced by x: positive iff x is
// strictly on the same side of facet i as vertex i.
template <class Triangulation, class Domain_predicate>
inline CGAL::
    Orientation Segment_walk_3<Triangulation, Domain_predicate>::orient_x(Cell_handle c, int i, const Point& x) const {
  switch (i) {
  case 0: return orient4(x, pt(c, 1), pt(c, 2), pt(c, 3));
  case 1: return orient4(pt(c, 0), x, pt(c, 2), pt(c, 3));
  case 2: return orient4(pt(c, 0), pt(c, 1), x, pt(c, 3));
  default: return orient4(pt(c, 0), pt(c, 1), pt(c, 2), x);
  }
}

// orientation(a, b, c, d) of the traits, behind an inlined semi-static filter.
template <class Triangulation, class Domain_predicate>
inline CGAL::
    Orientation Segment_walk_3<Triangulation, Domain_predicate>::orient4(const Point& a, const Point& b, const Point& c,
        const Point& d) const {
  if (double_coordinates) {
    const double ax = CGAL::to_double(a.x()), ay = CGAL::to_double(a.y()), az = CGAL::to_double(a.z());
    double ba[3], ca[3], da[3];
    diff(b, ax, ay, az, ba);
    diff(c, ax, ay, az, ca);
    diff(d, ax, ay, az, da);
    const int s = filtered_det_sign(ba, ca, da);
    if (s != 2) return CGAL::Orientation(s);
  }
  return orient_(a, b, c, d);
}

template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::coords(const Point& a, double* r) {
  r[0] = CGAL::to_double(a.x());
  r[1] = CGAL::to_double(a.y());
  r[2] = CGAL::to_double(a.z());
}

// Parameter of the point where the segment meets face s (crossing it, or
// through a vertex), with no bound on its position yet.
template <class Triangulation, class Domain_predicate>
inline double Segment_walk_3<Triangulation, Domain_predicate>::crossing_t(const Ctx& x, const Simplex& s) const {
  double v[3][3];
  int k = 0;
  for (int i = 0; i < 4 && k < 3; ++i)
    if (s.mask & (1u << i)) coords(pt(s.c, i), v[k++]);
  const double q[3] = {x.qx, x.qy, x.qz}, p[3] = {x.px, x.py, x.pz};
  double t = 0;
  if (certified_before_end(internal::walk_interval_parameter(q, p, k, v, t), t)) return t;
  return CGAL::to_double(exact_t(x, s));
}

// The same, for a facet s = (a, b, c), trying the normal form in double first.
template <class Triangulation, class Domain_predicate>
inline double Segment_walk_3<Triangulation, Domain_predicate>::
    facet_crossing_t(const Ctx& x, const Simplex& s, const double* a, const double* b, const double* c) const {
  const double q[3] = {x.qx, x.qy, x.qz}, d[3] = {x.dx, x.dy, x.dz};
  double t = 0;
  if (certified_before_end(internal::walk_plane_parameter(q, d, a, b, c, t), t)) return t;
  return crossing_t(x, s);
}

// Exit parameter of a piece that started at lo, where the segment meets face s.
template <class Triangulation, class Domain_predicate>
inline double Segment_walk_3<Triangulation, Domain_predicate>::t_of(const Ctx& x, const Simplex& s, double lo) const {
  return internal::walk_exit_parameter(crossing_t(x, s), lo);
}

// Semi-static filter for the sign of det[a, b, c] (rows), where the rows are
// differences of double coordinates computed in double, as in CGAL's static
// filter of Orientation_3: the same expression shape, with a bound twice
// as large. Returns 2 when the sign is not certified (the caller then asks
// the exact predicate of the traits).
template <class Triangulation, class Domain_predicate>
inline int Segment_walk_3<Triangulation, Domain_predicate>::
    filtered_det_sign(const double* a, const double* b, const double* c) {
  const double mx = std::max(std::fabs(a[0]), std::max(std::fabs(b[0]), std::fabs(c[0])));
  const double my = std::max(std::fabs(a[1]), std::max(std::fabs(b[1]), std::fabs(c[1])));
  const double mz = std::max(std::fabs(a[2]), std::max(std::fabs(b[2]), std::fabs(c[2])));
  if (!(mx >= 1e-90 && my >= 1e-90 && mz >= 1e-90 && mx <= 1e90 && my <= 1e90 && mz <= 1e90)) return 2;
  const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  const double eps = 1e-14 * mx * my * mz;
  if (det > eps) return 1;
  if (det < -eps) return -1;
  return 2;
}

template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::
    diff(const Point& a, double qx, double qy, double qz, double* r) {
  r[0] = CGAL::to_double(a.x()) - qx;
  r[1] = CGAL::to_double(a.y()) - qy;
  r[2] = CGAL::to_double(a.z()) - qz;
}

// orientation(q, p, d, v), with dq = d - q already computed.
template <class Triangulation, class Domain_predicate>
inline CGAL::
    Orientation Segment_walk_3<Triangulation, Domain_predicate>::orient_qp(const Ctx& x, const double* dq,
        const Point& d, const Point& v) const {
  if (double_coordinates) {
    double vq[3];
    diff(v, x.qx, x.qy, x.qz, vq);
    const double D[3] = {x.dx, x.dy, x.dz};
    const int s = filtered_det_sign(D, dq, vq);
    if (s != 2) return CGAL::Orientation(s);
  }
  return orient_(x.q, x.p, d, v);
}

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEGMENT_WALK_3_PREDICATES_H
