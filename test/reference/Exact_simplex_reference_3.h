// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TEST_REFERENCE_EXACT_SIMPLEX_REFERENCE_3_H
#define CGAL_EXT_TEST_REFERENCE_EXACT_SIMPLEX_REFERENCE_3_H

// Exact, brute-force reference for the segment walk (test only).
//
// For every simplex that is a face of a domain cell, the set of parameters t
// in [0,1] with q + t (p - q) in the simplex's relative interior is computed
// in exact rational arithmetic, independently of any adjacency or walking
// logic: the segment's line is intersected with the simplex's affine hull
// (orthogonal projection, exact), then clipped with the strict barycentric
// sign conditions. The non-empty sets are sorted, checked to partition the
// covered part of [0,1], and the uncovered parts become gaps.

#include <CGAL/Exact_rational.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL_ext {
namespace testing {

using Exact_rational = CGAL::Exact_rational;

/// One piece of the exact reference: the simplex (or a gap, dimension -1),
/// its sorted vertex ids and its exact parameter interval.
struct Reference_piece {
  int dimension;
  std::vector<std::size_t> vertices;
  Exact_rational t_in, t_out;
};

inline std::string to_string(const std::vector<Reference_piece>& pieces) {
  std::ostringstream os;
  for (const auto& r : pieces) {
    os << "  dim " << r.dimension << " {";
    for (std::size_t i = 0; i < r.vertices.size(); ++i) os << (i ? "," : "") << r.vertices[i];
    os << "} [" << r.t_in << " ~ " << CGAL::to_double(r.t_in) << ", " << r.t_out << " ~ " << CGAL::to_double(r.t_out)
       << "]\n";
  }
  return os.str();
}

/// Brute force over all faces of the domain cells of `tr`.
///
/// \tparam Triangulation a CGAL `Triangulation_3` with double coordinates
/// \tparam Domain_predicate unary predicate on cell handles
/// \tparam Vertex_id functor Vertex_handle -> std::size_t (distinct ids)
template <class Triangulation, class Domain_predicate, class Vertex_id>
class Exact_simplex_reference_3 {
  using Q = Exact_rational;
  using Vec = std::array<Q, 3>;

  // A simplex with the data that makes a query cheap: its first vertex v0,
  // the projector R onto the orthogonal complement of its direction space
  // (R w == 0 iff v0 + w is in the affine hull), and P with mu = P w the
  // coordinates of w in the edge basis (v_i - v0).
  struct Simplex {
    int dim;
    std::vector<std::size_t> ids;
    std::array<double, 3> lo, hi; // bounding box, for the exact filter
    Vec v0;
    std::array<Vec, 3> R;   // rows, unused for cells
    std::vector<Vec> P;     // dim rows
  };

  // Candidate piece with the information whether its end points are attained.
  struct Raw {
    int dim;
    const std::vector<std::size_t>* ids;
    Q lo, hi;
    bool lo_closed, hi_closed;
  };

public:
  Exact_simplex_reference_3(const Triangulation& tr, Domain_predicate in_domain, Vertex_id vertex_id) {
    std::map<std::vector<std::size_t>, std::vector<std::array<double, 3>>> faces;
    for (auto c : tr.all_cell_handles()) {
      if (!in_domain(c)) continue;
      if (tr.is_infinite(c)) throw std::logic_error("reference: the domain predicate accepts an infinite cell");
      for (int mask = 1; mask < 16; ++mask) {
        std::vector<std::pair<std::size_t, std::array<double, 3>>> vs;
        for (int i = 0; i < 4; ++i)
          if (mask & (1 << i)) {
            const auto& p = c->vertex(i)->point();
            vs.push_back({vertex_id(c->vertex(i)), {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}});
          }
        std::sort(vs.begin(), vs.end());
        std::vector<std::size_t> key;
        std::vector<std::array<double, 3>> pts;
        for (auto& v : vs) {
          key.push_back(v.first);
          pts.push_back(v.second);
        }
        const auto ins = faces.emplace(std::move(key), pts);
        if (!ins.second && ins.first->second != pts) throw std::logic_error("reference: vertex ids are not distinct");
      }
    }
    for (auto& f : faces) simplices_.push_back(make_simplex(f.first, f.second));
  }

  std::size_t number_of_simplices(int dim) const {
    return static_cast<std::size_t>(
        std::count_if(simplices_.begin(), simplices_.end(), [dim](const Simplex& s) { return s.dim == dim; }));
  }

  /// The exact pieces along q -> p, gaps included, sorted; throws
  /// std::logic_error if the simplices' pieces do not partition the covered set.
  std::vector<Reference_piece> operator()(const std::array<double, 3>& q, const std::array<double, 3>& p) const {
    const Vec eq{Q(q[0]), Q(q[1]), Q(q[2])};
    const Vec d{Q(p[0]) - eq[0], Q(p[1]) - eq[1], Q(p[2]) - eq[2]};
    std::array<double, 3> slo, shi;
    for (int i = 0; i < 3; ++i) slo[i] = std::min(q[i], p[i]), shi[i] = std::max(q[i], p[i]);

    std::vector<Raw> raw;
    for (const Simplex& s : simplices_) {
      // Exact filter: double comparisons of double coordinates are exact.
      bool disjoint = false;
      for (int i = 0; i < 3; ++i) disjoint = disjoint || s.hi[i] < slo[i] || s.lo[i] > shi[i];
      if (disjoint) continue;
      Raw r;
      if (intersect(s, eq, d, r)) raw.push_back(r);
    }
    std::sort(raw.begin(), raw.end(), [](const Raw& a, const Raw& b) {
      if (a.lo != b.lo) return a.lo < b.lo;
      return (a.lo == a.hi) && !(b.lo == b.hi); // zero length first
    });
    check_partition(raw, q == p);

    std::vector<Reference_piece> out;
    Q cur(0);
    for (const Raw& r : raw) {
      if (cur < r.lo) out.push_back({-1, {}, cur, r.lo});
      out.push_back({r.dim, *r.ids, r.lo, r.hi});
      if (cur < r.hi) cur = r.hi;
    }
    if (cur < Q(1) || out.empty()) out.push_back({-1, {}, cur, Q(1)});
    if (q == p && out.size() != 1) throw std::logic_error("reference: q == p must give exactly one piece");
    // Tiling of [0,1].
    if (out.front().t_in != Q(0) || out.back().t_out != Q(1)) throw std::logic_error("reference: pieces do not span [0,1]");
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (out[i].t_out < out[i].t_in) throw std::logic_error("reference: reversed interval");
      if (i > 0 && out[i].t_in != out[i - 1].t_out) throw std::logic_error("reference: pieces do not tile [0,1]");
    }
    return out;
  }

private:
  static Simplex make_simplex(const std::vector<std::size_t>& ids, const std::vector<std::array<double, 3>>& pts) {
    Simplex s;
    s.dim = static_cast<int>(ids.size()) - 1;
    s.ids = ids;
    s.lo = s.hi = pts[0];
    for (const auto& p : pts)
      for (int i = 0; i < 3; ++i) s.lo[i] = std::min(s.lo[i], p[i]), s.hi[i] = std::max(s.hi[i], p[i]);
    s.v0 = {Q(pts[0][0]), Q(pts[0][1]), Q(pts[0][2])};
    const int k = s.dim;
    std::vector<Vec> E(k); // edge vectors, the columns of the 3 x k matrix
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < 3; ++i) E[j][i] = Q(pts[j + 1][i]) - s.v0[i];
    // Gram matrix G = E^T E, and P = G^{-1} E^T by Gauss-Jordan on [G | E^T].
    std::vector<std::vector<Q>> A(k, std::vector<Q>(k + 3));
    for (int a = 0; a < k; ++a) {
      for (int b = 0; b < k; ++b) A[a][b] = E[a][0] * E[b][0] + E[a][1] * E[b][1] + E[a][2] * E[b][2];
      for (int i = 0; i < 3; ++i) A[a][k + i] = E[a][i];
    }
    for (int col = 0; col < k; ++col) {
      int piv = col;
      while (piv < k && A[piv][col] == Q(0)) ++piv;
      if (piv == k) throw std::logic_error("reference: degenerate simplex");
      std::swap(A[piv], A[col]);
      const Q inv = Q(1) / A[col][col];
      for (auto& x : A[col]) x *= inv;
      for (int r = 0; r < k; ++r)
        if (r != col && A[r][col] != Q(0)) {
          const Q f = A[r][col];
          for (int c = 0; c < k + 3; ++c) A[r][c] -= f * A[col][c];
        }
    }
    s.P.resize(k);
    for (int a = 0; a < k; ++a)
      for (int i = 0; i < 3; ++i) s.P[a][i] = A[a][k + i];
    // R = I - E P.
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Q x(i == j ? 1 : 0);
        for (int a = 0; a < k; ++a) x -= E[a][i] * s.P[a][j];
        s.R[i][j] = x;
      }
    return s;
  }

  static Q dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

  // The closure of {t in [0,1] : q + t d in relint(s)}, if not empty.
  bool intersect(const Simplex& s, const Vec& q, const Vec& d, Raw& out) const {
    const Vec w0{q[0] - s.v0[0], q[1] - s.v0[1], q[2] - s.v0[2]};
    // Line against affine hull: all t, one t, or none.
    bool single = false;
    Q ts;
    if (s.dim < 3) {
      const Vec r0{dot(s.R[0], w0), dot(s.R[1], w0), dot(s.R[2], w0)};
      const Vec r1{dot(s.R[0], d), dot(s.R[1], d), dot(s.R[2], d)};
      int i = 0;
      while (i < 3 && r1[i] == Q(0)) ++i;
      if (i == 3) {
        if (r0[0] != Q(0) || r0[1] != Q(0) || r0[2] != Q(0)) return false;
      } else {
        ts = -r0[i] / r1[i];
        for (int j = 0; j < 3; ++j)
          if (r0[j] + ts * r1[j] != Q(0)) return false;
        if (ts < Q(0) || ts > Q(1)) return false;
        single = true;
      }
    }
    // Barycentric coordinates lambda_j(t) = alpha_j + t beta_j.
    std::vector<Q> alpha(s.dim + 1), beta(s.dim + 1);
    alpha[0] = Q(1);
    beta[0] = Q(0);
    for (int a = 0; a < s.dim; ++a) {
      alpha[a + 1] = dot(s.P[a], w0);
      beta[a + 1] = dot(s.P[a], d);
      alpha[0] -= alpha[a + 1];
      beta[0] -= beta[a + 1];
    }
    if (single) {
      for (int j = 0; j <= s.dim; ++j)
        if (!(alpha[j] + ts * beta[j] > Q(0))) return false;
      out = {s.dim, &s.ids, ts, ts, true, true};
      return true;
    }
    // Open constraints alpha + t beta > 0, then [0,1].
    Q lo(0), hi(1);
    bool lo_closed = true, hi_closed = true;
    for (int j = 0; j <= s.dim; ++j) {
      if (beta[j] == Q(0)) {
        if (!(alpha[j] > Q(0))) return false;
        continue;
      }
      const Q b = -alpha[j] / beta[j];
      if (beta[j] > Q(0)) { // t > b
        if (b >= lo) lo = b, lo_closed = false;
      } else { // t < b
        if (b <= hi) hi = b, hi_closed = false;
      }
    }
    if (lo < hi || (lo == hi && lo_closed && hi_closed)) {
      out = {s.dim, &s.ids, lo, hi, lo_closed, hi_closed};
      return true;
    }
    return false;
  }

  // The relative interiors of the faces of a cell complex are disjoint, and
  // the complex is closed: every point of the closure of the covered set is
  // covered exactly once. Checked at every end point and between them.
  static void check_partition(const std::vector<Raw>& raw, bool point_segment) {
    std::vector<Q> ev{Q(0), Q(1)};
    for (const Raw& r : raw) ev.push_back(r.lo), ev.push_back(r.hi);
    std::sort(ev.begin(), ev.end());
    ev.erase(std::unique(ev.begin(), ev.end()), ev.end());
    auto count_at = [&](const Q& t, bool& in_closure) {
      int n = 0;
      in_closure = false;
      for (const Raw& r : raw) {
        if (r.lo <= t && t <= r.hi) in_closure = true;
        const bool in = (r.lo < t || (r.lo == t && r.lo_closed)) && (t < r.hi || (t == r.hi && r.hi_closed));
        n += in ? 1 : 0;
      }
      return n;
    };
    for (std::size_t i = 0; i < ev.size(); ++i) {
      bool cl;
      const int n = count_at(ev[i], cl);
      if (n > 1 || (cl && n != 1)) {
        std::ostringstream os;
        os << "reference: the point t = " << ev[i] << " is covered " << n << " times";
        throw std::logic_error(os.str());
      }
      if (i + 1 < ev.size() && count_at((ev[i] + ev[i + 1]) / Q(2), cl) > 1)
        throw std::logic_error("reference: overlapping relative interiors");
    }
    if (point_segment && raw.size() > 1) throw std::logic_error("reference: a point lies in two relative interiors");
  }

  std::vector<Simplex> simplices_;
};

template <class Triangulation, class Domain_predicate, class Vertex_id>
Exact_simplex_reference_3<Triangulation, Domain_predicate, Vertex_id>
make_exact_simplex_reference(const Triangulation& tr, Domain_predicate in_domain, Vertex_id vertex_id) {
  return Exact_simplex_reference_3<Triangulation, Domain_predicate, Vertex_id>(tr, in_domain, vertex_id);
}

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_REFERENCE_EXACT_SIMPLEX_REFERENCE_3_H
