// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_WALK_CELL_ARRAY_3_H
#define CGAL_EXT_INTERNAL_WALK_CELL_ARRAY_3_H

/// \file Walk_cell_array_3.h
/// A compact, read-only copy of the domain cells of a triangulation, laid out
/// for the inner loop of `Segment_walk_3`: 32-byte cell records in Morton
/// order of their centroids, vertex coordinates in one array, and the handle
/// tables to go back to the triangulation.

#include <CGAL_ext/internal/Huge_page_allocator.h>

#include <CGAL/number_utils.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// Dense index of the elements of a CGAL `Compact_container` (the cells or
/// vertices of a triangulation data structure) from their handles, without
/// a table of all the handles. The elements live in a few large blocks, so their addresses
/// form a few runs of consecutive slots with small gaps (free slots, block
/// sentinels). After `finish()`, the runs, sorted by address and merged
/// across small gaps, number their slots, gaps included: the index of an
/// element is the number of its slot. A lookup finds the runs that meet
/// the address's chunk of the address space (chunks of 64 KiB or more, at
/// most 512 or two per run) in a small hash table, then its run among them
/// (usually one or two): two or three cache lines, where a binary search
/// over all the runs of a large triangulation read about ten in a dependent
/// chain. Any other container also works, with one run per element at worst.
///
/// \tparam Handle a CGAL handle (pointer-like; `&*h` is the element address)
template <class Handle>
class Handle_index {
public:
  /// No element.
  static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

  /// Adds `h`.
  /// \param h the handle
  void push_back(Handle h) {
    const std::uintptr_t a = address(h);
    if (!runs_.empty() && a == runs_.back().begin + std::uintptr_t(runs_.back().count) * stride)
      ++runs_.back().count;
    else
      runs_.push_back({a, 0u, 1u});
  }
  /// Sorts and merges the runs and numbers the slots; call once, after the
  /// last `push_back` and before any look-up.
  void finish() {
    std::sort(runs_.begin(), runs_.end(), [](const Run& x, const Run& y) { return x.begin < y.begin; });
    std::vector<Run> merged;
    for (const Run& r : runs_) {
      if (!merged.empty()) {
        Run& m = merged.back();
        const std::uintptr_t e = end(m);
        // Sorted, disjoint runs: nothing lies between m and r.
        if (r.begin >= e && (r.begin - e) % stride == 0 && (r.begin - e) / stride <= max_gap) {
          m.count += std::uint32_t((r.begin - e) / stride) + r.count;
          continue;
        }
      }
      merged.push_back(r);
    }
    size_ = 0;
    for (Run& m : merged) {
      m.first = size_;
      size_ += m.count;
    }
    runs_.swap(merged);
    // The chunk table: chunks as small as possible, from 64 KiB, with at
    // most 512 (run, chunk) pairs, or two per run if there are more runs
    // (the table, at most half full, then takes 16 KiB, or 64 bytes per run).
    auto chunks_of = [&](int b) {
      std::size_t n = 0;
      for (const Run& r : runs_) n += std::size_t((end(r) - 1) >> b) - std::size_t(r.begin >> b) + 1;
      return n;
    };
    const std::size_t max_chunks = std::max<std::size_t>(512, 2 * runs_.size());
    const int max_bits = std::min(48, std::numeric_limits<std::uintptr_t>::digits - 1);
    chunk_bits_ = 16;
    std::size_t chunks = chunks_of(chunk_bits_);
    while (chunk_bits_ < max_bits && chunks > max_chunks) chunks = chunks_of(++chunk_bits_);
    int bits = 4;
    while ((std::size_t(1) << bits) < 2 * chunks) ++bits;
    shift_ = 64 - bits;
    table_.assign(std::size_t(1) << bits, Chunk{empty, 0u, 0u});
    for (std::size_t i = 0; i < runs_.size(); ++i)
      for (std::uintptr_t c = runs_[i].begin >> chunk_bits_; c <= (end(runs_[i]) - 1) >> chunk_bits_; ++c) {
        std::size_t s = hash(c);
        while (table_[s].key != empty && table_[s].key != c) s = (s + 1) & (table_.size() - 1);
        if (table_[s].key == empty) table_[s] = Chunk{c, std::uint32_t(i), std::uint32_t(i)};
        else table_[s].last = std::uint32_t(i); // runs in address order
      }
  }
  /// Slot index of `h`, or `none` if it is in no run.
  /// \param h the handle
  std::uint32_t operator()(Handle h) const {
    if (table_.empty()) return none;
    const std::uintptr_t a = address(h), c = a >> chunk_bits_;
    std::size_t s = hash(c);
    while (table_[s].key != c) {
      if (table_[s].key == empty) return none;
      s = (s + 1) & (table_.size() - 1);
    }
    // The run containing a, if any, is the last one that begins at or
    // before a, and it meets chunk c: a binary search over the runs of the
    // chunk (usually one or two), whose steps compile to conditional moves.
    const Run* base = runs_.data() + table_[s].first;
    std::size_t n = table_[s].last - table_[s].first + 1;
    while (n > 1) {
      const std::size_t half = n / 2;
      base = base[half].begin <= a ? base + half : base;
      n -= half;
    }
    if (a < base->begin) return none;
    const std::uintptr_t off = a - base->begin;
    if (off % stride != 0 || off / stride >= base->count) return none;
    return base->first + std::uint32_t(off / stride);
  }
  /// Number of slots (elements and gaps), after `finish()`.
  std::uint32_t size() const { return size_; }
  /// Number of runs.
  std::size_t number_of_runs() const { return runs_.size(); }
  /// log2 of the chunk size of the look-up table (for tests).
  int chunk_bits() const { return chunk_bits_; }

private:
  static constexpr std::uintptr_t stride = sizeof(decltype(*std::declval<Handle>()));
  static constexpr std::uintptr_t max_gap = 1024;
  static constexpr std::uintptr_t empty = std::numeric_limits<std::uintptr_t>::max(); // no chunk has this key
  static std::uintptr_t address(Handle h) { return reinterpret_cast<std::uintptr_t>(&*h); }
  struct Run {
    std::uintptr_t begin;
    std::uint32_t first, count;
  };
  static std::uintptr_t end(const Run& r) { return r.begin + std::uintptr_t(r.count) * stride; }
  struct Chunk {
    std::uintptr_t key;        // address >> chunk_bits_, or empty
    std::uint32_t first, last; // the runs meeting the chunk
  };
  // Fibonacci hashing to the table's index bits.
  std::size_t hash(std::uintptr_t c) const { return std::size_t((std::uint64_t(c) * 0x9E3779B97F4A7C15ULL) >> shift_); }
  std::vector<Run> runs_;
  std::vector<Chunk> table_;
  int chunk_bits_ = 16, shift_ = 60;
  std::uint32_t size_ = 0;
};

/// The domain cells of a 3D triangulation with double coordinates, copied
/// into flat arrays for the segment walk. Each cell keeps the local vertex
/// and neighbour numbering of the triangulation, so that local indices and
/// facet masks mean the same in both. Cells and vertices are in Morton
/// order (of centroids and points): cells met one after the other by a walk
/// then share cache lines and pages far more often than in allocation order.
///
/// Memory: 32 bytes per domain cell for the record and 8 for its handle, 32
/// per vertex of a domain cell, 4 per cell slot of the triangulation for the
/// look-up table.
///
/// \tparam Tr a CGAL `Triangulation_3` whose points have double coordinates
template <class Tr>
class Walk_cell_array_3 {
public:
  /// Cell handle type.
  using Cell_handle = typename Tr::Cell_handle;
  /// Vertex handle type.
  using Vertex_handle = typename Tr::Vertex_handle;

  /// One domain cell: its vertex indices, and per facet the neighbour across
  /// it as `(cell index << 2) | (index of this cell in the neighbour)`, or
  /// `outside` if the neighbour is not a domain cell.
  struct alignas(32) Record {
    std::int32_t v[4]; ///< vertex indices (into `vertices`)
    std::uint32_t n[4]; ///< neighbour links
  };
  /// One vertex: coordinates and handle, on the same cache line.
  struct alignas(32) Vertex_record {
    double xyz[3]; ///< coordinates
    Vertex_handle handle; ///< the vertex
  };
  /// Link to a cell that is not in the domain; also "no cell".
  static constexpr std::uint32_t outside = std::numeric_limits<std::uint32_t>::max();

  /// Builds the arrays. The domain predicate is evaluated once per finite cell.
  /// \tparam Domain_predicate unary predicate on `Cell_handle`
  /// \param tr the triangulation (dimension 3)
  /// \param in_domain the domain predicate
  template <class Domain_predicate>
  Walk_cell_array_3(const Tr& tr, const Domain_predicate& in_domain) {
    // The heavy loops run in parallel (TBB): each writes its own entries,
    // and the sort keys are unique, so the result does not depend on the
    // number of threads.
    std::vector<std::uint32_t> slot_to_domain;
    const std::vector<Cell_handle> domain = domain_cells(tr, in_domain, slot_to_domain);
    if (domain.size() >= (std::size_t(1) << 30)) return; // links keep 30 bits for the index; not valid()
    std::vector<std::array<std::int32_t, 4>> cell_vertices(domain.size()); // vertex ids of each domain cell
    order_vertices(tr, domain, cell_vertices);
    order_cells(domain, cell_vertices, slot_to_domain);
    link_records();
  }

  /// Whether the arrays are usable (false if the domain is empty or has 2^30 cells or more).
  bool valid() const { return !slot_to_record_.empty() && !records.empty(); }
  /// Index of a domain cell in `records`, or `outside`.
  /// \param c a cell handle of the triangulation (or null)
  std::uint32_t index(Cell_handle c) const {
    const std::uint32_t* e = index_entry(c);
    return e ? *e : outside;
  }
  /// The table entry that `index(c)` reads, or null (for walks that load
  /// it ahead of use).
  /// \param c a cell handle of the triangulation (or null)
  const std::uint32_t* index_entry(Cell_handle c) const {
    if (c == Cell_handle() || slot_to_record_.empty()) return nullptr;
    const std::uint32_t i = cell_index_(c);
    return i == Handle_index<Cell_handle>::none ? nullptr : &slot_to_record_[i];
  }
  /// Coordinates of vertex `k`.
  /// \param k a vertex index of a record
  const double* point(std::int32_t k) const { return vertices[std::size_t(k)].xyz; }
  /// Handle of vertex `k`.
  /// \param k a vertex index of a record
  Vertex_handle vertex_handle(std::int32_t k) const { return vertices[std::size_t(k)].handle; }

  /// A vector on huge pages where the system gives them (the walk reads it at random places).
  template <class T>
  using Page_vector = std::vector<T, Huge_page_allocator<T>>;
  Page_vector<Record> records;          ///< domain cells in Morton order
  Page_vector<Cell_handle> cell_handles; ///< handle of each record
  Page_vector<Vertex_record> vertices;  ///< vertices of the domain cells in Morton order
  std::array<double, 3> lo{}, hi{};     ///< bounding box of `vertices`

private:

  // Domain cells, and the slot tables of cells (cell_index_, and
  // slot_to_domain: a cell's slot to its position in the result). The
  // domain predicate is called concurrently, as during concurrent walks.
  template <class Domain_predicate>
  std::vector<Cell_handle> domain_cells(const Tr& tr, const Domain_predicate& in_domain,
                                        std::vector<std::uint32_t>& slot_to_domain) {
    std::vector<Cell_handle> all;
    all.reserve(tr.tds().number_of_cells());
    for (auto c = tr.tds().cells_begin(); c != tr.tds().cells_end(); ++c) {
      cell_index_.push_back(c);
      all.push_back(c);
    }
    cell_index_.finish();
    std::vector<std::uint32_t> all_slot(all.size());
    std::vector<std::uint8_t> keep(all.size());
    parallel(all.size(), [&](std::size_t i) {
      all_slot[i] = cell_index_(all[i]);
      keep[i] = !tr.is_infinite(all[i]) && in_domain(all[i]);
    });
    std::vector<Cell_handle> domain;
    domain.reserve(all.size());
    slot_to_domain.assign(cell_index_.size(), outside);
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (!keep[i]) continue;
      slot_to_domain[all_slot[i]] = std::uint32_t(domain.size());
      domain.push_back(all[i]);
    }
    return domain;
  }

  // The vertices of the domain cells in Morton order (vertices, lo, hi), and
  // each cell's vertex ids in that order.
  void order_vertices(const Tr& tr, const std::vector<Cell_handle>& domain,
                      std::vector<std::array<std::int32_t, 4>>& cell_vertices) {
    Handle_index<Vertex_handle> vertex_slots;
    for (auto v = tr.tds().vertices_begin(); v != tr.tds().vertices_end(); ++v) vertex_slots.push_back(v);
    vertex_slots.finish();

    // Vertices of domain cells, then their Morton order.
    std::vector<std::uint32_t> vertex_id(vertex_slots.size(), outside);
    std::vector<Vertex_record> used; // in the order first met
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::numeric_limits<double>::infinity();
      hi[d] = -std::numeric_limits<double>::infinity();
    }
    parallel(domain.size(), [&](std::size_t ci) {
      for (int i = 0; i < 4; ++i) cell_vertices[ci][i] = std::int32_t(vertex_slots(domain[ci]->vertex(i)));
    });
    for (std::size_t ci = 0; ci < domain.size(); ++ci)
      for (int i = 0; i < 4; ++i) {
        const Cell_handle c = domain[ci];
        const std::uint32_t slot = std::uint32_t(cell_vertices[ci][i]);
        std::uint32_t& id = vertex_id[slot];
        if (id != outside) continue;
        id = std::uint32_t(used.size());
        Vertex_record r;
        r.handle = c->vertex(i);
        for (int d = 0; d < 3; ++d) {
          r.xyz[d] = CGAL::to_double(r.handle->point()[d]);
          lo[d] = std::min(lo[d], r.xyz[d]);
          hi[d] = std::max(hi[d], r.xyz[d]);
        }
        used.push_back(r);
      }
    std::vector<std::pair<std::uint64_t, std::uint32_t>> key(used.size());
    parallel(used.size(), [&](std::size_t i) { key[i] = {morton(used[i].xyz), std::uint32_t(i)}; });
    tbb::parallel_sort(key.begin(), key.end());
    std::vector<std::uint32_t> order(used.size());
    vertices.resize(used.size());
    for (std::size_t i = 0; i < key.size(); ++i) {
      order[key[i].second] = std::uint32_t(i);
      vertices[i] = used[key[i].second];
    }
    for (std::uint32_t& id : vertex_id)
      if (id != outside) id = order[id];
    parallel(cell_vertices.size(), [&](std::size_t ci) {
      for (std::int32_t& k : cell_vertices[ci]) k = std::int32_t(vertex_id[std::size_t(k)]);
    });
  }

  // The records and cell handles, cells in Morton order of their centroids,
  // and the table from a cell's slot to its record.
  void order_cells(const std::vector<Cell_handle>& domain,
                   const std::vector<std::array<std::int32_t, 4>>& cell_vertices,
                   const std::vector<std::uint32_t>& slot_to_domain) {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> key(domain.size());
    parallel(domain.size(), [&](std::size_t i) {
      double g[3] = {0, 0, 0};
      for (int l = 0; l < 4; ++l)
        for (int d = 0; d < 3; ++d) g[d] += 0.25 * vertices[std::size_t(cell_vertices[i][l])].xyz[d];
      key[i] = {morton(g), std::uint32_t(i)};
    });
    tbb::parallel_sort(key.begin(), key.end());
    std::vector<std::uint32_t> order(domain.size(), 0);
    parallel(key.size(), [&](std::size_t i) { order[key[i].second] = std::uint32_t(i); });
    slot_to_record_.resize(slot_to_domain.size());
    parallel(slot_to_domain.size(), [&](std::size_t i) {
      slot_to_record_[i] = slot_to_domain[i] == outside ? outside : order[slot_to_domain[i]];
    });
    records.resize(domain.size());
    cell_handles.resize(domain.size());
    parallel(domain.size(), [&](std::size_t i) {
      const Cell_handle c = domain[i];
      const std::uint32_t ci = order[i];
      cell_handles[ci] = c;
      Record& r = records[ci];
      for (int l = 0; l < 4; ++l) {
        r.v[l] = cell_vertices[i][l];
        r.n[l] = index(c->neighbor(l));
      }
    });
  }

  // The neighbour links: the neighbour's record and, in the two low bits,
  // this cell's index in it.
  void link_records() {
    // Mirror indices from the records of the neighbours (in Morton order,
    // mostly in cache) rather than from the triangulation's cells: first
    // find them all with the plain indices, then pack the links.
    std::vector<std::uint8_t> mirror(4 * records.size(), 0);
    parallel(records.size(), [&](std::size_t ci) {
      for (int l = 0; l < 4; ++l) {
        const std::uint32_t ni = records[ci].n[l];
        if (ni == outside) continue;
        const Record& o = records[ni];
        std::uint8_t m = 0;
        while (m < 3 && o.n[m] != ci) ++m;
        mirror[4 * ci + std::size_t(l)] = m;
      }
    });
    parallel(records.size(), [&](std::size_t ci) {
      for (int l = 0; l < 4; ++l)
        if (records[ci].n[l] != outside) records[ci].n[l] = (records[ci].n[l] << 2) | mirror[4 * ci + std::size_t(l)];
    });
  }
  // f(i) for i in [0, n), in parallel chunks.
  template <class F>
  static void parallel(std::size_t n, const F& f) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
    });
  }
  // Interleaves the 21 low bits of x with two zero bits each.
  static std::uint64_t spread_bits(std::uint64_t x) {
    x &= 0x1fffffULL;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
  }
  // Morton code of a point of the bounding box (21 bits per axis).
  std::uint64_t morton(const double* g) const {
    std::uint64_t code = 0;
    for (int d = 0; d < 3; ++d) {
      const double ext = hi[d] - lo[d];
      const double u = ext > 0 ? (g[d] - lo[d]) / ext : 0.0;
      code |= spread_bits(std::uint64_t(std::min(std::max(u, 0.0), 1.0) * 2097151.0)) << d;
    }
    return code;
  }
  Handle_index<Cell_handle> cell_index_;
  Page_vector<std::uint32_t> slot_to_record_; // cell slot -> record index or outside
};

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_WALK_CELL_ARRAY_3_H
