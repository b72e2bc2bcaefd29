// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_HEX_COVERAGE_CEILING_3_H
#define CGAL_EXT_HEX_COVERAGE_CEILING_3_H

/// \file Hex_coverage_ceiling_3.h
/// How much of a domain with a curved boundary hexahedra of a given size can
/// cover at best, and the hex size that a coverage asks for.

#include <CGAL_ext/Sharp_features_3.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// The coverage (hex volume over tet volume) that hexahedra with straight
/// edges, their boundary vertices on the tet mesh's boundary, can reach at
/// best where that boundary is curved.
///
/// A bilinear boundary quad of side `l` with its corners on a surface of
/// mean curvature `H` lies below it by `2H l^2 / 12` on average, whatever its
/// orientation. The tet mesh's boundary is a faceted copy of such a
/// surface; where the quad's corners fall anywhere on the facets (as
/// HexEx's do), it cuts below the facets by the same on average. So the hexes miss `l^2 / 12` times the
/// integral of `2H` over the boundary's smooth part (creases are followed by
/// hex edges), out of the volume `V`:
/// `ceiling = max(0, 1 - l^2 / 12 * smooth_turning / V)`.
/// Concave parts (negative turning), where the quads bulge out, can give a
/// ceiling above 1. A second-order estimate: on unit balls with 5 to 7
/// hexes per side it lies 0.0025 to 0.0046 above the coverage such hexes
/// reach, and 0.005 below when every quad corner is a tet vertex
/// (`scripts/test_hex_mesh_quality.py`, whose script computes the same from
/// a hex mesh and its tet mesh).
///
/// All lengths in one unit: in the metric, where a hex edge is 1 and `V` the
/// metric volume, for the pipeline's fields.
/// \param smooth_turning the integral of `2H` over the smooth part of the boundary
///        (`Sharp_features_3::smooth_turning()`)
/// \param volume `V`, the domain's volume
/// \param hex_edge `l`, the hexahedra's edge length
/// \returns the ceiling; NaN if `volume` is not positive or a value is not finite
inline double hex_coverage_ceiling(double smooth_turning, double volume, double hex_edge) {
  if (!(volume > 0) || !std::isfinite(smooth_turning) || !std::isfinite(volume) || !std::isfinite(hex_edge))
    return std::numeric_limits<double>::quiet_NaN();
  return std::max(0.0, 1 - hex_edge * hex_edge / 12 * smooth_turning / volume);
}

/// \ingroup PkgCGALExtFrames
/// The largest hex edge whose `hex_coverage_ceiling()` reaches a coverage:
/// the inverse of that formula in `l`, `sqrt(12 (1 - coverage) V / smooth_turning)`.
/// \param smooth_turning the integral of `2H` over the smooth part of the boundary
/// \param volume the domain's volume
/// \param coverage the coverage asked for, in `[0, 1)`
/// \returns the hex edge; +infinity if the ceiling reaches `coverage` at every
///          size (a boundary that is flat or concave overall); NaN if
///          `volume` is not positive, `coverage` not in `[0, 1)`, or a value not finite
inline double hex_edge_for_coverage(double smooth_turning, double volume, double coverage) {
  if (!(volume > 0) || !(coverage >= 0 && coverage < 1) || !std::isfinite(smooth_turning) || !std::isfinite(volume))
    return std::numeric_limits<double>::quiet_NaN();
  if (!(smooth_turning > 0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(12 * (1 - coverage) * volume / smooth_turning);
}

/// \ingroup PkgCGALExtFrames
/// `hex_coverage_ceiling()` from the boundary measured by the sharp features.
/// \tparam Metric_field a model of `MetricField_3`
/// \param features the sharp features of the mesh in the metric (their angle
///        decides which edges are creases that hex edges follow)
/// \param metric_volume the domain's volume in the metric (`Metric_field_3::metric_volume()`)
/// \param hex_edge the hex edge in the metric (1 for the pipeline's fields)
/// \returns the ceiling, as `hex_coverage_ceiling()`
template <class Metric_field>
double hex_coverage_ceiling(const Sharp_features_3<Metric_field>& features, double metric_volume,
                            double hex_edge = 1) {
  return hex_coverage_ceiling(features.smooth_turning(), metric_volume, hex_edge);
}

} // namespace CGAL_ext

#endif // CGAL_EXT_HEX_COVERAGE_CEILING_3_H
