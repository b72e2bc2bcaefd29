// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_METRIC_FIELD_3_H
#define CGAL_EXT_METRIC_FIELD_3_H

/// \file Metric_field_3.h
/// A piecewise-linear metric field on a tetrahedral mesh that stores its
/// per-vertex square roots `A = g^{1/2}`, linear in each cell, with its
/// constant curl per cell and the connection one-form `W` (doc/math.md
/// sections 1 to 3). `Property_map_metric_field_3` reads them from a map of
/// the user's instead.

#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/Metric_tensor.h>
#include <CGAL_ext/Property_map_metric_field_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>

#include <CGAL/property_map.h>

#include <Eigen/Core>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL_ext {

namespace internal {

// The square roots a Metric_field_3 stores, one per vertex index (has[i]:
// whether index i has a vertex), and the lvalue map that reads them. A base
// class of Metric_field_3, so that it is filled before the field is built.
template <class Triangulation, class VertexIndexMap>
struct Metric_field_storage_3 {
  using Vertex_handle = typename Triangulation::Vertex_handle;

  struct Map {
    using key_type = Vertex_handle;
    using value_type = Eigen::Matrix3d;
    using reference = const Eigen::Matrix3d&;
    using category = boost::lvalue_property_map_tag;
    const std::vector<Eigen::Matrix3d>* roots;
    VertexIndexMap vim;
    friend reference get(const Map& m, key_type v) { return (*m.roots)[get(m.vim, v)]; }
  };

  std::vector<Eigen::Matrix3d> roots;
  std::vector<char> has;

  Metric_field_storage_3(const Triangulation& tr, const std::vector<Eigen::Matrix3d>& metrics,
                         const std::string& source, VertexIndexMap vim) {
    for (std::size_t i = 0; i < metrics.size(); ++i) {
      const std::string why = check_metric_tensor(metrics[i]);
      if (!why.empty()) throw Input_error(source, 0, metric_vertex_name(i), why);
    }
    for (Vertex_handle v : tr.finite_vertex_handles()) {
      const std::size_t i = get(vim, v);
      if (i >= metrics.size())
        throw Input_error(source, 0, metric_vertex_name(i),
                          "has no metric: only " + std::to_string(metrics.size()) + " metrics were given");
    }
    roots.resize(metrics.size());
    has.assign(metrics.size(), 0);
    for (Vertex_handle v : tr.finite_vertex_handles()) {
      const std::size_t i = get(vim, v);
      if (!has[i]) roots[i] = sqrt_spd(metrics[i]);
      has[i] = 1;
    }
  }

  template <class Function>
  Metric_field_storage_3(const Triangulation& tr, Function& g, VertexIndexMap vim) {
    resize_for_vertices(tr, vim);
    for (Vertex_handle v : tr.finite_vertex_handles()) {
      const Eigen::Matrix3d gv = g(v->point());
      const std::string why = check_metric_tensor(gv);
      if (!why.empty()) throw metric_vertex_error(get(vim, v), v->point(), why);
      roots[get(vim, v)] = sqrt_spd(gv);
      has[get(vim, v)] = 1;
    }
  }

  Metric_field_storage_3(const Triangulation& tr, const Eigen::Matrix3d& g, VertexIndexMap vim, int /*constant*/) {
    const std::string why = check_metric_tensor(g);
    if (!why.empty()) throw Input_error("", 0, "constant metric", why);
    const Eigen::Matrix3d A = sqrt_spd(g); // one root, so all vertices are bitwise equal
    resize_for_vertices(tr, vim);
    for (Vertex_handle v : tr.finite_vertex_handles()) {
      roots[get(vim, v)] = A;
      has[get(vim, v)] = 1;
    }
  }

  void resize_for_vertices(const Triangulation& tr, VertexIndexMap vim) {
    std::size_t n = 0;
    for (Vertex_handle v : tr.finite_vertex_handles()) n = std::max<std::size_t>(n, get(vim, v) + 1);
    roots.resize(n);
    has.assign(n, 0);
  }

  Map map(VertexIndexMap vim) const { return Map{&roots, vim}; }
};

} // namespace internal

/// \ingroup PkgCGALExtMetric
/// A metric field on the cells of a 3D triangulation, given by one SPD
/// metric tensor `g` per vertex (an edge `e` has length `sqrt(e^T g e)`),
/// whose square roots it stores.
///
/// - Stored per vertex: `A = g^{1/2}` (`sqrt_spd()`), indexed by the vertex
///   index of `VertexIndexMap`.
/// - Everything else is `Property_map_metric_field_3` over these roots:
///   **A (not g) is linear** in each cell (`A_at()`), `curl A` is constant
///   per cell (`curl()`), `W = connection_one_form(A, curl A)`
///   (`connection()`), the per-cell data is cached and safe to read from
///   several threads, and the domain is given by the cell index map.
/// - `set_metric()` and `put()` on `metric_map()` must not run concurrently
///   with anything else.
///
/// To use metric values kept elsewhere (a vertex's `info()`, a map of the
/// user's) without copying them, use `Property_map_metric_field_3`.
///
/// \tparam Triangulation a model of `TetMeshTriangulation_3` (e.g. `Tet_mesh_triangulation_3<>`)
/// \tparam VertexIndexMap a model of `VertexIndexMap_3`; default: the file index `v->info()`
/// \tparam CellIndexMap a model of `DomainCellIndexMap_3`; default: the
///         tetrahedron index `c->info().index`
///
/// \cgalModels `MetricField_3`
template <class Triangulation, class VertexIndexMap = Tet_mesh_vertex_index_map<Triangulation>,
          class CellIndexMap = Tet_mesh_cell_index_map<Triangulation>>
class Metric_field_3
    : private internal::Metric_field_storage_3<Triangulation, VertexIndexMap>,
      public Property_map_metric_field_3<Triangulation,
                                         typename internal::Metric_field_storage_3<Triangulation, VertexIndexMap>::Map,
                                         VertexIndexMap, CellIndexMap> {
  using Storage = internal::Metric_field_storage_3<Triangulation, VertexIndexMap>;
  using Base = Property_map_metric_field_3<Triangulation, typename Storage::Map, VertexIndexMap, CellIndexMap>;

public:
  /// The triangulation type.
  using Triangulation_3 = Triangulation;
  /// Vertex handle type.
  using Vertex_handle = typename Triangulation::Vertex_handle;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;
  /// Point type.
  using Point_3 = typename Triangulation::Point;

  /// Builds the field from one metric tensor per vertex index.
  /// \param tr the triangulation; it must outlive the field and not change
  /// \param metrics `metrics[i]` is `g` at the vertex of index `i` (entries
  ///        of indices without a vertex are validated too, but not used)
  /// \param source the file the metrics came from, for error messages (may be empty)
  /// \param vim the vertex index map
  /// \param cim the cell index map
  /// \throws Input_error naming the vertex (1-based, as in Medit files) if a
  ///         tensor is not finite, not symmetric or not positive definite
  ///         (see `check_metric_tensor()`), or if a vertex has no metric
  Metric_field_3(const Triangulation& tr, const std::vector<Eigen::Matrix3d>& metrics,
                 const std::string& source = {}, VertexIndexMap vim = VertexIndexMap(),
                 CellIndexMap cim = CellIndexMap())
      : Storage(tr, metrics, source, vim), Base(tr, Storage::map(vim), Vertex_metric_kind::sqrt_metric, vim, cim,
                                                typename Base::Unchecked()) {}

  /// Builds the field by evaluating a function at every finite vertex.
  /// \tparam Function a callable `Eigen::Matrix3d(const Point_3&)` giving `g`
  /// \param tr the triangulation; it must outlive the field and not change
  /// \param g the metric as a function of the position
  /// \param vim the vertex index map
  /// \param cim the cell index map
  /// \throws Input_error naming the vertex and its position if `g` is not a valid metric there
  template <class Function,
            class = std::enable_if_t<std::is_invocable_r_v<Eigen::Matrix3d, Function&, const Point_3&>>>
  Metric_field_3(const Triangulation& tr, Function g, VertexIndexMap vim = VertexIndexMap(),
                 CellIndexMap cim = CellIndexMap())
      : Storage(tr, g, vim), Base(tr, Storage::map(vim), Vertex_metric_kind::sqrt_metric, vim, cim,
                                  typename Base::Unchecked()) {}

  /// Builds a constant field. Its curl and connection are exactly zero, and
  /// every transport in it is exactly the identity.
  /// \param tr the triangulation; it must outlive the field and not change
  /// \param g the metric tensor everywhere
  /// \param vim the vertex index map
  /// \param cim the cell index map
  /// \throws Input_error if `g` is not a valid metric
  Metric_field_3(const Triangulation& tr, const Eigen::Matrix3d& g, VertexIndexMap vim = VertexIndexMap(),
                 CellIndexMap cim = CellIndexMap())
      : Storage(tr, g, vim, 0), Base(tr, Storage::map(vim), Vertex_metric_kind::sqrt_metric, vim, cim,
                                     typename Base::Unchecked()) {}

  /// The square root `A = g^{1/2}` at a vertex (symmetric positive definite).
  /// \param v a finite vertex
  /// \returns `A` at `v` (3x3)
  /// \throws std::invalid_argument if `v` has no metric (its index was not given one)
  const Eigen::Matrix3d& sqrt_metric(Vertex_handle v) const { return this->roots[checked_index(v)]; }

  /// The metric `g = A A` at a vertex.
  /// \param v a finite vertex
  /// \returns `g` at `v` (3x3, symmetric positive definite)
  Eigen::Matrix3d metric(Vertex_handle v) const {
    const Eigen::Matrix3d& A = sqrt_metric(v);
    return A * A;
  }

  /// Replaces the metric at a vertex and forgets the cached data of its cells.
  /// Not thread-safe: nothing else may use the field meanwhile.
  /// \param v a finite vertex
  /// \param g the new metric tensor
  /// \throws Input_error naming the vertex if `g` is not a valid metric
  void set_metric(Vertex_handle v, const Eigen::Matrix3d& g) {
    const std::size_t i = checked_index(v);
    const std::string why = check_metric_tensor(g);
    if (!why.empty()) throw Input_error("", 0, internal::metric_vertex_name(i), why);
    this->roots[i] = sqrt_spd(g);
    this->forget_cells_around(v);
  }

  /// \ingroup PkgCGALExtMetric
  /// Read-only lvalue property map `Vertex_handle -> const Eigen::Matrix3d&`, the square root `A`.
  class Sqrt_metric_map {
  public:
    using key_type = Vertex_handle;                 ///< key
    using value_type = Eigen::Matrix3d;             ///< value
    using reference = const Eigen::Matrix3d&;       ///< returned by reference
    using category = boost::lvalue_property_map_tag; ///< lvalue map
    /// \param f the field
    explicit Sqrt_metric_map(const Metric_field_3& f) : f_(&f) {}
    /// \param m the map \param v a finite vertex
    friend reference get(const Sqrt_metric_map& m, key_type v) { return m.f_->sqrt_metric(v); }
    /// \param v a finite vertex
    /// \returns `A` at `v`
    reference operator[](key_type v) const { return f_->sqrt_metric(v); }

  private:
    const Metric_field_3* f_;
  };

  /// \ingroup PkgCGALExtMetric
  /// Read-write property map `Vertex_handle -> Eigen::Matrix3d`, the metric `g`.
  /// `put` validates and calls `set_metric()` (same thread-safety caveat).
  class Metric_map {
  public:
    using key_type = Vertex_handle;                      ///< key
    using value_type = Eigen::Matrix3d;                  ///< value
    using reference = Eigen::Matrix3d;                   ///< returned by value
    using category = boost::read_write_property_map_tag; ///< read-write map
    /// \param f the field
    explicit Metric_map(Metric_field_3& f) : f_(&f) {}
    /// \param m the map \param v a finite vertex
    friend reference get(const Metric_map& m, key_type v) { return m.f_->metric(v); }
    /// \param m the map \param v a finite vertex \param g the new metric
    /// \throws Input_error if `g` is not a valid metric
    friend void put(const Metric_map& m, key_type v, const Eigen::Matrix3d& g) { m.f_->set_metric(v, g); }

  private:
    Metric_field_3* f_;
  };

  /// The square roots as a property map.
  /// \returns a map that reads this field, which must outlive it
  Sqrt_metric_map sqrt_metric_map() const { return Sqrt_metric_map(*this); }
  /// The metrics as a read-write property map.
  /// \returns a map that reads and writes this field, which must outlive it
  Metric_map metric_map() { return Metric_map(*this); }

private:
  std::size_t checked_index(Vertex_handle v) const {
    const std::size_t i = get(this->vertex_index_map(), v);
    if (i >= this->has.size() || !this->has[i]) throw std::invalid_argument("Metric_field_3: vertex without a metric");
    return i;
  }
};

} // namespace CGAL_ext

#endif // CGAL_EXT_METRIC_FIELD_3_H
