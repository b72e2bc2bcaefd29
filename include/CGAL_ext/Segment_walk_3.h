// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_SEGMENT_WALK_3_H
#define CGAL_EXT_SEGMENT_WALK_3_H

/// \file Segment_walk_3.h
/// The exact walk of a segment through a tetrahedral domain: every simplex
/// whose relative interior meets the segment, in order, with the parameter
/// interval of each piece, and the gaps outside the domain.

#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/internal/Walk_cell_array_3.h>
#include <CGAL_ext/internal/Walk_crossing_parameter.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>

#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtWalk
/// One piece of the output of `Segment_walk_3`: a simplex of the domain (or a
/// gap outside it) and the parameter interval where the segment
/// \f$x(t) = q + t (p - q)\f$ lies in its relative interior.
///
/// \tparam Triangulation a CGAL `Triangulation_3`
template <class Triangulation>
struct Segment_walk_piece_3 {
  /// -1 for a gap outside the domain, 0 vertex, 1 edge, 2 facet, 3 cell.
  int dimension = -1;
  /// The first `dimension + 1` entries are the vertices of the simplex (in no
  /// particular order); the others are default-constructed.
  std::array<typename Triangulation::Vertex_handle, 4> vertices{};
  /// A domain cell incident to the simplex (the cell itself for dimension 3);
  /// default-constructed for a gap.
  typename Triangulation::Cell_handle cell{};
  /// Start of the parameter interval.
  double t_in = 0;
  /// End of the parameter interval (`t_in == t_out` for a transversal crossing).
  double t_out = 0;
};

/// \ingroup PkgCGALExtWalk
/// One segment \f$[q, p]\f$ of a batch walk (`Segment_walk_3::fast_batch()`
/// and `Segment_walk_3::batch()`).
///
/// \tparam Triangulation a CGAL `Triangulation_3`
template <class Triangulation>
struct Segment_walk_query_3 {
  /// The start point.
  typename Triangulation::Point q;
  /// The end point.
  typename Triangulation::Point p;
  /// A cell near `q`, or null (ignored if not a domain cell).
  typename Triangulation::Cell_handle hint{};
};

namespace internal {

// Vertex indices of facet i of a positively oriented cell, ordered so that
// orientation(facet, vertex i) is positive (the cell is on the positive side).
inline constexpr std::array<int, 3> walk_inner_facet_table[4] = {{2, 1, 3}, {2, 3, 0}, {0, 3, 1}, {0, 1, 2}};
inline const std::array<int, 3>& walk_inner_facet(int i) { return walk_inner_facet_table[i]; }
// Moving from a cell r across its facet k into the neighbour n (whose facet
// m it is): for each local vertex i of n, the local index in r of the same
// vertex (2 bits per i; the vertex i = m, new, gets k), at entry
// (4 k + m) * 3 + rho, where n's vertex f[0] (f: inner facet m) is r's
// vertex g[rho] (g: inner facet k). A valid triangulation data structure
// orients neighbouring cells consistently, so the two cells see the shared
// facet in reverse cyclic order: f = (g[rho], g[rho - 1], g[rho + 1]).
constexpr std::array<std::uint8_t, 48> make_walk_facet_map() {
  std::array<std::uint8_t, 48> t{};
  for (int k = 0; k < 4; ++k)
    for (int m = 0; m < 4; ++m)
      for (int rho = 0; rho < 3; ++rho) {
        const std::array<int, 3>& g = walk_inner_facet_table[k];
        const std::array<int, 3>& f = walk_inner_facet_table[m];
        int l[4] = {0, 0, 0, 0};
        l[m] = k;
        l[f[0]] = g[rho];
        l[f[1]] = g[(rho + 2) % 3];
        l[f[2]] = g[(rho + 1) % 3];
        t[std::size_t((4 * k + m) * 3 + rho)] = std::uint8_t(l[0] | l[1] << 2 | l[2] << 4 | l[3] << 6);
      }
  return t;
}
inline constexpr std::array<std::uint8_t, 48> walk_facet_map = make_walk_facet_map();
// Output iterators that are std::back_inserter of a std::vector<Piece> get
// the pieces built in place: building a piece in a temporary and copying it
// makes the wide loads of the copy wait for the narrow stores that built it
// (a store-forwarding stall: a fifth of the samples of the full walk in a
// profile before this).
template <class It, class Piece>
struct Is_vector_back_inserter : std::false_type {};
template <class Piece, class Alloc>
struct Is_vector_back_inserter<std::back_insert_iterator<std::vector<Piece, Alloc>>, Piece> : std::true_type {};
template <class C>
C& back_inserter_container(std::back_insert_iterator<C>& it) {
  struct Access : std::back_insert_iterator<C> {
    static C* get(std::back_insert_iterator<C>& i) { return i.*(&Access::container); }
  };
  return *Access::get(it);
}

inline int walk_popcount(unsigned m) { return int(m & 1u) + int((m >> 1) & 1u) + int((m >> 2) & 1u) + int((m >> 3) & 1u); }

} // namespace internal

/// \ingroup PkgCGALExtWalk
/// Exact walk of a segment \f$[q, p]\f$ through the domain of a 3D triangulation.
///
/// The domain is the union of the cells for which the domain predicate is
/// true. A simplex (vertex, edge, facet, cell) is considered if it is a face
/// of at least one domain cell. `operator()` reports, in order along the
/// segment, every such simplex whose relative interior meets the closed
/// segment, with its parameter interval on \f$x(t) = q + t (p - q)\f$, and
/// the maximal parts of \f$[0, 1]\f$ outside the closed domain as gaps
/// (dimension -1). The intervals tile \f$[0, 1]\f$: the first starts at 0,
/// each one starts at the (same double) end of the previous one, and the last
/// ends at 1. A transversal crossing of a facet, an edge or a vertex is a
/// piece with `t_in == t_out`.
///
/// Every combinatorial decision (which simplex, which side, where the walk
/// re-enters the domain) is taken with exact predicates (orientations of the
/// input points and mesh vertices, and exact rational arithmetic for the
/// rare re-entry search). Every reported parameter is within 1e-12 of its
/// exact value: computed in double where an error bound certifies it (below
/// 2e-13), else in interval arithmetic, else exactly and rounded; a piece of
/// exact positive length has `t_in < t_out` (except pieces starting within a
/// few units in the last place of 1, which double cannot separate).
/// When the kernel's number type is `double`,
/// orientation tests first go through an inlined semi-static filter (the
/// expression shape and error bound of CGAL's own static filter of
/// `Orientation_3`, with a safety factor of 2) and call the traits'
/// `Orientation_3` whenever the filter cannot certify the sign, so the
/// decisions are those of the exact predicate; define
/// `CGAL_EXT_WALK_NO_STATIC_FILTER` to always call the traits' predicate.
///
/// With double coordinates, the walker keeps a compact copy of the domain
/// cells (`internal::Walk_cell_array_3`: 32-byte cell and vertex records in
/// Morton order, built in the constructor; about 44 bytes per domain cell
/// and 32 per vertex). A generic step there costs three dot products: each
/// vertex, once loaded, is turned into Pluecker-style data relative to the
/// segment line, and the signs of the three planes through the line and the
/// new vertex choose the exit facet; whether \f$p\f$ was reached, and the
/// exit parameter, come from the barycentric weights of the crossing point,
/// carried from cell to cell with their error bounds. These signs are certified by static error
/// bounds computed once per segment; an uncertain one is decided by the
/// traits' exact predicate. Degenerate configurations (the segment through
/// a vertex, along an edge, in a facet plane) are detected when a predicate
/// returns zero and handled by an exact general step over the star of the
/// current simplex.
///
/// `fast_batch()` and `batch()` walk many segments in one call, interleaving
/// up to 8 walks step by step so that their waits for memory overlap; each
/// segment gets exactly the pieces of a single call.
///
/// Infinite cells are never used geometrically, so the walk is valid on a
/// `Tet_mesh_triangulation_3` of a non-convex domain, with several
/// components, even touching along an edge or at a vertex. The re-entry
/// after a gap is found with an AABB tree over the boundary facets, built
/// lazily (once, thread-safely) on the first gap. Point location uses the
/// hint, or a coarse grid of cells built lazily, then a visibility walk, and
/// falls back on an exact segment walk from a vertex if the visibility walk
/// meets the boundary.
///
/// The walker does not modify the triangulation: several threads may walk
/// with the same walker concurrently. The triangulation must not change
/// while a walker is in use.
///
/// \tparam Triangulation a CGAL `Triangulation_3` (or `Delaunay_triangulation_3`,
///         or `Tet_mesh_triangulation_3`) whose geometric traits are a CGAL
///         kernel with double coordinates and exact predicates (e.g.
///         `Exact_predicates_inexact_constructions_kernel`); its finite cells
///         must be positively oriented, and its data structure valid
///         (neighbouring cells orient their common facet oppositely, as
///         `is_valid()` checks and `build_triangulation_from_tets()`
///         ensures).
/// \tparam Domain_predicate a unary predicate on `Cell_handle`, true for the
///         domain cells. Infinite cells are never in the domain. The
///         constructor calls it from several threads (TBB), so calls must
///         not modify shared state.
template <class Triangulation, class Domain_predicate = Is_finite_cell<Triangulation>>
class Segment_walk_3 {
public:
  /// The triangulation type.
  using Tr = Triangulation;
  /// The point type.
  using Point = typename Tr::Point;
  /// Cell handle type.
  using Cell_handle = typename Tr::Cell_handle;
  /// Vertex handle type.
  using Vertex_handle = typename Tr::Vertex_handle;
  /// The output piece type.
  using Piece = Segment_walk_piece_3<Tr>;
  /// The geometric traits (a CGAL kernel).
  using Kernel = typename Tr::Geom_traits;

  /// \param tr the triangulation; it must outlive the walker and not change
  /// \param in_domain the domain predicate
  /// \throws std::invalid_argument if `tr.dimension() < 3`
  Segment_walk_3(const Tr& tr, Domain_predicate in_domain)
      : tr_(&tr), in_domain_(std::move(in_domain)), shared_(std::make_shared<Shared>()),
        orient_(tr.geom_traits().orientation_3_object()),
        coplanar_orient_(tr.geom_traits().coplanar_orientation_3_object()),
        strictly_ordered_(tr.geom_traits().collinear_are_strictly_ordered_along_line_3_object()) {
    if (tr.dimension() < 3)
      throw std::invalid_argument("Segment_walk_3: the triangulation has dimension " + std::to_string(tr.dimension()) +
                                  "; the walk needs a 3-dimensional triangulation (at least 4 non-coplanar points)");
    // Every simplex is reported at most once and every star is searched at
    // most once per simplex: this bound is never reached on a valid input.
    max_steps_ = 64 * (tr.number_of_cells() + 4) + 1024;
    if (double_coordinates) {
      auto a = std::make_shared<const Cell_array>(tr, in_domain_);
      if (a->valid()) cells_ = std::move(a);
    }
  }

  /// Walker whose domain is every finite cell (only for `Is_finite_cell`).
  /// \tparam D the domain predicate (deduced; must be `Is_finite_cell<Tr>`)
  /// \param tr the triangulation
  template <class D = Domain_predicate,
            std::enable_if_t<std::is_same<D, Is_finite_cell<Triangulation>>::value, int> = 0>
  explicit Segment_walk_3(const Tr& tr) : Segment_walk_3(tr, Is_finite_cell<Tr>(tr)) {}

  /// Full output: every simplex whose relative interior meets \f$[q, p]\f$,
  /// in order, with gaps; see the class description.
  /// \tparam OutputIterator accepts `Piece`
  /// \param q the start point
  /// \param p the end point
  /// \param out receives the pieces
  /// \returns the output iterator past the last piece
  /// \throws std::invalid_argument if a coordinate is not finite
  template <class OutputIterator>
  OutputIterator operator()(const Point& q, const Point& p, OutputIterator out) const {
    return run<true>(q, p, out, Cell_handle());
  }

  /// Full output, with a hint for locating `q`.
  /// \tparam OutputIterator accepts `Piece`
  /// \param q the start point
  /// \param p the end point
  /// \param out receives the pieces
  /// \param hint a cell near `q` (ignored if null or not a domain cell)
  /// \returns the output iterator past the last piece
  template <class OutputIterator>
  OutputIterator operator()(const Point& q, const Point& p, OutputIterator out, Cell_handle hint) const {
    return run<true>(q, p, out, hint);
  }

  /// Fast mode: only the pieces of positive length (cells, edges and facets
  /// the segment runs along or through, and gaps), in order. These are the
  /// pieces of the full output without its zero-length pieces, so
  /// consecutive pieces are adjacent in t. "Positive length" is exact, and
  /// such a piece has `t_in < t_out` (see the class description).
  /// Consecutive gaps (separated by a point where the segment only touches
  /// the domain) are not merged. If `q == p` the one piece of the full
  /// output (of zero length) is reported.
  /// \tparam OutputIterator accepts `Piece`
  /// \param q the start point
  /// \param p the end point
  /// \param out receives the pieces
  /// \returns the output iterator past the last piece
  template <class OutputIterator>
  OutputIterator fast(const Point& q, const Point& p, OutputIterator out) const {
    return run<false>(q, p, out, Cell_handle());
  }

  /// Fast mode, with a hint for locating `q`.
  /// \tparam OutputIterator accepts `Piece`
  /// \param q the start point
  /// \param p the end point
  /// \param out receives the pieces
  /// \param hint a cell near `q` (ignored if null or not a domain cell)
  /// \returns the output iterator past the last piece
  template <class OutputIterator>
  OutputIterator fast(const Point& q, const Point& p, OutputIterator out, Cell_handle hint) const {
    return run<false>(q, p, out, hint);
  }

  /// A segment of a batch walk.
  using Query = Segment_walk_query_3<Tr>;

  /// Batch fast mode: the fast-mode pieces of many segments, walked several
  /// at a time. The output for each query is exactly that of
  /// `fast(q, p, out, hint)`, but the walks of up to 8 queries are
  /// interleaved step by step, and the cells, records and vertices they are
  /// about to visit are requested from memory ahead of use: on a mesh larger
  /// than the cache, a single walk spends most of its time waiting for each
  /// next cell, and the interleaved walks wait together. Single-threaded
  /// and deterministic: the sequence of callback calls depends only on the
  /// input.
  ///
  /// `f(i, piece)` is called for every piece of query `i`. The pieces of one
  /// query come in order along its segment; the pieces of different queries
  /// are interleaved, in an order that depends only on the input. Every
  /// query is complete when the call returns (there is no per-query "done"
  /// signal). All the points are checked before any piece is reported.
  ///
  /// Preconditions: the queries do not change during the call (the walk
  /// reads them ahead of their turn), and every hint is null or a cell
  /// handle of this walker's triangulation.
  /// \tparam QueryRange a range with `size()` and `operator[](std::size_t)`
  ///         whose elements have the members `q`, `p` (`Point`) and `hint`
  ///         (`Cell_handle`), such as `std::vector<Query>`
  /// \tparam PieceCallback callable as `f(std::size_t i, const Piece& piece)`
  /// \param queries the segments and their hints
  /// \param f receives the pieces
  /// \throws std::invalid_argument if a coordinate is not finite (naming the query), before any output
  /// \throws std::logic_error if a walk exceeds its step bound (an invalid
  ///         triangulation; the message names the query). This, and any
  ///         exception thrown by `f`, ends the call: the queries in progress
  ///         (up to 8) have then received part of their pieces, and the
  ///         later ones none.
  template <class QueryRange, class PieceCallback>
  void fast_batch(const QueryRange& queries, PieceCallback&& f) const {
    run_batch<false>(queries, f);
  }

  /// Batch full output: as `fast_batch()`, with the pieces of `operator()`.
  /// \tparam QueryRange as for `fast_batch()`
  /// \tparam PieceCallback callable as `f(std::size_t i, const Piece& piece)`
  /// \param queries the segments and their hints
  /// \param f receives the pieces
  /// \throws std::invalid_argument if a coordinate is not finite (naming the query), before any output
  /// \throws std::logic_error as for `fast_batch()`
  template <class QueryRange, class PieceCallback>
  void batch(const QueryRange& queries, PieceCallback&& f) const {
    run_batch<true>(queries, f);
  }

  /// Exact point location: the lowest-dimensional domain simplex containing
  /// `x`, as a piece with `t_in == t_out == 0`, or a gap (dimension -1) if
  /// `x` is outside the closed domain.
  /// \param x the point
  /// \param hint a cell near `x` (ignored if null or not a domain cell)
  /// \returns the simplex's dimension (-1 for a gap), vertices and a domain cell incident to it
  /// \throws std::invalid_argument if a coordinate is not finite
  Piece locate(const Point& x, Cell_handle hint = Cell_handle()) const {
    check_finite(x, "locate");
    return make_piece(locate_simplex(x, hint), 0.0, 0.0);
  }

  /// Whether `c` is a cell of the domain (finite and accepted by the predicate).
  /// \param c the cell
  /// \returns true for a finite cell that the predicate accepts; false for a null handle
  bool is_domain_cell(Cell_handle c) const {
    if (c == Cell_handle() || tr_->is_infinite(c)) return false;
    if (std::is_same<Domain_predicate, Is_finite_cell<Tr>>::value) return true; // already decided
    return in_domain_(c);
  }

private:
  using EK = CGAL::Simple_cartesian<CGAL::Exact_rational>;
  using EFT = EK::FT;
  using EPoint = EK::Point_3;
  using EVector = EK::Vector_3;
  using Triangle = typename Kernel::Triangle_3;
  using Tri_iterator = typename std::vector<Triangle>::const_iterator;
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, Tri_iterator>;
  using AABB = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  using Cell_array = internal::Walk_cell_array_3<Tr>;

  // A face of cell c: the vertices of c whose bit is set in mask (mask 0: none / outside).
  struct Simplex {
    Cell_handle c;
    unsigned mask = 0;
    bool valid() const { return mask != 0; }
    int dimension() const { return internal::walk_popcount(mask) - 1; }
  };

  // Data built lazily, shared by the copies of a walker.
  struct Shared {
    std::once_flag boundary_once, grid_once;
    // boundary facets of the domain: the domain cell and the facet index
    std::vector<Triangle> triangles;
    std::vector<std::pair<Cell_handle, int>> triangle_facets;
    std::unique_ptr<AABB> tree;
    // for boundary vertices whose star of cells is not connected through the
    // TDS (domains touching at a vertex): one domain cell per component
    std::unordered_map<const void*, std::vector<Cell_handle>> vertex_seeds;
    // coarse grid of domain cells, for the start of point location
    std::array<double, 3> lo{}, step{};
    std::array<int, 3> n{};
    std::vector<Cell_handle> grid;
    Cell_handle any_domain_cell;
  };

  // Per-call state.
  struct Ctx {
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

  // How a traversal ended: at p, or at a point of a face, from which the walk goes on.
  struct Next {
    bool done = true;
    Simplex s;
    double t = 1;
    bool crossed = false; // s is facet (s.c, k) crossed transversally out of s.c
  };

  // ---------------------------------------------------------------- output
  template <bool Full, class OutputIterator>
  struct Sink {
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
  struct Last_sink {
    const Segment_walk_3* w;
    Simplex last;
    void operator()(const Simplex& s, double, double, bool) { last = s; }
    void operator()(std::uint32_t ci, unsigned mask, double, double, bool) {
      last = Simplex{w->cells_->cell_handles[ci], mask};
    }
  };

  Piece make_piece(const Simplex& s, double a, double b) const {
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
  Piece make_piece(std::uint32_t ci, unsigned mask, double a, double b) const {
    Piece r;
    fill_piece(r, ci, mask, a, b);
    return r;
  }
  void fill_piece(Piece& r, std::uint32_t ci, unsigned mask, double a, double b) const {
    r.t_in = a;
    r.t_out = b;
    r.cell = cells_->cell_handles[ci];
    const typename Cell_array::Record& rec = cells_->records[ci];
    int k = 0;
    for (int i = 0; i < 4; ++i)
      if (mask & (1u << i)) r.vertices[k++] = cells_->vertex_handle(rec.v[i]);
    r.dimension = k - 1;
  }

  static void check_finite(const Point& x, const char* what, std::size_t query = std::size_t(-1)) {
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

  // The batch walk: lanes of queries in the cell array's loop, one step of
  // each in turn; everything else (no hint, q not strictly inside its hint,
  // degenerate steps, gaps) runs to the end of its query as in run().
  template <bool Full, class QueryRange, class F>
  void run_batch(const QueryRange& queries, F& f) const {
    // The output iterator of query i hands its pieces to f(i, piece).
    auto out_of = [&f](std::size_t i) {
      return boost::make_function_output_iterator([&f, i](const Piece& piece) { f(i, piece); });
    };
    using Sk = Sink<Full, decltype(out_of(0))>;
    const char* what = Full ? "batch" : "fast_batch";
    const std::size_t n = queries.size();
    for (std::size_t i = 0; i < n; ++i) {
      check_finite(queries[i].q, what, i);
      check_finite(queries[i].p, what, i);
    }
    if (!cells_) {
      for (std::size_t i = 0; i < n; ++i) run<Full>(queries[i].q, queries[i].p, out_of(i), queries[i].hint);
      return;
    }
    // 8 lanes: with the 5 prefetches of a step, enough loads in flight to
    // cover the latency of memory; 12 or 16 lanes, or steps split in two so
    // that only the record taken is prefetched, measured no faster.
    constexpr std::size_t lanes_n = 8;
    struct Lane {
      std::size_t i = 0;
      bool active = false;
      std::optional<Ctx> x;
      Array_state st;
      Array_position cur{};
    };
    std::array<Lane, lanes_n> lanes;
    // A query's start reads the record index of its hint (from the hint's
    // address alone), the record and its four vertices: they are requested
    // from memory in three stages, 3, 2 and 1 times lanes_n queries ahead,
    // each stage reading what the previous one requested; the table entries
    // and record indices are kept in rings for the next stages. (The ring
    // stores also keep the compiler from deleting this lambda's calls: with
    // prefetches alone it is "pure", and GCC 12 drops calls to pure
    // functions.)
    constexpr std::size_t ring_n = 4 * lanes_n;
    std::array<const std::uint32_t*, ring_n> entry;
    std::array<std::uint32_t, ring_n> record;
    auto read_entry = [&](std::size_t i) { return entry[i % ring_n] ? *entry[i % ring_n] : Cell_array::outside; };
    // Each stage runs for a group of lanes_n queries at once, first
    // computing its addresses and then requesting them back to back: a
    // request that misses the TLB holds up the instructions after it until
    // the page walk ends, and requests issued together wait together.
    auto stage = [&](std::size_t first, int s) {
      const std::size_t last = std::min(first + lanes_n, n);
      if (s == 0) {
        for (std::size_t i = first; i < last; ++i) entry[i % ring_n] = cells_->index_entry(queries[i].hint);
#if defined(__GNUC__)
        for (std::size_t i = first; i < last; ++i)
          if (entry[i % ring_n]) __builtin_prefetch(entry[i % ring_n]);
#endif
      } else if (s == 1) {
        for (std::size_t i = first; i < last; ++i) record[i % ring_n] = read_entry(i);
#if defined(__GNUC__)
        for (std::size_t i = first; i < last; ++i)
          if (record[i % ring_n] != Cell_array::outside) __builtin_prefetch(&cells_->records[record[i % ring_n]]);
#endif
      } else {
#if defined(__GNUC__)
        for (std::size_t i = first; i < last; ++i)
          if (record[i % ring_n] != Cell_array::outside)
            for (int l = 0; l < 4; ++l) __builtin_prefetch(cells_->point(cells_->records[record[i % ring_n]].v[l]));
#endif
      }
    };
    // At the first query of each group.
    auto prefetch_ahead = [&](std::size_t i) {
      if (i % lanes_n != 0) return;
      stage(i + 3 * lanes_n, 0);
      stage(i + 2 * lanes_n, 1);
      stage(i + lanes_n, 2);
    };
    for (std::size_t g = 0; g < 3; ++g) stage(g * lanes_n, 0);
    for (std::size_t g = 0; g < 2; ++g) stage(g * lanes_n, 1);
    std::size_t next = 0;
    // Starts queries until one is in the loop, in lane L; false if none is left.
    auto start = [&](Lane& L) {
      while (next < n) {
        const std::size_t i = next++;
        prefetch_ahead(i);
        const auto& qu = queries[i];
        Sk sink{this, out_of(i)};
        if (qu.q == qu.p) {
          *sink.out++ = make_piece(locate_simplex(qu.q, qu.hint), 0.0, 1.0);
          continue;
        }
        if (L.x) L.x->reset(qu.q, qu.p);
        else L.x.emplace(qu.q, qu.p, max_steps_);
        Ctx& x = *L.x;
        x.query = i;
        const std::uint32_t ci = record[i % ring_n];
        L.st.slots = Array_state().slots; // (array_enter writes every pool entry it reads)
        int k;
        if (prepare_fast(x) && ci != Cell_array::outside && array_enter(x, Cell_handle(), ci, L.st, k)) {
          L.i = i;
          L.cur = Array_position{&cells_->records[ci], ci, k, true, 0.0};
#if defined(__GNUC__)
          // the record after the first step (its own steps prefetch the next ones)
          const std::uint32_t link = L.cur.r->n[k];
          if (link != Cell_array::outside) __builtin_prefetch(&cells_->records[link >> 2]);
#endif
          return true;
        }
        finish(x, start_at(x, locate_simplex(qu.q, qu.hint), sink), sink);
      }
      return false;
    };
    std::size_t active = 0;
    for (Lane& L : lanes) active += (L.active = start(L)) ? 1 : 0;
    while (active > 0)
      for (Lane& L : lanes) {
        if (!L.active) continue;
        Sk sink{this, out_of(L.i)};
        Next nx;
        if (array_step(*L.x, L.st, L.cur, nx, sink)) continue;
        finish(*L.x, nx, sink);
        if (!(L.active = start(L))) --active;
      }
  }

  template <bool Full, class OutputIterator>
  OutputIterator run(const Point& q, const Point& p, OutputIterator out, Cell_handle hint) const {
    // The record of the hint first: its look-up is a cache miss on random
    // queries, which overlaps with the checks below.
    const std::uint32_t ci = cells_ ? cells_->index(hint) : Cell_array::outside;
    check_finite(q, Full ? "operator()" : "fast");
    check_finite(p, Full ? "operator()" : "fast");
    Sink<Full, OutputIterator> sink{this, out};
    if (q == p) {
      *sink.out++ = make_piece(locate_simplex(q, hint), 0.0, 1.0);
      return sink.out;
    }
    Ctx x(q, p, max_steps_);
    Next nx;
    // Common case first: q strictly inside the hint cell, found in the cell
    // array; otherwise exact location, then the walk from there.
    if (!(prepare_fast(x) && ci != Cell_array::outside && array_start(x, hint, ci, nx, sink)))
      nx = start_at(x, locate_simplex(q, hint), sink);
    finish(x, nx, sink);
    return sink.out;
  }

  // ------------------------------------------------------------ predicates
  const Point& pt(Cell_handle c, int i) const { return c->vertex(i)->point(); }

  // Orientation of cell c with vertex i replaced by x: positive iff x is
  // strictly on the same side of facet i as vertex i.
  CGAL::Orientation orient_x(Cell_handle c, int i, const Point& x) const {
    switch (i) {
    case 0: return orient4(x, pt(c, 1), pt(c, 2), pt(c, 3));
    case 1: return orient4(pt(c, 0), x, pt(c, 2), pt(c, 3));
    case 2: return orient4(pt(c, 0), pt(c, 1), x, pt(c, 3));
    default: return orient4(pt(c, 0), pt(c, 1), pt(c, 2), x);
    }
  }
  // orientation(a, b, c, d) of the traits, behind an inlined semi-static filter.
  CGAL::Orientation orient4(const Point& a, const Point& b, const Point& c, const Point& d) const {
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

  // ------------------------------------------------- crossing parameters
  // Every parameter the walk reports is within internal::walk_crossing_tolerance
  // of its exact value: computed in double where an error bound certifies it,
  // else in interval arithmetic, else exactly (rounded to double). A value
  // within twice the tolerance of 1 is always computed exactly, so that the
  // pieces that end near p keep their order and positive lengths.
  static bool certified_before_end(bool ok, double t) { return ok && t <= 1 - 2 * internal::walk_crossing_tolerance; }
  static void coords(const Point& a, double* r) {
    r[0] = CGAL::to_double(a.x());
    r[1] = CGAL::to_double(a.y());
    r[2] = CGAL::to_double(a.z());
  }
  // Parameter of the point where the segment meets face s (crossing it, or
  // through a vertex), with no bound on its position yet.
  double crossing_t(const Ctx& x, const Simplex& s) const {
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
  double facet_crossing_t(const Ctx& x, const Simplex& s, const double* a, const double* b, const double* c) const {
    const double q[3] = {x.qx, x.qy, x.qz}, d[3] = {x.dx, x.dy, x.dz};
    double t = 0;
    if (certified_before_end(internal::walk_plane_parameter(q, d, a, b, c, t), t)) return t;
    return crossing_t(x, s);
  }
  // Exit parameter of a piece that started at lo, where the segment meets face s.
  double t_of(const Ctx& x, const Simplex& s, double lo) const {
    return internal::walk_exit_parameter(crossing_t(x, s), lo);
  }

  // ------------------------------------------------------------------ walk
  template <class S>
  void walk(const Point& q, const Point& p, Simplex start, S& sink) const {
    Ctx x(q, p, max_steps_);
    prepare_fast(x);
    finish(x, start_at(x, start, sink), sink);
  }
  // The state at q, in the simplex start (or in a gap if start is invalid).
  template <class S>
  Next start_at(Ctx& x, const Simplex& start, S& sink) const {
    if (!start.valid()) return gap(x, Simplex(), 0.0, sink);
    Next nx;
    nx.done = false;
    nx.s = start;
    nx.t = 0.0;
    return nx;
  }
  template <class S>
  void finish(Ctx& x, Next nx, S& sink) const {
    while (!nx.done) {
      x.tick();
      nx = from_point(x, nx, sink);
    }
  }

  // The walk is at x(t) in the relative interior of nx.s (t < 1): emit that
  // zero-length piece (unless the segment goes on inside nx.s, which happens
  // only at q), find the simplex the segment enters next and traverse it.
  template <class S>
  Next from_point(Ctx& x, const Next& nx, S& sink) const {
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

  // Semi-static filter for the sign of det[a, b, c] (rows), where the rows are
  // differences of double coordinates computed in double, as in CGAL's static
  // filter of Orientation_3: the same expression shape, with a bound twice
  // as large. Returns 2 when the sign is not certified (the caller then asks
  // the exact predicate of the traits).
  static int filtered_det_sign(const double* a, const double* b, const double* c) {
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
#ifdef CGAL_EXT_WALK_NO_STATIC_FILTER
  static constexpr bool double_coordinates = false;
#else
  static constexpr bool double_coordinates = std::is_same<typename Kernel::FT, double>::value;
#endif
  static void diff(const Point& a, double qx, double qy, double qz, double* r) {
    r[0] = CGAL::to_double(a.x()) - qx;
    r[1] = CGAL::to_double(a.y()) - qy;
    r[2] = CGAL::to_double(a.z()) - qz;
  }
  // orientation(q, p, d, v), with dq = d - q already computed.
  CGAL::Orientation orient_qp(const Ctx& x, const double* dq, const Point& d, const Point& v) const {
    if (double_coordinates) {
      double vq[3];
      diff(v, x.qx, x.qy, x.qz, vq);
      const double D[3] = {x.dx, x.dy, x.dz};
      const int s = filtered_det_sign(D, dq, vq);
      if (s != 2) return CGAL::Orientation(s);
    }
    return orient_(x.q, x.p, d, v);
  }

  // The classic straight walk through cells entered by the interior of a
  // facet: two orientation tests choose the exit facet, a third tells
  // whether p was reached. A zero falls back on the exact general step.
  template <class S>
  Next fast_cells(Ctx& x, Cell_handle c, int j, double t_in, S& sink) const {
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

  // ------------------------------------------------ walk in the cell array
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
  struct Vertex_data {
    double x[3]; // coordinates
    double w[3], u[3], rho;
    double n1; // |w|_1
    double mu; // weight of the vertex in the current facet crossing
    double el; // |b - a|_1 for the edge (a, b) whose pi gave mu
  };
  struct Array_state {
    Vertex_data pool[4];
    // Pool entry of local vertex l of the current cell: bits 2l, 2l + 1
    // (kept in a register; a small array here costs store-forwarding stalls).
    unsigned slots = 0xE4u; // identity: 3 2 1 0
    int slot(int l) const { return int((slots >> (2 * l)) & 3u); }
    Vertex_data& at(int l) { return pool[slot(l)]; }
  };

  // Sets x.fast and the error bounds; false if the bounds cannot be used
  // (no cell array, or coordinates so small or large that products could
  // underflow or overflow).
  bool prepare_fast(Ctx& x) const {
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
  void load_vertex(const Ctx& x, std::int32_t k, Vertex_data& v) const { load_vertex(x, cells_->point(k), v); }
  static void load_vertex(const Ctx& x, const double* a, Vertex_data& v) {
    v.x[0] = a[0];
    v.x[1] = a[1];
    v.x[2] = a[2];
    v.w[0] = a[0] - x.qx;
    v.w[1] = a[1] - x.qy;
    v.w[2] = a[2] - x.qz;
    finish_vertex(x, a, v);
  }
  // u, rho and n1 from w.
  static void finish_vertex(const Ctx& x, const double* a, Vertex_data& v) {
    v.n1 = std::fabs(v.w[0]) + std::fabs(v.w[1]) + std::fabs(v.w[2]);
    v.u[0] = x.dy * v.w[2] - x.dz * v.w[1];
    v.u[1] = x.dz * v.w[0] - x.dx * v.w[2];
    v.u[2] = x.dx * v.w[1] - x.dy * v.w[0];
    v.rho = (a[0] - x.px) * x.dx + (a[1] - x.py) * x.dy + (a[2] - x.pz) * x.dz;
  }
  // det[D, a - q, b - q] in double, as u_a . (b - a); within
  // x.emu |a - q|_1 |b - a|_1 of its exact value.
  static double pi(const Vertex_data& a, const Vertex_data& b) {
    return a.u[0] * (b.x[0] - a.x[0]) + a.u[1] * (b.x[1] - a.x[1]) + a.u[2] * (b.x[2] - a.x[2]);
  }
  static double edge_l1(const Vertex_data& a, const Vertex_data& b) {
    return std::fabs(b.x[0] - a.x[0]) + std::fabs(b.x[1] - a.x[1]) + std::fabs(b.x[2] - a.x[2]);
  }
  const Point& array_point(std::int32_t k) const { return cells_->vertex_handle(k)->point(); }
  // Sign of orientation(q, p, a, b), given its value v in double.
  CGAL::Orientation side(const Ctx& x, double v, std::int32_t a, std::int32_t b) const {
    if (v > x.E) return CGAL::POSITIVE;
    if (v < -x.E) return CGAL::NEGATIVE;
    return orient4(x.q, x.p, array_point(a), array_point(b));
  }

  // Starts in record ci if q is certified strictly inside it and the line
  // certified to leave it through the interior of a facet; otherwise
  // returns false without output (the general path then starts over).
  // The vertices are read through the cell handle c (the cell of record
  // ci), so that loading them overlaps with the look-up of the record.
  template <class S>
  bool array_start(Ctx& x, Cell_handle c, std::uint32_t ci, Next& nx, S& sink) const {
    Array_state st;
    int k;
    if (!array_enter(x, c, ci, st, k)) return false;
    nx = array_loop(x, st, ci, k, true, 0.0, sink);
    return true;
  }
  // The set-up of array_start: the vertex data and the exit facet k.
  // The vertices come from the triangulation's cell c, or (if c is null)
  // from the record.
  bool array_enter(Ctx& x, Cell_handle c, std::uint32_t ci, Array_state& st, int& k) const {
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
  template <class S>
  Next array_cells(Ctx& x, std::uint32_t ci, int j, double t_in, S& sink) const {
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

  // Where the loop is: in record ci (at r), entered through facet j at
  // t_in (or, if have_exit, with the exit facet j already chosen and every
  // vertex loaded).
  struct Array_position {
    const typename Cell_array::Record* r;
    std::uint32_t ci;
    int j;
    bool have_exit;
    double t_in;
  };

  // The loop, one segment at a time.
  template <class S>
  Next array_loop(Ctx& x, Array_state& st, std::uint32_t ci, int j, bool have_exit, double t_in, S& sink) const {
    Array_position cur{&cells_->records[ci], ci, j, have_exit, t_in};
    Next nx;
    while (array_step(x, st, cur, nx, sink)) {
    }
    return nx;
  }

  // One step of the loop: the pieces of the current cell, then either the
  // move to the next record (true) or the end of the loop, with nx (false).
  template <class S>
  bool array_step(Ctx& x, Array_state& st, Array_position& cur, Next& nx, S& sink) const {
    const auto& recs = cells_->records;
    const typename Cell_array::Record* r = cur.r;
    const std::uint32_t ci = cur.ci;
    const int j = cur.j;
    const double t_in = cur.t_in;
    x.tick();
    int k = j;
    // Over the exit facet: G = sum mu rho, and for its error bound and the
    // parameter, sum mu, sum |rho|, sum mu |rho|, the range of rho, the
    // largest |w|_1 and the sum of the edges' |b - a|_1.
    double G, sum_mu, sum_rho, sum_mu_rho, rho_range, max_n1, sum_el;
    if (!cur.have_exit) {
      const std::array<int, 3>& f = internal::walk_inner_facet(j);
      Vertex_data& d = st.at(j);
      const Vertex_data& A = st.at(f[0]);
      const Vertex_data& B = st.at(f[1]);
      const Vertex_data& C = st.at(f[2]);
      const double* xyz = cells_->point(r->v[j]);
      d.x[0] = xyz[0];
      d.x[1] = xyz[1];
      d.x[2] = xyz[2];
      d.w[0] = xyz[0] - x.qx;
      d.w[1] = xyz[1] - x.qy;
      d.w[2] = xyz[2] - x.qz;
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
          nx = traverse_cell(x, cells_->cell_handles[ci], t_in, sink);
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
      G = md * d.rho + kept_g[e];
      sum_mu = md + kept_mu[e];
      sum_rho = std::fabs(d.rho) + kept_rho[e];
      sum_mu_rho = md * std::fabs(d.rho) + kept_mu_rho[e];
      rho_range = std::max(d.rho, std::max(rh[ia], rh[ib])) - std::min(d.rho, std::min(rh[ia], rh[ib]));
      const double n1_in[3] = {A.n1, B.n1, C.n1}, el_in[3] = {A.el, B.el, C.el};
      max_n1 = std::max(d.n1, std::max(n1_in[ia], n1_in[ib]));
      sum_el = el_in[e] + el_new[ia] + el_new[ib];
      d.mu = md;
      d.el = el_in[e];
      st.pool[pos[ia]].mu = av[ib];
      st.pool[pos[ib]].mu = av[ia];
      st.pool[pos[ia]].el = el_new[ib];
      st.pool[pos[ib]].el = el_new[ia];

    } else {
      const std::array<int, 3>& g = internal::walk_inner_facet(k);
      const Vertex_data &a = st.at(g[0]), &b = st.at(g[1]), &c = st.at(g[2]);
      G = a.mu * a.rho + b.mu * b.rho + c.mu * c.rho;
      sum_mu = a.mu + b.mu + c.mu;
      sum_rho = std::fabs(a.rho) + std::fabs(b.rho) + std::fabs(c.rho);
      sum_mu_rho = a.mu * std::fabs(a.rho) + b.mu * std::fabs(b.rho) + c.mu * std::fabs(c.rho);
      rho_range = std::max(a.rho, std::max(b.rho, c.rho)) - std::min(a.rho, std::min(b.rho, c.rho));
      max_n1 = std::max(a.n1, std::max(b.n1, c.n1));
      sum_el = a.el + b.el + c.el;
    }
    // Exit facet (g0, g1, g2), the cell on its positive side.
    const std::array<int, 3>& g = internal::walk_inner_facet(k);
    // |G~ - G| <= sum E |rho~| + (|mu~| + E) Er + 3.5 u |mu~ rho~| (see above), plus a floor for underflow.
    const double err = 1.01 * (x.E * sum_rho + x.Er * (sum_mu + 3 * x.E) + 4e-16 * sum_mu_rho) + 1e-300;
    int op = G > err ? 1 : G < -err ? -1 : 2;
    if (op == 2) op = int(orient4(array_point(r->v[g[0]]), array_point(r->v[g[1]]), array_point(r->v[g[2]]), x.p));
    if (op >= 0) {
      sink(ci, 15u, t_in, 1.0, false);
      if (op == 0) sink(ci, 15u & ~(1u << k), 1.0, 1.0, true);
      nx = Next();
      return false;
    }
    double t_out = 1.0 + G / (sum_mu * x.dd);
    if (!array_exit_certified(x, t_out, sum_mu, sum_mu_rho, rho_range, max_n1, sum_el)) t_out = array_exit_t(x, ci, k);
    t_out = internal::walk_exit_parameter(t_out, t_in);
    sink(ci, 15u, t_in, t_out, false);
    const std::uint32_t link = r->n[k];
    if (link == Cell_array::outside) {
      nx = Next{false, Simplex{cells_->cell_handles[ci], 15u & ~(1u << k)}, t_out, true};
      return false;
    }
    sink(ci, 15u & ~(1u << k), t_out, t_out, true);
    // Move to the neighbour n; its vertex opposite the shared facet takes
    // the pool entry of the vertex k left behind.
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
    return true;
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
  static bool array_exit_certified(const Ctx& x, double t, double sum_mu, double sum_mu_rho, double rho_range,
                                   double max_n1, double sum_el) {
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
#if defined(__GNUC__)
  __attribute__((noinline))
#endif
  double array_exit_t(const Ctx& x, std::uint32_t ci, int k) const {
    const std::array<int, 3>& g = internal::walk_inner_facet(k);
    const typename Cell_array::Record& r = cells_->records[ci];
    const double q[3] = {x.qx, x.qy, x.qz}, d[3] = {x.dx, x.dy, x.dz};
    double t2 = 0;
    if (certified_before_end(internal::walk_plane_parameter(q, d, cells_->point(r.v[g[0]]), cells_->point(r.v[g[1]]),
                                                            cells_->point(r.v[g[2]]), t2), t2))
      return t2;
    return crossing_t(x, Simplex{cells_->cell_handles[ci], 15u & ~(1u << k)});
  }

  // Exact general traversal of the open cell c, entered at parameter t_in.
  template <class S>
  Next traverse_cell(Ctx& x, Cell_handle c, double t_in, S& sink) const {
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
  template <class S>
  Next traverse_facet(Ctx& x, const Simplex& s, double t_in, S& sink) const {
    int v[3], k = 0;
    for (int i = 0; i < 4; ++i)
      if (s.mask & (1u << i)) v[k++] = i;
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
  template <class S>
  Next traverse_edge(Ctx& x, const Simplex& s, double t_in, S& sink) const {
    int v[2], k = 0;
    for (int i = 0; i < 4; ++i)
      if (s.mask & (1u << i)) v[k++] = i;
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

  [[noreturn]] void throw_inconsistent(const Ctx& x, const char* what) const {
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
  Simplex enter(Ctx& x, const Simplex& s) const {
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
  template <class F>
  void for_each_edge_cell(Ctx& x, Cell_handle c, Vertex_handle a, Vertex_handle b, F& f) const {
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
  template <class F>
  void for_each_vertex_cell(Ctx& x, Cell_handle c, Vertex_handle v, F& f) const {
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

  // ------------------------------------------------------------------- gap
  EPoint ek(const Point& a) const {
    return EPoint(CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z()));
  }

  // Exact parameter of the point where the segment meets face s (not along it).
  EFT exact_t(const Ctx& x, const Simplex& s) const {
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
  static EFT exact_t_line(const EPoint& Q, const EVector& D, const EPoint& a, const EPoint& b) {
    const EVector e = b - a;
    const EVector c2 = CGAL::cross_product(D, e);
    return (CGAL::cross_product(a - Q, e) * c2) / (c2 * c2);
  }

  // Exact parameter of the first point of the line (q, p) in boundary
  // triangle i (it may be < 0); false if the line misses it.
  bool first_t_in_triangle(const Ctx& x, std::size_t i, EFT& t) const {
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
  template <class S>
  Next gap(Ctx& x, const Simplex& s, double t, S& sink) const {
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
  void ensure_boundary() const {
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

  // -------------------------------------------------------------- location
  void ensure_grid() const {
    std::call_once(shared_->grid_once, [this] {
      Shared& sh = *shared_;
      std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      std::size_t nc = 0;
      for (auto c : tr_->finite_cell_handles()) {
        if (!is_domain_cell(c)) continue;
        if (sh.any_domain_cell == Cell_handle()) sh.any_domain_cell = c;
        ++nc;
        for (int i = 0; i < 4; ++i) {
          const Point& a = pt(c, i);
          const double xyz[3] = {CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z())};
          for (int d = 0; d < 3; ++d) {
            lo[d] = std::min(lo[d], xyz[d]);
            hi[d] = std::max(hi[d], xyz[d]);
          }
        }
      }
      if (nc == 0) return;
      const int r = std::max(1, std::min(64, int(std::cbrt(double(nc) / 8.0))));
      for (int d = 0; d < 3; ++d) {
        sh.lo[d] = lo[d];
        sh.n[d] = r;
        sh.step[d] = hi[d] > lo[d] ? (hi[d] - lo[d]) / r : 1.0;
      }
      sh.grid.assign(std::size_t(r) * r * r, Cell_handle());
      for (auto c : tr_->finite_cell_handles()) {
        if (!is_domain_cell(c)) continue;
        double g[3] = {0, 0, 0};
        for (int i = 0; i < 4; ++i) {
          const Point& a = pt(c, i);
          g[0] += 0.25 * CGAL::to_double(a.x());
          g[1] += 0.25 * CGAL::to_double(a.y());
          g[2] += 0.25 * CGAL::to_double(a.z());
        }
        Cell_handle& b = sh.grid[grid_index(g)];
        if (b == Cell_handle()) b = c;
      }
    });
  }
  int grid_coord(double v, int d) const {
    const Shared& sh = *shared_;
    const double u = (v - sh.lo[d]) / sh.step[d];
    if (!(u >= 0)) return 0;
    return u >= sh.n[d] ? sh.n[d] - 1 : int(u);
  }
  std::size_t grid_index(const double* g) const {
    const Shared& sh = *shared_;
    return (std::size_t(grid_coord(g[2], 2)) * sh.n[1] + grid_coord(g[1], 1)) * sh.n[0] + grid_coord(g[0], 0);
  }
  Cell_handle grid_start(const Point& x) const {
    ensure_grid();
    const Shared& sh = *shared_;
    if (sh.grid.empty()) return Cell_handle();
    const double g[3] = {CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z())};
    const int ci = grid_coord(g[0], 0), cj = grid_coord(g[1], 1), ck = grid_coord(g[2], 2);
    const int rmax = std::max(sh.n[0], std::max(sh.n[1], sh.n[2]));
    for (int r = 0; r <= rmax; ++r)
      for (int k = std::max(0, ck - r); k <= std::min(sh.n[2] - 1, ck + r); ++k)
        for (int j = std::max(0, cj - r); j <= std::min(sh.n[1] - 1, cj + r); ++j)
          for (int i = std::max(0, ci - r); i <= std::min(sh.n[0] - 1, ci + r); ++i) {
            if (std::max(std::abs(i - ci), std::max(std::abs(j - cj), std::abs(k - ck))) != r) continue;
            const Cell_handle c = sh.grid[(std::size_t(k) * sh.n[1] + j) * sh.n[0] + i];
            if (c != Cell_handle()) return c;
          }
    return sh.any_domain_cell;
  }

  // The lowest-dimensional domain simplex containing x, or invalid.
  Simplex locate_simplex(const Point& x, Cell_handle hint) const {
    Cell_handle c = is_domain_cell(hint) ? hint : grid_start(x);
    if (c == Cell_handle()) return Simplex(); // empty domain
    // Visibility walk among domain cells; it ends in Delaunay triangulations,
    // and is bounded otherwise.
    const std::size_t bound = 64 + 4 * static_cast<std::size_t>(std::cbrt(double(tr_->number_of_cells()))) * 8;
    unsigned rot = 0;
    for (std::size_t step = 0; step < bound; ++step) {
      CGAL::Orientation o[4];
      int neg = -1;
      const unsigned start = rot++ & 3u;
      for (unsigned r = 0; r < 4; ++r) {
        const int i = int((start + r) & 3u);
        o[i] = orient_x(c, i, x);
        if (o[i] == CGAL::NEGATIVE) {
          neg = i;
          break;
        }
      }
      if (neg < 0) {
        unsigned m = 0;
        for (int i = 0; i < 4; ++i)
          if (o[i] == CGAL::POSITIVE) m |= 1u << i;
        return Simplex{c, m};
      }
      const Cell_handle n = c->neighbor(neg);
      if (!is_domain_cell(n)) break;
      c = n;
    }
    // Exact fallback: walk from a vertex of c to x.
    const Point& v = pt(c, 0);
    if (v == x) return Simplex{c, 1u};
    Last_sink sink{this, Simplex()};
    walk(v, x, Simplex{c, 1u}, sink);
    return sink.last;
  }

  const Tr* tr_;
  Domain_predicate in_domain_;
  std::shared_ptr<Shared> shared_;
  std::shared_ptr<const Cell_array> cells_; // null if the walk cannot use it
  typename Kernel::Orientation_3 orient_;
  typename Kernel::Coplanar_orientation_3 coplanar_orient_;
  typename Kernel::Collinear_are_strictly_ordered_along_line_3 strictly_ordered_;
  std::size_t max_steps_ = 0;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_SEGMENT_WALK_3_H
