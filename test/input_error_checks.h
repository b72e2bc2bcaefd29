// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Shared by the tests of the file readers: the check that reading a bad file
// throws one clear CGAL_ext::Input_error.
#ifndef CGAL_EXT_TEST_INPUT_ERROR_CHECKS_H
#define CGAL_EXT_TEST_INPUT_ERROR_CHECKS_H

#include <CGAL_ext/Input_error.h>

#include <catch2/catch.hpp>

#include <cstddef>
#include <fstream>
#include <iterator>
#include <string>

namespace CGAL_ext {
namespace testing {

/// Expects `read()` to throw an `Input_error` naming `path`, at `line`
/// (0: not checked), about `element`, whose problem contains `words`, and
/// whose message starts with "path:".
template <class Read>
void expect_input_error(Read read, const std::string& path, std::size_t line, const std::string& element,
                        const std::string& words) {
  try {
    read();
    FAIL("no exception for " << path);
  } catch (const CGAL_ext::Input_error& e) {
    INFO(e.what());
    CHECK(e.file() == path);
    if (line) CHECK(e.line() == line);
    CHECK(e.element() == element);
    CHECK(e.problem().find(words) != std::string::npos);
    CHECK(std::string(e.what()).find(path + ":") == 0);
  }
}

/// The bytes of a file (empty if it cannot be read).
inline std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Writes `text` with its first `from` replaced by `to` to `path`, then
/// expects `read()` of it to throw as `expect_input_error()` says.
template <class Read>
void expect_input_error_after_edit(const std::string& text, const std::string& from, const std::string& to,
                                   const std::string& path, Read read, std::size_t line, const std::string& element,
                                   const std::string& words) {
  std::string edited = text;
  const auto at = edited.find(from);
  REQUIRE(at != std::string::npos);
  edited.replace(at, from.size(), to);
  std::ofstream(path, std::ios::binary) << edited;
  expect_input_error(read, path, line, element, words);
}

/// `expect_input_error_after_edit()` on one file and reader:
/// `Edited_file_errors expect_error{path, read}; expect_error(text, from, to, line, element, words);`
template <class Read>
struct Edited_file_errors {
  std::string path; ///< the file written
  Read read;        ///< reads `path`
  /// \param text the file's text before the edit
  /// \param from the text replaced (its first occurrence)
  /// \param to its replacement
  /// \param line the line expected in the error (0: not checked)
  /// \param element the element expected
  /// \param words words the problem must contain
  void operator()(const std::string& text, const std::string& from, const std::string& to, std::size_t line,
                  const std::string& element, const std::string& words) const {
    expect_input_error_after_edit(text, from, to, path, read, line, element, words);
  }
};
template <class Read>
Edited_file_errors(std::string, Read) -> Edited_file_errors<Read>;

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_INPUT_ERROR_CHECKS_H
