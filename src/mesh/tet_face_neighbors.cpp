// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/tet_face_neighbors.h>
#include <CGAL_ext/Input_error.h>

#include <algorithm>
#include <string>

namespace CGAL_ext {

std::vector<std::array<std::int64_t, 4>> tet_face_neighbors(const std::vector<std::array<std::size_t, 4>>& tets) {
  struct Facet {
    std::array<std::size_t, 3> v; // sorted
    std::size_t t;
    int f;
  };
  std::vector<Facet> facets;
  facets.reserve(4 * tets.size());
  for (std::size_t t = 0; t < tets.size(); ++t) {
    std::array<std::size_t, 4> s = tets[t];
    std::sort(s.begin(), s.end());
    if (std::adjacent_find(s.begin(), s.end()) != s.end())
      throw Input_error("", 0, "tetrahedron " + std::to_string(t + 1), "has a repeated vertex");
    for (int f = 0; f < 4; ++f) {
      Facet x{{}, t, f};
      for (int l = 0, k = 0; l < 4; ++l)
        if (l != f) x.v[std::size_t(k++)] = tets[t][std::size_t(l)];
      std::sort(x.v.begin(), x.v.end());
      facets.push_back(x);
    }
  }
  std::sort(facets.begin(), facets.end(), [](const Facet& a, const Facet& b) {
    return a.v != b.v ? a.v < b.v : a.t != b.t ? a.t < b.t : a.f < b.f;
  });
  std::vector<std::array<std::int64_t, 4>> n(tets.size(), {-1, -1, -1, -1});
  for (std::size_t k = 0; k < facets.size();) {
    std::size_t e = k + 1;
    while (e < facets.size() && facets[e].v == facets[k].v) ++e;
    if (e - k > 2)
      throw Input_error("", 0, "tetrahedra " + std::to_string(facets[k].t + 1) + ", " + std::to_string(facets[k + 1].t + 1) +
                                   " and " + std::to_string(facets[k + 2].t + 1),
                        "share one facet: the mesh is not a manifold");
    if (e - k == 2) {
      n[facets[k].t][std::size_t(facets[k].f)] = std::int64_t(facets[k + 1].t);
      n[facets[k + 1].t][std::size_t(facets[k + 1].f)] = std::int64_t(facets[k].t);
    }
    k = e;
  }
  return n;
}

} // namespace CGAL_ext
