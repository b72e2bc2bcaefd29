// Benchmark of the exact segment walk against CGAL's segment traverser, and
// of its point location against CGAL's locate(), on the Delaunay
// triangulation of N uniform random points in the unit cube.
//
// usage: benchmark_segment_walk [N = 100000] [segments per class = 2000] [seed = 1]
//
// For three classes of random segments (short: half the mean vertex
// spacing; medium: about 10 cells; long: across the cube), it measures in one
// run the cells per second of
//  - Segment_walk_3::fast, one segment per call;
//  - Segment_walk_3::fast_batch, all the segments in one call (the walks
//    are interleaved, 8 at a time);
//  - the same two for the full output (operator() and batch);
//  - Triangulation_3::segment_traverser_cell_handles, one segment at a time,
//    as CGAL offers it;
// twice: with cold caches (evicted before each timed run) and warm ones (the
// same run done just before). Cells are the finite cells reported (CGAL's
// traverser also reports the infinite cells it crosses, which are not
// counted); the cell sequences of our walk and CGAL's are compared, outside
// the timings, on the "check" line. All get the same hint (the cell
// containing q, located beforehand and not timed), single-threaded. The runs
// are interleaved in 5 rounds and the best thread CPU time of each is kept.
// The walker's construction (its cell array) is timed separately. Both
// forms of our walk hand each piece to the same counting code (through an
// output iterator for the single calls, as a callback for the batches).
//
// Point location: Point_locator_3 and Delaunay_triangulation_3::locate() on
// the same random points, without a hint and with the cell of the previous
// point as hint (random, so mostly far: our locator then starts from its
// grid), cold and warm, in points per second and as a ratio; the located
// cells are compared outside the timings.
#include <CGAL_ext/Point_locator_3.h>
#include <CGAL_ext/Segment_walk_3.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <array>
#include <functional>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iterator>
#include <random>
#include <string>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using DT = CGAL::Delaunay_triangulation_3<K>;
using Point = DT::Point;
using Walk = CGAL_ext::Segment_walk_3<DT>;
using Piece = CGAL_ext::Segment_walk_piece_3<DT>;

namespace {

struct Segment {
  Point q, p;
  DT::Cell_handle hint;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CPU time of this thread: less sensitive than wall time to other processes
// sharing the machine.
double thread_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Evicts the caches (writes a buffer larger than the last-level cache).
void evict_caches() {
  static std::vector<unsigned char> buffer(std::size_t(128) << 20);
  for (std::size_t i = 0; i < buffer.size(); i += 64) buffer[i] = static_cast<unsigned char>(buffer[i] + 1);
}

// Runs the measured functions in interleaved rounds (so that a load change
// on the machine affects them alike) and keeps the best time of each. Each
// function returns the number of cells it reported. Each timed run starts
// from the same cache state, whichever function ran before it:
//  - cold: the caches are evicted first; the data of the segments is not
//    in cache, as for queries at random places of a mesh much larger than
//    the cache;
//  - warm: the same run is done once, untimed, just before; what fits in
//    the cache is there, as for repeated or nearby queries. The timed run
//    is repeated until it has taken 50 ms (and at least 3 times, so that
//    every function's best is a best of means) and the mean is kept: a single
//    run of short segments lasts well under a millisecond, where the
//    virtual machine's timing varies most (a run that short measured
//    10-30% slower than the same run repeated, for our walk and CGAL's
//    alike).
// (Without either, a run profits from the data its predecessor loaded, which
// favours whichever walk shares memory with the one run before it.)
template <std::size_t N>
void interleaved(int rounds, bool cold, const std::array<std::function<std::size_t()>, N>& f,
                 std::array<double, N>& best, std::array<std::size_t, N>& cells) {
  best.fill(1e300);
  for (int r = 0; r < rounds; ++r)
    for (std::size_t i = 0; i < N; ++i) {
      if (cold) evict_caches();
      else f[i]();
      int runs = 0;
      const double t = thread_seconds();
      double elapsed = 0;
      do {
        cells[i] = f[i]();
        ++runs;
        elapsed = thread_seconds() - t;
      } while (!cold && (elapsed < 0.05 || runs < 3));
      best[i] = std::min(best[i], elapsed / runs);
    }
}

struct Segment_class {
  std::string name;
  double length; // < 0: across the cube
};

// per_class random segments of a class, endpoints in [lo, hi]^3, each with
// the cell containing q as its hint.
std::vector<Segment> random_segments(const DT& dt, const Segment_class& cl, std::size_t per_class, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double lo = 0.05, hi = 0.95; // endpoints well inside the convex hull
  std::uniform_real_distribution<double> in(lo, hi);
  std::vector<Segment> segs;
  while (segs.size() < per_class) {
    Point q(in(rng), in(rng), in(rng)), p;
    if (cl.length < 0) {
      // from near one face of the cube to near the opposite one
      const int axis = int(segs.size() % 3);
      double a[3] = {in(rng), in(rng), in(rng)}, b[3] = {in(rng), in(rng), in(rng)};
      a[axis] = lo;
      b[axis] = hi;
      q = Point(a[0], a[1], a[2]);
      p = Point(b[0], b[1], b[2]);
    } else {
      // random direction
      double d[3], len2 = 0;
      do {
        len2 = 0;
        for (double& x : d) {
          x = 2 * u(rng) - 1;
          len2 += x * x;
        }
      } while (len2 > 1 || len2 < 1e-4);
      const double s = cl.length / std::sqrt(len2);
      p = Point(q.x() + s * d[0], q.y() + s * d[1], q.z() + s * d[2]);
      if (p.x() < lo || p.x() > hi || p.y() < lo || p.y() > hi || p.z() < lo || p.z() > hi) continue;
    }
    segs.push_back({q, p, dt.locate(q)});
  }
  return segs;
}

// Times the five runs on the segments, cold and warm, and prints a line each.
void measure(const DT& dt, const Walk& walk, const Segment_class& cl, const std::vector<Segment>& segs) {
  std::vector<Walk::Query> queries;
  for (const Segment& x : segs) queries.push_back({x.q, x.p, x.hint});
  auto per_call = [&](bool full) {
    return [&, full] {
      std::size_t n_cells = 0;
      auto count = boost::make_function_output_iterator([&](const Piece& y) { n_cells += y.dimension == 3; });
      for (const Segment& x : segs) {
        if (full) walk(x.q, x.p, count, x.hint);
        else walk.fast(x.q, x.p, count, x.hint);
      }
      return n_cells;
    };
  };
  auto batched = [&](bool full) {
    return [&, full] {
      std::size_t n_cells = 0;
      auto count = [&](std::size_t, const Piece& y) { n_cells += y.dimension == 3; };
      if (full) walk.batch(queries, count);
      else walk.fast_batch(queries, count);
      return n_cells;
    };
  };
  const std::array<std::function<std::size_t()>, 5> runs = {
      per_call(false), batched(false), per_call(true), batched(true), [&] {
        std::size_t n_cells = 0;
        for (const Segment& x : segs)
          for (DT::Cell_handle c : dt.segment_traverser_cell_handles(x.q, x.p, x.hint)) n_cells += !dt.is_infinite(c);
        return n_cells;
      }};
  for (const bool cold : {true, false}) {
    std::array<double, 5> best;
    std::array<std::size_t, 5> cells;
    interleaved(5, cold, runs, best, cells);
    std::printf("%-20s %-6s %9zu %9.2f |", cl.name.c_str(), cold ? "cold" : "warm", segs.size(),
                double(cells[4]) / double(segs.size()));
    for (std::size_t i = 0; i < 5; ++i) std::printf(" %9.2f", double(cells[i]) / best[i] / 1e6);
    std::printf(" |");
    for (std::size_t i = 0; i < 4; ++i) std::printf(" %9.2f", (double(cells[i]) / best[i]) / (double(cells[4]) / best[4]));
    std::printf("\n");
    for (std::size_t i = 0; i < 4; ++i)
      if (cells[i] != cells[4])
        std::printf("  (run %zu reported %zu cells, CGAL's traverser %zu)\n", i, cells[i], cells[4]);
  }
}

// The number of segments whose cell sequence (single call or batch) differs from CGAL's traverser's.
std::size_t mismatches_with_cgal(const DT& dt, const Walk& walk, const std::vector<Segment>& segs) {
  std::vector<Walk::Query> queries;
  for (const Segment& x : segs) queries.push_back({x.q, x.p, x.hint});
  std::size_t mismatches = 0;
  std::vector<std::vector<DT::Cell_handle>> batch_cells(segs.size());
  walk.fast_batch(queries, [&](std::size_t i, const Piece& y) {
    if (y.dimension == 3) batch_cells[i].push_back(y.cell);
  });
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Segment& s = segs[i];
    std::vector<Piece> pieces;
    walk.fast(s.q, s.p, std::back_inserter(pieces), s.hint);
    std::vector<DT::Cell_handle> a, b;
    for (const Piece& x : pieces)
      if (x.dimension == 3) a.push_back(x.cell);
    for (DT::Cell_handle c : dt.segment_traverser_cell_handles(s.q, s.p, s.hint))
      if (!dt.is_infinite(c)) b.push_back(c);
    mismatches += a != b || batch_cells[i] != b;
  }
  return mismatches;
}

// Point_locator_3 against CGAL's locate() on `count` random points.
void measure_location(const DT& dt, std::size_t count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point> pts;
  for (std::size_t i = 0; i < count; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  const CGAL_ext::Point_locator_3<DT> locate(dt);
  std::vector<DT::Cell_handle> ours(count), cgal(count);
  std::vector<char> in_hull(count);
  // Each run returns the number of points located in a cell (all, for random points).
  auto run_ours = [&](bool hint) {
    std::size_t in_cell = 0;
    DT::Cell_handle h;
    for (std::size_t i = 0; i < count; ++i) {
      const auto l = locate(pts[i], hint ? h : DT::Cell_handle());
      ours[i] = h = l.cell;
      in_cell += l.dimension == 3;
    }
    return in_cell;
  };
  auto run_cgal = [&](bool hint) {
    std::size_t in_cell = 0;
    DT::Cell_handle h;
    DT::Locate_type lt;
    int li, lj;
    for (std::size_t i = 0; i < count; ++i) {
      cgal[i] = h = dt.locate(pts[i], lt, li, lj, hint ? h : DT::Cell_handle());
      in_cell += lt == DT::CELL;
      in_hull[i] = lt != DT::OUTSIDE_CONVEX_HULL;
    }
    return in_cell;
  };
  const std::array<std::function<std::size_t()>, 4> f = {[&] { return run_ours(false); }, [&] { return run_cgal(false); },
                                                         [&] { return run_ours(true); }, [&] { return run_cgal(true); }};
  std::printf("\npoint location, %zu random points, best of 5 interleaved rounds (thread CPU time), single thread\n", count);
  std::printf("%-6s | %12s %12s %12s %12s | %9s %9s\n", "", "Mpoints/s", "", "", "", "ratio to", "CGAL");
  std::printf("%-6s | %12s %12s %12s %12s | %9s %9s\n", "caches", "ours", "CGAL", "ours, hint", "CGAL, hint", "no hint",
              "hint");
  for (bool cold : {true, false}) {
    std::array<double, 4> best;
    std::array<std::size_t, 4> located;
    interleaved(5, cold, f, best, located);
    std::printf("%-6s | %12.3f %12.3f %12.3f %12.3f | %9.2f %9.2f\n", cold ? "cold" : "warm", count / best[0] / 1e6,
                count / best[1] / 1e6, count / best[2] / 1e6, count / best[3] / 1e6, best[1] / best[0], best[3] / best[2]);
  }
  run_ours(false);
  run_cgal(false);
  // Outside the convex hull CGAL gives an infinite cell, we give none (outside the domain).
  std::size_t differ = 0, outside = 0;
  for (std::size_t i = 0; i < count; ++i) {
    outside += !in_hull[i];
    differ += in_hull[i] ? ours[i] != cgal[i] : ours[i] != DT::Cell_handle();
  }
  std::printf("check  | %zu of %zu points located differently from CGAL (%zu outside the convex hull)\n", differ, count,
              outside);
}

} // namespace

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 100000;
  const std::size_t per_class = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2000;
  const unsigned seed = argc > 3 ? unsigned(std::strtoul(argv[3], nullptr, 10)) : 1u;
  if (n < 10 || per_class < 1) {
    std::fprintf(stderr, "usage: %s [N >= 10] [segments per class >= 1] [seed]\n", argv[0]);
    return 2;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point> pts;
  pts.reserve(n);
  for (std::size_t i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  auto t0 = std::chrono::steady_clock::now();
  DT dt(pts.begin(), pts.end());
  std::printf("Delaunay of %zu uniform random points in the unit cube (seed %u): %zu finite cells, built in %.2f s\n", n, seed,
              dt.number_of_finite_cells(), seconds_since(t0));

  const double spacing = std::cbrt(1.0 / double(n));
  const Segment_class classes[] = {{"short (0.5 h)", 0.5 * spacing}, {"medium (~10 cells)", 2.4 * spacing}, {"long (across)", -1}};

  t0 = std::chrono::steady_clock::now();
  const Walk walk(dt);
  std::printf("walker constructed in %.3f s; %zu segments per class, best of 5 interleaved rounds (thread CPU time), single thread\n\n",
              seconds_since(t0), per_class);
  std::printf("%-20s %-6s %9s %9s | %9s %9s %9s %9s %9s | %9s %9s %9s %9s\n", "", "", "", "", "Mcells/s", "", "", "", "",
              "ratio to", "CGAL", "", "");
  std::printf("%-20s %-6s %9s %9s | %9s %9s %9s %9s %9s | %9s %9s %9s %9s\n", "class", "caches", "segments", "cells/seg",
              "fast", "fast bat", "full", "full bat", "CGAL", "fast", "fast bat", "full", "full bat");

  for (const Segment_class& cl : classes) {
    const std::vector<Segment> segs = random_segments(dt, cl, per_class, rng);
    measure(dt, walk, cl, segs);
    // Cell sequences must agree on these generic segments (checked outside the timings).
    std::printf("%-20s %-6s %zu of %zu segments with a cell sequence (single call or batch) different from CGAL's\n", cl.name.c_str(), "check",
                mismatches_with_cgal(dt, walk, segs), segs.size());
  }
  measure_location(dt, 10 * per_class, rng);
  return 0;
}
