// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_REPAIR_3_H
#define CGAL_EXT_FRAME_FIELD_REPAIR_3_H

/// \file Frame_field_repair_3.h
/// Removal of the non-meshable singular edges of a frame field by local
/// re-optimisation around them.

#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// Options of `repair_singularities()`.
struct Singularity_repair_options {
  /// The radii of the regions re-optimised around the non-meshable edges,
  /// in rings of tetrahedra sharing a vertex: one round per radius, in
  /// order, while non-meshable edges remain. A larger region gives the
  /// re-optimisation more room and other boundary values.
  std::vector<int> radii = {2, 3, 4};
  /// If set, called after each round with its number (from 1), the radius,
  /// the regions tried and accepted, and the non-meshable edges left.
  std::function<void(int round, int radius, std::size_t tried, std::size_t accepted, std::size_t left)> progress;
};

/// \ingroup PkgCGALExtFrames
/// What `repair_singularities()` did.
struct Singularity_repair_report {
  /// Non-meshable singular edges before and after.
  std::size_t non_meshable_before = 0, non_meshable_after = 0;
  /// Rounds run, batches of regions re-optimised together, regions
  /// re-optimised, and regions kept (fewer non-meshable edges than before).
  std::size_t rounds = 0, batches = 0, regions_tried = 0, regions_accepted = 0;
  /// Tetrahedra in the regions kept.
  std::size_t tets_changed = 0;
  /// Smoothness energy before and after.
  double energy_before = 0, energy_after = 0;
  /// Duration in seconds.
  double seconds = 0;
};

/// \ingroup PkgCGALExtFrames
/// Removes non-meshable singular edges (`is_meshable()` false: third and
/// half turns, quarter turns across their curve) by local re-optimisation.
///
/// Each round groups the non-meshable edges into clusters (connected through
/// shared vertices) and takes around each cluster the tetrahedra within
/// `radius` vertex rings of its vertices: its region. Regions that share no
/// vertex form a batch and are re-optimised together with all other frames
/// fixed (`Frame_field_3::reoptimize()`, hard boundary constraints kept):
/// first from the `relaxed` start, then, for the regions not improved, from
/// the `propagated` one. An edge's tetrahedra meet at most one region of a
/// batch, so each region is judged alone: it is kept if the edges around its
/// tetrahedra then hold fewer non-meshable edges, and restored bit for bit
/// otherwise. Only the edges within `singular_curve_direction_span + 1`
/// rings of the regions can change type; they are typed from the edges
/// within `singular_curve_direction_span` more rings (the matchings are
/// updated, not recomputed), so a batch
/// costs time in proportion to its regions; if their count did not drop,
/// the batch is undone. A final count over all
/// edges checks the result: the field is never left with more non-meshable
/// edges than before. Deterministic: regions, their order and the
/// optimisation do not depend on the thread count.
///
/// \tparam Frame_field a `Frame_field_3`
/// \param ff the frame field, after `compute()`; its frames are changed in
///        place and its statistics updated
/// \param options the options
/// \returns what was done
template <class Frame_field>
Singularity_repair_report repair_singularities(Frame_field& ff, const Singularity_repair_options& options = {}) {
  const auto start = std::chrono::steady_clock::now();
  Singularity_repair_report report;
  report.energy_before = report.energy_after = ff.smoothness_energy();
  const std::size_t n = ff.size();
  auto non_meshable = [&](const std::vector<Singular_edge>& edges) {
    std::vector<std::array<std::size_t, 2>> out;
    for (const Singular_edge& e : edges)
      if (!is_meshable(e.type)) out.push_back(e.vertices);
    return out;
  };
  Frame_field_matchings_3<Frame_field> matchings(ff);
  std::vector<std::array<std::size_t, 2>> bad = non_meshable(singular_edges(ff, matchings));
  report.non_meshable_before = report.non_meshable_after = bad.size();
  if (bad.empty()) return report;
  std::vector<Eigen::Quaterniond> original(n); // to undo everything if the final check fails
  for (std::size_t i = 0; i < n; ++i) original[i] = ff.rotation_quaternion(i);

  // The tetrahedra around each vertex (compressed rows).
  std::size_t vertices = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) vertices = std::max(vertices, ff.vertex_index(ff.cell(i)->vertex(k)) + 1);
  std::vector<std::size_t> first(vertices + 1, 0), star(4 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) ++first[ff.vertex_index(ff.cell(i)->vertex(k)) + 1];
  for (std::size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
  {
    std::vector<std::size_t> fill(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 4; ++k) star[fill[ff.vertex_index(ff.cell(i)->vertex(k))]++] = i;
  }
  auto vertex_of = [&](std::size_t i, int k) { return ff.vertex_index(ff.cell(i)->vertex(k)); };
  // The tetrahedra within `radius` vertex rings of some vertices, sorted.
  std::vector<char> in(n, 0), reached(vertices, 0);
  auto region_of = [&](const std::vector<std::size_t>& seeds, int radius) {
    std::vector<std::size_t> tets, touched, ring = seeds;
    for (std::size_t v : ring) reached[v] = 1, touched.push_back(v);
    for (int r = 0; r < radius && !ring.empty(); ++r) {
      std::vector<std::size_t> next;
      for (std::size_t v : ring)
        for (std::size_t s = first[v]; s < first[v + 1]; ++s) {
          const std::size_t i = star[s];
          if (in[i]) continue;
          in[i] = 1;
          tets.push_back(i);
          for (int k = 0; k < 4; ++k) {
            const std::size_t w = vertex_of(i, k);
            if (!reached[w]) reached[w] = 1, touched.push_back(w), next.push_back(w);
          }
        }
      ring.swap(next);
    }
    for (std::size_t i : tets) in[i] = 0;
    for (std::size_t v : touched) reached[v] = 0;
    std::sort(tets.begin(), tets.end());
    return tets;
  };
  // The region (index) an edge belongs to: that of a tetrahedron around it, or -1.
  std::vector<std::int64_t> label(n, -1);
  std::vector<char> in_inner(n, 0);
  const int reach = singular_curve_direction_span + 1;
  auto edge_region = [&](const std::array<std::size_t, 2>& e) {
    for (std::size_t s = first[e[0]]; s < first[e[0] + 1]; ++s) {
      const std::size_t i = star[s];
      if (label[i] < 0) continue;
      for (int k = 0; k < 4; ++k)
        if (vertex_of(i, k) == e[1]) return label[i];
    }
    return std::int64_t(-1);
  };

  for (int radius : options.radii) {
    if (bad.empty()) break;
    ++report.rounds;
    std::size_t tried = 0, accepted = 0;
    // Clusters: the non-meshable edges connected through shared vertices
    // (a chain of them along one curve is one defect), each with its region.
    std::vector<std::size_t> parent(bad.size());
    for (std::size_t k = 0; k < bad.size(); ++k) parent[k] = k;
    std::function<std::size_t(std::size_t)> root = [&](std::size_t k) {
      return parent[k] == k ? k : parent[k] = root(parent[k]);
    };
    {
      std::map<std::size_t, std::size_t> edge_at;
      for (std::size_t k = 0; k < bad.size(); ++k)
        for (std::size_t v : bad[k]) {
          const auto it = edge_at.emplace(v, k).first;
          const std::size_t a = root(it->second), b = root(k);
          parent[std::max(a, b)] = std::min(a, b);
        }
    }
    std::map<std::size_t, std::vector<std::size_t>> cluster_vertices; // by the root (its first edge)
    for (std::size_t k = 0; k < bad.size(); ++k)
      for (std::size_t v : bad[k]) cluster_vertices[root(k)].push_back(v);
    std::vector<std::vector<std::size_t>> regions;
    for (auto& [r, vs] : cluster_vertices) {
      std::sort(vs.begin(), vs.end());
      vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
      regions.push_back(region_of(vs, radius));
    }
    // Batches of regions that share no vertex: an edge's tetrahedra then meet
    // at most one region of a batch, so the regions of a batch are
    // re-optimised together and judged one by one.
    std::vector<std::uint64_t> claimed(vertices, 0); // bit b: used by batch b (b < 64)
    std::vector<std::vector<std::size_t>> batches;
    for (std::size_t r = 0; r < regions.size(); ++r) {
      std::uint64_t used = 0;
      for (std::size_t i : regions[r])
        for (int k = 0; k < 4; ++k) used |= claimed[vertex_of(i, k)];
      std::size_t b = 0;
      while (b < 64 && (used >> b & 1)) ++b;
      if (b == 64) continue; // more than 64 overlapping regions: left to the next round
      if (b == batches.size()) batches.emplace_back();
      batches[b].push_back(r);
      for (std::size_t i : regions[r])
        for (int k = 0; k < 4; ++k) claimed[vertex_of(i, k)] |= std::uint64_t(1) << b;
    }
    using Start = typename Frame_field::Reoptimize_start;
    for (const std::vector<std::size_t>& batch : batches) {
      tried += batch.size();
      ++report.batches;
      std::vector<std::size_t> pending = batch; // regions not yet improved
      // Two starts: the relaxed one (as the whole field was made), then, for
      // the regions it did not improve, the propagated one.
      for (const Start start : {Start::relaxed, Start::propagated}) {
        if (bad.empty() || pending.empty()) break;
        std::vector<std::size_t> tets, seeds;
        for (std::size_t m = 0; m < pending.size(); ++m)
          for (std::size_t i : regions[pending[m]]) {
            label[i] = std::int64_t(m), tets.push_back(i);
            for (int k = 0; k < 4; ++k) seeds.push_back(vertex_of(i, k));
          }
        // The edges whose type a change of the regions can change: those of
        // the tetrahedra within `reach` rings of the regions' vertices (a
        // curve's direction is taken `singular_curve_direction_span` edges
        // away). They are typed from the edges within
        // `singular_curve_direction_span` more rings, so that their curves'
        // directions are those a count of all edges finds.
        std::sort(seeds.begin(), seeds.end());
        seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
        const std::vector<std::size_t> inner = region_of(seeds, reach);
        const std::vector<std::size_t> examined = region_of(seeds, reach + singular_curve_direction_span);
        for (std::size_t i : inner) in_inner[i] = 1;
        auto inner_edge = [&](const std::array<std::size_t, 2>& e) {
          for (std::size_t s = first[e[0]]; s < first[e[0] + 1]; ++s)
            if (in_inner[star[s]])
              for (int k = 0; k < 4; ++k)
                if (vertex_of(star[s], k) == e[1]) return true;
          return false;
        };
        auto count = [&](const std::vector<std::array<std::size_t, 2>>& edges) {
          std::vector<std::size_t> c(pending.size(), 0);
          for (const auto& e : edges) {
            const std::int64_t r = edge_region(e);
            if (r >= 0) ++c[std::size_t(r)];
          }
          return c;
        };
        auto examine = [&] {
          std::vector<std::array<std::size_t, 2>> out;
          for (const auto& e : non_meshable(singular_edges(ff, matchings, &examined)))
            if (inner_edge(e)) out.push_back(e);
          return out;
        };
        const std::vector<std::array<std::size_t, 2>> old_here = examine();
        const std::vector<std::size_t> before = count(old_here);
        std::vector<Eigen::Quaterniond> saved(tets.size());
        for (std::size_t k = 0; k < tets.size(); ++k) saved[k] = ff.rotation_quaternion(tets[k]);
        ff.reoptimize(tets, start);
        matchings.update(ff, tets);
        std::vector<std::array<std::size_t, 2>> here = examine();
        const std::vector<std::size_t> after = count(here);
        std::vector<std::size_t> restored;
        for (std::size_t k = 0; k < tets.size(); ++k) {
          const std::size_t m = std::size_t(label[tets[k]]);
          if (after[m] < before[m]) continue;
          ff.set_rotation(tets[k], saved[k]);
          restored.push_back(tets[k]);
        }
        if (!restored.empty()) {
          matchings.update(ff, restored);
          here = examine();
        }
        for (std::size_t i : tets) label[i] = -1;
        if (here.size() >= old_here.size()) { // a curve's typing reaches past a region: undo
          for (std::size_t k = 0; k < tets.size(); ++k) ff.set_rotation(tets[k], saved[k]);
          matchings.update(ff, tets);
        } else {
          // The non-meshable edges: those elsewhere, and those examined now.
          std::vector<std::array<std::size_t, 2>> now;
          for (const auto& e : bad)
            if (!inner_edge(e)) now.push_back(e);
          now.insert(now.end(), here.begin(), here.end());
          bad.swap(now);
          std::vector<std::size_t> still;
          for (std::size_t m = 0; m < pending.size(); ++m) {
            if (after[m] < before[m]) {
              ++accepted;
              report.tets_changed += regions[pending[m]].size();
            } else {
              still.push_back(pending[m]);
            }
          }
          pending.swap(still);
        }
        for (std::size_t i : inner) in_inner[i] = 0;
      }
    }
    report.regions_tried += tried;
    report.regions_accepted += accepted;
    if (options.progress) options.progress(int(report.rounds), radius, tried, accepted, bad.size());
  }
  // The final count from all edges; the field is never left worse.
  bad = non_meshable(singular_edges(ff));
  if (bad.size() > report.non_meshable_before) {
    for (std::size_t i = 0; i < n; ++i) ff.set_rotation(i, original[i]);
    bad.resize(report.non_meshable_before);
    report.regions_accepted = report.tets_changed = 0;
  }
  ff.update_statistics();
  report.non_meshable_after = bad.size();
  report.energy_after = ff.smoothness_energy();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_FRAME_FIELD_REPAIR_3_H
