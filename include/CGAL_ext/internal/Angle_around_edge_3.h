// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_ANGLE_AROUND_EDGE_3_H
#define CGAL_EXT_INTERNAL_ANGLE_AROUND_EDGE_3_H

/// \file
/// Exact angular order of points around an oriented line, with orientation
/// predicates only (no angle is computed).

#include <CGAL/enum.h>

namespace CGAL_ext {
namespace internal {

/// The order of the half-planes bounded by the line (a, b) as they turn
/// about it, starting at the half-plane through `ref`, in the sense where w
/// follows u (by less than half a turn) when `orientation(a, b, u, w)` is
/// positive. Points are compared by their half-plane only, so two points in
/// the same half-plane are equivalent.
/// \tparam Geom_traits a CGAL kernel
template <class Geom_traits>
class Angle_around_edge_3 {
public:
  using Point = typename Geom_traits::Point_3;

  /// \param a the origin of the axis
  /// \param b a second point of the axis (not `a`)
  /// \param ref a point off the line (a, b), at angle 0
  /// \param traits the kernel whose exact predicates decide
  Angle_around_edge_3(const Point& a, const Point& b, const Point& ref, const Geom_traits& traits = Geom_traits())
      : a_(a), b_(b), ref_(ref), orientation_(traits.orientation_3_object()),
        coplanar_orientation_(traits.coplanar_orientation_3_object()) {}

  /// 0 if the angle of `p` from `ref` is in [0, pi), 1 if it is in [pi, 2 pi).
  /// \param p a point off the line (a, b)
  int half(const Point& p) const {
    const CGAL::Orientation o = orientation_(a_, b_, ref_, p);
    if (o != CGAL::COPLANAR) return o == CGAL::POSITIVE ? 0 : 1;
    // In the plane of the axis and ref: the half-plane of ref, or the other one.
    return coplanar_orientation_(a_, b_, ref_, p) == CGAL::POSITIVE ? 0 : 1;
  }

  /// Whether the angle of `u` (in half `hu`, see `half()`) is strictly less
  /// than that of `w` (in half `hw`).
  /// \param u a point off the line
  /// \param hu `half(u)`
  /// \param w a point off the line
  /// \param hw `half(w)`
  bool less(const Point& u, int hu, const Point& w, int hw) const {
    if (hu != hw) return hu < hw;
    // Within one half (less than pi wide), w follows u iff the orientation is positive.
    return orientation_(a_, b_, u, w) == CGAL::POSITIVE;
  }

  /// Whether the angle of `u` is strictly less than that of `w`.
  /// \param u a point off the line
  /// \param w a point off the line
  bool less(const Point& u, const Point& w) const { return less(u, half(u), w, half(w)); }

private:
  Point a_, b_, ref_;
  typename Geom_traits::Orientation_3 orientation_;
  typename Geom_traits::Coplanar_orientation_3 coplanar_orientation_;
};

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_ANGLE_AROUND_EDGE_3_H
