// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_SINGULARITIES_3_H
#define CGAL_EXT_FRAME_FIELD_SINGULARITIES_3_H

/// \file Frame_field_singularities_3.h
/// The singular edges of an octahedral frame field: interior mesh edges
/// around which the frames do not come back to themselves (MATH.md section 5).

#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Octahedral_frame.h>

#include <Eigen/Core>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// The type of an interior edge of a frame field, from the monodromy around it.
enum class Singularity_type {
  regular,       ///< the product of matchings is the identity
  plus_quarter,  ///< a quarter turn about the edge, index +1/4 (3 hexahedra around the edge)
  minus_quarter, ///< a quarter turn against the edge, index -1/4 (5 hexahedra around the edge)
  half,          ///< a half turn about a frame axis: index +-1/2 (2 or 6 hexahedra); unstable
  other          ///< a turn about a frame axis nearly across the edge, or a third turn about a
                 ///< cube diagonal: no hexahedral edge fits (a defect of the field)
};

/// \ingroup PkgCGALExtFrames
/// The name used in outputs: "regular", "+1/4", "-1/4", "1/2", "other".
/// \param t the type
inline const char* singularity_type_name(Singularity_type t) {
  switch (t) {
    case Singularity_type::regular: return "regular";
    case Singularity_type::plus_quarter: return "+1/4";
    case Singularity_type::minus_quarter: return "-1/4";
    case Singularity_type::half: return "1/2";
    default: return "other";
  }
}

/// \ingroup PkgCGALExtFrames
/// A singular interior edge.
struct Singular_edge {
  /// The 0-based vertex indices of the edge, sorted.
  std::array<std::size_t, 2> vertices;
  /// The type.
  Singularity_type type;
  /// The number of hexahedra the edge would have around it (4 - 4 index):
  /// 3 for +1/4, 5 for -1/4, 0 when it is not defined (half turns, other).
  int valence;
  /// The index of the product of matchings in `octahedral_group()`.
  int monodromy;
  /// The number of tetrahedra around the edge.
  int loop_size;
};

/// \ingroup PkgCGALExtFrames
/// Finds the singular edges of a frame field.
///
/// For each interior edge (no incident cell outside the domain), the cells
/// `c_0, ..., c_{n-1}` around it, in the circulation order, give the
/// matchings `G_k = closest_octahedral_matching(T(k->k+1) R_k, R_{k+1}).G`
/// (transports included, MATH.md section 5) and their product
/// `P = G_{n-1} ... G_0` (exact: signed permutations). The edge is regular iff
/// `P = I`. Otherwise the monodromy `R_0 P R_0^T` is the rotation of the
/// continued frame after one turn: a quarter turn about the frame axis
/// `a = R_0 axis(P)`; its sign is that of the turn about the edge direction
/// `t` oriented by the circulation (right-hand rule), compared through the
/// frame vector `A^{-1} a`: `+1/4` (3 hexahedra around the edge) if it turns
/// positively about `t`, `-1/4` (5) otherwise. A half turn is `half`. When the
/// axis is nearly across the edge (`|cos| <= 0.2`, beyond about 78 degrees:
/// the discrete curve zigzags, so edges at 45 degrees and more from the axis
/// are common and still carry the curve), or `P` is a third turn about a cube
/// diagonal, the edge has no hexahedral meaning and is reported as `other`.
///
/// The edges are returned sorted by their vertex indices (deterministic).
///
/// \tparam Frame_field a `Frame_field_3` after `compute()`
/// \param ff the frame field
/// \returns the singular edges (regular edges are not listed)
template <class Frame_field>
std::vector<Singular_edge> singular_edges(const Frame_field& ff) {
  using Cell_handle = typename Frame_field::Cell_handle;
  const auto& tr = ff.metric_field().triangulation();
  std::vector<Singular_edge> out;
  std::vector<Cell_handle> loop;
  // Each tetrahedron is in about six edge loops: canonicalize its frame once.
  std::vector<Eigen::Matrix3d> R(ff.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, R.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) R[i] = ff.rotation(i);
  });
  for (auto e = tr.finite_edges_begin(); e != tr.finite_edges_end(); ++e) {
    loop.clear();
    bool interior = true;
    auto circ = tr.incident_cells(*e), done = circ;
    do {
      const Cell_handle c = circ;
      if (tr.is_infinite(c) || ff.index(c) < 0) {
        interior = false;
        break;
      }
      loop.push_back(c);
    } while (++circ != done);
    if (!interior) continue;
    const auto u = e->first->vertex(e->second), v = e->first->vertex(e->third);
    const Eigen::Vector3d pu = internal::to_eigen_vector(u->point()), pv = internal::to_eigen_vector(v->point());
    // The product of the matchings around the loop.
    const int n = int(loop.size());
    Eigen::Matrix3d P = Eigen::Matrix3d::Identity();
    double turn = 0; // orientation of the circulation about u -> v
    for (int k = 0; k < n; ++k) {
      const Cell_handle a = loop[k], b = loop[(k + 1) % n];
      const std::size_t ia = ff.index(a), ib = ff.index(b);
      const int fb = b->index(a); // facet of b shared with a
      const Eigen::Matrix3d T = ff.transport_into(ib, fb); // T(a->b)
      P = closest_octahedral_matching(T * R[ia], R[ib]).G * P;
      turn += (ff.centroid(ia) - pu).cross(ff.centroid(ib) - pu).dot(pv - pu);
    }
    const int index = octahedral_group_index(P);
    if (index == 0) continue;
    Singular_edge s;
    s.vertices = {ff.vertex_index(u), ff.vertex_index(v)};
    if (s.vertices[0] > s.vertices[1]) std::swap(s.vertices[0], s.vertices[1]);
    s.monodromy = index;
    s.loop_size = n;
    s.valence = 0;
    s.type = Singularity_type::other;
    // Classify P: its rotation angle (trace) and axis (the +1 eigenvector).
    const double tr_p = P.trace(); // 1 + 2 cos(angle): 1 quarter, -1 half, 0 third turn
    if (tr_p == 1 || tr_p == -1) {
      Eigen::Vector3d axis_frame = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k)
        if (P(k, k) == 1) axis_frame(k) = 1;
      const std::size_t i0 = ff.index(loop[0]);
      const Eigen::Matrix3d& R0 = R[i0];
      const Eigen::Vector3d t = ((pv - pu) * (turn >= 0 ? 1.0 : -1.0)).normalized();
      const Eigen::Vector3d frame_dir = (ff.sqrt_metric(i0).inverse() * (R0 * axis_frame)).normalized();
      const double c = frame_dir.dot(t);
      // Discrete singular curves zigzag along mesh edges: an edge may make a
      // large angle with the turn's axis and still carry the curve; only an
      // axis nearly across the edge (beyond about 78 degrees) is "other".
      if (tr_p == -1) {
        if (std::abs(c) > 0.2) s.type = Singularity_type::half;
      } else if (std::abs(c) > 0.2) {
        // Sense of the quarter turn about axis_frame: the skew part of P.
        const Eigen::Vector3d w(P(2, 1) - P(1, 2), P(0, 2) - P(2, 0), P(1, 0) - P(0, 1));
        const double sense = w.dot(axis_frame) * c; // positive: turns positively about t
        s.type = sense > 0 ? Singularity_type::plus_quarter : Singularity_type::minus_quarter;
        s.valence = sense > 0 ? 3 : 5;
      }
    }
    out.push_back(s);
  }
  std::sort(out.begin(), out.end(),
            [](const Singular_edge& a, const Singular_edge& b) { return a.vertices < b.vertices; });
  return out;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_FRAME_FIELD_SINGULARITIES_3_H
