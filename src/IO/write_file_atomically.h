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

} // namespace CGAL_ext::IO::internal

#endif
