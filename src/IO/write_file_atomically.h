// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Internal to the library's writers.
#ifndef CGAL_EXT_SRC_IO_WRITE_FILE_ATOMICALLY_H
#define CGAL_EXT_SRC_IO_WRITE_FILE_ATOMICALLY_H

#include <cstdio>
#include <functional>
#include <string>

namespace CGAL_ext::IO::internal {

// Writes `path` through `body` into a temporary file next to it (named
// ".mf-tmp-PID-N", short whatever the length of `path`'s name), then renames
// it into place: a failed or interrupted write never leaves a half-written
// `path` nor destroys what was there. Throws std::runtime_error naming `path`
// (the temporary file is removed) if the file cannot be opened, written,
// closed or moved; an exception from `body` also removes it and propagates.
void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& body);

// Checks that `dir` can take output files, so that a command can fail before
// its computation rather than after: `dir` is a directory, or does not exist
// and its nearest existing ancestor is a directory; and a file can be
// created there (tried: a temporary file, removed at once). Creates nothing
// that stays. Throws std::runtime_error naming `dir` and the reason.
void check_output_directory(const std::string& dir);

} // namespace CGAL_ext::IO::internal

#endif
