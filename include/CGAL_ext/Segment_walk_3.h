// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_SEGMENT_WALK_3_H
#define CGAL_EXT_SEGMENT_WALK_3_H

/// \file Segment_walk_3.h
/// The exact walk of a segment through a tetrahedral domain: every simplex
/// whose relative interior meets the segment, in order, with the parameter
/// interval of each piece, and the gaps outside the domain.

#include <CGAL_ext/Point_locator_3.h>
#include <CGAL_ext/Segment_walk_piece_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/internal/Walk_cell_array_3.h>
#include <CGAL_ext/internal/Walk_crossing_parameter.h>
#include <CGAL_ext/internal/Walk_tables.h>

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
/// lazily (once, thread-safely) on the first gap. The start of a segment is
/// found by `Point_locator_3` (a visibility walk from the hint or a coarse
/// grid, and an exact test of the cells of the point's bucket where the
/// visibility walk meets the boundary), which does not use the walk.
///
/// The walker does not modify the triangulation: several threads may walk
/// with the same walker concurrently. The triangulation must not change
/// while a walker is in use.
///
/// \tparam Triangulation a model of `TetMeshTriangulation_3`: a CGAL
///         `Triangulation_3` (or `Delaunay_triangulation_3`, or
///         `Tet_mesh_triangulation_3`) whose geometric traits are a CGAL
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
      : tr_(&checked_dimension(tr)), in_domain_(std::move(in_domain)), locator_(tr, in_domain_),
        shared_(std::make_shared<Shared>()),
        orient_(tr.geom_traits().orientation_3_object()),
        coplanar_orient_(tr.geom_traits().coplanar_orientation_3_object()),
        strictly_ordered_(tr.geom_traits().collinear_are_strictly_ordered_along_line_3_object()) {
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
    return locator_(x, hint);
  }

  /// Whether `c` is a cell of the domain (finite and accepted by the predicate).
  /// \param c the cell
  /// \returns true for a finite cell that the predicate accepts; false for a null handle
  bool is_domain_cell(Cell_handle c) const { return locator_.is_domain_cell(c); }

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
    // The local indices of its vertices, in increasing order; returns their number.
    int vertices(int* v) const {
      int k = 0;
      for (int i = 0; i < 4; ++i)
        if (mask & (1u << i)) v[k++] = i;
      return k;
    }
  };

  // Data built lazily, shared by the copies of a walker.
  struct Shared {
    std::once_flag boundary_once;
    // boundary facets of the domain: the domain cell and the facet index
    std::vector<Triangle> triangles;
    std::vector<std::pair<Cell_handle, int>> triangle_facets;
    std::unique_ptr<AABB> tree;
    // for boundary vertices whose star of cells is not connected through the
    // TDS (domains touching at a vertex): one domain cell per component
    std::unordered_map<const void*, std::vector<Cell_handle>> vertex_seeds;
  };

  // Per-call state (internal/Segment_walk_3_state.h).
  struct Ctx;


  // How a traversal ended: at p, or at a point of a face, from which the walk goes on.
  struct Next {
    bool done = true;
    Simplex s;
    double t = 1;
    bool crossed = false; // s is facet (s.c, k) crossed transversally out of s.c
  };

  // The output: a sink for output iterators (internal/Segment_walk_3_state.h).
  template <bool Full, class OutputIterator>
  struct Sink;


  Piece make_piece(const Simplex& s, double a, double b) const;

  Piece make_piece(std::uint32_t ci, unsigned mask, double a, double b) const;
  void fill_piece(Piece& r, std::uint32_t ci, unsigned mask, double a, double b) const;

  static void check_finite(const Point& x, const char* what, std::size_t query = std::size_t(-1));

  template <bool Full, class QueryRange, class F>
  void run_batch(const QueryRange& queries, F& f) const;

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

  CGAL::Orientation orient_x(Cell_handle c, int i, const Point& x) const;
  CGAL::Orientation orient4(const Point& a, const Point& b, const Point& c, const Point& d) const;

  // ------------------------------------------------- crossing parameters
  // Every parameter the walk reports is within internal::walk_crossing_tolerance
  // of its exact value: computed in double where an error bound certifies it,
  // else in interval arithmetic, else exactly (rounded to double). A value
  // within twice the tolerance of 1 is always computed exactly, so that the
  // pieces that end near p keep their order and positive lengths.
  static bool certified_before_end(bool ok, double t) { return ok && t <= 1 - 2 * internal::walk_crossing_tolerance; }
  static void coords(const Point& a, double* r);
  double crossing_t(const Ctx& x, const Simplex& s) const;
  double facet_crossing_t(const Ctx& x, const Simplex& s, const double* a, const double* b, const double* c) const;
  double t_of(const Ctx& x, const Simplex& s, double lo) const;

  template <class S>
  void walk(const Point& q, const Point& p, Simplex start, S& sink) const;
  template <class S>
  Next start_at(Ctx& x, const Simplex& start, S& sink) const;
  template <class S>
  void finish(Ctx& x, Next nx, S& sink) const;

  template <class S>
  Next from_point(Ctx& x, const Next& nx, S& sink) const;

  static int filtered_det_sign(const double* a, const double* b, const double* c);
#ifdef CGAL_EXT_WALK_NO_STATIC_FILTER
  static constexpr bool double_coordinates = false;
#else
  static constexpr bool double_coordinates = std::is_same<typename Kernel::FT, double>::value;
#endif
  static void diff(const Point& a, double qx, double qy, double qz, double* r);
  CGAL::Orientation orient_qp(const Ctx& x, const double* dq, const Point& d, const Point& v) const;

  template <class S>
  Next fast_cells(Ctx& x, Cell_handle c, int j, double t_in, S& sink) const;

  // -------------------- walk in the cell array (internal/Segment_walk_3_cell_array_walk.h)
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

  bool prepare_fast(Ctx& x) const;
  void load_vertex(const Ctx& x, std::int32_t k, Vertex_data& v) const { load_vertex(x, cells_->point(k), v); }
  static void set_position(const Ctx& x, const double* a, Vertex_data& v);
  static void load_vertex(const Ctx& x, const double* a, Vertex_data& v);
  static void finish_vertex(const Ctx& x, const double* a, Vertex_data& v);
  static double pi(const Vertex_data& a, const Vertex_data& b);
  static double edge_l1(const Vertex_data& a, const Vertex_data& b);
  const Point& array_point(std::int32_t k) const { return cells_->vertex_handle(k)->point(); }
  CGAL::Orientation side(const Ctx& x, double v, std::int32_t a, std::int32_t b) const;

  template <class S>
  bool array_start(Ctx& x, Cell_handle c, std::uint32_t ci, Next& nx, S& sink) const;
  bool array_enter(Ctx& x, Cell_handle c, std::uint32_t ci, Array_state& st, int& k) const;

  template <class S>
  Next array_cells(Ctx& x, std::uint32_t ci, int j, double t_in, S& sink) const;

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

  template <class S>
  Next array_loop(Ctx& x, Array_state& st, std::uint32_t ci, int j, bool have_exit, double t_in, S& sink) const;

  // The sums over an exit facet that its test and its parameter need: G =
  // sum mu rho, sum mu, sum |rho|, sum mu |rho|, the range of rho, the
  // largest |w|_1 and the sum of the edges' |b - a|_1.
  struct Exit_sums {
    double G, sum_mu, sum_rho, sum_mu_rho, rho_range, max_n1, sum_el;
  };

  template <class S>
  bool array_step(Ctx& x, Array_state& st, Array_position& cur, Next& nx, S& sink) const;
  template <class S>
  bool array_choose_exit(Ctx& x, Array_state& st, const Array_position& cur, int& k, Exit_sums& sums, Next& nx,
                         S& sink) const;
  static void exit_sums(const Array_state& st, int k, Exit_sums& e);
  void array_move(Array_state& st, Array_position& cur, int k, double t_out) const;

  static bool array_exit_certified(const Ctx& x, double t, double sum_mu, double sum_mu_rho, double rho_range,
                                   double max_n1, double sum_el);
#if defined(__GNUC__)
  __attribute__((noinline)) // rarely needed: out of the loop's code
#endif
  double array_exit_t(const Ctx& x, std::uint32_t ci, int k) const;

  template <class S>
  Next traverse_cell(Ctx& x, Cell_handle c, double t_in, S& sink) const;

  template <class S>
  Next traverse_facet(Ctx& x, const Simplex& s, double t_in, S& sink) const;

  template <class S>
  Next traverse_edge(Ctx& x, const Simplex& s, double t_in, S& sink) const;

  [[noreturn]] void throw_inconsistent(const Ctx& x, const char* what) const;

  Simplex enter(Ctx& x, const Simplex& s) const;

  template <class F>
  void for_each_edge_cell(Ctx& x, Cell_handle c, Vertex_handle a, Vertex_handle b, F& f) const;

  template <class F>
  void for_each_vertex_cell(Ctx& x, Cell_handle c, Vertex_handle v, F& f) const;

  EPoint ek(const Point& a) const;

  EFT exact_t(const Ctx& x, const Simplex& s) const;
  static EFT exact_t_line(const EPoint& Q, const EVector& D, const EPoint& a, const EPoint& b);

  bool first_t_in_triangle(const Ctx& x, std::size_t i, EFT& t) const;

  template <class S>
  Next gap(Ctx& x, const Simplex& s, double t, S& sink) const;

  void ensure_boundary() const;

  // The simplex of the domain containing x, from Point_locator_3 (invalid if outside).
  Simplex locate_simplex(const Point& x, Cell_handle hint) const {
    const auto face = locator_.locate_face(x, hint);
    return Simplex{face.first, face.second};
  }

  static const Tr& checked_dimension(const Tr& tr) {
    if (tr.dimension() < 3)
      throw std::invalid_argument("Segment_walk_3: the triangulation has dimension " + std::to_string(tr.dimension()) +
                                  "; the walk needs a 3-dimensional triangulation (at least 4 non-coplanar points)");
    return tr;
  }

  const Tr* tr_;
  Domain_predicate in_domain_;
  Point_locator_3<Tr, Domain_predicate> locator_;
  std::shared_ptr<Shared> shared_;
  std::shared_ptr<const Cell_array> cells_; // null if the walk cannot use it
  typename Kernel::Orientation_3 orient_;
  typename Kernel::Coplanar_orientation_3 coplanar_orient_;
  typename Kernel::Collinear_are_strictly_ordered_along_line_3 strictly_ordered_;
  std::size_t max_steps_ = 0;
};

} // namespace CGAL_ext

// The member definitions, one file per part of the walk.
#include <CGAL_ext/internal/Segment_walk_3_state.h>
#include <CGAL_ext/internal/Segment_walk_3_output.h>
#include <CGAL_ext/internal/Segment_walk_3_predicates.h>
#include <CGAL_ext/internal/Segment_walk_3_traversal.h>
#include <CGAL_ext/internal/Segment_walk_3_cell_array_walk.h>
#include <CGAL_ext/internal/Segment_walk_3_gap_search.h>
#include <CGAL_ext/internal/Segment_walk_3_batch.h>

#endif // CGAL_EXT_SEGMENT_WALK_3_H
