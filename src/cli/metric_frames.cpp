// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// metric-frames: the command-line tool of CGAL Metric Frames. This file only
// dispatches to the subcommands of commands.h.
#include "cli_common.h"
#include "commands.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace {

struct Subcommand {
  const char* name;
  const char* summary;
  int (*run)(const std::vector<std::string>&);
};

const Subcommand subcommands[] = {
    {"generate", "frame field in a metric: frames.fra, mesh, VTU files, singular edges, report", CGAL_ext::cli::command_generate},
    {"info", "print counts, bounding box, volume and dihedral angles of a tet mesh", CGAL_ext::cli::command_info},
    {"walk", "list every vertex, edge, facet and tet that segments meet, as JSON lines", CGAL_ext::cli::command_walk},
    {"transport", "transport T(a->b) of a metric between point pairs, as JSON lines", CGAL_ext::cli::command_transport},
    {"metric", "write a metric .sol file from formulas in x, y, z (or a constant tensor)", CGAL_ext::cli::command_metric},
};

void print_help(std::ostream& os) {
  os << "metric-frames: metric-driven 3D frame fields on tetrahedral meshes (CGAL Metric Frames)\n\n"
        "Usage: metric-frames SUBCOMMAND [ARGS...]\n"
        "       metric-frames SUBCOMMAND --help\n"
        "       metric-frames help [SUBCOMMAND]\n\n"
        "Subcommands:\n";
  for (const auto& s : subcommands) os << "  " << s.name << std::string(11 - std::strlen(s.name), ' ') << s.summary << "\n";
  os << "\nOptions:\n  -h, --help    this help\n  --version     the version\n\n"
        "Meshes are ASCII Medit .mesh files (as MMG, Gmsh and TetGen -g write them).\n"
        "Exit codes: 0 success, 1 bad input or failure, 2 bad usage.\n";
}

} // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    print_help(std::cerr);
    return 2;
  }
  if (args[0] == "-h" || args[0] == "--help" || (args[0] == "help" && args.size() == 1)) {
    print_help(std::cout);
    return 0;
  }
  if (args[0] == "help") { // help SUBCOMMAND: that subcommand's --help
    if (args.size() == 2)
      for (const auto& s : subcommands)
        if (args[1] == s.name) return s.run({"--help"});
    std::cerr << "metric-frames help: expected one subcommand name (see metric-frames --help)\n";
    return 2;
  }
  if (args[0] == "--version") {
    std::cout << "metric-frames " << CGAL_EXT_VERSION << "\n";
    return 0;
  }
  for (const auto& s : subcommands)
    if (args[0] == s.name) {
      try {
        return s.run(std::vector<std::string>(args.begin() + 1, args.end()));
      } catch (const CGAL_ext::cli::Usage_error& e) {
        std::cerr << "metric-frames " << s.name << ": " << e.what() << "\n";
        return 2;
      } catch (const std::exception& e) {
        std::cerr << "metric-frames " << s.name << ": error: " << e.what() << "\n";
        return 1;
      }
    }
  std::cerr << "metric-frames: unknown subcommand '" << args[0] << "' (see metric-frames --help)\n";
  return 2;
}
