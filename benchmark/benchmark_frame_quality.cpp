// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The quality of the frame fields that `metric-frames generate` makes with
// its default options (identity metric, Mesh_3 at the bounding-box diagonal
// / 20 for surfaces and built-in shapes), model by model: what decides
// whether an integer-grid map can mesh the field (singular edges of each
// kind, curves, nodes, curves ending inside the volume) and how smooth it
// is (face angles, energy, boundary alignment).
//
//   benchmark_frame_quality [size_fraction=F] [INPUT ...]
//
// INPUT: builtin:NAME, a closed surface (.off .obj .stl .ply) meshed by
// Mesh_3, or a tet mesh (.mesh, e.g. written by TetGen or Gmsh). Without
// INPUT: the built-in ball, torus, box_with_hole and blobby, then CGAL's
// fandisk, anchor, joint, rotor and elephant from the directory
// $CGAL_DATA_MESHES if it is set (see doc/benchmarks.md for unpacking
// Debian's libcgal-demo data). size_fraction: Mesh_3 size as a fraction of
// the bounding-box diagonal (default 1/20, generate's default).
#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/tetrahedralize.h>

#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Field = CGAL_ext::Metric_field_3<Tr>;
using Frames = CGAL_ext::Frame_field_3<Field>;

namespace {

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

double diagonal(const std::vector<std::array<double, 3>>& points) {
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& p : points)
    for (std::size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  return std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

// The mesh of an input, as generate makes it.
CGAL_ext::IO::Medit_mesh mesh_of(const std::string& input, double size_fraction) {
  namespace fs = std::filesystem;
  if (fs::path(input).extension() == ".mesh") return CGAL_ext::IO::read_medit_mesh(input);
  CGAL_ext::Tetrahedralize_options mo;
  if (size_fraction > 0) {
    // The size is a fraction of the domain's diagonal: mesh coarsely once
    // to find it (Mesh_3's own automatic size is the diagonal / 20).
    CGAL_ext::Tetrahedralize_options coarse;
    const bool builtin = input.rfind("builtin:", 0) == 0;
    const auto m = builtin ? CGAL_ext::tetrahedralize_builtin(input.substr(8), coarse)
                           : CGAL_ext::tetrahedralize_surface(input, coarse);
    mo.size = diagonal(m.vertices) * size_fraction;
  }
  return input.rfind("builtin:", 0) == 0 ? CGAL_ext::tetrahedralize_builtin(input.substr(8), mo)
                                         : CGAL_ext::tetrahedralize_surface(input, mo);
}

struct Quality {
  std::size_t tets = 0, singular = 0, plus = 0, minus = 0, non_meshable = 0, curves = 0, nodes = 0,
              interior_ends = 0;
  double angle_mean = 0, angle_median = 0, energy_per_weight = 0, align_mean = 0, align_max = 0;
  double seconds_mesh = 0, seconds_field = 0;
};

Quality measure(const std::string& input, double size_fraction) {
  Quality q;
  auto t = std::chrono::steady_clock::now();
  const CGAL_ext::IO::Medit_mesh mesh = mesh_of(input, size_fraction);
  q.seconds_mesh = since(t);
  t = std::chrono::steady_clock::now();
  Tr tr;
  CGAL_ext::build_triangulation_from_tets(mesh.vertices, mesh.tetrahedra, mesh.tetrahedron_references, tr);
  const Field field(tr, Eigen::Matrix3d::Identity().eval());
  Frames ff(field);
  const CGAL_ext::Frame_field_statistics& st = ff.compute(CGAL_ext::Frame_field_options());
  const CGAL_ext::Frame_field_matchings_3<Frames> matchings(ff);
  const auto edges = CGAL_ext::singular_edges(ff, matchings);
  const CGAL_ext::Singularity_graph graph = CGAL_ext::singularity_graph(ff, edges);
  q.seconds_field = since(t);

  q.tets = ff.size();
  q.singular = edges.size();
  for (const auto& e : edges) {
    q.plus += e.type == CGAL_ext::Singularity_type::plus_quarter;
    q.minus += e.type == CGAL_ext::Singularity_type::minus_quarter;
    q.non_meshable += !CGAL_ext::is_meshable(e.type);
  }
  q.curves = graph.curves.size();
  q.nodes = graph.nodes.size();
  q.interior_ends = graph.interior_ends;
  const CGAL_ext::Face_angle_statistics angles = matchings.face_angle_statistics(ff);
  q.angle_mean = angles.mean_deg;
  q.angle_median = angles.median_deg;
  q.energy_per_weight = st.smoothness_energy / st.total_face_weight;
  q.align_mean = st.boundary_error_mean_deg;
  q.align_max = st.boundary_error_max_deg;
  return q;
}

} // namespace

int main(int argc, char** argv) {
  double size_fraction = 0;
  std::vector<std::string> inputs;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("size_fraction=", 0) == 0) {
      size_fraction = std::atof(arg.c_str() + 14);
      if (!(size_fraction > 0 && size_fraction < 1)) {
        std::fprintf(stderr, "size_fraction must be in (0, 1), got '%s'\n", arg.c_str() + 14);
        return 2;
      }
    } else if (arg == "-h" || arg == "--help") {
      std::printf("usage: benchmark_frame_quality [size_fraction=F] [INPUT ...]\n"
                  "INPUT: builtin:NAME, a closed surface (.off .obj .stl .ply), or a tet mesh (.mesh)\n");
      return 0;
    } else {
      inputs.push_back(arg);
    }
  }
  if (inputs.empty()) {
    inputs = {"builtin:ball", "builtin:torus", "builtin:box_with_hole", "builtin:blobby"};
    if (const char* dir = std::getenv("CGAL_DATA_MESHES"))
      for (const char* model : {"fandisk", "anchor", "joint", "rotor", "elephant"})
        inputs.push_back(std::string(dir) + "/" + model + ".off");
  }
  std::printf("Frame-field quality with generate's default options (identity metric, Frame_field_options()), %d threads.\n"
              "Singular edges: all, +1/4, -1/4, non-meshable (neither quarter turn about the edge); curves, nodes, curves\n"
              "ending inside the volume; face angle between matched neighbouring frames (deg); energy per unit face\n"
              "weight; boundary alignment error (deg); seconds for Mesh_3 and for the field (triangulation to curves).\n\n",
              tbb::info::default_concurrency());
  std::printf("%-22s %8s %6s %5s %5s %5s %6s %5s %6s %8s %8s %8s %7s %7s %7s %7s\n", "model", "tets", "sing", "+1/4",
              "-1/4", "nonm", "curves", "nodes", "in-end", "ang.mean", "ang.med", "E/w", "al.mean", "al.max", "mesh s",
              "field s");
  int failures = 0;
  for (const std::string& input : inputs) {
    const std::string name = input.rfind("builtin:", 0) == 0 ? input : std::filesystem::path(input).filename().string();
    try {
      const Quality q = measure(input, size_fraction);
      std::printf("%-22s %8zu %6zu %5zu %5zu %5zu %6zu %5zu %6zu %8.3f %8.3f %8.4f %7.3f %7.2f %7.1f %7.1f\n",
                  name.c_str(), q.tets, q.singular, q.plus, q.minus, q.non_meshable, q.curves, q.nodes, q.interior_ends,
                  q.angle_mean, q.angle_median, q.energy_per_weight, q.align_mean, q.align_max, q.seconds_mesh,
                  q.seconds_field);
    } catch (const std::exception& e) {
      std::printf("%-22s error: %s\n", name.c_str(), e.what());
      ++failures;
    }
    std::fflush(stdout);
  }
  return failures == 0 ? 0 : 1;
}
