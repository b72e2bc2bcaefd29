// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_METRIC_FIELD_3_H
#define CGAL_EXT_METRIC_FIELD_3_H

/// \file Metric_field_3.h
/// A piecewise-linear metric field on a tetrahedral mesh: the square root
/// `A = g^{1/2}` per vertex, linear in each cell, its constant curl per cell
/// and the connection one-form `W` (doc/math.md sections 1 to 3).

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
#include <type_traits>
#include <vector>

namespace CGAL_ext {

namespace internal {
// A point's coordinates as an Eigen vector of doubles.
template <class Point_3>
Eigen::Vector3d to_eigen_vector(const Point_3& p) {
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}
} // namespace internal

/// \ingroup PkgCGALExtMetric
/// A metric field on the cells of a 3D triangulation, given by one SPD
/// metric tensor `g` per vertex (an edge `e` has length `sqrt(e^T g e)`).
///
/// - Stored per vertex: `A = g^{1/2}` (`sqrt_spd()`), indexed by the vertex
///   index of `VertexIndexMap`.
/// - Inside a cell, **A (not g) is linear** in the barycentric coordinates
///   (`A_at()`), so `A` is continuous and `curl A` is constant per cell
///   (`curl()`), and `W = connection_one_form(A, curl A)` (`connection()`).
/// - The per-cell data (inverse edge matrix, curl) is computed on first use
///   and cached. Concurrent reads (`A_at`, `curl`, `connection`) from several
///   threads are safe and give the same bits whatever the order;
///   `precompute()` fills the whole cache in parallel with TBB.
///   `set_metric()` and `put()` on `metric_map()` must not run concurrently
///   with anything else.
///
/// Derivatives in a cell with vertices `p0..p3` use the edge matrix
/// `E = [p1 - p0, p2 - p0, p3 - p0]`: the barycentric coordinates of `x`
/// are `(1 - sum, E^{-1} (x - p0))`, so `d_k A = sum_{v=1..3} E^{-1}(v-1, k) (A_v - A_0)`.
/// It is the `sum_v T[v][k] A_v` of doc/math.md section 2, written with
/// differences so that a constant metric gives exactly zero curl.
///
/// \tparam Triangulation a CGAL `Triangulation_3` (e.g. `Tet_mesh_triangulation_3<>`)
/// \tparam VertexIndexMap a readable property map from `Vertex_handle` to a
///         0-based `std::size_t` index; default: the file index `v->info()`
/// \tparam CellIndexMap a readable property map from `Cell_handle` to a signed
///         index, negative for cells outside the domain; default: the
///         tetrahedron index `c->info().index`
///
/// \cgalModels `MetricField_3`
template <class Triangulation, class VertexIndexMap = Tet_mesh_vertex_index_map<Triangulation>,
          class CellIndexMap = Tet_mesh_cell_index_map<Triangulation>>
class Metric_field_3 {
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
      : tr_(&tr), vim_(vim), cim_(cim) {
    for (std::size_t i = 0; i < metrics.size(); ++i) {
      const std::string why = check_metric_tensor(metrics[i]);
      if (!why.empty()) throw Input_error(source, 0, vertex_name(i), why);
    }
    std::size_t n = metrics.size();
    for (Vertex_handle v : tr.finite_vertex_handles()) {
      const std::size_t i = get(vim_, v);
      if (i >= metrics.size())
        throw Input_error(source, 0, vertex_name(i),
                          "has no metric: only " + std::to_string(metrics.size()) + " metrics were given");
    }
    sqrt_.resize(n);
    has_.assign(n, 0);
    for (Vertex_handle v : tr.finite_vertex_handles()) {
      const std::size_t i = get(vim_, v);
      if (!has_[i]) sqrt_[i] = sqrt_spd(metrics[i]);
      has_[i] = 1;
    }
    init_cells();
  }

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
      : tr_(&tr), vim_(vim), cim_(cim) {
    resize_for_vertices();
    for (Vertex_handle v : tr.finite_vertex_handles()) {
      const Eigen::Matrix3d gv = g(v->point());
      const std::string why = check_metric_tensor(gv);
      if (!why.empty()) {
        std::ostringstream s;
        s << why << " at (" << v->point() << ")";
        throw Input_error("", 0, vertex_name(get(vim_, v)), s.str());
      }
      sqrt_[get(vim_, v)] = sqrt_spd(gv);
      has_[get(vim_, v)] = 1;
    }
    init_cells();
  }

  /// Builds a constant field. Its curl and connection are exactly zero, and
  /// every transport in it is exactly the identity.
  /// \param tr the triangulation; it must outlive the field and not change
  /// \param g the metric tensor everywhere
  /// \param vim the vertex index map
  /// \param cim the cell index map
  /// \throws Input_error if `g` is not a valid metric
  Metric_field_3(const Triangulation& tr, const Eigen::Matrix3d& g, VertexIndexMap vim = VertexIndexMap(),
                 CellIndexMap cim = CellIndexMap())
      : tr_(&tr), vim_(vim), cim_(cim) {
    const std::string why = check_metric_tensor(g);
    if (!why.empty()) throw Input_error("", 0, "constant metric", why);
    const Eigen::Matrix3d A = sqrt_spd(g); // one root, so all vertices are bitwise equal
    resize_for_vertices();
    for (Vertex_handle v : tr.finite_vertex_handles()) {
      sqrt_[get(vim_, v)] = A;
      has_[get(vim_, v)] = 1;
    }
    init_cells();
  }

  /// The triangulation.
  /// \returns the triangulation given to the constructor
  const Triangulation& triangulation() const { return *tr_; }

  /// The square root `A = g^{1/2}` at a vertex (symmetric positive definite).
  /// \param v a finite vertex
  /// \returns `A` at `v` (3x3)
  const Eigen::Matrix3d& sqrt_metric(Vertex_handle v) const { return sqrt_[checked_index(v)]; }

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
    if (!why.empty()) throw Input_error("", 0, vertex_name(i), why);
    sqrt_[i] = sqrt_spd(g);
    std::vector<Cell_handle> cells;
    tr_->incident_cells(v, std::back_inserter(cells));
    for (Cell_handle c : cells) {
      const std::int64_t k = static_cast<std::int64_t>(get(cim_, c));
      if (k >= 0 && static_cast<std::size_t>(k) < n_cells_) cells_[k].ready.store(false, std::memory_order_release);
    }
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
    const Eigen::Matrix3d& A0 = sqrt_[get(vim_, c->vertex(0))];
    Eigen::Matrix3d A = A0;
    for (int v = 1; v < 4; ++v) A += l(v - 1) * (sqrt_[get(vim_, c->vertex(v))] - A0);
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
      A[v] = sqrt_[get(vim_, c->vertex(v))];
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
  struct Cell_data {
    std::atomic<bool> ready{false};
    Eigen::Vector3d p0;
    Eigen::Matrix3d inverse_edges; // E^{-1}, E = [p1 - p0, p2 - p0, p3 - p0]
    Eigen::Matrix3d curl;
  };

  static std::string vertex_name(std::size_t i) { return "vertex " + std::to_string(i + 1); }
  static std::string volume_text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }


  std::size_t checked_index(Vertex_handle v) const {
    const std::size_t i = get(vim_, v);
    if (i >= has_.size() || !has_[i]) throw std::invalid_argument("Metric_field_3: vertex without a metric");
    return i;
  }

  void resize_for_vertices() {
    std::size_t n = 0;
    for (Vertex_handle v : tr_->finite_vertex_handles()) n = std::max<std::size_t>(n, get(vim_, v) + 1);
    sqrt_.resize(n);
    has_.assign(n, 0);
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
  // Areas, volumes and their products with the metric are formed in double:
  // within these lengths none of them overflows or underflows, and the
  // results are the same for every unit of length (checked bit for bit under
  // scalings by 2^+-150). Outside, a clear error rather than wrong numbers.

public:
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

public:
  /// The range of mesh sizes (the largest side of the domain's bounding
  /// box) that the metric field accepts: every computation in double stays
  /// far from overflow and underflow there, so results do not depend on the
  /// unit of length. The constructors throw `Input_error` outside it.
  static constexpr double supported_length_min = 1e-60;
  /// The largest accepted mesh size (see `supported_length_min`).
  static constexpr double supported_length_max = 1e60;

private:

  // The cached data of c, computed on first use. Double-checked with a striped
  // lock; the values depend only on c, so the order of threads does not matter.
  const Cell_data& data(Cell_handle c) const {
    const std::int64_t k = static_cast<std::int64_t>(get(cim_, c));
    if (k < 0 || static_cast<std::size_t>(k) >= n_cells_)
      throw std::invalid_argument("Metric_field_3: the cell is not a cell of the domain");
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
    const Eigen::Matrix3d& A0 = sqrt_[get(vim_, c->vertex(0))];
    std::array<Eigen::Matrix3d, 3> dA; // dA[k] = d A / d x_k
    for (int k = 0; k < 3; ++k) dA[k].setZero();
    for (int v = 1; v < 4; ++v) {
      const Eigen::Matrix3d diff = sqrt_[get(vim_, c->vertex(v))] - A0;
      for (int k = 0; k < 3; ++k) dA[k] += d.inverse_edges(v - 1, k) * diff;
    }
    for (int i = 0; i < 3; ++i)
      d.curl.col(i) = Eigen::Vector3d(dA[1](2, i) - dA[2](1, i), dA[2](0, i) - dA[0](2, i), dA[0](1, i) - dA[1](0, i));
  }

  static constexpr std::size_t n_locks = 64;

  const Triangulation* tr_;
  VertexIndexMap vim_;
  CellIndexMap cim_;
  std::vector<Eigen::Matrix3d> sqrt_;
  std::vector<char> has_;
  std::vector<Cell_handle> domain_cells_;
  std::size_t n_cells_ = 0;
  std::unique_ptr<Cell_data[]> cells_;
  mutable std::array<std::mutex, n_locks> locks_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_METRIC_FIELD_3_H
