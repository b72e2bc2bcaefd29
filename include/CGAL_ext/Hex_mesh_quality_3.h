// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_HEX_MESH_QUALITY_3_H
#define CGAL_EXT_HEX_MESH_QUALITY_3_H

/// \file Hex_mesh_quality_3.h
/// The quality of a hexahedral mesh: Verdict's scaled Jacobian, volumes,
/// coverage of the domain, and sizes against those a metric asks for.

#include <CGAL_ext/Hex_mesh_3.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtHex
/// The scaled Jacobian of one hexahedron.
struct Hex_scaled_jacobian {
  /// Verdict's `hex_scaled_jacobian` (what VTK's `vtkMeshQuality` and
  /// ParaView report): the least, over 9 frames, of `det(a, b, c) / (|a| |b| |c|)`.
  /// The frames are the 8 corner frames (at corner 0: `p1 - p0`, `p3 - p0`,
  /// `p4 - p0`, and likewise at the others) and the centre frame of the
  /// three principal axes (each the sum of the 4 parallel edges of a family,
  /// `hex_edge_families`). In `[-1, 1]`; 1 for a cuboid.
  double value = 0;
  /// The least of the 8 corner frames alone.
  double corners = 0;
  /// Whether a frame has a vector of length 0 (or one that is not finite:
  /// coordinates whose differences overflow). That frame counts 0, so a
  /// collapsed hexahedron is bad;
  /// Verdict returns a huge value there instead (`VERDICT_DBL_MAX`, 1e30 in
  /// VTK 9), which would hide it.
  bool degenerate = false;
};

/// \ingroup PkgCGALExtHex
/// The scaled Jacobian of a hexahedron (see `Hex_scaled_jacobian`).
/// \param p the 8 vertices in VTK order (`Hex_mesh_3`)
/// \returns Verdict's value, the corners' value, and whether it is degenerate
Hex_scaled_jacobian hex_scaled_jacobian(const std::array<Eigen::Vector3d, 8>& p);

/// \ingroup PkgCGALExtHex
/// The signed volume of the trilinear hexahedron through 8 points: the
/// integral of `det J` over the unit cube, exact (2 x 2 x 2 Gauss points;
/// `det J` has degree at most 2 in each variable). Positive for a
/// positively oriented hexahedron.
/// \param p the 8 vertices in VTK order
/// \returns the volume
double hex_volume(const std::array<Eigen::Vector3d, 8>& p);

/// \ingroup PkgCGALExtHex
/// What `hex_mesh_quality()` measures besides the hexahedra themselves.
struct Hex_mesh_quality_options {
  /// The volume of the domain the hexahedra should fill (the tet mesh's);
  /// with it, the report gives the coverage. NaN: not given.
  double domain_volume = std::numeric_limits<double>::quiet_NaN();
  /// The metric asked for, scaled so that the hex edge asked for has length
  /// 1 (for hexes of edge `h` and no other metric, `I / h^2`). With it, the
  /// report gives the edges' lengths and the hexahedra's sizes in it. Empty:
  /// not given. Called from one thread, on points of the hexahedra.
  std::function<Eigen::Matrix3d(const Eigen::Vector3d&)> metric;
};

/// \ingroup PkgCGALExtHex
/// Count, least, median (the mean of the two middle values for an even
/// count), mean and largest of a set of values; NaN when the set is empty.
struct Hex_quality_summary {
  std::size_t count = 0;                                  ///< the number of values
  double min = std::numeric_limits<double>::quiet_NaN();    ///< the least value
  double median = std::numeric_limits<double>::quiet_NaN(); ///< the median
  double mean = std::numeric_limits<double>::quiet_NaN();   ///< the mean
  double max = std::numeric_limits<double>::quiet_NaN();    ///< the largest value
};

/// \ingroup PkgCGALExtHex
/// The summary of a set of values (see `Hex_quality_summary`).
/// \param values the values, all finite; taken by value since they are sorted
/// \returns their summary
Hex_quality_summary hex_quality_summary(std::vector<double> values);

/// \ingroup PkgCGALExtHex
/// The quality of a hexahedral mesh, as `hex_mesh_quality()` measures it.
struct Hex_mesh_quality_3 {
  std::size_t hexahedra = 0; ///< the number of hexahedra
  std::size_t vertices = 0;  ///< the number of points used by a hexahedron

  /// Per hexahedron, Verdict's scaled Jacobian (for a file's cell data).
  std::vector<double> scaled_jacobians;
  /// Verdict's scaled Jacobian over the hexahedra.
  Hex_quality_summary scaled_jacobian;
  /// The corner frames' scaled Jacobian over the hexahedra.
  Hex_quality_summary scaled_jacobian_corners;
  std::size_t scaled_jacobian_at_most_0 = 0; ///< hexahedra whose scaled Jacobian is `<= 0`: not valid
  std::size_t scaled_jacobian_below_0_2 = 0; ///< hexahedra whose scaled Jacobian is `< 0.2`
  std::size_t scaled_jacobian_below_0_5 = 0; ///< hexahedra whose scaled Jacobian is `< 0.5`
  std::size_t degenerate = 0; ///< hexahedra with a frame vector of length 0 (`Hex_scaled_jacobian::degenerate`)
  /// Histogram of the scaled Jacobian: bin `k` counts the values in
  /// `[-1 + k / 10, -1 + (k + 1) / 10)`, the last bin includes 1.
  std::array<std::size_t, 20> scaled_jacobian_histogram{};

  double volume = 0;                    ///< the sum of the signed volumes (`hex_volume()`)
  std::size_t negative_volume_hexes = 0; ///< hexahedra whose signed volume is negative
  /// `volume` over `Hex_mesh_quality_options::domain_volume`; NaN if that is not given.
  double coverage = std::numeric_limits<double>::quiet_NaN();

  Hex_quality_summary edge_length;      ///< the lengths of the mesh's edges, each counted once
  std::size_t boundary_quadrilaterals = 0; ///< faces that belong to one hexahedron
  /// Root mean square length of the boundary faces' edges, each counted
  /// once: the `l` of `hex_coverage_ceiling()` for these hexahedra.
  double boundary_edge_rms = std::numeric_limits<double>::quiet_NaN();

  /// With a metric: the edges' lengths in it (1 is the size asked for),
  /// integrated along each edge (3 Gauss points).
  Hex_quality_summary metric_edge_length;
  /// With a metric: the share of the edges whose metric length is in `[0.8, 1.25]`.
  double metric_edges_within_25_percent = std::numeric_limits<double>::quiet_NaN();
  /// With a metric: per hexahedron, the cube root of its volume in the
  /// metric (`integral of sqrt(det g) det J`, 2 x 2 x 2 Gauss points,
  /// signed): 1 for a hexahedron of the volume asked for, whatever its shape.
  Hex_quality_summary metric_size;
  /// With a metric: the share of the hexahedra whose `metric_size` is in `[0.8, 1.25]`.
  double metric_sizes_within_25_percent = std::numeric_limits<double>::quiet_NaN();
};

/// \ingroup PkgCGALExtHex
/// Measures a hexahedral mesh: Verdict's scaled Jacobian per hexahedron
/// (the figure hex meshes are judged by: a mesh is valid when every value is
/// positive), signed volumes and the coverage of the domain, edge lengths,
/// and with a metric the sizes against those asked for.
/// \param mesh the hexahedra (its quadrilaterals and edges are not used:
///        the boundary is found from the hexahedra)
/// \param options the domain's volume and the metric, both optional
/// \returns the figures
/// \throws std::invalid_argument if a vertex index is out of range or a
///   point not finite (naming the hexahedron, 1-based), if the mesh is not
///   manifold (`hex_mesh_boundary_quadrilaterals()`), or if the metric gives
///   a matrix that is not finite, not symmetric or not positive definite
///   (naming the hexahedron)
Hex_mesh_quality_3 hex_mesh_quality(const Hex_mesh_3& mesh, const Hex_mesh_quality_options& options = {});

} // namespace CGAL_ext

#endif // CGAL_EXT_HEX_MESH_QUALITY_3_H
