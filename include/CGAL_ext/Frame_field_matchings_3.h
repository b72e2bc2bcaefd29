// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_MATCHINGS_3_H
#define CGAL_EXT_FRAME_FIELD_MATCHINGS_3_H

/// \file Frame_field_matchings_3.h
/// The matchings of a frame field across its interior faces: which frame
/// vector of one tetrahedron continues as which (signed) vector of its
/// neighbour, transports included (doc/math.md section 5). The singular edges,
/// and CubeCover's `.perm` file, are made from them.

#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/IO/Perm_file.h>
#include <CGAL_ext/Octahedral_frame.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// Angles between matched neighbouring frames over the interior faces (see
/// `Frame_field_matchings_3::face_angle_statistics()`).
struct Face_angle_statistics {
  /// The number of interior faces.
  std::size_t faces = 0;
  /** @{ */
  /// The mean, median and largest angle, in degrees.
  double mean_deg = 0, median_deg = 0, max_deg = 0;
  /** @} */
};

/// \ingroup PkgCGALExtFrames
/// The face matchings of a frame field, computed once.
///
/// For tetrahedron `i` and its neighbour `j` across local facet `f`, the
/// matching is the element `G` of `octahedral_group()` with
/// `T(i->j) R_i ~ R_j G` (`closest_octahedral_matching(T(i->j) R_i, R_j)`),
/// where `R_i = ff.rotation(i)` is the canonical rotation of tetrahedron `i`
/// (the one whose columns the output files hold). Column by column,
/// `T(i->j) R_i e_k ~ sign_k R_j e_{pi(k)}`: vector `k` of `i` continues as
/// `sign_k` times vector `pi(k)` of `j`.
///
/// Each interior face is matched once, from its tetrahedron of smaller index,
/// and the other side holds the inverse `G^T` exactly, so the two sides always
/// agree, and products of matchings around edges are exact.
///
/// \tparam Frame_field a `Frame_field_3` after `compute()` (or `set_rotations()`)
template <class Frame_field>
class Frame_field_matchings_3 {
public:
  /// Computes the matchings of every interior face (in parallel; the result
  /// does not depend on the number of threads).
  /// \param ff the frame field; the matchings are those of its current rotations
  explicit Frame_field_matchings_3(const Frame_field& ff) : index_(ff.size()), rotation_(ff.size()) {
    const std::size_t n = ff.size();
    internal::parallel_for_each_index(n, [&](std::size_t i) { rotation_[i] = ff.rotation(i); });
    internal::parallel_for_each_index(n, [&](std::size_t i) {
      for (int f = 0; f < 4; ++f) index_[i][f] = match(ff, i, f);
    });
  }

  /// Recomputes the matchings of the faces of some tetrahedra (from both
  /// sides) after their frames changed; the same as computing all again.
  /// \param ff the frame field the matchings were computed from
  /// \param tets the tetrahedra whose rotations changed
  void update(const Frame_field& ff, const std::vector<std::size_t>& tets) {
    for (std::size_t i : tets) rotation_[i] = ff.rotation(i);
    for (std::size_t i : tets)
      for (int f = 0; f < 4; ++f) {
        index_[i][f] = match(ff, i, f);
        const std::int64_t j = ff.neighbor(i, f);
        if (j >= 0) index_[std::size_t(j)][mirror_facet(ff, i, f)] = std::int8_t(inverse_index(index_[i][f]));
      }
  }

  /// The number of tetrahedra.
  /// \returns the number of tetrahedra of the frame field
  std::size_t size() const { return index_.size(); }

  /// The index in `octahedral_group()` of the matching from tetrahedron `i`
  /// to its neighbour across local facet `f`, or -1 on the boundary.
  /// \param i a tetrahedron index
  /// \param f a local facet index in 0..3
  /// \returns an index in 0..23, or -1
  int index(std::size_t i, int f) const { return index_[i][f]; }

  /// The matching from tetrahedron `i` across local facet `f` (an exact
  /// signed permutation matrix); the identity on the boundary.
  /// \param i a tetrahedron index
  /// \param f a local facet index in 0..3
  /// \returns the 3x3 matrix `G`, an element of `octahedral_group()`
  const Eigen::Matrix3d& matching(std::size_t i, int f) const {
    return octahedral_group()[index_[i][f] < 0 ? 0 : index_[i][f]];
  }

  /// The rotation `R_i` the matchings were computed with (`ff.rotation(i)`).
  /// \param i a tetrahedron index
  /// \returns the canonical rotation matrix `R_i`
  const Eigen::Matrix3d& rotation(std::size_t i) const { return rotation_[i]; }

  /// The angle, in degrees, between the frame of tetrahedron `i` carried
  /// into its neighbour `j` across local facet `f` and the matched frame of
  /// `j`: the rotation angle of `(R_j G)^T T(i->j) R_i`, in [0, 180]; 0 on
  /// the boundary. Small on most faces of a good field, which concentrates
  /// its rotation near the singular curves; the same from either side.
  /// \param ff the frame field the matchings were computed from
  /// \param i a tetrahedron index
  /// \param f a local facet index in 0..3
  /// \returns the angle in degrees; 0 on the boundary
  double face_angle_deg(const Frame_field& ff, std::size_t i, int f) const {
    const std::int64_t j = ff.neighbor(i, f);
    if (j < 0) return 0;
    const Eigen::Matrix3d T = ff.transport_into(std::size_t(j), mirror_facet(ff, i, f)); // T(i->j)
    const Eigen::Matrix3d D = (rotation_[std::size_t(j)] * matching(i, f)).transpose() * T * rotation_[i];
    // Through the quaternion: accurate near 0, unlike acos((trace - 1) / 2).
    return Eigen::AngleAxisd(D).angle() * 180 / M_PI;
  }

  /// The mean, median and largest of `face_angle_deg()` over the interior
  /// faces (each face once), and their number; all 0 without interior faces.
  /// A field that concentrates its rotation near its singular curves has a
  /// median far below its mean.
  /// \param ff the frame field the matchings were computed from
  /// \returns the number of interior faces and the angles in degrees
  Face_angle_statistics face_angle_statistics(const Frame_field& ff) const {
    std::vector<double> angles;
    for (std::size_t i = 0; i < size(); ++i)
      for (int f = 0; f < 4; ++f)
        if (ff.neighbor(i, f) > std::int64_t(i)) angles.push_back(face_angle_deg(ff, i, f));
    Face_angle_statistics out;
    out.faces = angles.size();
    if (angles.empty()) return out;
    double sum = 0;
    for (double a : angles) sum += a, out.max_deg = std::max(out.max_deg, a);
    out.mean_deg = sum / double(angles.size());
    const auto middle = angles.begin() + std::ptrdiff_t(angles.size() / 2);
    std::nth_element(angles.begin(), middle, angles.end());
    out.median_deg = *middle;
    return out;
  }

  /// The matchings as CubeCover's `.perm` file holds them (see
  /// `IO::write_perm()`): one face per interior face whose matching is not
  /// the identity, from its tetrahedron of smaller index, in the order of
  /// that index and of the local facet. With the frames
  /// `ff.parameter_gradients(i)` (or `ff.frame(i)`) in a `.fra` file, vector
  /// `k` of a tetrahedron is column `k` of that matrix.
  /// \param ff the frame field the matchings were computed from
  /// \returns the `.perm` file's content, for `IO::write_perm()`
  IO::Perm_file perm_file(const Frame_field& ff) const {
    IO::Perm_file out;
    out.tets = size();
    for (std::size_t i = 0; i < size(); ++i)
      for (int f = 0; f < 4; ++f) {
        const std::int64_t j = ff.neighbor(i, f);
        if (j > std::int64_t(i) && index_[i][f] != 0)
          out.faces.push_back({i, std::size_t(j), signed_permutation(index_[i][f])});
      }
    return out;
  }

  /// The signed, 1-based vector correspondence of a matching, as CubeCover's
  /// `.perm` files write it: `p[k] = sign_k (pi(k) + 1)`, so that vector `k`
  /// of the first tetrahedron times `sign(p[k])` is vector `|p[k]| - 1` of
  /// the second.
  /// \param group_index an index in `octahedral_group()`
  /// \returns `p`; the absolute values of its entries are a permutation of 1, 2, 3
  static std::array<int, 3> signed_permutation(int group_index) {
    const Eigen::Matrix3d& G = octahedral_group()[group_index];
    std::array<int, 3> p{};
    for (int k = 0; k < 3; ++k)
      for (int r = 0; r < 3; ++r)
        if (G(r, k) != 0) p[k] = (G(r, k) > 0 ? 1 : -1) * (r + 1);
    return p;
  }

  /// The index in `octahedral_group()` of the inverse of element `k`.
  /// \param k an index in `octahedral_group()`
  /// \returns the index of the transpose of element `k`, in 0..23
  static int inverse_index(int k) {
    static const std::array<int, 24> table = [] {
      std::array<int, 24> t{};
      for (int m = 0; m < 24; ++m) t[m] = octahedral_group_index(octahedral_group()[m].transpose(), 0);
      return t;
    }();
    return table[k];
  }

private:
  // The matching from tetrahedron i across facet f (-1 on the boundary). The
  // face is matched from the smaller index; the larger one takes the
  // inverse (G^T), found in the group table.
  std::int8_t match(const Frame_field& ff, std::size_t i, int f) const {
    const std::int64_t j = ff.neighbor(i, f);
    if (j < 0) return -1;
    const bool first = std::size_t(j) > i;
    const std::size_t a = first ? i : std::size_t(j), b = first ? std::size_t(j) : i;
    const int fb = first ? mirror_facet(ff, i, f) : f; // facet of b towards a
    const Eigen::Matrix3d T = ff.transport_into(b, fb); // T(a->b)
    const int k = closest_octahedral_matching(T * rotation_[a], rotation_[b]).index;
    return std::int8_t(first ? k : inverse_index(k));
  }

  // The local facet of neighbour j = ff.neighbor(i, f) that faces i.
  static int mirror_facet(const Frame_field& ff, std::size_t i, int f) {
    return ff.cell(std::size_t(ff.neighbor(i, f)))->index(ff.cell(i));
  }

  std::vector<std::array<std::int8_t, 4>> index_;
  std::vector<Eigen::Matrix3d> rotation_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_FRAME_FIELD_MATCHINGS_3_H
