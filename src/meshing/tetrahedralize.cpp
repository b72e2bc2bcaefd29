// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tetrahedral meshing with CGAL Mesh_3: closed surfaces read from a file
// (polyhedral domain with features) and built-in shapes (implicit or
// polyhedral domains), converted to a Medit_mesh. The only translation unit
// of the library that instantiates Mesh_3.
#include <CGAL_ext/tetrahedralize.h>

#include "../IO/input_file.h"
#include "read_closed_surface.h"

// False positives inside Boost.Graph (instantiated by detect_features).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/refine_mesh_3.h>
#include <CGAL/property_map.h>

#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <unistd.h>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>
#include <tuple>
#include <utility>

namespace CGAL_ext {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
namespace params = CGAL::parameters;

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Surface = CGAL::Surface_mesh<Point>;

// Polyhedral domains: input surfaces, box_with_hole, cube.
using Polyhedral_domain = CGAL::Polyhedral_mesh_domain_with_features_3<K, Surface>;
using Polyhedral_tr = CGAL::Mesh_triangulation_3<Polyhedral_domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Polyhedral_c3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Polyhedral_tr, Polyhedral_domain::Corner_index,
                                                                 Polyhedral_domain::Curve_index>;

// Implicit domains: ball, torus, blobby.
using Implicit_domain = CGAL::Labeled_mesh_domain_3<K>;
using Implicit_tr = CGAL::Mesh_triangulation_3<Implicit_domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Implicit_c3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Implicit_tr>;
using Implicit_function = std::function<double(const Point&)>;


using Clock = std::chrono::steady_clock;

// Seeds CGAL's default random generator for the duration of a meshing, and
// gives the caller's generator back afterwards.
class Seeded_default_random {
public:
  explicit Seeded_default_random(unsigned seed) : saved_(CGAL::get_default_random()) {
    CGAL::get_default_random() = CGAL::Random(seed);
  }
  ~Seeded_default_random() { CGAL::get_default_random() = saved_; }
  Seeded_default_random(const Seeded_default_random&) = delete;
  Seeded_default_random& operator=(const Seeded_default_random&) = delete;

private:
  CGAL::Random saved_;
};

} // namespace

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 0;
}

namespace {

std::string number(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

// The size and facet distance actually used, the estimated number of
// tetrahedra, and the memory limit in bytes (infinite for none).
struct Sizes {
  double size;
  double facet_distance;
  double estimated_tets;
  double memory_limit;
};

// Checks the options and fills in the automatic values. `volume` is the
// volume of the domain (or an upper bound), for the refusal of absurd sizes.
Sizes resolve_sizes(const Tetrahedralize_options& o, double bbox_diagonal, double volume, const std::string& file,
                    const std::string& element) {
  if (!std::isfinite(o.size) || o.size < 0)
    throw Input_error(file, 0, element,
                      "the size must be positive and finite, or 0 for automatic (got " + number(o.size) + ")");
  if (!std::isfinite(o.facet_distance) || o.facet_distance < 0)
    throw Input_error(file, 0, element,
                      "the facet distance must be positive and finite, or 0 for automatic (got " +
                          number(o.facet_distance) + ")");
  if (!(o.sharp_angle_deg > 0 && o.sharp_angle_deg <= 180))
    throw Input_error(file, 0, element,
                      "the sharp-edge angle must be in (0, 180] degrees (got " + number(o.sharp_angle_deg) + ")");
  if (!std::isfinite(o.max_automatic_size) || o.max_automatic_size < 0)
    throw Input_error(file, 0, element,
                      "the cap of the automatic size must be positive and finite, or 0 for none (got " +
                          number(o.max_automatic_size) + ")");
  Sizes s;
  s.size = o.size > 0 ? o.size : bbox_diagonal / 20;
  if (!(s.size > 0) || !std::isfinite(s.size)) // (before the cap, which would hide it)
    throw Input_error(file, 0, element, "the domain is degenerate: its bounding box has no extent");
  const bool capped = o.size == 0 && o.max_automatic_size > 0 && o.max_automatic_size < s.size;
  if (capped) s.size = o.max_automatic_size;
  s.facet_distance = o.facet_distance > 0 ? o.facet_distance : s.size / 10;
  if (!std::isfinite(o.memory_limit))
    throw Input_error(file, 0, element, "the memory limit must be finite (got " + number(o.memory_limit) + ")");
  const double estimate = tetrahedra_per_unit_volume * volume / (s.size * s.size * s.size);
  const double bytes = estimate * bytes_per_tetrahedron;
  const double limit = o.memory_limit > 0 ? o.memory_limit : o.memory_limit < 0 ? HUGE_VAL : physical_memory_bytes();
  // (a limit of 0 where the machine's memory is unknown: no limit)
  if (limit > 0 && !(bytes <= limit))
    throw Input_error(file, 0, element,
                      "the size " + number(s.size) +
                          (capped ? " (automatic: the diagonal / 20 capped at " + number(o.max_automatic_size) + ")"
                                  : std::string()) +
                          " is too small for this domain: about " + number(estimate) +
                          " tetrahedra would be made, needing about " + number(bytes / 1e9) + " GB, more than " +
                          (o.memory_limit > 0 ? "the memory limit of " : "the memory of this machine, ") +
                          number(limit / 1e9) + " GB (give a larger size" + (capped ? " or cap" : "") +
                          ", or a larger memory limit to go on)");
  s.estimated_tets = estimate;
  s.memory_limit = limit > 0 ? limit : HUGE_VAL;
  return s;
}

std::string sizes_text(const Sizes& s) {
  return "size " + number(s.size) + ", facet distance " + number(s.facet_distance);
}

// ---------------------------------------------------------------------------
// From the complex to the Medit mesh.

// Rotates a positively oriented tetrahedron (an even permutation keeps the
// orientation) so that its smallest index comes first and its second
// smallest second.
std::array<std::size_t, 4> canonical_tet(std::array<std::size_t, 4> t) {
  // Even permutations: the 3-cycles (0 1 2), and (0 1)(2 3) etc.
  const std::size_t m = static_cast<std::size_t>(std::min_element(t.begin(), t.end()) - t.begin());
  // Bring the smallest to position 0 with an even permutation: a double
  // transposition (0 m)(a b) where {a, b} is the complement of {0, m}.
  if (m == 1) t = {t[1], t[0], t[3], t[2]};
  else if (m == 2) t = {t[2], t[3], t[0], t[1]};
  else if (m == 3) t = {t[3], t[2], t[1], t[0]};
  // Rotate the last three (a 3-cycle is even) to bring their smallest first.
  while (t[1] > t[2] || t[1] > t[3]) t = {t[0], t[2], t[3], t[1]};
  return t;
}

// Rotates a triangle (keeping its orientation) so that its smallest index comes first.
std::array<std::size_t, 3> canonical_triangle(std::array<std::size_t, 3> t) {
  while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  return t;
}

// Sorts records by their vertex indices and splits them into two arrays.
template <std::size_t N>
void sort_records(std::vector<std::pair<std::array<std::size_t, N>, int>>& records,
                  std::vector<std::array<std::size_t, N>>& cells, std::vector<int>& references) {
  std::sort(records.begin(), records.end());
  cells.resize(records.size());
  references.resize(records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    cells[i] = records[i].first;
    references[i] = records[i].second;
  }
}

// The vertices of the cells of a complex, numbered in Hilbert-curve order
// (locality for the users of the mesh).
template <class C3t3>
struct Complex_vertices {
  using Vertex_handle = typename C3t3::Triangulation::Vertex_handle;
  std::unordered_map<Vertex_handle, std::size_t> first_index; // order of first use
  std::vector<Vertex_handle> handles;                         // by first use
  std::vector<Point> points;                                  // by first use
  std::vector<std::size_t> order;                             // Hilbert position -> first use
  std::vector<std::size_t> new_index;                         // first use -> Hilbert position

  explicit Complex_vertices(const C3t3& c3t3) {
    const auto& tr = c3t3.triangulation();
    const auto bare = tr.geom_traits().construct_point_3_object();
    first_index.reserve(c3t3.number_of_cells_in_complex() / 4 + 16);
    for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
      for (int i = 0; i < 4; ++i) {
        const Vertex_handle v = c->vertex(i);
        if (first_index.emplace(v, handles.size()).second) {
          handles.push_back(v);
          points.push_back(bare(tr.point(v)));
        }
      }
    order.resize(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    using Hilbert_traits = CGAL::Spatial_sort_traits_adapter_3<K, CGAL::Pointer_property_map<Point>::type>;
    CGAL::hilbert_sort(order.begin(), order.end(), Hilbert_traits(CGAL::make_property_map(points)));
    new_index.resize(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) new_index[order[i]] = i;
  }
  std::size_t index_of(Vertex_handle v) const { return new_index[first_index.find(v)->second]; }
};

// The protected sharp edges of the complex, sorted, with their curve indices.
template <class C3t3>
void add_complex_edges(const C3t3& c3t3, const Complex_vertices<C3t3>& vertices, IO::Medit_mesh& m) {
  const auto& first_index = vertices.first_index;
  const auto& new_index = vertices.new_index;
  std::vector<std::pair<std::array<std::size_t, 2>, int>> edges;
  for (auto e = c3t3.edges_in_complex_begin(); e != c3t3.edges_in_complex_end(); ++e) {
    const auto a = first_index.find(e->first->vertex(e->second));
    const auto b = first_index.find(e->first->vertex(e->third));
    if (a == first_index.end() || b == first_index.end()) continue;
    const std::size_t i = new_index[a->second], j = new_index[b->second];
    edges.emplace_back(std::array<std::size_t, 2>{std::min(i, j), std::max(i, j)},
                       static_cast<int>(c3t3.curve_index(*e)));
  }
  sort_records(edges, m.edges, m.edge_references);
}

// Converts the cells of the complex to a Medit mesh: vertices numbered in
// Hilbert order, tetrahedra positively oriented, boundary facets oriented
// outwards, everything sorted. Linear but for the sorts.
template <class C3t3>
IO::Medit_mesh to_medit_mesh(const C3t3& c3t3) {
  using Tr = typename C3t3::Triangulation;
  using Vertex_handle = typename Tr::Vertex_handle;
  using Cell_handle = typename Tr::Cell_handle;
  using Surface_patch_index = typename C3t3::Surface_patch_index;
  const Tr& tr = c3t3.triangulation();
  const auto bare = tr.geom_traits().construct_point_3_object();

  const Complex_vertices<C3t3> vertices(c3t3);
  const auto index_of = [&](Vertex_handle v) { return vertices.index_of(v); };

  IO::Medit_mesh m;
  m.vertices.resize(vertices.points.size());
  m.vertex_references.resize(vertices.points.size());
  for (std::size_t i = 0; i < vertices.order.size(); ++i) {
    const Point& p = vertices.points[vertices.order[i]];
    m.vertices[i] = {p.x(), p.y(), p.z()};
    const int dimension = c3t3.in_dimension(vertices.handles[vertices.order[i]]);
    m.vertex_references[i] = dimension >= 0 && dimension <= 3 ? dimension : 3;
  }

  // Surface patches, numbered 1, 2... in the order of their indices.
  std::map<Surface_patch_index, int> patch_reference;
  for (auto f = c3t3.facets_in_complex_begin(); f != c3t3.facets_in_complex_end(); ++f)
    patch_reference.emplace(c3t3.surface_patch_index(*f), 0);
  int next_patch = 1;
  for (auto& p : patch_reference) p.second = next_patch++;

  // Tetrahedra, and the facets between a cell of the complex and a cell
  // outside, oriented outwards: for a positive tetrahedron (0, 1, 2, 3) the
  // outward facet opposite vertex i is facet_vertices[i].
  static constexpr int facet_vertices[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::vector<std::pair<std::array<std::size_t, 4>, int>> tets;
  std::vector<std::pair<std::array<std::size_t, 3>, int>> triangles;
  tets.reserve(c3t3.number_of_cells_in_complex());
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    const Cell_handle ch = c;
    // perm[k]: the vertex of the cell at position k of the tetrahedron.
    std::array<int, 4> perm = {0, 1, 2, 3};
    const auto vertex_point = [&](int i) { return bare(tr.point(ch->vertex(i))); };
    // CGAL's cells are positively oriented; checked anyway with the exact predicate.
    if (CGAL::orientation(vertex_point(0), vertex_point(1), vertex_point(2), vertex_point(3)) == CGAL::NEGATIVE)
      std::swap(perm[0], perm[1]);
    std::array<std::size_t, 4> t;
    for (int k = 0; k < 4; ++k) t[k] = index_of(ch->vertex(perm[k]));
    tets.emplace_back(canonical_tet(t), static_cast<int>(c3t3.subdomain_index(ch)));
    for (int k = 0; k < 4; ++k) {
      const int i = perm[k];
      if (c3t3.is_in_complex(ch->neighbor(i))) continue;
      const std::array<std::size_t, 3> tri = {t[facet_vertices[k][0]], t[facet_vertices[k][1]], t[facet_vertices[k][2]]};
      int reference = 0;
      if (c3t3.is_in_complex(ch, i)) reference = patch_reference[c3t3.surface_patch_index(ch, i)];
      triangles.emplace_back(canonical_triangle(tri), reference);
    }
  }
  sort_records(tets, m.tetrahedra, m.tetrahedron_references);
  sort_records(triangles, m.triangles, m.triangle_references);

  add_complex_edges(c3t3, vertices, m);
  return m;
}

void fill_report(Tetrahedralize_report* report, const IO::Medit_mesh& m, const Sizes& s, Clock::time_point start,
                 std::string domain) {
  if (!report) return;
  report->size = s.size;
  report->vertices = m.vertices.size();
  report->tets = m.tetrahedra.size();
  report->boundary_triangles = m.triangles.size();
  report->seconds = std::chrono::duration<double>(Clock::now() - start).count();
  report->domain = std::move(domain);
}

// The optimizers aim at a smallest dihedral angle of 15 degrees. A bound,
// rather than Mesh_3's default 0 ("as good as possible"), keeps the
// exudation cheap: on fandisk with 1.8e5 tets, 5 s instead of 17 s, and a
// smallest angle of 15 instead of 12 degrees. No time limit: Mesh_3's
// default limit, the time of the refinement, would make the result depend
// on the load of the machine.
constexpr double sliver_bound_degrees = 15;

std::string optimize_text(const Tetrahedralize_options& o) {
  return o.optimize ? "perturbed and exuded (sliver bound " + number(sliver_bound_degrees) + " degrees)"
                    : std::string("not optimized");
}

// ---------------------------------------------------------------------------
// Mesh_3 in rounds.

// A Delaunay mesh has about 6 tetrahedra per vertex (5.5 to 6.5 measured on
// the built-in shapes): caps and progress are counted in vertices, as Mesh_3's.
constexpr double tets_per_vertex = 6;
// Meshes expected to be smaller are made in one call, as make_mesh_3 alone:
// they take seconds (1.3 10^5 vertices: about 8 s on this machine).
constexpr double vertices_for_rounds = 1.5e5;
// A round adds a quarter of the expected vertices (automatic rounds): each
// resumption rescans the whole mesh, about 2 s on a ball of 8.4 10^5
// tetrahedra (21 s in one call, 28 s in quarters, 27 s in eighths).
constexpr double rounds_per_estimate = 4;

// make_mesh_3, in rounds when the mesh is expected to be large: the first
// round stops at a vertex cap (Mesh_3's `maximal_number_of_vertices`), the
// next ones resume it with refine_mesh_3 (keeping the protecting balls of
// the sharp edges), each adding `round_vertices` (by default a quarter of
// the expected vertices), and `progress` reports after each. Resuming
// rescans the mesh for bad elements (doc/meshing.md: what it costs). A
// completed refinement that ends on a cap just takes one more, empty,
// round. The caps depend on
// the estimate only, so the result is as deterministic as one call. Beyond
// the vertices that the memory limit allows, meshing stops with an error
// that gives the count reached: the limit holds even where the estimate is
// wrong. `make(mesh_options)` calls make_mesh_3 with the domain's features
// parameter, without optimizers, which run at the end as in make_mesh_3.
//
// The first round also holds Mesh_3's protection of the sharp edges, which
// stops at the cap too: it is given room for `protection_vertices` (twice
// the sharp edges' length over the size, an upper bound of the protecting
// balls' centres, plus room for corners and initial points), so that only
// the memory limit can interrupt it.
template <class C3t3, class Domain, class Criteria, class Make>
C3t3 mesh_3_in_rounds(const Domain& domain, const Criteria& criteria, Make make, const Tetrahedralize_options& o,
                      const Sizes& s, std::size_t protection_vertices, const std::string& file,
                      const std::string& element, Clock::time_point start) {
  const double expected = s.estimated_tets / tets_per_vertex;
  const double allowed = s.memory_limit / bytes_per_tetrahedron / tets_per_vertex;
  const std::size_t hard_cap = std::isfinite(allowed) ? static_cast<std::size_t>(std::max(allowed, 1.0)) : 0;
  const std::size_t step = o.round_vertices > 0                ? o.round_vertices
                           : expected >= vertices_for_rounds ? static_cast<std::size_t>(expected / rounds_per_estimate)
                                                             : 0;
  const auto cap_for = [&](std::size_t cap) {
    return cap == 0 ? hard_cap : hard_cap == 0 ? cap : std::min(cap, hard_cap);
  };
  std::size_t cap = cap_for(step == 0 ? 0 : step + protection_vertices);
  CGAL::Mesh_error_code code = CGAL::CGAL_MESH_3_NO_ERROR;
  C3t3 c3t3 = make(params::mesh_3_options(params::maximal_number_of_vertices = cap,
                                          params::pointer_to_error_code = &code));
  while (code == CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED) {
    const std::size_t vertices = c3t3.triangulation().number_of_vertices();
    if (hard_cap != 0 && vertices >= hard_cap)
      throw Input_error(file, 0, element,
                        "meshing stopped at " + std::to_string(vertices) + " vertices (about " +
                            number(double(vertices) * tets_per_vertex) +
                            " tetrahedra), the most that the memory limit of " + number(s.memory_limit / 1e9) +
                            " GB allows; about " + number(s.estimated_tets) +
                            " tetrahedra were expected (give a larger size, or a larger memory limit to go on)");
    if (o.progress)
      o.progress(vertices, static_cast<std::size_t>(expected),
                 std::chrono::duration<double>(Clock::now() - start).count());
    cap = cap_for(cap + step);
    code = CGAL::CGAL_MESH_3_NO_ERROR;
    CGAL::refine_mesh_3(c3t3, domain, criteria, params::no_reset_c3t3(), params::no_perturb(), params::no_exude(),
                        params::no_lloyd(), params::no_odt(),
                        params::mesh_3_options(params::maximal_number_of_vertices = cap,
                                               params::pointer_to_error_code = &code));
  }
  if (o.optimize) {
    CGAL::perturb_mesh_3(c3t3, domain, params::time_limit = 0, params::sliver_bound = sliver_bound_degrees);
    CGAL::exude_mesh_3(c3t3, params::time_limit = 0, params::sliver_bound = sliver_bound_degrees);
  }
  return c3t3;
}

// ---------------------------------------------------------------------------
// Polyhedral domains.

// Meshes the inside of a closed, outward oriented, triangulated surface.
IO::Medit_mesh mesh_polyhedral(const Surface& surface, const Tetrahedralize_options& o, const std::string& file,
                               const std::string& element, std::string description,
                               Tetrahedralize_report* report, Clock::time_point start) {
  const CGAL::Bbox_3 box = PMP::bbox(surface);
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  const double volume = CGAL::to_double(PMP::volume(surface));
  const Sizes s = resolve_sizes(o, diagonal, volume, file, element);

  Seeded_default_random seeded(o.seed);
  CGAL::Random rng(o.seed);
  Polyhedral_domain domain(surface, &rng);
  if (o.sharp_features) domain.detect_features(o.sharp_angle_deg);
  // Room for the protection of the sharp edges in the first round of Mesh_3.
  std::vector<std::tuple<Polyhedral_domain::Curve_index, std::pair<Point, Polyhedral_domain::Index>,
                         std::pair<Point, Polyhedral_domain::Index>>>
      curves;
  double sharp_length = 0;
  if (o.sharp_features) {
    domain.get_curves(std::back_inserter(curves));
    for (const auto& c : curves) sharp_length += CGAL::to_double(domain.curve_length(std::get<0>(c)));
  }
  const std::size_t protection_vertices = static_cast<std::size_t>(2 * sharp_length / s.size) + 1000;

  const CGAL::Mesh_criteria_3<Polyhedral_tr> criteria(
      params::edge_size = s.size, params::facet_angle = 25, params::facet_size = s.size,
      params::facet_distance = s.facet_distance, params::cell_radius_edge_ratio = 3, params::cell_size = s.size);
  const Polyhedral_c3t3 c3t3 = mesh_3_in_rounds<Polyhedral_c3t3>(
      domain, criteria,
      [&](const auto& mesh_options) {
        return CGAL::make_mesh_3<Polyhedral_c3t3>(
            domain, criteria, o.sharp_features ? params::features(domain) : params::no_features(),
            params::no_lloyd(), params::no_odt(), params::no_perturb(), params::no_exude(), mesh_options);
      },
      o, s, protection_vertices, file, element, start);
  if (c3t3.number_of_cells_in_complex() == 0)
    throw Input_error(file, 0, element,
                      "meshing produced no tetrahedra (is the size " + number(s.size) + " too large for the domain?)");
  IO::Medit_mesh m = to_medit_mesh(c3t3);
  description += "; " + sizes_text(s) + "; sharp edges " +
                 (o.sharp_features ? "protected (" + number(o.sharp_angle_deg) + " degrees, " + std::to_string(m.edges.size()) + " mesh edges)"
                                   : std::string("not protected")) +
                 "; " + optimize_text(o);
  fill_report(report, m, s, start, std::move(description));
  return m;
}

// ---------------------------------------------------------------------------
// Built-in shapes.

// Adds a polygon soup triangle.
void add(std::vector<std::vector<std::size_t>>& faces, std::size_t a, std::size_t b, std::size_t c) {
  faces.push_back({a, b, c});
}

Surface surface_from_soup(std::vector<Point>& points, std::vector<std::vector<std::size_t>>& faces) {
  Surface s;
  PMP::polygon_soup_to_polygon_mesh(points, faces, s);
  return s;
}

// The cube [-1,1]^3, outward oriented.
Surface cube_surface() {
  std::vector<Point> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  // Quads (outward, counterclockwise seen from outside), split in two.
  const std::size_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<std::vector<std::size_t>> faces;
  for (const auto& q : quads) {
    add(faces, q[0], q[1], q[2]);
    add(faces, q[0], q[2], q[3]);
  }
  return surface_from_soup(points, faces);
}

constexpr std::size_t hole_sides = 96; // sides of the prism that stands for the cylinder
constexpr double hole_radius = 0.4;

// The box [-1,1]^2 x [-0.5,0.5] minus the prism over the regular
// `hole_sides`-gon of radius 0.4 around the z axis, outward oriented. The
// annuli at the top and bottom join polygon vertex i to the point of the
// square on the same ray (the square's corners are on rays 45 + 90k degrees).
Surface box_with_hole_surface() {
  const std::size_t n = hole_sides;
  const double pi = 3.14159265358979323846;
  std::vector<Point> points;
  // Index of: inner (0) / outer (1) ring, bottom (0) / top (1), position i.
  const auto id = [](int outer, int top, std::size_t i) { return ((outer * 2 + top) * n) + (i % n); };
  for (int outer = 0; outer < 2; ++outer)
    for (int top = 0; top < 2; ++top)
      for (std::size_t i = 0; i < n; ++i) {
        const double a = 2 * pi * static_cast<double>(i) / static_cast<double>(n);
        double x = std::cos(a), y = std::sin(a);
        if (outer) {
          const double m = std::max(std::abs(x), std::abs(y));
          x /= m;
          y /= m;
          // Exactly on the square (the corners included).
          if (std::abs(std::abs(x) - 1) < 1e-9) x = x > 0 ? 1 : -1;
          if (std::abs(std::abs(y) - 1) < 1e-9) y = y > 0 ? 1 : -1;
        } else {
          x *= hole_radius;
          y *= hole_radius;
        }
        points.emplace_back(x, y, top ? 0.5 : -0.5);
      }
  std::vector<std::vector<std::size_t>> faces;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + 1;
    // Top annulus (normal +z): inner i, outer i, outer j, inner j counterclockwise from above.
    add(faces, id(0, 1, i), id(1, 1, i), id(1, 1, j));
    add(faces, id(0, 1, i), id(1, 1, j), id(0, 1, j));
    // Bottom annulus (normal -z): reversed.
    add(faces, id(0, 0, i), id(1, 0, j), id(1, 0, i));
    add(faces, id(0, 0, i), id(0, 0, j), id(1, 0, j));
    // Outer walls (normal away from the axis).
    add(faces, id(1, 0, i), id(1, 0, j), id(1, 1, j));
    add(faces, id(1, 0, i), id(1, 1, j), id(1, 1, i));
    // Inner wall (normal towards the axis).
    add(faces, id(0, 0, i), id(0, 1, j), id(0, 0, j));
    add(faces, id(0, 0, i), id(0, 1, i), id(0, 1, j));
  }
  return surface_from_soup(points, faces);
}

// An implicit shape: negative inside, with a bounding sphere and box.
struct Implicit_shape {
  Implicit_function function;
  Point center;
  double bounding_radius; // of a sphere containing the shape, strictly
  double bbox_diagonal;   // of the shape's bounding box
  double volume;          // the shape's volume, or an upper bound
  std::string description;
};

double squared_norm(const Point& p) { return p.x() * p.x() + p.y() * p.y() + p.z() * p.z(); }

Implicit_shape ball_shape() {
  return {[](const Point& p) { return squared_norm(p) - 1; }, CGAL::ORIGIN, 2, 2 * std::sqrt(3.0),
          4.0 / 3 * 3.14159265358979323846, "built-in shape 'ball' (unit ball, implicit)"};
}

Implicit_shape torus_shape() {
  const double R = 1, r = 0.4;
  return {[R, r](const Point& p) {
            const double q = std::sqrt(p.x() * p.x() + p.y() * p.y()) - R;
            return q * q + p.z() * p.z() - r * r;
          },
          CGAL::ORIGIN, 2, std::sqrt(2 * CGAL::square(2 * (R + r)) + CGAL::square(2 * r)),
          2 * CGAL::square(3.14159265358979323846) * R * r * r,
          "built-in shape 'torus' (R = 1, r = 0.4, implicit)"};
}

Implicit_shape blobby_shape() {
  struct Ball {
    double x, y, z, r;
  };
  static constexpr Ball balls[] = {
      {0, 0, 0, 0.8}, {0.9, 0.2, 0.1, 0.5}, {-0.6, 0.5, 0.4, 0.45}, {0.1, -0.7, -0.3, 0.5}};
  constexpr double k = 0.08; // blending distance of the smooth minimum
  // Smooth minimum of the signed distances to the balls: -k log sum exp(-d/k),
  // shifted so that the exponents stay small.
  const auto f = [](const Point& p) {
    double d[4], m = 1e300;
    for (int i = 0; i < 4; ++i) {
      const Ball& b = balls[i];
      d[i] = std::sqrt(CGAL::square(p.x() - b.x) + CGAL::square(p.y() - b.y) + CGAL::square(p.z() - b.z)) - b.r;
      m = std::min(m, d[i]);
    }
    double s = 0;
    for (double di : d) s += std::exp(-(di - m) / k);
    return m - k * std::log(s);
  };
  // Bounding box of the balls, grown by the blend (at most k log 4).
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const Ball& b : balls) {
    const double c[3] = {b.x, b.y, b.z};
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], c[a] - b.r - k * std::log(4.0));
      hi[a] = std::max(hi[a], c[a] + b.r + k * std::log(4.0));
    }
  }
  const double diagonal = std::sqrt(CGAL::square(hi[0] - lo[0]) + CGAL::square(hi[1] - lo[1]) +
                                    CGAL::square(hi[2] - lo[2]));
  return {f, CGAL::ORIGIN, 2.5, diagonal, (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]),
          "built-in shape 'blobby' (smooth union of 4 balls, implicit)"};
}

IO::Medit_mesh mesh_implicit(const Implicit_shape& shape, const Tetrahedralize_options& o, const std::string& element,
                             Tetrahedralize_report* report, Clock::time_point start) {
  const Sizes s = resolve_sizes(o, shape.bbox_diagonal, shape.volume, "", element);
  Seeded_default_random seeded(o.seed);
  CGAL::Random rng(o.seed);
  const Implicit_domain domain = Implicit_domain::create_implicit_mesh_domain(
      shape.function, K::Sphere_3(shape.center, CGAL::square(shape.bounding_radius)),
      params::relative_error_bound = 1e-6, params::p_rng = &rng);
  const CGAL::Mesh_criteria_3<Implicit_tr> criteria(params::facet_angle = 25, params::facet_size = s.size,
                                                    params::facet_distance = s.facet_distance,
                                                    params::cell_radius_edge_ratio = 3, params::cell_size = s.size);
  const Implicit_c3t3 c3t3 = mesh_3_in_rounds<Implicit_c3t3>(
      domain, criteria,
      [&](const auto& mesh_options) {
        return CGAL::make_mesh_3<Implicit_c3t3>(domain, criteria, params::no_lloyd(), params::no_odt(),
                                                params::no_perturb(), params::no_exude(), mesh_options);
      },
      o, s, 0, "", element, start);
  if (c3t3.number_of_cells_in_complex() == 0)
    throw Input_error("", 0, element,
                      "meshing produced no tetrahedra (is the size " + number(s.size) + " too large for the shape?)");
  IO::Medit_mesh m = to_medit_mesh(c3t3);
  fill_report(report, m, s, start, shape.description + "; " + sizes_text(s) + "; " + optimize_text(o));
  return m;
}

} // namespace

IO::Medit_mesh tetrahedralize_surface(const std::string& path, const Tetrahedralize_options& options,
                                      Tetrahedralize_report* report) {
  const auto start = Clock::now();
  std::vector<std::string> repairs;
  const Surface surface = internal::read_closed_surface(path, repairs);
  std::string description = "surface '" + path + "' (" + std::to_string(surface.number_of_vertices()) +
                            " vertices, " + std::to_string(surface.number_of_faces()) + " triangles)";
  for (std::size_t i = 0; i < repairs.size(); ++i) description += (i == 0 ? "; repaired: " : ", ") + repairs[i];
  return mesh_polyhedral(surface, options, path, "", std::move(description), report, start);
}

IO::Medit_mesh tetrahedralize_builtin(const std::string& name, const Tetrahedralize_options& options,
                                      Tetrahedralize_report* report) {
  const auto start = Clock::now();
  const std::string element = "built-in shape '" + name + "'";
  if (name == "ball") return mesh_implicit(ball_shape(), options, element, report, start);
  if (name == "torus") return mesh_implicit(torus_shape(), options, element, report, start);
  if (name == "blobby") return mesh_implicit(blobby_shape(), options, element, report, start);
  if (name == "box_with_hole")
    return mesh_polyhedral(box_with_hole_surface(), options, "", element,
                           "built-in shape 'box_with_hole' ([-1,1]^2 x [-0.5,0.5] minus a " +
                               std::to_string(hole_sides) + "-gon prism of radius 0.4, polyhedral)",
                           report, start);
  if (name == "cube")
    return mesh_polyhedral(cube_surface(), options, "", element,
                           "built-in shape 'cube' ([-1,1]^3, polyhedral)", report, start);
  std::string valid;
  for (const std::string& n : builtin_shape_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw Input_error("", 0, element, "unknown shape; the built-in shapes are: " + valid);
}

std::vector<std::string> builtin_shape_names() { return {"ball", "blobby", "box_with_hole", "cube", "torus"}; }

} // namespace CGAL_ext
