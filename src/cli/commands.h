// The subcommands of the metric-frames tool. Each takes the arguments after
// its name, prints its output on stdout and its progress and errors on
// stderr, and returns the process exit code (0 success, 1 bad input or
// failure, 2 bad usage).
#ifndef CGAL_EXT_CLI_COMMANDS_H
#define CGAL_EXT_CLI_COMMANDS_H

#include <string>
#include <vector>

namespace CGAL_ext::cli {

/// `metric-frames info MESH`: counts, bounding box, volume, dihedral angles.
int command_info(const std::vector<std::string>& args);

/// `metric-frames walk MESH --segments FILE`: the simplices met by segments, as JSON lines.
int command_walk(const std::vector<std::string>& args);

/// `metric-frames transport MESH --metric SOL --pairs FILE`: transports between point pairs, as JSON lines.
int command_transport(const std::vector<std::string>& args);

/// `metric-frames metric MESH (--expr EXPRS | --size EXPR) -o OUT.sol`: a .sol file from formulas.
int command_metric(const std::vector<std::string>& args);

/// `metric-frames generate INPUT [--metric SOL | ...] -o OUTDIR`: the frame field, its singularities and output files.
int command_generate(const std::vector<std::string>& args);

} // namespace CGAL_ext::cli

#endif
