// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"
#include "json_output.h"
#include "point_pairs_file.h"

#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Segment_walk_3.h>

#include <array>
#include <cstdio>
#include <iterator>

namespace CGAL_ext::cli {

namespace {

using Tr = Tet_mesh_triangulation_3<>;

// A piece as JSON: its dimension, its sorted 0-based vertex ids and its parameter interval.
Json piece_json(const Segment_walk_piece_3<Tr>& piece) {
  // At most 4 ids: an insertion sort (std::sort on a 4-array trips GCC 12's -Warray-bounds).
  std::array<std::size_t, 4> ids{};
  for (int j = 0; j <= piece.dimension; ++j) {
    const std::size_t id = piece.vertices[j]->info();
    int m = j;
    for (; m > 0 && ids[m - 1] > id; --m) ids[m] = ids[m - 1];
    ids[m] = id;
  }
  Json vertices = Json::array();
  for (int j = 0; j <= piece.dimension; ++j) vertices.push_back(ids[j]);
  return {{"dim", piece.dimension}, {"vertices", vertices}, {"t", {piece.t_in, piece.t_out}}};
}

} // namespace

int run_walk(const Walk_request& request) {
  Stage_timer timer;
  Tr tr;
  print_build_notes(IO::read_tet_mesh(request.mesh, tr), "the walk is the same on either orientation");
  timer.stage("read and build");
  // Read all segments first: a malformed line stops before any output.
  const std::vector<Point_pair> segments = read_point_pairs(request.segments, "qx qy qz px py pz");
  timer.stage("read segments");

  const Segment_walk_3<Tr, Is_tet_mesh_domain_cell> walk(tr, Is_tet_mesh_domain_cell());
  std::vector<Segment_walk_piece_3<Tr>> pieces;
  std::size_t total = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const auto& s = segments[i];
    const Tr::Point q(s.a[0], s.a[1], s.a[2]), p(s.b[0], s.b[1], s.b[2]);
    pieces.clear();
    if (request.fast) walk.fast(q, p, std::back_inserter(pieces));
    else walk(q, p, std::back_inserter(pieces));
    total += pieces.size();
    Json line = {{"segment", i}, {"pieces", Json::array()}};
    for (const auto& piece : pieces) line["pieces"].push_back(piece_json(piece));
    print_json_line(line);
  }
  timer.stage("walk");
  std::fprintf(stderr, "[summary] %zu segments, %zu pieces\n", segments.size(), total);
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
