// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/Integer_grid_map_3.h>
#include <CGAL_ext/Octahedral_frame.h>

#include "foldover_free_map.h"

#include <Eigen/LU>
#include <Eigen/SparseCore>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <numeric>
#include <optional>
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

// The input's mesh with edges (vertex pairs) split at their midpoints: each
// tetrahedron around one becomes two with the same orientation, the half at
// the edge's first vertex keeping its index; `parent` maps them to the input's.
struct Split_mesh {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<std::size_t, 4>> tets;
  std::vector<std::size_t> parent;
};

Split_mesh split_edges(const Integer_grid_map_input& in, const std::vector<std::array<std::size_t, 2>>& edges) {
  Split_mesh out{in.positions, in.tets, std::vector<std::size_t>(in.tets.size())};
  std::iota(out.parent.begin(), out.parent.end(), std::size_t(0));
  std::vector<std::vector<std::size_t>> at(in.positions.size()); // the tetrahedra at each vertex
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    for (std::size_t v : in.tets[t]) at[v].push_back(t);
  for (const auto& [a, b] : edges) {
    const std::size_t m = out.positions.size();
    out.positions.push_back((in.positions[a] + in.positions[b]) / 2);
    at.emplace_back();
    std::vector<std::size_t> around;
    for (std::size_t t : at[a])
      if (local_index(out.tets[t], b) >= 0) around.push_back(t);
    for (std::size_t t : around) {
      const std::size_t t2 = out.tets.size();
      std::array<std::size_t, 4> q2 = out.tets[t];
      q2[std::size_t(local_index(q2, a))] = m;                  // the half at b
      out.tets[t][std::size_t(local_index(out.tets[t], b))] = m; // the half at a keeps slot t
      out.tets.push_back(q2);
      out.parent.push_back(out.parent[t]);
      at[b].erase(std::find(at[b].begin(), at[b].end(), t));
      for (std::size_t v : q2) at[v].push_back(t2);
      at[m].push_back(t);
    }
  }
  return out;
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
Eigen::Matrix<double, 3, 4> gradient_operator(const std::vector<Eigen::Vector3d>& p, const std::array<std::size_t, 4>& q,
                                              double& volume) {
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

// The map is defined up to a translation: per component and axis, one
// coordinate is fixed at 0. A coordinate that must be an integer anyway (a
// boundary plane's, a singular curve's), where the component has one, so
// that the pin only chooses which integer, and moves no plane or curve
// relative to the mesh; else its root's.
void add_pins(const Integer_grid_map_input& in, const Topology& top, const std::vector<std::size_t>& node,
              Assembly& as) {
  const std::size_t components = top.component_root.size();
  std::vector<std::array<std::size_t, 3>> pin(components);
  std::vector<std::array<char, 3>> integral(components, {0, 0, 0});
  for (std::size_t c = 0; c < components; ++c)
    for (std::size_t k = 0; k < 3; ++k) pin[c][k] = 3 * node[4 * top.component_root[c]] + k;
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    for (std::size_t corner = 0; corner < 4; ++corner)
      for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t c = top.component[t], v = 3 * node[4 * t + corner] + k;
        if (as.integer[v] && !integral[c][k]) pin[c][k] = v, integral[c][k] = 1;
      }
  for (const auto& p : pin)
    for (std::size_t v : p) as.problem.equalities.push_back({{{v, 1.0}}, 0.0});
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
    const Eigen::Matrix<double, 3, 4> B = gradient_operator(in.positions, in.tets[t], vol);
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

// The mesh the parameters live on: the input's or a refinement of it, each
// tetrahedron with its chart (its parent's) and the unknown point (the
// cut-mesh vertex, 3 entries of x from 3 node) of each corner.
struct Map_mesh {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<std::size_t, 4>> tets;
  std::vector<std::size_t> parent, node; // per tetrahedron; per corner 4 t + c
  std::vector<Eigen::Matrix3d> target;   // per tetrahedron: C G^T, the rows the gradients fit
};

Map_mesh unrefined(const Integer_grid_map_input& in, const Topology& top, const std::vector<std::size_t>& node) {
  Map_mesh m{in.positions, in.tets, {}, node, {}};
  m.parent.resize(in.tets.size());
  std::iota(m.parent.begin(), m.parent.end(), std::size_t(0));
  for (std::size_t t = 0; t < in.tets.size(); ++t) m.target.push_back(combed_jacobian(in, top, t));
  return m;
}

// The parameters of corner c of tetrahedron t.
Eigen::Vector3d corner(const Map_mesh& m, const Eigen::VectorXd& x, std::size_t t, std::size_t c) {
  return x.segment<3>(Eigen::Index(3 * m.node[4 * t + c]));
}

// Of tetrahedron t: its parameter volume, the volume due (its volume times
// det of its target), and the fitting error vol |grad u - target|^2.
struct Tet_measure {
  double parameter_volume = 0, due = 0, fit = 0;
  bool inverted() const { return parameter_volume < 0; }
  bool flat() const { return parameter_volume >= 0 && parameter_volume <= 1e-3 * due; }
};

Tet_measure measure_tet(const Map_mesh& m, const Eigen::VectorXd& x, std::size_t t) {
  double vol = 0;
  const Eigen::Matrix<double, 3, 4> B = gradient_operator(m.positions, m.tets[t], vol);
  Eigen::Matrix<double, 3, 4> U;
  for (std::size_t c = 0; c < 4; ++c) U.col(Eigen::Index(c)) = corner(m, x, t, c);
  Eigen::Matrix3d P;
  P << U.col(1) - U.col(0), U.col(2) - U.col(0), U.col(3) - U.col(0);
  const Eigen::Matrix3d grad = U * B.transpose(); // rows: grad u_k
  Tet_measure r;
  r.parameter_volume = P.determinant() / 6;
  r.due = vol * m.target[t].determinant();
  r.fit = vol * (grad - m.target[t]).squaredNorm();
  return r;
}

// Fit error (not yet normalised), volumes, inverted and flat tetrahedra of x on m.
void measure(const Map_mesh& m, const Eigen::VectorXd& x, Integer_grid_map_report& rep) {
  rep.parameter_volume = rep.due_volume = rep.fit_error = 0;
  rep.inverted_tets = rep.flat_tets = 0;
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const Tet_measure r = measure_tet(m, x, t);
    rep.parameter_volume += r.parameter_volume;
    rep.due_volume += r.due;
    rep.fit_error += r.fit;
    rep.inverted_tets += r.inverted();
    rep.flat_tets += r.flat();
  }
}

// A point for the midpoint of edge (a, b) that leaves both halves of every
// tetrahedron around it positive, if there is one that the relaxation
// method (Agmon, Motzkin and Schoenberg) finds from the middle of the
// edge's parameters: each half's determinant is affine in the point, so
// the point is moved onto the most violated of these half-spaces, with a
// margin, until none is.
std::optional<Eigen::Vector3d> lifted_midpoint(const Map_mesh& m, const Eigen::VectorXd& x,
                                               const std::vector<std::size_t>& around, std::size_t a, std::size_t b) {
  struct Half_space { // n . p + d > 0
    Eigen::Vector3d n;
    double d;
  };
  std::vector<Half_space> halves;
  double size = 0;
  for (std::size_t t : around)
    for (std::size_t replaced : {a, b}) {
      auto det = [&](const Eigen::Vector3d& p) {
        std::array<Eigen::Vector3d, 4> Q;
        for (std::size_t c = 0; c < 4; ++c) Q[c] = m.tets[t][c] == replaced ? p : corner(m, x, t, c);
        Eigen::Matrix3d D;
        D << Q[1] - Q[0], Q[2] - Q[0], Q[3] - Q[0];
        return D.determinant();
      };
      Half_space h{Eigen::Vector3d::Zero(), det(Eigen::Vector3d::Zero())};
      for (int k = 0; k < 3; ++k) h.n[k] = det(Eigen::Vector3d::Unit(k)) - h.d;
      size = std::max(size, h.n.norm());
      halves.push_back(h);
    }
  const std::size_t t0 = around.front();
  Eigen::Vector3d p = (corner(m, x, t0, std::size_t(local_index(m.tets[t0], a))) +
                       corner(m, x, t0, std::size_t(local_index(m.tets[t0], b)))) / 2;
  // A margin of 1e-3 of the largest gradient norm (a parameter length squared).
  const double margin = 1e-3 * size * std::sqrt(size);
  for (int it = 0; it < 200; ++it) {
    const Half_space* worst = nullptr;
    double lowest = margin;
    for (const Half_space& h : halves)
      if (h.n.dot(p) + h.d < lowest) lowest = h.n.dot(p) + h.d, worst = &h;
    if (!worst) return p;
    if (worst->n.squaredNorm() == 0) return std::nullopt; // a half that the point cannot lift
    p += (2 * margin - lowest) / worst->n.squaredNorm() * worst->n;
  }
  return std::nullopt;
}

// The flat tetrahedra of x refined: for each, an interior edge, not
// singular, with no cut face around it and no tetrahedron around it that
// another split halves, is split at its midpoint if a point for it leaves
// every half around the edge positive; the point is a
// new unknown (appended to x: one point, since no cut face is around the
// edge), started there. The integers hold a flat tetrahedron's vertices on
// one plane or line; the midpoint is free to lift the halves off it.
Map_mesh refine_flat(const Integer_grid_map_input& in, const Topology& top, const std::vector<Edge_loop>& loops,
                     const Map_mesh& base, Eigen::VectorXd& x, std::size_t& split) {
  std::vector<std::optional<Eigen::Vector3d>> chosen(top.edges.size());
  std::vector<char> tried(top.edges.size(), 0), taken(base.tets.size(), 0);
  for (std::size_t t = 0; t < base.tets.size(); ++t) {
    if (!measure_tet(base, x, t).flat()) continue;
    for (int e = 0; e < 6; ++e) {
      const std::size_t id = top.tet_edges[t][std::size_t(e)];
      const Edge_loop& loop = loops[id];
      const bool cut = std::any_of(loop.faces.begin(), loop.faces.end(), [&](std::size_t f) { return top.cut[f] != 0; });
      if (loop.faces.empty() || loop.holonomy != 0 || cut) continue; // on the boundary, singular, or on a seam
      if (chosen[id]) break;
      if (tried[id]) continue;
      tried[id] = 1;
      std::vector<std::size_t> around;
      for (std::size_t f : loop.faces) around.push_back(top.faces[f].t), around.push_back(top.faces[f].u);
      std::sort(around.begin(), around.end());
      around.erase(std::unique(around.begin(), around.end()), around.end());
      // The halves' check holds for one split per tetrahedron: none around this edge may have another.
      if (std::any_of(around.begin(), around.end(), [&](std::size_t u) { return taken[u] != 0; })) continue;
      chosen[id] = lifted_midpoint(base, x, around, top.edges[id][0], top.edges[id][1]);
      if (!chosen[id]) continue;
      for (std::size_t u : around) taken[u] = 1;
      break;
    }
  }
  std::vector<std::array<std::size_t, 2>> edges;
  std::vector<Eigen::Vector3d> start;
  for (std::size_t e = 0; e < top.edges.size(); ++e)
    if (chosen[e]) edges.push_back(top.edges[e]), start.push_back(*chosen[e]);
  split = edges.size();
  if (edges.empty()) return base;
  const Split_mesh fine = split_edges(in, edges);
  const std::vector<std::size_t>& parent = fine.parent;
  const std::size_t nv = in.positions.size(), first_new = std::size_t(x.size()) / 3;
  Map_mesh m{fine.positions, fine.tets, parent, std::vector<std::size_t>(4 * fine.tets.size()), {}};
  Eigen::VectorXd grown = Eigen::VectorXd::Zero(x.size() + Eigen::Index(3 * edges.size()));
  grown.head(x.size()) = x;
  for (std::size_t t = 0; t < fine.tets.size(); ++t) {
    const std::size_t p = parent[t];
    m.target.push_back(base.target[p]);
    for (std::size_t c = 0; c < 4; ++c) {
      const std::size_t v = fine.tets[t][c];
      m.node[4 * t + c] = v < nv ? base.node[4 * p + std::size_t(local_index(in.tets[p], v))] : first_new + (v - nv);
    }
  }
  for (std::size_t k = 0; k < edges.size(); ++k) grown.segment<3>(Eigen::Index(3 * (first_new + k))) = start[k];
  x.swap(grown);
  return m;
}

// The region the untangling moves: the tetrahedra within `rings` vertex
// rings of an inverted or flat one, and the unknown points (nodes) all of
// whose tetrahedra are in it. Away from the defects the map stays as the
// rounding left it, and the untangling's cost follows the defects, not the mesh.
std::vector<char> movable_nodes(const Map_mesh& m, const Eigen::VectorXd& x, std::size_t nodes, int rings) {
  std::vector<std::vector<std::size_t>> at(m.positions.size());
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (std::size_t v : m.tets[t]) at[v].push_back(t);
  std::vector<char> in_region(m.tets.size(), 0), reached(m.positions.size(), 0);
  std::vector<std::size_t> front;
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const Tet_measure r = measure_tet(m, x, t);
    if (r.inverted() || r.flat()) in_region[t] = 1, front.push_back(t);
  }
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<std::size_t> next;
    for (std::size_t t : front)
      for (std::size_t v : m.tets[t]) {
        if (reached[v]) continue;
        reached[v] = 1;
        for (std::size_t u : at[v])
          if (!in_region[u]) in_region[u] = 1, next.push_back(u);
      }
    front.swap(next);
  }
  std::vector<char> movable(nodes, 1);
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    if (!in_region[t])
      for (std::size_t c = 0; c < 4; ++c) movable[m.node[4 * t + c]] = 0;
  return movable;
}

// Untangles x0 on m in the solver's reduced space x = E y + c, grown by the
// free points appended to x0 after E's rows (the split edges' midpoints).
// Moved: the real columns of y all of whose entries of x are movable nodes
// (`movable_nodes()`); the integer columns are held. Returns the new x, its
// integer variables snapped.
Eigen::VectorXd untangle_map(const Map_mesh& m, const Eigen::VectorXd& x0, const Assembly& as,
                             const Mixed_integer_quadratic_solution& sol, const Integer_grid_map_options& options,
                             Integer_grid_map_report& rep) {
  const Eigen::Index n = sol.E.rows(), k = sol.E.cols(), extra = x0.size() - n;
  const std::vector<char> movable = movable_nodes(m, x0, std::size_t(x0.size()) / 3, 3);
  std::vector<Eigen::Triplet<double>> t;
  std::vector<char> fixed = sol.integer_column;
  fixed.resize(std::size_t(k + extra), 0);
  for (int j = 0; j < sol.E.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(sol.E, j); it; ++it) {
      t.emplace_back(int(it.row()), j, it.value());
      if (!movable[std::size_t(it.row()) / 3]) fixed[std::size_t(j)] = 1;
    }
  for (Eigen::Index i = 0; i < extra; ++i) {
    t.emplace_back(int(n + i), int(k + i), 1.0);
    if (!movable[std::size_t(n + i) / 3]) fixed[std::size_t(k + i)] = 1;
  }
  Eigen::SparseMatrix<double> E(n + extra, k + extra);
  E.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n + extra), y(k + extra);
  c.head(n) = sol.c;
  y << sol.y, x0.tail(extra);
  internal::Foldover_free_problem pb;
  for (std::size_t i = 0; i < m.tets.size(); ++i) { // the tetrahedra a movable point moves
    bool moves = false;
    for (std::size_t j = 0; j < 4; ++j) moves = moves || movable[m.node[4 * i + j]];
    if (!moves) continue;
    pb.corner.push_back({});
    for (std::size_t j = 0; j < 4; ++j) pb.corner.back()[j] = 3 * m.node[4 * i + j];
    pb.volume.push_back(0);
    pb.B.push_back(gradient_operator(m.positions, m.tets[i], pb.volume.back()));
    pb.M.push_back(m.target[i].inverse());
  }
  pb.E = &E;
  pb.c = &c;
  pb.fixed = std::move(fixed);
  internal::Foldover_free_settings settings;
  settings.max_rounds = options.untangle_rounds;
  settings.max_iterations = options.untangle_iterations;
  const internal::Foldover_free_outcome out = internal::untangle(pb, y, settings);
  rep.untangled = true;
  rep.untangle_tets = pb.corner.size();
  rep.untangle_rounds = out.rounds;
  rep.untangle_iterations = out.iterations;
  rep.min_relative_det_rounded = out.min_det_before;
  rep.min_relative_det = out.min_det_after;
  Eigen::VectorXd x = E * y + c;
  for (std::size_t v = 0; v < as.integer.size(); ++v) // exact again after E y
    if (as.integer[v] && std::abs(x[Eigen::Index(v)] - std::round(x[Eigen::Index(v)])) < 1e-6)
      x[Eigen::Index(v)] = std::round(x[Eigen::Index(v)]);
  return x;
}

// Fewer inverted tetrahedra, then fewer flat ones: inverted ones break the
// hexes, flat ones HexEx extracts.
bool fewer_defects(const Integer_grid_map_report& a, const Integer_grid_map_report& b) {
  return a.inverted_tets != b.inverted_tets ? a.inverted_tets < b.inverted_tets : a.flat_tets < b.flat_tets;
}

// Fills the map's mesh and parameters from x on m.
void set_map(const Integer_grid_map_input& input, const Map_mesh& m, const Eigen::VectorXd& x, Integer_grid_map& map) {
  map.positions = m.positions;
  map.tets = m.tets;
  map.parent = m.parent;
  map.parameters.resize(m.tets.size());
  map.input_parameters.resize(input.tets.size());
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c) {
      map.parameters[t][c] = corner(m, x, t, c);
      const int l = local_index(input.tets[m.parent[t]], m.tets[t][c]); // each input corner from a child with it
      if (l >= 0) map.input_parameters[m.parent[t]][std::size_t(l)] = map.parameters[t][c];
    }
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

  Map_mesh mesh = unrefined(in, top, node);
  Mixed_integer_quadratic_options mo = options.rounding;
  mo.round = options.quantize;
  const Mixed_integer_quadratic_solution sol = solve_mixed_integer_quadratic(as.problem, mo);
  rep.solver = sol.report;
  rep.seconds_solve = std::chrono::duration<double>(Clock::now() - solve_start).count();

  Eigen::VectorXd x = sol.x;
  measure(mesh, x, rep);
  rep.inverted_tets_rounded = rep.inverted_tets;
  rep.flat_tets_rounded = rep.flat_tets;
  if (options.untangle && rep.inverted_tets + rep.flat_tets > 0) {
    const auto untangle_start = Clock::now();
    Integer_grid_map_report trial = rep;
    Eigen::VectorXd x_fine = x;
    const Map_mesh fine =
        options.split_edges && rep.flat_tets > 0 ? refine_flat(in, top, loops, mesh, x_fine, trial.split_edges) : mesh;
    x_fine = untangle_map(fine, x_fine, as, sol, options, trial);
    measure(fine, x_fine, trial);
    trial.seconds_untangle = std::chrono::duration<double>(Clock::now() - untangle_start).count();
    // Kept only if better: where the integers admit no valid map, the
    // barrier can end worse than it began.
    if (fewer_defects(trial, rep)) {
      rep = trial;
      mesh = fine;
      x.swap(x_fine);
    } else {
      rep.untangle_rounds = trial.untangle_rounds;
      rep.untangle_iterations = trial.untangle_iterations;
      rep.untangle_tets = trial.untangle_tets;
      rep.min_relative_det_rounded = rep.min_relative_det = trial.min_relative_det_rounded;
      rep.seconds_untangle = trial.seconds_untangle;
      rep.split_edges_rejected = trial.split_edges;
    }
  }
  rep.map_tets = mesh.tets.size();
  set_map(in, mesh, x, map);
  map.chart.resize(mesh.tets.size());
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) map.chart[t] = top.chart[mesh.parent[t]];
  const double norm = as.target_norm > 0 ? as.target_norm : 1;
  rep.fit_error /= norm;
  rep.fit_error_relaxed = std::max(0.0, 1 + sol.report.objective_relaxed / norm);
  return map;
}

} // namespace CGAL_ext
