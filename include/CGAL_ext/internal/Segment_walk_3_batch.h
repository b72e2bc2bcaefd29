// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEGMENT_WALK_3_BATCH_H
#define CGAL_EXT_INTERNAL_SEGMENT_WALK_3_BATCH_H

// The batch walk of Segment_walk_3: lanes of queries interleaved in the
// cell array's loop, one step of each in turn.
//
// Member definitions of Segment_walk_3, included at the end of
// <CGAL_ext/Segment_walk_3.h>; not a header of its own.

namespace CGAL_ext {

namespace internal {

// The start of a batch query reads the record index of its hint (from the
// hint's address alone), the record and its four vertices: they are
// requested from memory in three stages, 3, 2 and 1 times lanes_n queries
// ahead, each stage reading what the previous one requested; the table
// entries and record indices are kept in rings for the next stages. (The
// ring stores also keep the compiler from deleting the stages' calls: with
// prefetches alone they are "pure", and GCC 12 drops calls to pure
// functions.) Each stage runs for a group of lanes_n queries at once, first
// computing its addresses and then requesting them back to back: a request
// that misses the TLB holds up the instructions after it until the page
// walk ends, and requests issued together wait together.
template <class Cell_array, class QueryRange, std::size_t lanes_n>
class Walk_batch_prefetcher {
public:
  Walk_batch_prefetcher(const Cell_array& cells, const QueryRange& queries)
      : cells_(&cells), queries_(&queries), n_(queries.size()) {
    for (std::size_t g = 0; g < 3; ++g) stage(g * lanes_n, 0);
    for (std::size_t g = 0; g < 2; ++g) stage(g * lanes_n, 1);
  }
  // Called at every query i, in order: at the first query of each group,
  // the stages of the groups ahead.
  void ahead(std::size_t i) {
    if (i % lanes_n != 0) return;
    stage(i + 3 * lanes_n, 0);
    stage(i + 2 * lanes_n, 1);
    stage(i + lanes_n, 2);
  }
  // The record of the hint of query i (Cell_array::outside if none).
  std::uint32_t record(std::size_t i) const { return record_[i % ring_n]; }

private:
  static constexpr std::size_t ring_n = 4 * lanes_n;

  std::uint32_t read_entry(std::size_t i) const {
    return entry_[i % ring_n] ? *entry_[i % ring_n] : Cell_array::outside;
  }
  void stage(std::size_t first, int s) {
    const std::size_t last = std::min(first + lanes_n, n_);
    const QueryRange& queries = *queries_;
    if (s == 0) {
      for (std::size_t i = first; i < last; ++i) entry_[i % ring_n] = cells_->index_entry(queries[i].hint);
#if defined(__GNUC__)
      for (std::size_t i = first; i < last; ++i)
        if (entry_[i % ring_n]) __builtin_prefetch(entry_[i % ring_n]);
#endif
    } else if (s == 1) {
      for (std::size_t i = first; i < last; ++i) record_[i % ring_n] = read_entry(i);
#if defined(__GNUC__)
      for (std::size_t i = first; i < last; ++i)
        if (record_[i % ring_n] != Cell_array::outside) __builtin_prefetch(&cells_->records[record_[i % ring_n]]);
#endif
    } else {
#if defined(__GNUC__)
      for (std::size_t i = first; i < last; ++i)
        if (record_[i % ring_n] != Cell_array::outside)
          for (int l = 0; l < 4; ++l) __builtin_prefetch(cells_->point(cells_->records[record_[i % ring_n]].v[l]));
#endif
    }
  }

  const Cell_array* cells_;
  const QueryRange* queries_;
  std::size_t n_;
  std::array<const std::uint32_t*, ring_n> entry_;
  std::array<std::uint32_t, ring_n> record_;
};

} // namespace internal

// The batch walk: lanes of queries in the cell array's loop, one step of
// each in turn; everything else (no hint, q not strictly inside its hint,
// degenerate steps, gaps) runs to the end of its query as in run().
template <class Triangulation, class Domain_predicate>
template <bool Full, class QueryRange, class F>
inline void Segment_walk_3<Triangulation, Domain_predicate>::run_batch(const QueryRange& queries, F& f) const {
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
  internal::Walk_batch_prefetcher<Cell_array, QueryRange, lanes_n> prefetch(*cells_, queries);
  std::size_t next = 0;
  // Starts queries until one is in the loop, in lane L; false if none is left.
  auto start = [&](Lane& L) {
    while (next < n) {
      const std::size_t i = next++;
      prefetch.ahead(i);
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
      const std::uint32_t ci = prefetch.record(i);
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

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEGMENT_WALK_3_BATCH_H
