// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Shared by the libFuzzer harnesses: the readers take paths, so each input is
// written to a private file (in /dev/shm when it exists: no disk traffic) and
// read back through the public API, as a user's file would be.
#ifndef CGAL_EXT_TEST_FUZZ_FUZZ_INPUT_H
#define CGAL_EXT_TEST_FUZZ_FUZZ_INPUT_H

#include <CGAL_ext/Input_error.h>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

namespace fuzz {

// The file an input is written to: one per process and extension, removed at exit.
inline std::string input_path(const std::string& extension) {
  static const std::string dir = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
  return dir + "/cgal-ext-fuzz-" + std::to_string(::getpid()) + extension;
}

// Writes `data` to input_path(extension) and returns the path.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const std::string path = input_path(extension);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) {
    std::perror(path.c_str());
    std::abort();
  }
  if (size && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

// Longest message accepted: a message quotes tokens, it never echoes a file.
constexpr std::size_t max_message_length = 4096;

// Runs `read`: an Input_error is the expected answer to a bad file, and its
// message must name `file` (when not empty) and stay short. Any other
// exception is a finding (the library promises Input_error for bad input),
// reported and turned into a crash so that libFuzzer keeps the input.
template <class Read>
void expect_input_error_only(Read&& read, const std::string& file = {}) {
  try {
    read();
  } catch (const CGAL_ext::Input_error& e) {
    const std::string message = e.what();
    if (message.empty() || message.size() > max_message_length ||
        (!file.empty() && message.find(file) == std::string::npos)) {
      std::fprintf(stderr, "finding: an Input_error that is empty, too long or does not name %s: %.300s\n",
                   file.c_str(), message.c_str());
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "finding: exception other than Input_error: %s\n", e.what());
    std::abort();
  }
}

} // namespace fuzz

#endif // CGAL_EXT_TEST_FUZZ_FUZZ_INPUT_H
