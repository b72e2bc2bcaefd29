// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the Medit .mesh reader and the triangulation built from its
// tetrahedra (read_tet_mesh): any input must give a triangulation holding
// every tetrahedron, positively oriented, with consistent adjacency and no
// two tetrahedra overlapping (a point strictly inside both), or an
// Input_error naming the file.
#include "fuzz_input.h"

#include <CGAL_ext/IO/read_tet_mesh.h>

#include <cstdlib>
#include <vector>

namespace {

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;

bool strictly_inside(const Tr::Point& x, Tr::Cell_handle c) {
  for (int m = 0; m < 4; ++m) {
    std::array<Tr::Point, 4> r;
    for (int k = 0; k < 4; ++k) r[std::size_t(k)] = k == m ? x : c->vertex(k)->point();
    if (CGAL::orientation(r[0], r[1], r[2], r[3]) != CGAL::POSITIVE) return false;
  }
  return true;
}

// An oracle independent of the library's overlap tests: the (rounded)
// centroid of a tetrahedron, where it is strictly inside it, must not be
// strictly inside another one.
void check_no_overlap(const Tr& tr) {
  std::vector<Tr::Cell_handle> cells;
  for (auto c : tr.finite_cell_handles()) cells.push_back(c);
  if (cells.size() > 512) return; // quadratic
  for (auto a : cells) {
    const Tr::Point x = CGAL::centroid(a->vertex(0)->point(), a->vertex(1)->point(), a->vertex(2)->point(),
                                       a->vertex(3)->point());
    if (!strictly_inside(x, a)) continue;
    for (auto b : cells)
      if (b != a && strictly_inside(x, b)) std::abort();
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".mesh");
  fuzz::expect_input_error_only(
      [&] {
        CGAL_ext::Tet_mesh_triangulation_3<> tr;
        CGAL_ext::IO::Medit_mesh mesh;
        const CGAL_ext::Tet_mesh_build_report report = CGAL_ext::IO::read_tet_mesh(path, tr, &mesh);
        // Every tetrahedron of the file is a positively oriented cell, and
        // the adjacency is consistent. (Not tr.is_valid(): its Euler check
        // fails on the non-manifold domains that the library accepts and
        // reports, e.g. blocks touching along an edge.)
        std::size_t domain_cells = 0;
        for (auto c : tr.all_cell_handles()) {
          for (int i = 0; i < 4; ++i) {
            const auto n = c->neighbor(i);
            if (n == nullptr || !n->has_neighbor(c) || n->neighbor(n->index(c)) != c) std::abort();
          }
          if (!c->info().in_domain()) continue;
          ++domain_cells;
          if (tr.is_infinite(c) ||
              CGAL::orientation(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                                c->vertex(3)->point()) != CGAL::POSITIVE)
            std::abort();
        }
        if (domain_cells != mesh.tetrahedra.size()) std::abort();
        check_no_overlap(tr);
        (void)report;
      },
      path);
  return 0;
}
