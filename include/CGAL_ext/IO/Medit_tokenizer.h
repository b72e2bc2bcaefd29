// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_MEDIT_TOKENIZER_H
#define CGAL_EXT_IO_MEDIT_TOKENIZER_H

/// \file Medit_tokenizer.h
/// The token reader shared by the Medit `.mesh` and `.sol` readers.

#include <CGAL_ext/Input_error.h>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// Splits a Medit ASCII file into white-space separated tokens, skipping `#`
/// comments, and reads typed values with errors that name the file and line.
///
/// Medit files are free-format: a keyword's value may follow on the same or
/// the next line, and lines may be indented, so the readers work on tokens,
/// not lines.
class Medit_tokenizer {
public:
  /// Reads the whole file.
  /// \param path the file
  /// \throws Input_error if the file cannot be opened, is a directory or not
  ///         a regular file (a device or a FIFO, checked before opening), or is empty
  explicit Medit_tokenizer(std::string path);

  /// The file name, for messages.
  /// \returns the path given to the constructor
  const std::string& path() const { return path_; }
  /// The 1-based line of the last token read (or of the position, at the end).
  /// \returns the line number, from 1
  std::size_t line() const { return line_; }
  /// Number of bytes not read yet; an upper bound for what the rest of the file can hold.
  /// \returns the number of bytes after the position
  std::size_t remaining_bytes() const { return data_.size() - pos_; }

  /// Reads the next token.
  /// \param token receives a view into the file's text
  /// \returns false at the end of the file
  bool next(std::string_view& token);

  /// Reads a token that must exist.
  /// \param what what is expected, for the message
  /// \returns a view into the file's text
  /// \throws Input_error at the end of the file
  std::string_view expect(const char* what);

  /// Reads an integer.
  /// \param what what is expected, for the message (e.g. "vertex index")
  /// \returns the value (an optional `+` sign is accepted)
  /// \throws Input_error at the end of the file, for a token that is not an
  ///         integer, or for one out of range
  std::int64_t read_int(const char* what);

  /// Reads a finite double; NaN and Inf are errors.
  /// \param what what is expected, for the message
  /// \returns the value (an optional `+` sign is accepted)
  /// \throws Input_error at the end of the file, for a token that is not a
  ///         number, or for one that is not finite
  double read_double(const char* what);

  /// Reads the record count of a section and checks that the rest of the
  /// file can hold that many records of `tokens_per_record` tokens (each
  /// needs at least two bytes), so that no absurd count is ever allocated.
  /// \param section the section name, for the message
  /// \param tokens_per_record the number of tokens of one record
  /// \returns the record count
  /// \throws Input_error for a negative count, or one that the rest of the file cannot hold
  std::size_t read_count(const std::string& section, std::size_t tokens_per_record);

  /// Throws an Input_error at the current line.
  /// \param element the element concerned (may be empty)
  /// \param problem what is wrong
  [[noreturn]] void fail(const std::string& element, const std::string& problem) const {
    throw Input_error(path_, line_, element, problem);
  }

  /// Case-insensitive comparison of a token with a keyword.
  /// \param token the token
  /// \param keyword the keyword
  /// \returns true if they are equal up to ASCII case
  static bool keyword_equals(std::string_view token, std::string_view keyword);

private:
  std::string path_;
  std::string data_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_MEDIT_TOKENIZER_H
