// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Internal to the readers that open a path: the check made before opening it.
#ifndef CGAL_EXT_SRC_IO_INPUT_FILE_H
#define CGAL_EXT_SRC_IO_INPUT_FILE_H

#include <CGAL_ext/Input_error.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace CGAL_ext::IO::internal {

// Throws an Input_error naming `path` if it is a directory or not a regular
// file (after following links). A directory opens and reads as an empty
// file, /dev/zero or a FIFO would be read until memory runs out, and a FIFO
// without a writer blocks the open: all are refused before opening. A
// missing or unreadable file is left to the open, which reports it.
inline void check_input_file(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status s = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(s)) return;
  if (std::filesystem::is_directory(s)) throw Input_error(path, 0, "", "is a directory, not a file");
  if (!std::filesystem::is_regular_file(s))
    throw Input_error(path, 0, "", "is not a regular file (a device, a FIFO or a socket)");
}

} // namespace CGAL_ext::IO::internal

#endif
