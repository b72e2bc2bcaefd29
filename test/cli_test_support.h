// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Shared by the command-line tests: run metric-frames with arguments,
// capture its exit code, stdout and stderr, and write input files, all in a
// scratch directory of the test process.
#ifndef CGAL_EXT_TEST_CLI_TEST_SUPPORT_H
#define CGAL_EXT_TEST_CLI_TEST_SUPPORT_H

#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace CGAL_ext {
namespace testing {

/// The test data directory (test/data).
inline const std::string data_dir = CGAL_EXT_TEST_DATA_DIR;

/// The scratch directory. CTest runs the test cases of a test file as
/// parallel processes: each process gets its own directory, named after its
/// pid, so that their outputs never mix. It is removed at exit.
inline const std::filesystem::path work =
    std::filesystem::temp_directory_path() / ("cgal_ext_test_cli_" + std::to_string(::getpid()));

/// Removes the scratch directory when the test process ends.
struct Remove_work_at_exit {
  ~Remove_work_at_exit() {
    std::error_code ec;
    std::filesystem::remove_all(work, ec);
  }
};
inline Remove_work_at_exit remove_work_at_exit;

/// What a run of metric-frames gave.
struct Run {
  int exit_code; ///< -1 if killed by a signal
  std::string out, err;
};

/// The content of a file (empty if it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Runs `PREFIX metric-frames ARGS` through the shell, stdin from /dev/null.
inline Run run_with_prefix(const std::string& prefix, const std::string& args) {
  std::filesystem::create_directories(work);
  const std::string cmd = prefix + CGAL_EXT_CLI + " " + args + " >" + (work / "out").string() + " 2>" +
                          (work / "err").string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  Run r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(work / "out");
  r.err = slurp(work / "err");
  return r;
}

/// Runs `metric-frames ARGS` through the shell, stdin from /dev/null.
inline Run run(const std::string& args) { return run_with_prefix("", args); }

#if defined(__SANITIZE_ADDRESS__)
#define CGAL_EXT_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CGAL_EXT_TEST_ASAN 1
#endif
#endif

/// As run(), but with at most 1 GB of memory and `seconds` of time (then
/// exit code 124): for inputs that a broken build would read forever. The
/// memory bound is the address space (`ulimit -v`), or, in the sanitized
/// build, where AddressSanitizer reserves terabytes of shadow address space,
/// its own limits on the resident set and on single allocations.
inline Run run_bounded(const std::string& args, int seconds = 30) {
#ifdef CGAL_EXT_TEST_ASAN
  const std::string memory = "ASAN_OPTIONS=\"$ASAN_OPTIONS:hard_rss_limit_mb=1024:malloc_limit_mb=1024\" ";
#else
  const std::string memory = "ulimit -v 1048576; ";
#endif
  return run_with_prefix(memory + "timeout " + std::to_string(seconds) + " ", args);
}

/// Writes `content` to the file `name` of the scratch directory; returns its path.
inline std::string file_with(const std::string& name, const std::string& content) {
  std::filesystem::create_directories(work);
  const auto p = work / name;
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}

/// The number of lines (newlines) of a text.
inline std::size_t lines(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

/// The JSON values of a text of JSON lines (one value per line); a line
/// that is not JSON throws nlohmann::json::parse_error, which fails the test.
inline std::vector<nlohmann::json> json_lines(const std::string& text) {
  std::vector<nlohmann::json> values;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) values.push_back(nlohmann::json::parse(line));
  return values;
}

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_CLI_TEST_SUPPORT_H
