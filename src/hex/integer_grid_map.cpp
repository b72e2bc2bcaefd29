// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/Integer_grid_map_3.h>
#include <CGAL_ext/Octahedral_frame.h>

#include <Eigen/LU>
#include <Eigen/SparseCore>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace CGAL_ext {
namespace {

// The local vertex pairs of a tetrahedron's six edges.
constexpr int edge_vertices[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// Products and inverses in octahedral_group(), by index.
struct Group_table {
  std::array<std::array<int, 24>, 24> product{};
  std::array<int, 24> inverse{};
  Group_table() {
    const auto& g = octahedral_group();
    for (int a = 0; a < 24; ++a) {
      for (int b = 0; b < 24; ++b) product[a][b] = octahedral_group_index(g[a] * g[b]);
      inverse[a] = octahedral_group_index(g[a].transpose());
    }
  }
  int operator()(int a, int b) const { return product[a][b]; }
};
const Group_table& group_table() {
  static const Group_table table;
  return table;
}

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("compute_integer_grid_map: " + what); }
std::string tet_name(std::size_t t) { return "tetrahedron " + std::to_string(t + 1); }

int local_index(const std::array<std::size_t, 4>& tet, std::size_t v) {
  for (int l = 0; l < 4; ++l)
    if (tet[std::size_t(l)] == v) return l;
  return -1;
}

// The interior faces (each once), the edges, and the cut.
struct Topology {
  struct Face {
    std::size_t t, u; // the tetrahedra, t < u
    int f, g;         // their local facets
  };
  std::vector<Face> faces;
  std::vector<std::array<std::int64_t, 4>> face_of; // per facet: face index or -1
  std::vector<std::array<std::size_t, 2>> edges;     // sorted vertex pairs
  std::vector<std::array<std::size_t, 6>> tet_edges;
  std::vector<int> chart;      // per tetrahedron: the combing rotation C_t
  std::vector<char> cut;       // per face
  std::vector<std::size_t> component_root; // the lowest tetrahedron of each component
  std::vector<std::size_t> component;      // per tetrahedron
};

void check_input(const Integer_grid_map_input& in) {
  const std::size_t n = in.tets.size();
  if (in.neighbors.size() != n || in.matchings.size() != n || in.gradients.size() != n)
    fail("tets, neighbors, matchings and gradients must have one entry per tetrahedron");
  if (!in.free_boundary.empty() && in.free_boundary.size() != n)
    fail("free_boundary must be empty or have one entry per tetrahedron");
  for (std::size_t v = 0; v < in.positions.size(); ++v)
    if (!in.positions[v].allFinite()) fail("vertex " + std::to_string(v + 1) + " has a coordinate that is not finite");
  for (std::size_t t = 0; t < n; ++t) {
    for (std::size_t v : in.tets[t])
      if (v >= in.positions.size()) fail(tet_name(t) + " has a vertex index out of range");
    const auto& p = in.positions;
    const auto& q = in.tets[t];
    Eigen::Matrix3d D;
    D << p[q[1]] - p[q[0]], p[q[2]] - p[q[0]], p[q[3]] - p[q[0]];
    if (!(D.determinant() > 0)) fail(tet_name(t) + " is flat or negatively oriented");
    if (!in.gradients[t].allFinite() || !(in.gradients[t].determinant() > 0))
      fail(tet_name(t) + ": its gradients are not finite or not positively oriented");
  }
}

// Faces, with the neighbours and matchings checked from both sides.
void build_faces(const Integer_grid_map_input& in, Topology& top) {
  const std::size_t n = in.tets.size();
  top.face_of.assign(n, {-1, -1, -1, -1});
  for (std::size_t t = 0; t < n; ++t)
    for (int f = 0; f < 4; ++f) {
      const std::int64_t nb = in.neighbors[t][std::size_t(f)];
      if (nb < 0) {
        if (in.matchings[t][std::size_t(f)] != -1) fail(tet_name(t) + ": a boundary facet has a matching");
        continue;
      }
      if (std::size_t(nb) >= n || std::size_t(nb) == t) fail(tet_name(t) + " has a neighbour index out of range");
      const auto u = std::size_t(nb);
      int g = -1;
      for (int h = 0; h < 4; ++h)
        if (in.neighbors[u][std::size_t(h)] == std::int64_t(t)) g = h;
      const int m = in.matchings[t][std::size_t(f)];
      if (g < 0 || m < 0 || m >= 24 || in.matchings[u][std::size_t(g)] != group_table().inverse[m])
        fail(tet_name(t) + " and " + tet_name(u) + " do not agree on their face (neighbours or matchings)");
      for (int l = 0; l < 4; ++l)
        if (l != f && local_index(in.tets[u], in.tets[t][std::size_t(l)]) < 0)
          fail(tet_name(t) + " and " + tet_name(u) + " are neighbours without sharing a face");
      if (t < u) {
        top.face_of[t][std::size_t(f)] = std::int64_t(top.faces.size());
        top.face_of[u][std::size_t(g)] = std::int64_t(top.faces.size());
        top.faces.push_back({t, u, f, g});
      }
    }
}

void build_edges(const Integer_grid_map_input& in, Topology& top) {
  const std::size_t n = in.tets.size();
  std::vector<std::array<std::size_t, 3>> all; // (a, b, 6 t + e)
  all.reserve(6 * n);
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t e = 0; e < 6; ++e) {
      std::size_t a = in.tets[t][std::size_t(edge_vertices[e][0])], b = in.tets[t][std::size_t(edge_vertices[e][1])];
      if (a > b) std::swap(a, b);
      all.push_back({a, b, 6 * t + e});
    }
  std::sort(all.begin(), all.end());
  top.tet_edges.assign(n, {});
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (k == 0 || all[k][0] != all[k - 1][0] || all[k][1] != all[k - 1][1]) top.edges.push_back({all[k][0], all[k][1]});
    top.tet_edges[all[k][2] / 6][all[k][2] % 6] = top.edges.size() - 1;
  }
}

// Combs the matchings along a breadth-first dual spanning tree; the faces off
// the tree are cut.
void comb(const Integer_grid_map_input& in, Topology& top) {
  const std::size_t n = in.tets.size();
  const auto& G = group_table();
  top.chart.assign(n, -1);
  top.component.assign(n, 0);
  top.cut.assign(top.faces.size(), 1);
  std::deque<std::size_t> queue;
  for (std::size_t root = 0; root < n; ++root) {
    if (top.chart[root] >= 0) continue;
    top.component_root.push_back(root);
    top.chart[root] = 0;
    queue.push_back(root);
    while (!queue.empty()) {
      const std::size_t t = queue.front();
      queue.pop_front();
      top.component[t] = top.component_root.size() - 1;
      for (std::size_t f = 0; f < 4; ++f) {
        const std::int64_t u = in.neighbors[t][f];
        if (u < 0 || top.chart[std::size_t(u)] >= 0) continue;
        // C_u = C_t G^-1: the combed matching C_u G C_t^-1 is the identity.
        top.chart[std::size_t(u)] = G(top.chart[t], G.inverse[in.matchings[t][f]]);
        top.cut[std::size_t(top.face_of[t][f])] = 0;
        queue.push_back(std::size_t(u));
      }
    }
  }
}

// The combed matching from t across its facet f: C_u G C_t^-1.
int combed_matching(const Integer_grid_map_input& in, const Topology& top, std::size_t t, std::size_t f) {
  const auto& G = group_table();
  const auto u = std::size_t(in.neighbors[t][f]);
  return G(G(top.chart[u], in.matchings[t][f]), G.inverse[top.chart[t]]);
}

// The loop of faces around an edge, from a tetrahedron that has it, and the
// holonomy (the product of combed matchings around it, in the chart of that
// tetrahedron); empty faces for an edge on the boundary.
struct Edge_loop {
  std::size_t start = 0;
  std::vector<std::size_t> faces;
  int holonomy = 0;
};

Edge_loop edge_loop(const Integer_grid_map_input& in, const Topology& top, std::size_t t, int local_edge) {
  const auto& G = group_table();
  const auto& q = in.tets[t];
  const std::size_t a = q[std::size_t(edge_vertices[local_edge][0])], b = q[std::size_t(edge_vertices[local_edge][1])];
  std::size_t opposite = a, keep = a;
  for (std::size_t v : q)
    if (v != a && v != b) (opposite == a ? opposite : keep) = v;
  Edge_loop loop;
  loop.start = t;
  std::size_t cur = t;
  for (std::size_t step = 0; step <= in.tets.size(); ++step) {
    const auto f = std::size_t(local_index(in.tets[cur], opposite));
    if (in.neighbors[cur][f] < 0) return Edge_loop{t, {}, 0};
    loop.faces.push_back(std::size_t(top.face_of[cur][f]));
    loop.holonomy = G(combed_matching(in, top, cur, f), loop.holonomy);
    const auto next = std::size_t(in.neighbors[cur][f]);
    std::size_t fresh = a; // the vertex of next off the face crossed
    for (std::size_t v : in.tets[next])
      if (v != a && v != b && v != keep) fresh = v;
    opposite = keep;
    keep = fresh;
    cur = next;
    if (cur == t) return loop;
  }
  throw std::logic_error("compute_integer_grid_map: the tetrahedra around an edge do not close");
}

// The loops of the interior edges (boundary edges: no faces), one per edge,
// from the lowest tetrahedron that has it.
std::vector<Edge_loop> edge_loops(const Integer_grid_map_input& in, const Topology& top) {
  std::vector<Edge_loop> loops(top.edges.size());
  std::vector<char> done(top.edges.size(), 0);
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    for (int e = 0; e < 6; ++e) {
      const std::size_t id = top.tet_edges[t][std::size_t(e)];
      if (!done[id]) done[id] = 1, loops[id] = edge_loop(in, top, t, e);
    }
  return loops;
}

// Glues back the cut faces that a regular interior edge determines, until
// no regular interior edge has exactly one cut face around it.
void glue(Topology& top, const std::vector<Edge_loop>& loops) {
  std::vector<std::size_t> cut_around(loops.size(), 0);
  for (std::size_t e = 0; e < loops.size(); ++e)
    for (std::size_t f : loops[e].faces) cut_around[e] += top.cut[f];
  auto gluable = [&](std::size_t e) { return !loops[e].faces.empty() && loops[e].holonomy == 0 && cut_around[e] == 1; };
  std::deque<std::size_t> queue;
  for (std::size_t e = 0; e < loops.size(); ++e)
    if (gluable(e)) queue.push_back(e);
  while (!queue.empty()) {
    const std::size_t e = queue.front();
    queue.pop_front();
    if (!gluable(e)) continue;
    std::size_t face = 0;
    for (std::size_t f : loops[e].faces)
      if (top.cut[f]) face = f;
    top.cut[face] = 0;
    const auto& fc = top.faces[face];
    for (int k = 0; k < 6; ++k) {
      if (edge_vertices[k][0] == fc.f || edge_vertices[k][1] == fc.f) continue; // not an edge of the face
      const std::size_t e2 = top.tet_edges[fc.t][std::size_t(k)];
      --cut_around[e2];
      if (gluable(e2)) queue.push_back(e2);
    }
  }
}

// Union-find of the corners (4 t + c) across the uncut faces: the vertices of
// the cut mesh, numbered by their lowest corner.
std::vector<std::size_t> cut_mesh_vertices(const Integer_grid_map_input& in, const Topology& top, std::size_t& count) {
  std::vector<std::size_t> parent(4 * in.tets.size());
  std::iota(parent.begin(), parent.end(), std::size_t(0));
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t k = 0; k < top.faces.size(); ++k) {
    if (top.cut[k]) continue;
    const auto& fc = top.faces[k];
    for (int l = 0; l < 4; ++l) {
      if (l == fc.f) continue;
      const int m = local_index(in.tets[fc.u], in.tets[fc.t][std::size_t(l)]);
      std::size_t x = find(4 * fc.t + std::size_t(l)), y = find(4 * fc.u + std::size_t(m));
      if (x != y) parent[std::max(x, y)] = std::min(x, y);
    }
  }
  std::vector<std::size_t> node(parent.size());
  std::vector<std::size_t> id(parent.size(), std::size_t(-1));
  count = 0;
  for (std::size_t c = 0; c < parent.size(); ++c) {
    const std::size_t r = find(c);
    if (id[r] == std::size_t(-1)) id[r] = count++;
    node[c] = id[r];
  }
  return node;
}

// The map's chart of a tetrahedron: J' = C_t G_t^T, whose rows are the
// gradients the parameters fit.
Eigen::Matrix3d combed_jacobian(const Integer_grid_map_input& in, const Topology& top, std::size_t t) {
  return octahedral_group()[std::size_t(top.chart[t])] * in.gradients[t].transpose();
}

// The matrix B (3 x 4) of a tetrahedron: grad u = B (u_0 .. u_3)^T.
Eigen::Matrix<double, 3, 4> gradient_operator(const Integer_grid_map_input& in, std::size_t t, double& volume) {
  const auto& p = in.positions;
  const auto& q = in.tets[t];
  Eigen::Matrix3d D;
  D << p[q[1]] - p[q[0]], p[q[2]] - p[q[0]], p[q[3]] - p[q[0]];
  volume = D.determinant() / 6;
  Eigen::Matrix<double, 3, 4> S;
  S << -1, 1, 0, 0, -1, 0, 1, 0, -1, 0, 0, 1;
  return D.transpose().inverse() * S;
}

// The problem being assembled: variables are 3 per cut-mesh vertex, then 3
// per cut face (the translations).
struct Assembly {
  Mixed_integer_quadratic_problem problem;
  std::vector<char> integer;
  std::size_t variables = 0;
  double target_norm = 0; // sum_t vol_t |G_t|^2
  void mark_integer(std::size_t v) { integer[v] = 1; }
  void equal(std::size_t a, std::size_t b) { problem.equalities.push_back({{{a, 1.0}, {b, -1.0}}, 0.0}); }
};

void add_cut_face_equalities(const Integer_grid_map_input& in, const Topology& top,
                             const std::vector<std::size_t>& node, Assembly& as) {
  std::size_t next = as.variables;
  for (std::size_t k = 0; k < top.faces.size(); ++k) {
    if (!top.cut[k]) continue;
    const auto& fc = top.faces[k];
    const Eigen::Matrix3d& G = octahedral_group()[std::size_t(combed_matching(in, top, fc.t, std::size_t(fc.f)))];
    const std::size_t tau = next;
    next += 3;
    for (int r = 0; r < 3; ++r) as.mark_integer(tau + std::size_t(r));
    for (int l = 0; l < 4; ++l) {
      if (l == fc.f) continue;
      const int m = local_index(in.tets[fc.u], in.tets[fc.t][std::size_t(l)]);
      const std::size_t xi = 3 * node[4 * fc.t + std::size_t(l)], xj = 3 * node[4 * fc.u + std::size_t(m)];
      for (int r = 0; r < 3; ++r) {
        Linear_equality eq; // x_j[r] - sum_c G(r, c) x_i[c] - tau[r] = 0
        eq.terms.push_back({xj + std::size_t(r), 1.0});
        for (int c = 0; c < 3; ++c)
          if (G(r, c) != 0) eq.terms.push_back({xi + std::size_t(c), -G(r, c)});
        eq.terms.push_back({tau + std::size_t(r), -1.0});
        as.problem.equalities.push_back(std::move(eq));
      }
    }
  }
  as.variables = next;
}

// Boundary faces on integer planes, along the axis nearest their normal in
// parameter space (J'^-T n).
void add_boundary_equalities(const Integer_grid_map_input& in, const Topology& top,
                             const std::vector<std::size_t>& node, Assembly& as, Integer_grid_map_report& rep) {
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    for (int f = 0; f < 4; ++f) {
      if (in.neighbors[t][std::size_t(f)] >= 0) continue;
      if (!in.free_boundary.empty() && in.free_boundary[t]) {
        ++rep.boundary_faces_free;
        continue;
      }
      std::array<std::size_t, 3> corner{};
      for (int l = 0, k = 0; l < 4; ++l)
        if (l != f) corner[std::size_t(k++)] = std::size_t(l);
      const auto& p = in.positions;
      const auto& q = in.tets[t];
      Eigen::Vector3d n = (p[q[corner[1]]] - p[q[corner[0]]]).cross(p[q[corner[2]]] - p[q[corner[0]]]);
      if (n.dot(p[q[std::size_t(f)]] - p[q[corner[0]]]) > 0) n = -n;
      const Eigen::Vector3d d = combed_jacobian(in, top, t).inverse().transpose() * n;
      Eigen::Index axis = 0;
      d.cwiseAbs().maxCoeff(&axis);
      const std::size_t x0 = 3 * node[4 * t + corner[0]] + std::size_t(axis);
      as.mark_integer(x0);
      as.equal(x0, 3 * node[4 * t + corner[1]] + std::size_t(axis));
      as.equal(x0, 3 * node[4 * t + corner[2]] + std::size_t(axis));
      ++rep.boundary_faces_constrained;
    }
}

// Singular edges on grid lines: the coordinates across the holonomy's axis
// integer at both vertices, in the chart of the loop's first tetrahedron.
void add_singular_edge_constraints(const Integer_grid_map_input& in, const Topology& top,
                                   const std::vector<Edge_loop>& loops, const std::vector<std::size_t>& node,
                                   Assembly& as, Integer_grid_map_report& rep) {
  for (std::size_t e = 0; e < loops.size(); ++e) {
    if (loops[e].faces.empty() || loops[e].holonomy == 0) continue;
    ++rep.singular_edges;
    const Eigen::Matrix3d& H = octahedral_group()[std::size_t(loops[e].holonomy)];
    int axis = -1;
    for (int k = 0; k < 3; ++k)
      if (H(k, k) == 1) axis = k;
    if (axis < 0) {
      ++rep.singular_edges_unconstrained;
      continue;
    }
    ++rep.singular_edges_on_grid_lines;
    const std::size_t t = loops[e].start;
    for (std::size_t v : top.edges[e]) {
      const std::size_t x = 3 * node[4 * t + std::size_t(local_index(in.tets[t], v))];
      for (int k = 0; k < 3; ++k)
        if (k != axis) as.mark_integer(x + std::size_t(k));
    }
  }
}

// One vertex per component pinned at 0 (the map is defined up to a
// translation): a vertex of its first boundary face, else of its root.
void add_pins(const Integer_grid_map_input& in, const Topology& top, const std::vector<std::size_t>& node,
              Assembly& as) {
  std::vector<std::size_t> pin;
  std::vector<char> on_boundary(top.component_root.size(), 0);
  for (std::size_t root : top.component_root) pin.push_back(4 * root);
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    for (std::size_t f = 0; f < 4; ++f) {
      const std::size_t k = top.component[t];
      if (in.neighbors[t][f] < 0 && !on_boundary[k]) pin[k] = 4 * t + (f + 1) % 4, on_boundary[k] = 1;
    }
  for (std::size_t c : pin)
    for (std::size_t r = 0; r < 3; ++r) as.problem.equalities.push_back({{{3 * node[c] + r, 1.0}}, 0.0});
}

// H = sum_t vol_t B^T B (per coordinate), b = sum_t vol_t B^T g_k.
void add_objective(const Integer_grid_map_input& in, const Topology& top, const std::vector<std::size_t>& node,
                   Assembly& as) {
  const std::size_t n = in.tets.size();
  std::vector<Eigen::Triplet<double>> lap;
  lap.reserve(16 * n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(Eigen::Index(as.variables));
  for (std::size_t t = 0; t < n; ++t) {
    double vol = 0;
    const Eigen::Matrix<double, 3, 4> B = gradient_operator(in, t, vol);
    const Eigen::Matrix4d K = vol * B.transpose() * B;
    const Eigen::Matrix3d J = combed_jacobian(in, top, t);
    as.target_norm += vol * J.squaredNorm();
    for (int c = 0; c < 4; ++c) {
      const std::size_t x = 3 * node[4 * t + std::size_t(c)];
      for (int d = 0; d < 4; ++d) lap.emplace_back(int(x / 3), int(node[4 * t + std::size_t(d)]), K(c, d));
      for (int k = 0; k < 3; ++k) b[Eigen::Index(x) + k] += vol * B.col(c).dot(J.row(k).transpose());
    }
  }
  const auto nodes = Eigen::Index(as.variables / 3);
  Eigen::SparseMatrix<double> L(nodes, nodes);
  L.setFromTriplets(lap.begin(), lap.end());
  std::vector<Eigen::Triplet<double>> h;
  h.reserve(std::size_t(3 * L.nonZeros()));
  for (int k = 0; k < L.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it)
      for (int r = 0; r < 3; ++r) h.emplace_back(int(3 * it.row() + r), int(3 * it.col() + r), it.value());
  as.problem.H.resize(Eigen::Index(as.variables), Eigen::Index(as.variables));
  as.problem.H.setFromTriplets(h.begin(), h.end());
  as.problem.b = std::move(b);
}

void measure(const Integer_grid_map_input& in, const Topology& top, Integer_grid_map& map) {
  auto& rep = map.report;
  double fit = 0;
  for (std::size_t t = 0; t < in.tets.size(); ++t) {
    double vol = 0;
    const Eigen::Matrix<double, 3, 4> B = gradient_operator(in, t, vol);
    Eigen::Matrix<double, 3, 4> U;
    for (int c = 0; c < 4; ++c) U.col(c) = map.parameters[t][std::size_t(c)];
    const Eigen::Matrix3d grad = U * B.transpose(); // rows: grad u_k
    fit += vol * (grad - combed_jacobian(in, top, t)).squaredNorm();
    Eigen::Matrix3d P;
    P << U.col(1) - U.col(0), U.col(2) - U.col(0), U.col(3) - U.col(0);
    const double pv = P.determinant() / 6, due = vol * in.gradients[t].determinant();
    rep.parameter_volume += pv;
    rep.due_volume += due;
    if (pv < 0)
      ++rep.inverted_tets;
    else if (pv <= 1e-3 * due)
      ++rep.flat_tets;
  }
  rep.fit_error = fit;
}

} // namespace

Integer_grid_map compute_integer_grid_map(const Integer_grid_map_input& in, const Integer_grid_map_options& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  check_input(in);
  Integer_grid_map map;
  auto& rep = map.report;
  rep.tets = in.tets.size();
  Topology top;
  build_faces(in, top);
  build_edges(in, top);
  comb(in, top);
  rep.cut_faces_tree = std::size_t(std::count(top.cut.begin(), top.cut.end(), 1));
  const std::vector<Edge_loop> loops = edge_loops(in, top);
  glue(top, loops);
  rep.cut_faces = std::size_t(std::count(top.cut.begin(), top.cut.end(), 1));
  std::size_t nodes = 0;
  const std::vector<std::size_t> node = cut_mesh_vertices(in, top, nodes);
  rep.cut_vertices = nodes;

  Assembly as;
  as.variables = 3 * nodes;
  as.integer.assign(3 * nodes + 3 * rep.cut_faces, 0);
  add_cut_face_equalities(in, top, node, as);
  add_boundary_equalities(in, top, node, as, rep);
  add_singular_edge_constraints(in, top, loops, node, as, rep);
  add_pins(in, top, node, as);
  add_objective(in, top, node, as);
  for (std::size_t v = 0; v < as.variables; ++v)
    if (as.integer[v]) as.problem.integer_variables.push_back(v);
  const auto solve_start = Clock::now();
  rep.seconds_setup = std::chrono::duration<double>(solve_start - start).count();

  Mixed_integer_quadratic_options mo = options.rounding;
  mo.round = options.quantize;
  const Mixed_integer_quadratic_solution sol = solve_mixed_integer_quadratic(as.problem, mo);
  rep.solver = sol.report;
  rep.seconds_solve = std::chrono::duration<double>(Clock::now() - solve_start).count();

  map.chart = top.chart;
  map.parameters.resize(in.tets.size());
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c) map.parameters[t][c] = sol.x.segment<3>(Eigen::Index(3 * node[4 * t + c]));
  measure(in, top, map);
  const double norm = as.target_norm > 0 ? as.target_norm : 1;
  rep.fit_error /= norm;
  rep.fit_error_relaxed = std::max(0.0, 1 + sol.report.objective_relaxed / norm);
  return map;
}

} // namespace CGAL_ext
