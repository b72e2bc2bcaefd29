// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEGMENT_WALK_3_STATE_H
#define CGAL_EXT_INTERNAL_SEGMENT_WALK_3_STATE_H

// The per-call state of Segment_walk_3 (the segment, its error bounds, the
// step count and the scratch vectors of the gap search and of the stars)
// and its output sinks.
//
// Definitions of nested types of Segment_walk_3, included at the end of
// <CGAL_ext/Segment_walk_3.h>; not a header of its own.

namespace CGAL_ext {

// Per-call state.
template <class Triangulation, class Domain_predicate>
struct Segment_walk_3<Triangulation, Domain_predicate>::Ctx {
  Point q, p;
  double qx, qy, qz, dx, dy, dz, dd;
  double d1, dinf; // |D|_1 and |D|_inf, for the error bounds of crossing parameters
  double px, py, pz;
  // Static filter bounds of the cell-array walk (valid iff `fast`): any
  // det[D, a - q, b - q] of mesh vertices computed in double is within E
  // of the exact value, any (v - p).D within Er.
  bool fast = false;
  double E = 0, Er = 0;
  double emu = 0; // pi(a, b) is within emu |w_a|_1 |b - a|_1 of its exact value
  std::size_t steps = 0;
  std::size_t max_steps;
  std::size_t query = std::size_t(-1); // index in a batch, for messages
  // gap search: candidates sorted by the exact parameter of their first point
  bool candidates_ready = false;
  std::vector<std::pair<EFT, std::size_t>> candidates;
  // star enumeration
  std::vector<Cell_handle> visited, stack;
  Ctx(const Point& q_, const Point& p_, std::size_t ms) : max_steps(ms) { reset(q_, p_); }
  // The state at the start of the segment (q_, p_), keeping the vectors'
  // memory (a batch reuses one Ctx per lane).
  void reset(const Point& q_, const Point& p_) {
    q = q_;
    p = p_;
    qx = CGAL::to_double(q.x()); qy = CGAL::to_double(q.y()); qz = CGAL::to_double(q.z());
    dx = CGAL::to_double(p.x()) - qx; dy = CGAL::to_double(p.y()) - qy; dz = CGAL::to_double(p.z()) - qz;
    dd = dx * dx + dy * dy + dz * dz;
    d1 = std::fabs(dx) + std::fabs(dy) + std::fabs(dz);
    dinf = std::max(std::fabs(dx), std::max(std::fabs(dy), std::fabs(dz)));
    px = CGAL::to_double(p.x()); py = CGAL::to_double(p.y()); pz = CGAL::to_double(p.z());
    fast = false;
    E = Er = emu = 0;
    steps = 0;
    query = std::size_t(-1);
    candidates_ready = false;
    candidates.clear();
    visited.clear();
    stack.clear();
  }
  void tick() {
    if (++steps > max_steps) {
      std::ostringstream os;
      os.precision(17);
      os << "Segment_walk_3: step bound exceeded on the segment ";
      if (query != std::size_t(-1)) os << "of query " << query << " ";
      os << "(" << q << ") -> (" << p << "); the triangulation is probably not valid";
      throw std::logic_error(os.str());
    }
  }
};

// Hands the pieces to an output iterator (Full: also the zero-length pieces).
template <class Triangulation, class Domain_predicate>
template <bool Full, class OutputIterator>
struct Segment_walk_3<Triangulation, Domain_predicate>::Sink {
  const Segment_walk_3* w;
  OutputIterator out;
  // zero: a structural zero-length piece (crossing, hit vertex, end point)
  void operator()(const Simplex& s, double a, double b, bool zero) {
    if (!Full && zero) return;
    *out++ = w->make_piece(s, a, b);
  }
  // The face `mask` of record ci of the cell array.
  void operator()(std::uint32_t ci, unsigned mask, double a, double b, bool zero) {
    if (!Full && zero) return;
    if constexpr (internal::Is_vector_back_inserter<OutputIterator, Piece>::value)
      w->fill_piece(internal::back_inserter_container(out).emplace_back(), ci, mask, a, b);
    else
      *out++ = w->make_piece(ci, mask, a, b);
  }
};

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEGMENT_WALK_3_STATE_H
