// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What every subcommand of metric-frames shares: argument parsing with
// usage errors (exit 2), and stage timing on stderr.
#ifndef CGAL_EXT_CLI_COMMON_H
#define CGAL_EXT_CLI_COMMON_H

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <iostream>
#include <memory>

#include <CGAL_ext/internal/json_text.h>

#include <CGAL/Real_timer.h>

#include <tbb/global_control.h>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL_ext::cli {

/// A mistake in the command line; main() prints it with the usage and exits with 2.
struct Usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Minimal parser: `--name VALUE` options, `--flag` flags and positionals, in any order.
/// Every argument must be consumed; finish() rejects the rest. Ask for the
/// options and flags before the positionals, so that an option's value is
/// never taken for a positional.
class Arguments {
public:
  Arguments(std::vector<std::string> args, std::string command, const char* help)
      : args_(std::move(args)), used_(args_.size(), false), command_(std::move(command)), help_(help) {
    for (std::size_t i = 0; i < args_.size(); ++i)
      if (args_[i] == "-h" || args_[i] == "--help") {
        std::cout << help_;
        help_requested_ = true;
      }
  }
  bool help_requested() const { return help_requested_; }

  /// The value of `--name VALUE` or `--name=VALUE`, if given.
  std::optional<std::string> option(const std::string& name) {
    for (std::size_t i = 0; i < args_.size(); ++i) {
      if (used_[i]) continue;
      if (args_[i] == name) {
        if (i + 1 >= args_.size()) fail("option " + name + " needs a value");
        used_[i] = used_[i + 1] = true;
        return args_[i + 1];
      }
      if (args_[i].rfind(name + "=", 0) == 0) {
        used_[i] = true;
        return args_[i].substr(name.size() + 1);
      }
    }
    return std::nullopt;
  }
  /// The value of a required option.
  std::string required_option(const std::string& name) {
    auto v = option(name);
    if (!v) fail("missing option " + name);
    return *v;
  }
  /// Whether `--name` is given.
  bool flag(const std::string& name) {
    for (std::size_t i = 0; i < args_.size(); ++i)
      if (!used_[i] && args_[i] == name) return used_[i] = true;
    return false;
  }
  /// The next positional argument; `what` names it in the error if missing.
  std::string positional(const std::string& what) {
    for (std::size_t i = 0; i < args_.size(); ++i)
      if (!used_[i] && (args_[i].empty() || args_[i][0] != '-' || args_[i] == "-")) {
        used_[i] = true;
        return args_[i];
      }
    fail("missing argument " + what);
  }
  /// Rejects any argument that was not consumed.
  void finish() {
    for (std::size_t i = 0; i < args_.size(); ++i)
      if (!used_[i]) fail("unexpected argument '" + args_[i] + "'");
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw Usage_error(message + " (see metric-frames " + command_ + " --help)");
  }

private:
  std::vector<std::string> args_;
  std::vector<bool> used_;
  std::string command_;
  const char* help_;
  bool help_requested_ = false;
};

/// Prints "[stage] name  1.23 s" lines on stderr, and a total at the end
/// (wall-clock time, CGAL::Real_timer).
class Stage_timer {
public:
  Stage_timer() {
    total_.start();
    lap_.start();
  }
  void stage(const char* name) {
    std::fprintf(stderr, "[stage] %-22s %8.3f s\n", name, lap_.time());
    lap_.reset();
  }
  void summary() const { std::fprintf(stderr, "[done]  %-22s %8.3f s\n", "total", total_.time()); }

private:
  CGAL::Real_timer total_, lap_;
};

using internal::json_escape;

/// A positive finite number, or a usage error naming the option.
inline double parse_positive(Arguments& a, const std::string& option, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (end == value.c_str() || *end != '\0' || !(v > 0) || !std::isfinite(v))
    a.fail(option + " '" + value + "': expected a positive finite number");
  return v;
}

/// The `--threads N` option: a limit on TBB's worker threads for the
/// command's lifetime, or null (all cores) if the option is absent.
inline std::unique_ptr<tbb::global_control> thread_limit(Arguments& a) {
  const auto n = a.option("--threads");
  if (!n) return nullptr;
  const double v = parse_positive(a, "--threads", *n);
  if (v != std::floor(v) || v > 1024) a.fail("--threads '" + *n + "': expected a whole number from 1 to 1024");
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(v));
}

} // namespace CGAL_ext::cli

#endif
