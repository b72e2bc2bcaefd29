// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEGMENT_WALK_3_OUTPUT_H
#define CGAL_EXT_INTERNAL_SEGMENT_WALK_3_OUTPUT_H

// The output of Segment_walk_3: pieces built from simplices or from records
// of the cell array, and the check of the input points.
//
// Member definitions of Segment_walk_3, included at the end of
// <CGAL_ext/Segment_walk_3.h>; not a header of its own.

namespace CGAL_ext {

template <class Triangulation, class Domain_predicate>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    make_piece(const Simplex& s, double a, double b) const -> Piece {
  Piece r;
  r.t_in = a;
  r.t_out = b;
  if (!s.valid()) return r;
  r.cell = s.c;
  int k = 0;
  for (int i = 0; i < 4; ++i)
    if (s.mask & (1u << i)) r.vertices[k++] = s.c->vertex(i);
  r.dimension = k - 1;
  return r;
}

// The same from the cell array, without touching the triangulation's cell.
template <class Triangulation, class Domain_predicate>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    make_piece(std::uint32_t ci, unsigned mask, double a, double b) const -> Piece {
  Piece r;
  fill_piece(r, ci, mask, a, b);
  return r;
}

template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::
    fill_piece(Piece& r, std::uint32_t ci, unsigned mask, double a, double b) const {
  r.t_in = a;
  r.t_out = b;
  r.cell = cells_->cell_handles[ci];
  const typename Cell_array::Record& rec = cells_->records[ci];
  int k = 0;
  for (int i = 0; i < 4; ++i)
    if (mask & (1u << i)) r.vertices[k++] = cells_->vertex_handle(rec.v[i]);
  r.dimension = k - 1;
}

template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::
    check_finite(const Point& x, const char* what, std::size_t query) {
  const double c[3] = {CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z())};
  for (double v : c)
    if (!std::isfinite(v)) {
      std::ostringstream os;
      os << "Segment_walk_3::" << what << ": ";
      if (query != std::size_t(-1)) os << "query " << query << ": ";
      os << "the point (" << c[0] << ", " << c[1] << ", " << c[2] << ") has a coordinate that is not finite";
      throw std::invalid_argument(os.str());
    }
}

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEGMENT_WALK_3_OUTPUT_H
