// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/internal/Boundary_overlap.h>

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>

namespace CGAL_ext {
namespace internal {

std::optional<std::array<std::size_t, 2>> find_boundary_overlap(const std::vector<std::array<double, 3>>& points,
                                                                 const std::vector<std::array<std::size_t, 3>>& triangles) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
  auto point = [&](std::size_t v) { return K::Point_3(points[v][0], points[v][1], points[v][2]); };
  std::vector<Box> boxes;
  boxes.reserve(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    boxes.emplace_back(point(t[0]).bbox() + point(t[1]).bbox() + point(t[2]).bbox(), i);
  }
  std::optional<std::array<std::size_t, 2>> found;
  auto test = [&](const Box& a, const Box& b) {
    std::array<std::size_t, 2> pair{std::min(a.info(), b.info()), std::max(a.info(), b.info())};
    if (found && !(pair < *found)) return;
    const auto &s = triangles[pair[0]], &t = triangles[pair[1]];
    for (std::size_t u : s)
      if (std::find(t.begin(), t.end(), u) != t.end()) return; // shares a vertex: not tested
    if (CGAL::do_intersect(K::Triangle_3(point(s[0]), point(s[1]), point(s[2])),
                           K::Triangle_3(point(t[0]), point(t[1]), point(t[2]))))
      found = pair;
  };
  // (closed boxes: triangles that only touch are found too)
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), test);
  return found;
}

} // namespace internal
} // namespace CGAL_ext
