// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/Mixed_integer_quadratic_solver.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace CGAL_ext {
namespace {

using Terms = std::vector<std::pair<std::size_t, double>>;

// An eliminated variable: sum of coefficients times free variables, plus a constant.
struct Expression {
  Terms terms; // sorted by variable, no zero coefficient
  double constant = 0;
};

// Sorts terms by variable, adds up repeats and drops the coefficients that
// cancelled (relative to the largest one).
void normalize(Terms& t) {
  std::sort(t.begin(), t.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  Terms out;
  double largest = 0;
  for (const auto& [i, a] : t) {
    if (!out.empty() && out.back().first == i)
      out.back().second += a;
    else
      out.push_back({i, a});
    largest = std::max(largest, std::abs(a));
  }
  const double cut = 1e-12 * std::max(1.0, largest);
  t.clear();
  for (const auto& term : out)
    if (std::abs(term.second) > cut) t.push_back(term);
}

bool is_integral(double a) { return std::abs(a - std::round(a)) <= 1e-9 * std::max(1.0, std::abs(a)); }

// Gaussian elimination of the equalities into expressions of the free variables.
class Eliminator {
public:
  Eliminator(std::size_t n, const std::vector<char>& is_integer)
      : is_integer_(is_integer), eliminated_(n, 0), expression_(n), users_(n) {}

  // Returns false if the equality was redundant.
  bool add(const Linear_equality& eq, std::size_t number) {
    Terms row;
    double rhs = eq.rhs;
    for (const auto& [i, a] : eq.terms) {
      if (!eliminated_[i]) {
        row.push_back({i, a});
        continue;
      }
      for (const auto& [q, c] : expression_[i].terms) row.push_back({q, a * c});
      rhs -= a * expression_[i].constant;
    }
    normalize(row);
    if (row.empty()) {
      if (std::abs(rhs) > 1e-9 * std::max(1.0, std::abs(eq.rhs)))
        throw std::runtime_error("solve_mixed_integer_quadratic: equality " + std::to_string(number + 1) +
                                 " contradicts the ones before it (residual " + std::to_string(rhs) + ")");
      return false;
    }
    const std::size_t k = pivot(row);
    const std::size_t p = row[k].first;
    const double ap = row[k].second;
    Expression e;
    e.constant = rhs / ap;
    for (std::size_t m = 0; m < row.size(); ++m)
      if (m != k) e.terms.push_back({row[m].first, -row[m].second / ap});
    substitute(p, e);
    for (const auto& t : e.terms) users_[t.first].push_back(p);
    expression_[p] = std::move(e);
    eliminated_[p] = 1;
    return true;
  }

  bool eliminated(std::size_t i) const { return eliminated_[i] != 0; }
  // Whether eliminated variable i is an integer combination of integer
  // variables (its final expression: integer columns, integral
  // coefficients and constant), so integral once they are.
  bool integer_combination(std::size_t i) const {
    const Expression& x = expression_[i];
    return is_integral(x.constant) && std::all_of(x.terms.begin(), x.terms.end(), [&](const auto& t) {
             return is_integer_[t.first] && is_integral(t.second);
           });
  }
  const Expression& expression(std::size_t i) const { return expression_[i]; }

private:
  // A real variable if any (with a coefficient not too small against the
  // row's largest), else an integer one with a unit coefficient and integral
  // other terms; among those, the one fewest expressions use.
  std::size_t pivot(const Terms& row) const {
    double largest = 0;
    for (const auto& t : row) largest = std::max(largest, std::abs(t.second));
    bool any_real = false;
    for (const auto& t : row)
      if (!is_integer_[t.first] && std::abs(t.second) >= 0.1 * largest) any_real = true;
    bool all_integral = true;
    for (const auto& t : row) all_integral = all_integral && is_integral(t.second);
    std::size_t best = row.size();
    auto better = [&](std::size_t m) {
      if (best == row.size()) return true;
      const std::size_t um = users_[row[m].first].size(), ub = users_[row[best].first].size();
      if (um != ub) return um < ub;
      return std::abs(row[m].second) > std::abs(row[best].second);
    };
    for (std::size_t m = 0; m < row.size(); ++m) {
      const bool integer = is_integer_[row[m].first] != 0;
      const double a = std::abs(row[m].second);
      bool candidate;
      if (any_real)
        candidate = !integer && a >= 0.1 * largest;
      else
        candidate = all_integral && std::abs(a - 1) < 1e-12;
      if (candidate && better(m)) best = m;
    }
    // No unit integer pivot: a real variable, however small its coefficient,
    // then the largest coefficient.
    for (int pass = 0; pass < 2 && best == row.size(); ++pass)
      for (std::size_t m = 0; m < row.size(); ++m)
        if ((pass == 1 || !is_integer_[row[m].first]) &&
            (best == row.size() || std::abs(row[m].second) > std::abs(row[best].second)))
          best = m;
    return best;
  }

  // Replaces p by e in every expression that uses p.
  void substitute(std::size_t p, const Expression& e) {
    std::vector<std::size_t> users;
    users.swap(users_[p]);
    for (std::size_t u : users) {
      Expression& x = expression_[u];
      auto it = std::lower_bound(x.terms.begin(), x.terms.end(), p,
                                 [](const auto& t, std::size_t v) { return t.first < v; });
      if (it == x.terms.end() || it->first != p) continue; // a stale or repeated entry
      const double c = it->second;
      x.terms.erase(it);
      for (const auto& [q, a] : e.terms) {
        x.terms.push_back({q, c * a});
        users_[q].push_back(u);
      }
      x.constant += c * e.constant;
      normalize(x.terms);
    }
  }

  const std::vector<char>& is_integer_;
  std::vector<char> eliminated_;
  std::vector<Expression> expression_;
  std::vector<std::vector<std::size_t>> users_;
};

void check(const Mixed_integer_quadratic_problem& pb) {
  const auto n = std::size_t(pb.H.rows());
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("solve_mixed_integer_quadratic: " + what);
  };
  if (std::size_t(pb.H.cols()) != n || std::size_t(pb.b.size()) != n) fail("H must be n x n and b of size n");
  if (!pb.b.allFinite()) fail("b has a value that is not finite");
  for (int k = 0; k < pb.H.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(pb.H, k); it; ++it)
      if (!std::isfinite(it.value())) fail("H has a value that is not finite");
  for (std::size_t e = 0; e < pb.equalities.size(); ++e) {
    if (!std::isfinite(pb.equalities[e].rhs)) fail("equality " + std::to_string(e + 1) + " has a right-hand side that is not finite");
    for (const auto& [i, a] : pb.equalities[e].terms)
      if (i >= n || !std::isfinite(a)) fail("equality " + std::to_string(e + 1) + " has a term out of range or not finite");
  }
  for (std::size_t i : pb.integer_variables)
    if (i >= n) fail("integer variable " + std::to_string(i) + " is out of range");
}

// The reduced system y -> x = E y + c, with Hr = E^T H E and br = E^T (b - H c).
struct Reduced {
  Eigen::SparseMatrix<double> E, Hr;
  Eigen::VectorXd c, br;
  std::vector<std::size_t> free; // column -> variable
};

Reduced reduce(const Mixed_integer_quadratic_problem& pb, const Eliminator& elim, double regularization) {
  const std::size_t n = std::size_t(pb.H.rows());
  Reduced r;
  std::vector<std::size_t> column(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (!elim.eliminated(i)) column[i] = r.free.size(), r.free.push_back(i);
  std::vector<Eigen::Triplet<double>> t;
  r.c = Eigen::VectorXd::Zero(Eigen::Index(n));
  for (std::size_t i = 0; i < n; ++i) {
    if (!elim.eliminated(i)) {
      t.emplace_back(int(i), int(column[i]), 1.0);
      continue;
    }
    const Expression& e = elim.expression(i);
    r.c[Eigen::Index(i)] = e.constant;
    for (const auto& [q, a] : e.terms) t.emplace_back(int(i), int(column[q]), a);
  }
  r.E.resize(Eigen::Index(n), Eigen::Index(r.free.size()));
  r.E.setFromTriplets(t.begin(), t.end());
  const Eigen::SparseMatrix<double> Et = r.E.transpose();
  r.Hr = Et * (pb.H * r.E);
  r.br = Et * (pb.b - pb.H * r.c);
  double mean_diagonal = 0;
  for (Eigen::Index k = 0; k < r.Hr.rows(); ++k) mean_diagonal += r.Hr.coeff(k, k);
  mean_diagonal = r.Hr.rows() > 0 ? mean_diagonal / double(r.Hr.rows()) : 1;
  Eigen::SparseMatrix<double> I(r.Hr.rows(), r.Hr.cols());
  I.setIdentity();
  r.Hr += (regularization * (mean_diagonal > 0 ? mean_diagonal : 1)) * I;
  r.Hr.makeCompressed();
  return r;
}

double objective(const Mixed_integer_quadratic_problem& pb, const Eigen::VectorXd& x) {
  return x.dot(pb.H * x) - 2 * pb.b.dot(x);
}

// The reduced system K y = br with some integer columns fixed at values,
// from one factorisation of K: fixing the columns F is the constraint
// C^T y = v (C the columns of I at F), whose solution is
// y = y0 - Z_F S^-1 (y0_F - v), with y0 = K^-1 br, Z = K^-1 C over all the
// integer columns (one solve each, made once) and S = C^T Z_F. Each re-solve
// is then a small dense system, not a factorisation.
class Fixing_solver {
public:
  Fixing_solver(const Reduced& r, const std::vector<std::size_t>& integer_columns)
      : position_(std::size_t(r.Hr.rows()), std::size_t(-1)) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(r.Hr);
    if (ldlt.info() != Eigen::Success)
      throw std::runtime_error("solve_mixed_integer_quadratic: the reduced system is not positive definite");
    y0_ = ldlt.solve(r.br);
    Z_.resize(r.Hr.rows(), Eigen::Index(integer_columns.size()));
    for (std::size_t p = 0; p < integer_columns.size(); ++p) {
      position_[integer_columns[p]] = p;
      Z_.col(Eigen::Index(p)) = ldlt.solve(Eigen::VectorXd::Unit(r.Hr.rows(), Eigen::Index(integer_columns[p])));
    }
  }

  Eigen::VectorXd solve() {
    ++solves;
    const auto f = Eigen::Index(fixed_.size());
    Eigen::MatrixXd S(f, f);
    Eigen::VectorXd d(f);
    for (Eigen::Index a = 0; a < f; ++a) {
      d[a] = y0_[Eigen::Index(fixed_[std::size_t(a)])] - value_[std::size_t(a)];
      for (Eigen::Index b = 0; b < f; ++b) S(a, b) = Z_(Eigen::Index(fixed_[std::size_t(a)]), column(std::size_t(b)));
    }
    S_ = S.ldlt();
    Eigen::VectorXd y = y0_;
    if (f > 0) {
      const Eigen::VectorXd lambda = S_.solve(d);
      for (Eigen::Index b = 0; b < f; ++b) y -= lambda[b] * Z_.col(column(std::size_t(b)));
    }
    for (std::size_t a = 0; a < fixed_.size(); ++a) y[Eigen::Index(fixed_[a])] = value_[a]; // exact
    return y;
  }

  void fix(std::size_t k, double v) { fixed_.push_back(k), value_.push_back(v); }
  bool fixed(std::size_t k) const { return std::find(fixed_.begin(), fixed_.end(), k) != fixed_.end(); }
  // (K_F^-1)_kk for the columns fixed at the last solve: how freely column k
  // still moves, z_k[k] - w^T S^-1 w with w = z_k at the fixed columns.
  double inverse_diagonal(std::size_t k) const {
    const Eigen::Index c = Eigen::Index(position_[k]);
    Eigen::VectorXd w(Eigen::Index(fixed_.size()));
    for (std::size_t a = 0; a < fixed_.size(); ++a) w[Eigen::Index(a)] = Z_(Eigen::Index(fixed_[a]), c);
    return Z_(Eigen::Index(k), c) - (fixed_.empty() ? 0.0 : w.dot(S_.solve(w)));
  }

  std::size_t solves = 0;

private:
  Eigen::Index column(std::size_t a) const { return Eigen::Index(position_[fixed_[a]]); }

  std::vector<std::size_t> position_; // integer column -> column of Z
  Eigen::VectorXd y0_;
  Eigen::MatrixXd Z_;
  std::vector<std::size_t> fixed_;
  std::vector<double> value_;
  Eigen::LDLT<Eigen::MatrixXd> S_;
};

// The free integer columns, cheapest to round first: by the rise of the
// objective when the column alone is fixed at its nearest integer and the
// rest re-optimised, d^2 / (K^-1)_kk for a distance d; or by d.
std::vector<std::pair<double, std::size_t>> rounding_order(const Fixing_solver& fs, const Eigen::VectorXd& y,
                                                           const std::vector<std::size_t>& integer_columns,
                                                           bool least_cost) {
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t k : integer_columns) {
    if (fs.fixed(k)) continue;
    const double d = std::abs(y[Eigen::Index(k)] - std::round(y[Eigen::Index(k)]));
    order.push_back({least_cost ? d * d / std::max(fs.inverse_diagonal(k), 1e-300) : d, k});
  }
  std::sort(order.begin(), order.end());
  return order;
}

} // namespace

Mixed_integer_quadratic_solution solve_mixed_integer_quadratic(const Mixed_integer_quadratic_problem& pb,
                                                               const Mixed_integer_quadratic_options& options) {
  check(pb);
  const std::size_t n = std::size_t(pb.H.rows());
  Mixed_integer_quadratic_solution out;
  auto& rep = out.report;
  rep.variables = n;
  rep.equalities = pb.equalities.size();
  std::vector<char> is_integer(n, 0);
  for (std::size_t i : pb.integer_variables) is_integer[i] = 1;
  rep.integer_variables = pb.integer_variables.size();

  Eliminator elim(n, is_integer);
  for (std::size_t e = 0; e < pb.equalities.size(); ++e)
    if (!elim.add(pb.equalities[e], e)) ++rep.redundant_equalities;
  const Reduced r = reduce(pb, elim, options.regularization);
  const std::size_t m = r.free.size();
  rep.free_variables = m;
  std::vector<std::size_t> integer_columns;
  for (std::size_t k = 0; k < m; ++k)
    if (is_integer[r.free[k]]) integer_columns.push_back(k);
  rep.free_integer_variables = integer_columns.size();

  Fixing_solver fs(r, integer_columns);
  Eigen::VectorXd y = fs.solve();
  rep.objective_relaxed = objective(pb, r.E * y + r.c);
  std::size_t left = options.round ? integer_columns.size() : 0;
  while (left > 0) {
    const auto order = rounding_order(fs, y, integer_columns, options.least_cost_first);
    const std::size_t cap = std::max<std::size_t>(1, std::size_t(options.rounding_batch_share * double(left)));
    std::size_t take = 0;
    auto distance = [&](std::size_t a) {
      const double v = y[Eigen::Index(order[a].second)];
      return std::abs(v - std::round(v));
    };
    while (take < order.size() && take < cap && distance(take) < options.rounding_threshold) ++take;
    take = std::max<std::size_t>(take, 1);
    for (std::size_t a = 0; a < take; ++a) fs.fix(order[a].second, std::round(y[Eigen::Index(order[a].second)]));
    left -= take;
    y = fs.solve();
  }
  rep.solves = fs.solves;
  out.x = r.E * y + r.c;
  for (std::size_t i = 0; i < n; ++i)
    if (is_integer[i] && options.round) {
      if (!elim.eliminated(i)) continue;
      if (elim.integer_combination(i)) out.x[Eigen::Index(i)] = std::round(out.x[Eigen::Index(i)]); // exact again
      else if (!is_integral(out.x[Eigen::Index(i)])) ++rep.non_integral_eliminated;
    }
  rep.objective_rounded = objective(pb, out.x);
  out.E = r.E;
  out.c = r.c;
  out.y = y;
  out.integer_column.assign(m, 0);
  for (std::size_t k : integer_columns) out.integer_column[k] = 1;
  return out;
}

} // namespace CGAL_ext
