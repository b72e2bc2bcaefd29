// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "write_file_atomically.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace CGAL_ext::IO::internal {

namespace {

// Creates a new file in `dir` (the current directory if empty) and returns
// its descriptor, or -1 with errno set. The name, ".mf-tmp-PID-N", is short
// whatever the target's name (a target name of NAME_MAX characters plus a
// suffix would be too long), and the process id and a counter keep
// concurrent writers apart. Mode 0666 minus the umask, as for fopen().
int create_temporary_file(const std::filesystem::path& dir, std::string& name) {
  static std::atomic<unsigned long> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    name = (dir / (".mf-tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++))).string();
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

} // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& body) {
  std::string tmp;
  const int fd = create_temporary_file(std::filesystem::path(path).parent_path(), tmp);
  std::FILE* f = fd >= 0 ? ::fdopen(fd, "w") : nullptr;
  if (!f) {
    const int error = errno;
    if (fd >= 0) {
      ::close(fd);
      std::remove(tmp.c_str());
    }
    throw std::runtime_error(path + ": cannot open for writing: " + std::strerror(error));
  }
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

void check_output_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw std::runtime_error(dir + ": the output directory exists and is not a directory");
  // The directory, or the nearest existing ancestor it will be created in.
  fs::path existing = dir;
  while (!existing.empty() && !fs::exists(existing, ec)) existing = existing.parent_path();
  if (existing.empty()) existing = ".";
  if (!fs::is_directory(existing, ec))
    throw std::runtime_error(dir + ": cannot create the output directory: " + existing.string() +
                             " is not a directory");
  // Whether files can be created there is best asked by creating one: as
  // root, permissions say nothing, yet /proc or a read-only mount refuse.
  std::string probe;
  const int fd = create_temporary_file(existing, probe);
  if (fd < 0) {
    const std::string reason = std::string("cannot create files in ") + existing.string() + ": " + std::strerror(errno);
    throw std::runtime_error(dir + (existing == fs::path(dir) ? ": " : ": cannot create the output directory: ") +
                             reason);
  }
  ::close(fd);
  std::remove(probe.c_str());
}

} // namespace CGAL_ext::IO::internal
