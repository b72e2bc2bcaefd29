// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TEST_METRIC_FIELD_ARCHETYPE_H
#define CGAL_EXT_TEST_METRIC_FIELD_ARCHETYPE_H

// The archetype of the MetricField_3 concept (doc/Concepts/MetricField_3.h):
// exactly the concept's types and members, nothing else, so that a
// component needing more than the concept says fails to compile in
// test_concepts.cpp. It is a constant metric, so its results are known.

#include <boost/property_map/property_map.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <cstddef>
#include <cstdint>

namespace CGAL_ext {
namespace testing {

// The archetypes of VertexIndexMap_3 and DomainCellIndexMap_3
// (doc/Concepts): a readable property map's four types and get(), nothing
// else (not even default construction: the components take the maps from
// the field). They read the tet mesh's info; the domain is the tetrahedra.
template <class Tr>
class Vertex_index_map_archetype {
public:
  typedef typename Tr::Vertex_handle key_type;
  typedef std::size_t value_type;
  typedef std::size_t reference;
  typedef boost::readable_property_map_tag category;
  explicit Vertex_index_map_archetype(int) {}
  friend std::size_t get(const Vertex_index_map_archetype&, key_type v) { return v->info(); }
};

template <class Tr>
class Cell_index_map_archetype {
public:
  typedef typename Tr::Cell_handle key_type;
  typedef std::int64_t value_type;
  typedef std::int64_t reference;
  typedef boost::readable_property_map_tag category;
  explicit Cell_index_map_archetype(int) {}
  friend std::int64_t get(const Cell_index_map_archetype&, key_type c) { return c->info().index; }
};

template <class Tr>
class Metric_field_archetype_3 {
public:
  typedef Tr Triangulation_3;
  typedef typename Tr::Vertex_handle Vertex_handle;
  typedef typename Tr::Cell_handle Cell_handle;
  typedef typename Tr::Point Point_3;
  typedef Vertex_index_map_archetype<Tr> Vertex_index_map;
  typedef Cell_index_map_archetype<Tr> Cell_index_map;

  Metric_field_archetype_3(const Tr& tr, const Eigen::Matrix3d& A) : tr_(&tr), A_(A) {}
  Metric_field_archetype_3(const Metric_field_archetype_3&) = delete; // the components keep it by address

  const Triangulation_3& triangulation() const { return *tr_; }
  Vertex_index_map vertex_index_map() const { return Vertex_index_map(0); }
  Cell_index_map cell_index_map() const { return Cell_index_map(0); }
  Eigen::Matrix3d sqrt_metric(Vertex_handle) const { return A_; }
  Eigen::Matrix3d A_at(Cell_handle, const Point_3&) const { return A_; }
  Eigen::Matrix3d curl(Cell_handle) const { return Eigen::Matrix3d::Zero(); }
  Eigen::Vector4d barycentric_coordinates(Cell_handle c, const Point_3& p) const {
    Eigen::Matrix3d E;
    const Point_3& o = c->vertex(0)->point();
    for (int k = 0; k < 3; ++k) {
      const Point_3& q = c->vertex(k + 1)->point();
      E.col(k) = Eigen::Vector3d(q.x() - o.x(), q.y() - o.y(), q.z() - o.z());
    }
    const Eigen::Vector3d l = E.lu().solve(Eigen::Vector3d(p.x() - o.x(), p.y() - o.y(), p.z() - o.z()));
    return Eigen::Vector4d(1 - l.sum(), l(0), l(1), l(2));
  }

private:
  const Tr* tr_;
  Eigen::Matrix3d A_;
};

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_METRIC_FIELD_ARCHETYPE_H
