// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "write_file_atomically.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace CGAL_ext::IO::internal {

void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& body) {
  // The process id keeps concurrent writers of the same path apart.
  const std::string tmp = path + ".tmp-write-" + std::to_string(::getpid());
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot open for writing");
  try {
    body(f);
  } catch (...) {
    std::fclose(f);
    std::remove(tmp.c_str());
    throw;
  }
  const bool ok = std::ferror(f) == 0;
  if (std::fclose(f) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": write error");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": cannot move the written file into place: " + ec.message());
  }
}

} // namespace CGAL_ext::IO::internal
