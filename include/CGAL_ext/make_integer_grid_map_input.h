// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_MAKE_INTEGER_GRID_MAP_INPUT_H
#define CGAL_EXT_MAKE_INTEGER_GRID_MAP_INPUT_H

/// \file make_integer_grid_map_input.h
/// The input of the integer-grid map from a computed frame field.

#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Integer_grid_map_3.h>

#include <stdexcept>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtHex
/// The input of `compute_integer_grid_map()` from a frame field: the
/// tetrahedra with their vertices in the triangulation's cell order
/// (positively oriented), their neighbours, the matchings, the parameter
/// gradients `A R` divided by `hex_size` (1 for a metric already scaled to
/// the hex size, as the pipeline's), and as free boundary the tetrahedra
/// whose hard constraint the repair released.
/// \tparam Frame_field a `Frame_field_3`
/// \param ff the frame field, after `compute()`
/// \param matchings its matchings
/// \param positions the position of every vertex, by index (the
///   triangulation's, or moved ones such as the straightening's)
/// \param hex_size the hex edge in the metric's unit length
/// \returns the map's input
/// \throws std::invalid_argument if a vertex index is not below
///   `positions.size()`, or `hex_size` is not positive and finite
template <class Frame_field>
Integer_grid_map_input make_integer_grid_map_input(const Frame_field& ff,
                                                   const Frame_field_matchings_3<Frame_field>& matchings,
                                                   const std::vector<Eigen::Vector3d>& positions, double hex_size = 1) {
  if (!(hex_size > 0) || !std::isfinite(hex_size))
    throw std::invalid_argument("make_integer_grid_map_input: the hex size must be positive and finite");
  Integer_grid_map_input in;
  in.positions = positions;
  const std::size_t n = ff.size();
  in.tets.resize(n);
  in.neighbors.resize(n);
  in.matchings.resize(n);
  in.gradients.resize(n);
  in.free_boundary.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int f = 0; f < 4; ++f) {
      const std::size_t v = ff.vertex_index(ff.cell(i)->vertex(f));
      if (v >= positions.size())
        throw std::invalid_argument("make_integer_grid_map_input: vertex " + std::to_string(v + 1) + " has no position");
      in.tets[i][std::size_t(f)] = v;
      in.neighbors[i][std::size_t(f)] = ff.neighbor(i, f);
      in.matchings[i][std::size_t(f)] = matchings.index(i, f);
    }
    in.gradients[i] = ff.parameter_gradients(i) / hex_size;
    in.free_boundary[i] = ff.hard_constraint_released(i);
  }
  return in;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_MAKE_INTEGER_GRID_MAP_INPUT_H
