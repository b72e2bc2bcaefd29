// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"
#include "point_pairs_file.h"

#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Segment_walk_3.h>

#include <algorithm>
#include <cstdio>
#include <iterator>

namespace CGAL_ext::cli {

namespace {
const char* walk_help =
    "Usage: metric-frames walk MESH --segments FILE\n\n"
    "For each segment q -> p of FILE (one per line: qx qy qz px py pz; blank\n"
    "lines and lines starting with # are skipped), prints one JSON object per\n"
    "line on stdout, in order:\n\n"
    "  {\"segment\": i, \"pieces\": [{\"dim\": d, \"vertices\": [...], \"t\": [t_in, t_out]}, ...]}\n\n"
    "i counts the segments from 0. The pieces are every vertex (dim 0), edge (1),\n"
    "facet (2) and tetrahedron (3) of the mesh whose relative interior meets the\n"
    "closed segment x(t) = q + t (p - q), t in [0, 1], in order along it, and the\n"
    "parts outside the mesh (dim -1, \"vertices\": []). \"vertices\" are the sorted\n"
    "0-based vertex indices of the mesh file. A crossing of a facet, an edge or a\n"
    "vertex has t_in = t_out; the pieces tile [0, 1]. Which simplex is met is\n"
    "decided with exact predicates; t is computed in double.\n\n"
    "Options:\n"
    "  --segments FILE   the segments (- for standard input)\n"
    "  --fast            only the pieces of positive length\n"
    "  -h, --help        this help\n";
}

int command_walk(const std::vector<std::string>& args) {
  Arguments a(args, "walk", walk_help);
  if (a.help_requested()) return 0;
  const std::string segments_path = a.required_option("--segments");
  const bool fast = a.flag("--fast");
  const std::string mesh_path = a.positional("MESH");
  a.finish();

  Stage_timer timer;
  using Tr = Tet_mesh_triangulation_3<>;
  Tr tr;
  IO::read_tet_mesh(mesh_path, tr);
  timer.stage("read and build");
  // Read all segments first: a malformed line stops before any output.
  const std::vector<Point_pair> segments = read_point_pairs(segments_path);
  timer.stage("read segments");

  const Segment_walk_3<Tr, Is_tet_mesh_domain_cell> walk(tr, Is_tet_mesh_domain_cell());
  std::vector<Segment_walk_piece_3<Tr>> pieces;
  std::size_t total = 0;
  std::string out;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const auto& s = segments[i];
    const Tr::Point q(s.a[0], s.a[1], s.a[2]), p(s.b[0], s.b[1], s.b[2]);
    pieces.clear();
    if (fast) walk.fast(q, p, std::back_inserter(pieces));
    else walk(q, p, std::back_inserter(pieces));
    total += pieces.size();
    out = "{\"segment\": " + std::to_string(i) + ", \"pieces\": [";
    char buf[96];
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const auto& piece = pieces[k];
      // At most 4 ids: an insertion sort (std::sort on a 4-array trips GCC 12's -Warray-bounds).
      std::array<std::size_t, 4> ids{};
      for (int j = 0; j <= piece.dimension; ++j) {
        const std::size_t id = piece.vertices[j]->info();
        int m = j;
        for (; m > 0 && ids[m - 1] > id; --m) ids[m] = ids[m - 1];
        ids[m] = id;
      }
      out += (k ? ", {\"dim\": " : "{\"dim\": ") + std::to_string(piece.dimension) + ", \"vertices\": [";
      for (int j = 0; j <= piece.dimension; ++j) out += (j ? ", " : "") + std::to_string(ids[j]);
      std::snprintf(buf, sizeof buf, "], \"t\": [%.17g, %.17g]}", piece.t_in, piece.t_out);
      out += buf;
    }
    out += "]}\n";
    std::fputs(out.c_str(), stdout);
  }
  timer.stage("walk");
  std::fprintf(stderr, "[summary] %zu segments, %zu pieces\n", segments.size(), total);
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
