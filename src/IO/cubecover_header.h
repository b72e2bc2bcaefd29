// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Internal to the readers of CubeCover's files (.fra, .perm): their first and
// last tokens.
#ifndef CGAL_EXT_SRC_IO_CUBECOVER_HEADER_H
#define CGAL_EXT_SRC_IO_CUBECOVER_HEADER_H

#include <CGAL_ext/IO/Medit_tokenizer.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace CGAL_ext::IO::internal {

// Reads the "WORD 1" that starts a CubeCover file: `word` (e.g. "FRA") and
// the version, which must be 1 as in CubeCover. `extension` (".fra") and
// `kind` ("frame field") name the file type in messages.
inline void read_cubecover_header(Medit_tokenizer& tk, const std::string& word, const std::string& extension,
                                  const std::string& kind) {
  const std::string_view found = tk.expect(("the word " + word).c_str());
  if (found != word)
    tk.fail("", "expected '" + word + "', found " + Input_error::quote(found) + ": not a CubeCover " + kind + " (" +
                    extension + ") file");
  const std::int64_t version = tk.read_int(("the " + extension + " version").c_str());
  if (version != 1)
    tk.fail("", extension + " version " + std::to_string(version) + ": only version 1 is supported (as in CubeCover)");
}

// Checks that the file ends after its `count` records (`records`: "frames").
inline void expect_end_of_records(Medit_tokenizer& tk, std::size_t count, const std::string& records) {
  std::string_view extra;
  if (tk.next(extra))
    tk.fail("", "unexpected " + Input_error::quote(extra) + " after the last of the " + std::to_string(count) + " " +
                    records + " (the count is too small?)");
}

} // namespace CGAL_ext::IO::internal

#endif
