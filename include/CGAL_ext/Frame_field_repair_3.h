// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_REPAIR_3_H
#define CGAL_EXT_FRAME_FIELD_REPAIR_3_H

/// \file Frame_field_repair_3.h
/// Removal of the non-meshable singular edges and nodes of a frame field by
/// local re-optimisation around them.

#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/internal/seeded_rotation.h>
#include <CGAL_ext/internal/tets_around_vertices.h>

#include <CGAL/Real_timer.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// What `repair_singularities()` did.
struct Singularity_repair_report {
  /** @{ */
  /// Non-meshable singular edges before and after.
  std::size_t non_meshable_before = 0, non_meshable_after = 0;
  /** @} */
  /** @{ */
  /// Non-meshable nodes and curve turns before and after
  /// (`Singularity_graph::non_meshable_vertices()`).
  std::size_t non_meshable_nodes_before = 0, non_meshable_nodes_after = 0;
  /** @} */
  /** @{ */
  /// Rounds run, batches of regions re-optimised together, regions
  /// re-optimised, and regions kept (fewer defects than before).
  std::size_t rounds = 0, batches = 0, regions_tried = 0, regions_kept = 0;
  /** @} */
  /// Regions kept whose frames came from a restart (`Singularity_repair_options::restarts`).
  std::size_t regions_from_restarts = 0;
  /** @{ */
  /// Regions kept from the released rounds
  /// (`Singularity_repair_options::max_released_rounds`), and the
  /// tetrahedra with a hard constraint among them, left released.
  std::size_t regions_released = 0, tets_released = 0;
  /** @} */
  /// Tetrahedra in the regions kept.
  std::size_t tets_changed = 0;
  /** @{ */
  /// L-BFGS iterations of all the re-optimisations, and their sum over the
  /// tetrahedra re-optimised (a measure of the work, independent of the
  /// machine).
  std::size_t lbfgs_iterations = 0, lbfgs_tet_iterations = 0;
  /** @} */
  /** @{ */
  /// Smoothness energy before and after.
  double energy_before = 0, energy_after = 0;
  /** @} */
  /// Duration in seconds.
  double seconds = 0;
};

namespace internal {

// The non-meshable edges of a list of singular edges, by their vertices.
inline std::vector<std::array<std::size_t, 2>> non_meshable_edges(const std::vector<Singular_edge>& edges) {
  std::vector<std::array<std::size_t, 2>> out;
  for (const Singular_edge& e : edges)
    if (!is_meshable(e.type)) out.push_back(e.vertices);
  return out;
}

// The repair's defects: the non-meshable edges, then the vertices of
// non_meshable_nodes() as edges {v, v} (which the regions, clusters and
// counts below take as they take edges).
template <class Place>
std::vector<std::array<std::size_t, 2>> repair_defects(const std::vector<Singular_edge>& edges, Place place) {
  std::vector<std::array<std::size_t, 2>> out = non_meshable_edges(edges);
  for (std::size_t v : non_meshable_nodes(edges, place)) out.push_back({v, v});
  return out;
}

// A defect's weight: an edge outweighs any number of nodes a region can
// hold, so that a region never trades nodes for an edge.
inline std::size_t defect_weight(const std::array<std::size_t, 2>& d) { return d[0] == d[1] ? 1 : 1 << 16; }

inline std::size_t defect_weight(const std::vector<std::array<std::size_t, 2>>& defects) {
  std::size_t w = 0;
  for (const auto& d : defects) w += defect_weight(d);
  return w;
}

// The clusters of some edges: the vertex lists (sorted) of the sets of edges
// connected through shared vertices, ordered by their first edge.
inline std::vector<std::vector<std::size_t>> edge_clusters(const std::vector<std::array<std::size_t, 2>>& edges) {
  std::vector<std::size_t> parent(edges.size());
  for (std::size_t k = 0; k < edges.size(); ++k) parent[k] = k;
  std::function<std::size_t(std::size_t)> root = [&](std::size_t k) {
    return parent[k] == k ? k : parent[k] = root(parent[k]);
  };
  std::map<std::size_t, std::size_t> edge_at;
  for (std::size_t k = 0; k < edges.size(); ++k)
    for (std::size_t v : edges[k]) {
      const std::size_t a = root(edge_at.emplace(v, k).first->second), b = root(k);
      parent[std::max(a, b)] = std::min(a, b);
    }
  std::map<std::size_t, std::vector<std::size_t>> by_root;
  for (std::size_t k = 0; k < edges.size(); ++k)
    for (std::size_t v : edges[k]) by_root[root(k)].push_back(v);
  std::vector<std::vector<std::size_t>> out;
  for (auto& [r, vs] : by_root) {
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    out.push_back(std::move(vs));
  }
  return out;
}

// The state of `repair_singularities()`: the tetrahedra around each vertex,
// the matchings kept up to date, the defects, and scratch marks.
template <class Frame_field>
class Singularity_repairer {
public:
  using Start = typename Frame_field::Reoptimize_start;
  using Edges = std::vector<std::array<std::size_t, 2>>;

  Singularity_repairer(Frame_field& ff, const Singularity_repair_options& options, Singularity_repair_report& report)
      : ff_(ff), options_(options), report_(report), matchings_(ff), in_(ff.size(), 0), inner_(ff.size(), 0) {
    const std::size_t n = ff.size();
    std::size_t vertices = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 4; ++k) vertices = std::max(vertices, vertex(i, k) + 1);
    tets_around_vertices(ff, vertices, first_, star_);
    reached_.assign(vertices, 0);
    place_ = vertex_places(ff);
    bad_ = defects(singular_edges(ff, matchings_));
  }

  // The defects left: non-meshable edges, and nodes as {v, v}.
  const Edges& non_meshable() const { return bad_; }
  Edges defects(const std::vector<Singular_edge>& edges) const {
    return repair_defects(edges, [&](std::size_t v) { return place_[v]; });
  }
  // The tetrahedra that released rounds left released, in the order kept.
  const std::vector<std::size_t>& released() const { return released_; }
  // The matchings of the current frames (updated after every change).
  const Frame_field_matchings_3<Frame_field>& matchings() const { return matchings_; }

  // Round `index` (from 0): regions of `radius` rings around the clusters, in
  // batches of regions that share no vertex. A released round (`release`)
  // takes only the regions with a held hard constraint, and releases them.
  // Returns the regions tried and kept.
  std::pair<std::size_t, std::size_t> round(std::size_t index, int radius, int restarts, bool release = false) {
    std::vector<std::vector<std::size_t>> regions;
    for (const auto& cluster : edge_clusters(bad_)) regions.push_back(region(cluster, radius));
    if (release)
      regions.erase(std::remove_if(regions.begin(), regions.end(),
                                   [&](const std::vector<std::size_t>& tets) {
                                     return std::none_of(tets.begin(), tets.end(),
                                                         [&](std::size_t i) { return releasable(i); });
                                   }),
                    regions.end());
    std::size_t tried = 0, kept = 0;
    for (const std::vector<std::size_t>& batch : batches(regions)) {
      if (bad_.empty()) break;
      tried += batch.size();
      ++report_.batches;
      kept += repair_batch(index, restarts, regions, batch, release);
    }
    return {tried, kept};
  }

private:
  std::size_t vertex(std::size_t i, int k) const { return ff_.vertex_index(ff_.cell(i)->vertex(k)); }
  // Whether a released round can free tetrahedron i: a hard constraint, held.
  bool releasable(std::size_t i) const { return ff_.has_hard_constraint(i) && !ff_.hard_constraint_released(i); }

  // The tetrahedra within `radius` vertex rings of some vertices, sorted.
  std::vector<std::size_t> region(const std::vector<std::size_t>& seeds, int radius) {
    std::vector<std::size_t> tets, touched, ring = seeds;
    for (std::size_t v : ring) reached_[v] = 1, touched.push_back(v);
    for (int r = 0; r < radius && !ring.empty(); ++r) {
      std::vector<std::size_t> next;
      for (std::size_t v : ring)
        for (std::size_t s = first_[v]; s < first_[v + 1]; ++s) {
          const std::size_t i = star_[s];
          if (in_[i]) continue;
          in_[i] = 1;
          tets.push_back(i);
          for (int k = 0; k < 4; ++k) {
            const std::size_t w = vertex(i, k);
            if (!reached_[w]) reached_[w] = 1, touched.push_back(w), next.push_back(w);
          }
        }
      ring.swap(next);
    }
    for (std::size_t i : tets) in_[i] = 0;
    for (std::size_t v : touched) reached_[v] = 0;
    std::sort(tets.begin(), tets.end());
    return tets;
  }

  // A tetrahedron around edge e for which `pick` is true, or none (n).
  template <class Pick>
  std::size_t tet_around(const std::array<std::size_t, 2>& e, Pick pick) const {
    for (std::size_t s = first_[e[0]]; s < first_[e[0] + 1]; ++s) {
      const std::size_t i = star_[s];
      if (!pick(i)) continue;
      for (int k = 0; k < 4; ++k)
        if (vertex(i, k) == e[1]) return i;
    }
    return ff_.size();
  }

  // Batches of regions that share no vertex: an edge's tetrahedra then meet
  // at most one region of a batch, so its regions are re-optimised together
  // and judged one by one. At most 64 batches; a region that overlaps all of
  // them waits for the next round.
  std::vector<std::vector<std::size_t>> batches(const std::vector<std::vector<std::size_t>>& regions) {
    std::vector<std::uint64_t> claimed(reached_.size(), 0); // bit b: used by batch b
    std::vector<std::vector<std::size_t>> out;
    for (std::size_t r = 0; r < regions.size(); ++r) {
      std::uint64_t used = 0;
      for (std::size_t i : regions[r])
        for (int k = 0; k < 4; ++k) used |= claimed[vertex(i, k)];
      std::size_t b = 0;
      while (b < 64 && (used >> b & 1)) ++b;
      if (b == 64) continue;
      if (b == out.size()) out.emplace_back();
      out[b].push_back(r);
      for (std::size_t i : regions[r])
        for (int k = 0; k < 4; ++k) claimed[vertex(i, k)] |= std::uint64_t(1) << b;
    }
    return out;
  }

  // Re-optimises the regions of a batch (all other frames fixed) from each
  // start in turn: the relaxed one (as the whole field was made), the
  // propagated one, then the restarts, each start for the regions that
  // still have non-meshable edges. Keeps for each region the frames with the
  // fewest non-meshable edges, the lowest energy among equals, if fewer than
  // before; restores the others bit for bit. With `release`, the regions'
  // held hard constraints are released while they are re-optimised, and
  // stay so in the regions kept. Returns the regions kept.
  std::size_t repair_batch(std::size_t round, int restarts, const std::vector<std::vector<std::size_t>>& regions,
                           const std::vector<std::size_t>& batch, bool release) {
    const std::size_t m = batch.size();
    std::vector<std::size_t> tets, seeds;
    for (std::size_t r = 0; r < m; ++r)
      for (std::size_t i : regions[batch[r]]) {
        tets.push_back(i);
        for (int k = 0; k < 4; ++k) seeds.push_back(vertex(i, k));
      }
    // A change of the regions can retype only the edges within `reach`
    // rings of their vertices (a curve's direction is taken
    // `singular_curve_direction_span` edges away); those are typed from the
    // edges within that many more rings, as a count of all edges types them.
    std::sort(seeds.begin(), seeds.end());
    seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
    const int reach = singular_curve_direction_span + 1;
    // A region is judged by the edges its frames can retype: those with a
    // tetrahedron within `reach` rings of it (an edge near two regions
    // counts for both), so that a start cannot gain by pushing a defect just
    // outside the region's own tetrahedra. Their union is `inner`.
    std::vector<std::vector<std::size_t>> near(m);
    std::vector<std::size_t> inner;
    for (std::size_t r = 0; r < m; ++r) {
      std::vector<std::size_t> vertices;
      for (std::size_t i : regions[batch[r]])
        for (int k = 0; k < 4; ++k) vertices.push_back(vertex(i, k));
      std::sort(vertices.begin(), vertices.end());
      vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
      near[r] = region(vertices, reach);
      inner.insert(inner.end(), near[r].begin(), near[r].end());
    }
    std::sort(inner.begin(), inner.end());
    inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
    for (std::size_t i : inner) inner_[i] = 1;
    auto is_inner = [&](const std::array<std::size_t, 2>& e) {
      return tet_around(e, [&](std::size_t i) { return inner_[i] != 0; }) < ff_.size();
    };
    // The examination types the edges of `examined` as singular_edges() on
    // it would. It reaches one ring beyond the typing of the edges near
    // `inner`: a node there has edges one ring further out, whose typing
    // follows their curve `singular_curve_direction_span` edges on. Those
    // of no tetrahedron of the batch keep their holonomy while the batch is
    // re-optimised: found once (`outside`), and only the batch's own edges
    // again after each start.
    std::vector<internal::Singular_edge_holonomy> outside;
    {
      const std::vector<std::size_t> examined = region(seeds, reach + singular_curve_direction_span + 1);
      for (std::size_t i : tets) in_[i] = 1;
      for (auto& h : singular_edge_holonomies(ff_, matchings_, &examined, nullptr))
        if (tet_around(h.edge.vertices, [&](std::size_t i) { return in_[i] != 0; }) == ff_.size())
          outside.push_back(std::move(h));
      for (std::size_t i : tets) in_[i] = 0;
    }
    auto examine = [&] {
      const auto own = singular_edge_holonomies(ff_, matchings_, &tets, nullptr);
      std::vector<internal::Singular_edge_holonomy> all(outside.size() + own.size());
      std::merge(outside.begin(), outside.end(), own.begin(), own.end(), all.begin(),
                 [](const auto& a, const auto& b) { return a.edge.vertices < b.edge.vertices; });
      Edges out;
      for (const auto& e : defects(type_singular_edges(all)))
        if (is_inner(e)) out.push_back(e);
      return out;
    };
    auto count = [&](const Edges& edges) { // weighted, per region
      std::vector<std::size_t> c(m, 0);
      for (const auto& e : edges)
        for (std::size_t r = 0; r < m; ++r)
          if (tet_around(e, [&](std::size_t t) { return std::binary_search(near[r].begin(), near[r].end(), t); }) <
              ff_.size())
            c[r] += defect_weight(e);
      return c;
    };
    // The energy that a region's frames change: that of its tetrahedra and
    // their face neighbours (which meet no other region of the batch, as
    // they share three vertices with it).
    std::vector<std::vector<std::size_t>> energy_set(m);
    for (std::size_t r = 0; r < m; ++r) {
      std::vector<std::size_t>& set = energy_set[r];
      for (std::size_t i : regions[batch[r]]) {
        set.push_back(i);
        for (int f = 0; f < 4; ++f)
          if (ff_.neighbor(i, f) >= 0) set.push_back(std::size_t(ff_.neighbor(i, f)));
      }
      std::sort(set.begin(), set.end());
      set.erase(std::unique(set.begin(), set.end()), set.end());
    }
    // With `release`, the objective of the re-optimisation itself (the
    // region's faces and soft boundary terms), so that a start does not win
    // by leaving the boundary.
    auto energy = [&](std::size_t r) {
      if (release) {
        std::vector<Eigen::Vector3d> gradient;
        return ff_.refinement_objective(regions[batch[r]], gradient);
      }
      double e = 0;
      for (std::size_t i : energy_set[r]) e += ff_.local_smoothness_energy(i);
      return e;
    };
    Edges old_here; // typed as the examination types them (see above)
    for (const auto& e : bad_)
      if (is_inner(e)) old_here.push_back(e);
    struct Best {
      std::size_t count;
      double energy;
      std::vector<Eigen::Quaterniond> frames; // empty: the original ones
      int start;                              // the start that gave them
    };
    std::vector<Best> best(m);
    {
      const std::vector<std::size_t> before = count(old_here);
      for (std::size_t r = 0; r < m; ++r) best[r] = {before[r], energy(r), {}, -1};
    }
    std::vector<Eigen::Quaterniond> saved(tets.size());
    for (std::size_t k = 0; k < tets.size(); ++k) saved[k] = ff_.rotation_quaternion(tets[k]);
    // A released round frees the held constraints of its regions (those
    // released by an earlier batch stay so, whatever this one keeps).
    std::vector<std::size_t> freed;
    if (release) {
      for (std::size_t i : tets)
        if (releasable(i)) freed.push_back(i);
      ff_.release_hard_constraints(freed, true);
      std::sort(freed.begin(), freed.end());
    }

    // The relaxed start of the open regions `relaxed_open`, solved once for
    // all the restarts from it (the open regions change rarely).
    std::vector<std::size_t> relaxed_open;
    std::vector<Eigen::Quaterniond> relaxed;
    const int starts = 2 + restarts;
    for (int s = 0; s < starts; ++s) {
      std::vector<std::size_t> open, open_tets; // the regions still short of zero
      for (std::size_t r = 0; r < m; ++r)
        if (best[r].count > 0) open.push_back(r);
      if (open.empty()) break;
      for (std::size_t r : open) open_tets.insert(open_tets.end(), regions[batch[r]].begin(), regions[batch[r]].end());
      // Restart seeds differ between rounds, starts and batches (by their first tetrahedron).
      const std::uint64_t seed = s < 2 ? 0 : split_seed(std::uint64_t(round), std::uint64_t(s), tets.front());
      Start start = Start::propagated;
      if (s != 1) {
        if (open != relaxed_open) {
          ff_.start_frames(open_tets, Start::relaxed);
          relaxed_open = open;
          relaxed.resize(open_tets.size());
          for (std::size_t k = 0; k < open_tets.size(); ++k) relaxed[k] = ff_.rotation_quaternion(open_tets[k]);
        } else {
          for (std::size_t k = 0; k < open_tets.size(); ++k) ff_.set_rotation(open_tets[k], relaxed[k]);
        }
        start = Start::current;
      }
      const std::size_t iterations = std::size_t(
          ff_.reoptimize(open_tets, start, seed, options_.restart_angle_deg * M_PI / 180, options_.lbfgs_memory));
      report_.lbfgs_iterations += iterations;
      report_.lbfgs_tet_iterations += iterations * open_tets.size();
      matchings_.update(ff_, open_tets);
      const std::vector<std::size_t> now = count(examine());
      for (std::size_t r : open) {
        const double e = energy(r);
        if (now[r] < best[r].count || (now[r] == best[r].count && !best[r].frames.empty() && e < best[r].energy)) {
          best[r].count = now[r], best[r].energy = e, best[r].start = s;
          best[r].frames.clear();
          for (std::size_t i : regions[batch[r]]) best[r].frames.push_back(ff_.rotation_quaternion(i));
        }
      }
    }
    // Each region's best frames, or its original ones (`tets` lists the regions in turn).
    for (std::size_t r = 0, k = 0; r < m; ++r)
      for (std::size_t j = 0; j < regions[batch[r]].size(); ++j, ++k)
        ff_.set_rotation(tets[k], best[r].frames.empty() ? saved[k] : best[r].frames[j]);
    matchings_.update(ff_, tets);
    const Edges here = examine();
    // The tetrahedra of `freed` in region r; held again unless r is kept.
    auto freed_in = [&](std::size_t r) {
      std::vector<std::size_t> out;
      for (std::size_t i : regions[batch[r]])
        if (std::binary_search(freed.begin(), freed.end(), i)) out.push_back(i);
      return out;
    };
    for (std::size_t r = 0; r < m; ++r)
      if (best[r].frames.empty()) ff_.release_hard_constraints(freed_in(r), false);
    if (defect_weight(here) >= defect_weight(old_here)) { // a curve's typing reaches past a region: undo
      ff_.release_hard_constraints(freed, false);
      for (std::size_t k = 0; k < tets.size(); ++k) ff_.set_rotation(tets[k], saved[k]);
      matchings_.update(ff_, tets);
      for (std::size_t i : inner) inner_[i] = 0;
      return 0;
    }
    Edges now; // those elsewhere, and those examined now
    for (const auto& e : bad_)
      if (!is_inner(e)) now.push_back(e);
    now.insert(now.end(), here.begin(), here.end());
    bad_.swap(now);
    for (std::size_t i : inner) inner_[i] = 0;
    std::size_t kept = 0;
    for (std::size_t r = 0; r < m; ++r)
      if (!best[r].frames.empty()) {
        ++kept;
        report_.regions_from_restarts += best[r].start >= 2;
        report_.tets_changed += regions[batch[r]].size();
        const std::vector<std::size_t> now_released = freed_in(r);
        if (!now_released.empty()) {
          ++report_.regions_released;
          report_.tets_released += now_released.size();
          released_.insert(released_.end(), now_released.begin(), now_released.end());
        }
      }
    return kept;
  }

  // A restart's seed, never 0 (0 is no restart).
  static std::uint64_t split_seed(std::uint64_t round, std::uint64_t start, std::uint64_t tet) {
    const std::uint64_t h = split_mix_64(split_mix_64(split_mix_64(round) ^ start) ^ tet);
    return h == 0 ? 1 : h;
  }

  Frame_field& ff_;
  const Singularity_repair_options& options_;
  Singularity_repair_report& report_;
  Frame_field_matchings_3<Frame_field> matchings_;
  std::vector<std::size_t> first_, star_; // the tetrahedra around each vertex (compressed rows)
  std::vector<char> in_, reached_, inner_;
  std::vector<Vertex_place> place_;
  Edges bad_;
  std::vector<std::size_t> released_;
};

} // namespace internal

/// \ingroup PkgCGALExtFrames
/// Removes non-meshable singular edges (`is_meshable()` false: third and
/// half turns, quarter turns across their curve) and non-meshable nodes and
/// curve turns (`Singularity_graph::non_meshable_vertices()`) by local
/// re-optimisation.
///
/// The defects are the non-meshable edges and those vertices; an edge
/// outweighs any number of vertices in every count, so that a region never
/// trades vertices for an edge. Each round groups the defects into clusters
/// (connected through shared vertices) and takes around each cluster the
/// tetrahedra within `radius` vertex rings of its vertices: its region.
/// Regions that share no vertex form a batch and are re-optimised together
/// with all other frames fixed (`Frame_field_3::reoptimize()`, hard boundary
/// constraints held): from the `relaxed` start, the `propagated` one, and
/// the round's restarts (`Singularity_repair_options::restarts`: the relaxed
/// start turned by seeded random rotations), each start for the regions
/// that still have defects. Each region is judged alone, by the defects its
/// frames can retype (those within `singular_curve_direction_span + 1`
/// rings of it): of all its starts it keeps the frames with the fewest (the
/// lowest smoothness energy among equals) if fewer than before, and is
/// restored bit for bit otherwise. After the rounds of
/// `Singularity_repair_options::radii`, further rounds
/// (`max_further_rounds`, `further_radii`, `further_restarts`) go on from
/// the frames the previous ones left while defects remain, until a whole
/// turn of their radii keeps nothing. Then released rounds
/// (`max_released_rounds`) go on alike, for the regions that have hard
/// boundary constraints, with those released (soft boundary terms only: a
/// released tetrahedron at a feature curve or corner no longer holds its
/// tangent or corner frame), for defects that frames pinned to the
/// boundary force; a start is then judged by the re-optimisation's own
/// objective (smoothness and soft boundary terms). The regions kept stay
/// released (`Frame_field_3::hard_constraint_released()`), also for a
/// later call.
/// Only the edges within `singular_curve_direction_span + 1`
/// rings of the regions can change type; they are typed from the edges
/// within `singular_curve_direction_span + 1` more rings (the matchings are
/// updated, not recomputed), so a batch costs time in proportion to its
/// regions; if their count did not drop, the batch is undone. A final count
/// over all edges checks the result: the field is never left with more
/// non-meshable edges than before, nor with as many and more non-meshable
/// vertices. Deterministic: regions, their order, the restarts' rotations
/// and the optimisation do not depend on the thread count.
///
/// \tparam Frame_field a `Frame_field_3`
/// \param ff the frame field, after `compute()`; its frames are changed in
///        place and its statistics updated
/// \param options the options
/// \returns what was done
/// \throws std::invalid_argument for a radius below 1, a negative count of
///         restarts or rounds, a negative L-BFGS memory, or a restart angle
///         outside [0, 180] degrees
template <class Frame_field>
Singularity_repair_report repair_singularities(Frame_field& ff, const Singularity_repair_options& options = {}) {
  auto positive = [](const std::vector<int>& radii) {
    return std::all_of(radii.begin(), radii.end(), [](int r) { return r > 0; });
  };
  if (!positive(options.radii) || !positive(options.further_radii))
    throw std::invalid_argument("repair_singularities: region radii must be at least 1");
  if (options.max_further_rounds < 0 || options.max_released_rounds < 0 || options.further_restarts < 0 ||
      options.lbfgs_memory < 0 ||
      std::any_of(options.restarts.begin(), options.restarts.end(), [](int r) { return r < 0; }))
    throw std::invalid_argument("repair_singularities: restarts, rounds and lbfgs_memory must not be negative");
  if (!(options.restart_angle_deg >= 0 && options.restart_angle_deg <= 180))
    throw std::invalid_argument("repair_singularities: restart_angle_deg must be in [0, 180]");
  CGAL::Real_timer timer;
  timer.start();
  Singularity_repair_report report;
  report.energy_before = report.energy_after = ff.smoothness_energy();
  internal::Singularity_repairer<Frame_field> repairer(ff, options, report);
  auto count = [&](const std::vector<std::array<std::size_t, 2>>& defects, std::size_t& edges, std::size_t& nodes) {
    nodes = std::size_t(std::count_if(defects.begin(), defects.end(), [](const auto& d) { return d[0] == d[1]; }));
    edges = defects.size() - nodes;
  };
  count(repairer.non_meshable(), report.non_meshable_before, report.non_meshable_nodes_before);
  report.non_meshable_after = report.non_meshable_before;
  report.non_meshable_nodes_after = report.non_meshable_nodes_before;
  if (repairer.non_meshable().empty()) return report;
  std::vector<Eigen::Quaterniond> original(ff.size()); // to undo everything if the final check fails
  for (std::size_t i = 0; i < ff.size(); ++i) original[i] = ff.rotation_quaternion(i);
  auto round = [&](int radius, int restarts, bool release = false) {
    ++report.rounds;
    const auto [tried, kept] = repairer.round(report.rounds - 1, radius, restarts, release);
    report.regions_tried += tried;
    report.regions_kept += kept;
    if (options.progress) options.progress(int(report.rounds), radius, tried, kept, repairer.non_meshable().size());
    return kept;
  };
  for (std::size_t k = 0; k < options.radii.size() && !repairer.non_meshable().empty(); ++k)
    round(options.radii[k], k < options.restarts.size() ? options.restarts[k] : 0);
  // Further rounds, then released ones, each until a whole turn of their
  // radii keeps nothing.
  const std::size_t turn = options.further_radii.size();
  auto rounds_until_idle = [&](int max_rounds, bool release) {
    for (int k = 0, idle = 0; k < max_rounds && turn > 0 && idle < int(turn) && !repairer.non_meshable().empty(); ++k) {
      const std::size_t kept = round(options.further_radii[std::size_t(k) % turn], options.further_restarts, release);
      idle = kept > 0 ? 0 : idle + 1;
    }
  };
  rounds_until_idle(options.max_further_rounds, false);
  rounds_until_idle(options.max_released_rounds, true);
  // The final count from all edges: the field is never left worse (more
  // non-meshable edges, or as many and more nodes).
  count(repairer.defects(singular_edges(ff, repairer.matchings())), report.non_meshable_after,
        report.non_meshable_nodes_after);
  if (std::make_pair(report.non_meshable_after, report.non_meshable_nodes_after) >
      std::make_pair(report.non_meshable_before, report.non_meshable_nodes_before)) {
    ff.release_hard_constraints(repairer.released(), false);
    for (std::size_t i = 0; i < ff.size(); ++i) ff.set_rotation(i, original[i]);
    report.regions_released = report.tets_released = 0;
    report.non_meshable_after = report.non_meshable_before;
    report.non_meshable_nodes_after = report.non_meshable_nodes_before;
    report.regions_kept = report.regions_from_restarts = report.tets_changed = 0;
  }
  ff.update_statistics();
  report.energy_after = ff.smoothness_energy();
  report.seconds = timer.time();
  return report;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_FRAME_FIELD_REPAIR_3_H
