// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_PROPERTY_MAP_METRIC_FIELD_3_H
#define CGAL_EXT_PROPERTY_MAP_METRIC_FIELD_3_H

/// \file Property_map_metric_field_3.h
/// A piecewise-linear metric field that reads its per-vertex values from the
/// user's property map, without copying them: `A = g^{1/2}` linear in each
/// cell, its constant curl per cell and the connection one-form `W`
/// (doc/math.md sections 1 to 3). `Metric_field_3` is the same field over
/// values it stores itself.

#include <CGAL_ext/Connection_3.h>
#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/Metric_tensor.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>

#include <CGAL/number_utils.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL_ext {

namespace internal {
// A point's coordinates as an Eigen vector of doubles.
template <class Point_3>
Eigen::Vector3d to_eigen_vector(const Point_3& p) {
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}
// How messages about a metric field name the vertex of 0-based index i.
inline std::string metric_vertex_name(std::size_t i) { return "vertex " + std::to_string(i + 1); }
// The error for an invalid metric value `why` at the vertex of index i at point p.
template <class Point_3>
Input_error metric_vertex_error(std::size_t i, const Point_3& p, const std::string& why) {
  std::ostringstream s;
  s << why << " at (" << p << ")";
  return Input_error("", 0, metric_vertex_name(i), s.str());
}
} // namespace internal

/// \ingroup PkgCGALExtMetric
/// What the values of a per-vertex metric property map are.
enum class Vertex_metric_kind {
  metric,     ///< the metric tensor `g` (its root is taken at each read)
  sqrt_metric ///< its square root `A = g^{1/2}`, used as given
};

/// \ingroup PkgCGALExtMetric
/// A metric field on the cells of a 3D triangulation whose per-vertex values
/// are read from a property map of the user's, never copied: the map may
/// be a vertex's `info()`, a `boost::associative_property_map`, or any
/// readable property map from `Vertex_handle` to `Eigen::Matrix3d`.
///
/// - The map holds `g` or `A = g^{1/2}` (`Vertex_metric_kind`). `A` is used
///   as given (it must be symmetric); for `g` the root `sqrt_spd(g)` is
///   taken at every read, which costs one 3x3 symmetric eigendecomposition
///   per vertex read: give `A` where speed matters (doc/metric_field.md
///   gives the measured cost).
/// - Inside a cell, **A (not g) is linear** in the barycentric coordinates
///   (`A_at()`), so `A` is continuous and `curl A` is constant per cell
///   (`curl()`), and `W = connection_one_form(A, curl A)` (`connection()`).
/// - The domain is the set of cells with a non-negative index in the cell
///   index map (`cell_index_map()`); the frame field and the transports take
///   the domain and both index maps from the field, so they agree.
/// - The per-cell data (inverse edge matrix, curl) is computed on first use
///   and cached. Concurrent reads from several threads are safe and give the
///   same bits whatever the order; `precompute()` fills the whole cache in
///   parallel with TBB. If the map's value at a vertex changes, call
///   `metric_changed()` before the next read (nothing else may use the
///   field meanwhile).
///
/// Derivatives in a cell with vertices `p0..p3` use the edge matrix
/// `E = [p1 - p0, p2 - p0, p3 - p0]`: the barycentric coordinates of `x`
/// are `(1 - sum, E^{-1} (x - p0))`, so `d_k A = sum_{v=1..3} E^{-1}(v-1, k) (A_v - A_0)`.
/// It is the `sum_v T[v][k] A_v` of doc/math.md section 2, written with
/// differences so that a constant metric gives exactly zero curl.
///
/// \tparam Triangulation a model of `TetMeshTriangulation_3` (e.g. `Tet_mesh_triangulation_3<>`)
/// \tparam VertexMetricMap a readable property map from `Vertex_handle` to
///         `Eigen::Matrix3d` (`g` or `A`, see `Vertex_metric_kind`)
/// \tparam VertexIndexMap a model of `VertexIndexMap_3`; default: the file index `v->info()`
/// \tparam CellIndexMap a model of `DomainCellIndexMap_3`; default: the
///         tetrahedron index `c->info().index`
///
/// \cgalModels `MetricField_3`
template <class Triangulation, class VertexMetricMap, class VertexIndexMap = Tet_mesh_vertex_index_map<Triangulation>,
          class CellIndexMap = Tet_mesh_cell_index_map<Triangulation>>
class Property_map_metric_field_3 {
public:
  /// The triangulation type.
  using Triangulation_3 = Triangulation;
  /// Vertex handle type.
  using Vertex_handle = typename Triangulation::Vertex_handle;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;
  /// Point type.
  using Point_3 = typename Triangulation::Point;
  /// The vertex index map type.
  using Vertex_index_map = VertexIndexMap;
  /// The cell index map type (it defines the domain).
  using Cell_index_map = CellIndexMap;
  /// The per-vertex metric map type.
  using Vertex_metric_map = VertexMetricMap;

  /// Builds the field over the user's map and checks its value at every
  /// finite vertex (`check_metric_tensor()`); nothing is copied.
  /// \param tr the triangulation; it must outlive the field and not change
  /// \param map the per-vertex values; the map (and what it reads) must outlive the field
  /// \param kind whether the map holds `g` or `A`
  /// \param vim the vertex index map (its indices name vertices in messages)
  /// \param cim the cell index map (non-negative on the domain cells)
  /// \throws Input_error naming the vertex (1-based index) if a value is not
  ///         finite, not symmetric or not positive definite, or if the
  ///         domain's bounding box is outside the supported lengths
  Property_map_metric_field_3(const Triangulation& tr, VertexMetricMap map, Vertex_metric_kind kind,
                              VertexIndexMap vim = VertexIndexMap(), CellIndexMap cim = CellIndexMap())
      : Property_map_metric_field_3(tr, map, kind, vim, cim, Unchecked()) {
    for (Vertex_handle v : tr.finite_vertex_handles()) check_vertex(v);
  }

  Property_map_metric_field_3(const Property_map_metric_field_3&) = delete; ///< the components keep it by address
  Property_map_metric_field_3& operator=(const Property_map_metric_field_3&) = delete; ///< not assignable

  /// The triangulation.
  /// \returns the triangulation given to the constructor
  const Triangulation& triangulation() const { return *tr_; }
  /// The vertex index map.
  /// \returns the map given to the constructor
  VertexIndexMap vertex_index_map() const { return vim_; }
  /// The cell index map, which defines the domain.
  /// \returns the map given to the constructor
  CellIndexMap cell_index_map() const { return cim_; }
  /// The per-vertex map the field reads.
  /// \returns the map given to the constructor
  VertexMetricMap vertex_metric_map() const { return map_; }
  /// What the map holds.
  /// \returns `g` or `A`
  Vertex_metric_kind vertex_metric_kind() const { return kind_; }

  /// The square root `A = g^{1/2}` at a vertex, read from the map.
  /// \param v a finite vertex
  /// \returns `A` at `v` (3x3)
  Eigen::Matrix3d sqrt_metric(Vertex_handle v) const { return vertex_sqrt(v); }

  /// The metric `g` at a vertex, read from the map.
  /// \param v a finite vertex
  /// \returns `g` at `v` (3x3)
  Eigen::Matrix3d metric(Vertex_handle v) const {
    if (kind_ == Vertex_metric_kind::metric) return get(map_, v);
    const Eigen::Matrix3d A = get(map_, v);
    return A * A;
  }

  /// Tells the field that the map's value at `v` changed: checks it and
  /// forgets the cached data of the cells around `v`. Not thread-safe:
  /// nothing else may use the field meanwhile.
  /// \param v a finite vertex
  /// \throws Input_error naming the vertex if the new value is not valid
  void metric_changed(Vertex_handle v) {
    check_vertex(v);
    forget_cells_around(v);
  }

  /// The barycentric coordinates of `p` in the cell `c`, in the order of
  /// `c->vertex(0..3)`. They sum to 1; they are all in `[0, 1]` iff `p` is in `c`.
  /// \param c a cell of the domain
  /// \param p a point
  /// \returns the four coordinates, summing to 1
  Eigen::Vector4d barycentric_coordinates(Cell_handle c, const Point_3& p) const {
    const Cell_data& d = data(c);
    const Eigen::Vector3d l = d.inverse_edges * (internal::to_eigen_vector(p) - d.p0);
    return Eigen::Vector4d(1 - l.sum(), l(0), l(1), l(2));
  }

  /// The square root `A` at a point, interpolated linearly in the cell `c`
  /// (doc/math.md section 1). Outside `c` this extrapolates `c`'s linear field.
  /// \param c a cell of the domain
  /// \param p a point, normally in `c`
  /// \returns `A(p)` (3x3, symmetric)
  Eigen::Matrix3d A_at(Cell_handle c, const Point_3& p) const {
    const Cell_data& d = data(c);
    const Eigen::Vector3d l = d.inverse_edges * (internal::to_eigen_vector(p) - d.p0);
    const Eigen::Matrix3d A0 = vertex_sqrt(c->vertex(0));
    Eigen::Matrix3d A = A0;
    for (int v = 1; v < 4; ++v) A += l(v - 1) * (vertex_sqrt(c->vertex(v)) - A0);
    return A;
  }

  /// The curl of `A` in the cell `c`, constant in the cell (doc/math.md section 2):
  /// column `i` is `curl` of column `i` of `A`,
  /// `(d_y A(2,i) - d_z A(1,i), d_z A(0,i) - d_x A(2,i), d_x A(1,i) - d_y A(0,i))`.
  /// Computed on first use and cached.
  /// \param c a cell of the domain
  /// \returns the 3x3 matrix of the curls of the columns of `A`
  /// \throws std::invalid_argument if `c` is not a cell of the domain
  /// \throws Input_error naming the tetrahedron if it is too flat for
  ///         double precision (its edge matrix is singular once rounded);
  ///         the same from every member that reads the cell's data, and
  ///         from `precompute()`
  const Eigen::Matrix3d& curl(Cell_handle c) const { return data(c).curl; }

  /// The connection one-form `W` at a point of the cell `c` (doc/math.md section 3):
  /// `connection_one_form(A_at(c, p), curl(c))`.
  /// \param c a cell of the domain
  /// \param p a point, normally in `c`
  /// \returns `W` (3x3); column `k` holds the (dx, dy, dz) coefficients of
  ///          the k-th of `(omega_23, omega_31, omega_12)`
  Eigen::Matrix3d connection(Cell_handle c, const Point_3& p) const {
    return connection_one_form(A_at(c, p), curl(c));
  }

  /// Computes the data of every cell of the domain now, in parallel (TBB).
  /// The results are the same as those computed on demand.
  void precompute() const {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, domain_cells_.size()),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) data(domain_cells_[i]);
                      });
  }

  /// Number of cells of the domain.
  /// \returns the number of finite cells with a non-negative index
  std::size_t number_of_domain_cells() const { return domain_cells_.size(); }

  /// The volume of the cell `c` measured in the metric, `int_c det A dV`.
  /// `det A` is a cubic polynomial in the cell, so Keast's degree-3 rule
  /// (the centroid and four points at barycentric `(1/2, 1/6, 1/6, 1/6)`)
  /// gives it exactly up to rounding. With unit length in the metric one
  /// hexahedron edge, it is the number of hexahedra the cell asks for.
  /// \param c a cell of the domain
  /// \returns the metric volume of `c`
  double metric_volume(Cell_handle c) const {
    std::array<Eigen::Matrix3d, 4> A;
    Eigen::Matrix3d E;
    const Eigen::Vector3d p0 = internal::to_eigen_vector(c->vertex(0)->point());
    for (int v = 0; v < 4; ++v) {
      A[v] = vertex_sqrt(c->vertex(v));
      if (v > 0) E.col(v - 1) = internal::to_eigen_vector(c->vertex(v)->point()) - p0;
    }
    const Eigen::Matrix3d sum = A[0] + A[1] + A[2] + A[3];
    double q = -0.8 * (0.25 * sum).determinant();
    for (int v = 0; v < 4; ++v) q += 0.45 * ((sum + 2 * A[v]) / 6).determinant();
    return q * std::abs(E.determinant()) / 6;
  }

  /// The volume of the domain measured in the metric, the sum of
  /// `metric_volume(c)` over its cells (in parallel, added in a fixed order:
  /// the same bits whatever the number of threads).
  /// \returns the metric volume of the domain
  double metric_volume() const {
    std::vector<double> v(domain_cells_.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, v.size()), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) v[i] = metric_volume(domain_cells_[i]);
    });
    double total = 0;
    for (double x : v) total += x;
    return total;
  }

  // Areas, volumes and their products with the metric are formed in double:
  // within these lengths none of them overflows or underflows, and the
  // results are the same for every unit of length (checked bit for bit under
  // scalings by 2^+-150). Outside, a clear error rather than wrong numbers.

  /// Throws `Input_error` naming `file` if the finite vertices of `tr` span
  /// a size (the largest side of their bounding box) outside
  /// [`supported_length_min`, `supported_length_max`], as the constructors
  /// do for the domain: lets a pipeline refuse such a mesh before any other work.
  /// \param tr the triangulation
  /// \param file the mesh's file, for the message
  static void check_extent(const Triangulation& tr, const std::string& file) {
    long double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<long double>::infinity(), hi[k] = -lo[k];
    for (auto v : tr.finite_vertex_handles())
      for (int k = 0; k < 3; ++k) {
        const long double x = CGAL::to_double(v->point()[k]);
        lo[k] = std::min(lo[k], x);
        hi[k] = std::max(hi[k], x);
      }
    try {
      check_extent(std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}));
    } catch (const Input_error& e) {
      throw Input_error(file, 0, e.element(), e.problem());
    }
  }

  /// Throws `Input_error` if a mesh of size `extent` (the largest side of its
  /// bounding box) is outside [`supported_length_min`, `supported_length_max`].
  /// \param extent the largest side of the mesh's bounding box
  static void check_extent(long double extent) {
    if (extent >= supported_length_min && extent <= supported_length_max) return;
    std::ostringstream s;
    s.precision(6);
    s << "spans " << extent << " (the largest side of its bounding box): the metric field computes in double with "
      << "lengths between " << supported_length_min << " and " << supported_length_max
      << "; change the unit of length (scale the coordinates)";
    throw Input_error("", 0, "the mesh", s.str());
  }

  /// The range of mesh sizes (the largest side of the domain's bounding
  /// box) that the metric field accepts: every computation in double stays
  /// far from overflow and underflow there, so results do not depend on the
  /// unit of length. The constructors throw `Input_error` outside it.
  static constexpr double supported_length_min = 1e-60;
  /// The largest accepted mesh size (see `supported_length_min`).
  static constexpr double supported_length_max = 1e60;

protected:
  /// Tag of the constructor that does not check the values (`Metric_field_3`
  /// checks its tensors before taking their roots).
  struct Unchecked {};

  /// Builds the field without checking the map's values.
  /// \param tr the triangulation \param map the values \param kind their kind
  /// \param vim the vertex index map \param cim the cell index map
  Property_map_metric_field_3(const Triangulation& tr, VertexMetricMap map, Vertex_metric_kind kind,
                              VertexIndexMap vim, CellIndexMap cim, Unchecked)
      : tr_(&tr), map_(map), kind_(kind), vim_(vim), cim_(cim) {
    init_cells();
  }

  /// Forgets the cached data of the cells around `v`.
  /// \param v a finite vertex
  void forget_cells_around(Vertex_handle v) {
    std::vector<Cell_handle> cells;
    tr_->incident_cells(v, std::back_inserter(cells));
    for (Cell_handle c : cells) {
      const std::int64_t k = static_cast<std::int64_t>(get(cim_, c));
      if (k >= 0 && static_cast<std::size_t>(k) < n_cells_) cells_[k].ready.store(false, std::memory_order_release);
    }
  }

private:
  struct Cell_data {
    std::atomic<bool> ready{false};
    Eigen::Vector3d p0;
    Eigen::Matrix3d inverse_edges; // E^{-1}, E = [p1 - p0, p2 - p0, p3 - p0]
    Eigen::Matrix3d curl;
  };

  Eigen::Matrix3d vertex_sqrt(Vertex_handle v) const {
    if (kind_ == Vertex_metric_kind::sqrt_metric) return get(map_, v);
    return sqrt_spd(get(map_, v));
  }

  void check_vertex(Vertex_handle v) const {
    const Eigen::Matrix3d value = get(map_, v);
    std::string why = check_metric_tensor(value);
    if (kind_ == Vertex_metric_kind::sqrt_metric) {
      // A passing the checks made for g does not make g = A A pass them: its
      // condition number is squared, and it can over- or underflow.
      if (!why.empty())
        why = "its square root A: " + why;
      else if (!(why = check_metric_tensor(value * value)).empty())
        why = "g = A A of its square root A: " + why;
    }
    if (why.empty()) return;
    throw internal::metric_vertex_error(get(vim_, v), v->point(), why);
  }

  static std::string volume_text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  void init_cells() {
    std::int64_t max_index = -1;
    // (long double: the extent of coordinates near +-1e308 does not overflow)
    long double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<long double>::infinity(), hi[k] = -lo[k];
    for (Cell_handle c : tr_->finite_cell_handles()) {
      const std::int64_t k = static_cast<std::int64_t>(get(cim_, c));
      if (k < 0) continue;
      domain_cells_.push_back(c);
      max_index = std::max(max_index, k);
      for (int v = 0; v < 4; ++v)
        for (int a = 0; a < 3; ++a) {
          const long double x = CGAL::to_double(c->vertex(v)->point()[a]);
          lo[a] = std::min(lo[a], x);
          hi[a] = std::max(hi[a], x);
        }
    }
    if (!domain_cells_.empty()) check_extent(std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}));
    n_cells_ = static_cast<std::size_t>(max_index + 1);
    cells_.reset(new Cell_data[n_cells_]);
  }

  // The cached data of c, computed on first use. Double-checked with a striped
  // lock; the values depend only on c, so the order of threads does not matter.
  const Cell_data& data(Cell_handle c) const {
    const std::int64_t k = static_cast<std::int64_t>(get(cim_, c));
    if (k < 0 || static_cast<std::size_t>(k) >= n_cells_)
      throw std::invalid_argument("the metric field: the cell is not a cell of the domain");
    Cell_data& d = cells_[k];
    if (d.ready.load(std::memory_order_acquire)) return d;
    std::lock_guard<std::mutex> lock(locks_[static_cast<std::size_t>(k) % n_locks]);
    if (d.ready.load(std::memory_order_relaxed)) return d;
    compute(c, d);
    d.ready.store(true, std::memory_order_release);
    return d;
  }

  void compute(Cell_handle c, Cell_data& d) const {
    d.p0 = internal::to_eigen_vector(c->vertex(0)->point());
    Eigen::Matrix3d E;
    for (int v = 1; v < 4; ++v) E.col(v - 1) = internal::to_eigen_vector(c->vertex(v)->point()) - d.p0;
    d.inverse_edges = E.inverse();
    // Exactly positive tets can be flat in double (a volume that underflows,
    // or vertices that round onto a plane): no gradient exists there.
    if (!(std::abs(E.determinant()) > 0) || !d.inverse_edges.allFinite())
      throw Input_error("", 0, "tetrahedron " + std::to_string(static_cast<std::int64_t>(get(cim_, c)) + 1),
                        "too flat for double precision: its volume is " + volume_text(std::abs(E.determinant()) / 6) +
                            " in double");
    const Eigen::Matrix3d A0 = vertex_sqrt(c->vertex(0));
    std::array<Eigen::Matrix3d, 3> dA; // dA[k] = d A / d x_k
    for (int k = 0; k < 3; ++k) dA[k].setZero();
    for (int v = 1; v < 4; ++v) {
      const Eigen::Matrix3d diff = vertex_sqrt(c->vertex(v)) - A0;
      for (int k = 0; k < 3; ++k) dA[k] += d.inverse_edges(v - 1, k) * diff;
    }
    for (int i = 0; i < 3; ++i)
      d.curl.col(i) = Eigen::Vector3d(dA[1](2, i) - dA[2](1, i), dA[2](0, i) - dA[0](2, i), dA[0](1, i) - dA[1](0, i));
  }

  static constexpr std::size_t n_locks = 64;

  const Triangulation* tr_;
  VertexMetricMap map_;
  Vertex_metric_kind kind_;
  VertexIndexMap vim_;
  CellIndexMap cim_;
  std::vector<Cell_handle> domain_cells_;
  std::size_t n_cells_ = 0;
  std::unique_ptr<Cell_data[]> cells_;
  mutable std::array<std::mutex, n_locks> locks_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_PROPERTY_MAP_METRIC_FIELD_3_H
