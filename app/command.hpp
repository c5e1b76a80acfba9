// The `masonry` executable is one CLI11 app; each library directory adds its subcommands
// through a `cli.cpp` of its own (thin front ends), and main() runs the one that was chosen.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

namespace masonry {

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;  // returns the exit code; throws for bad input or errors
};
using Commands = std::vector<Command>;

void add_prd_commands(CLI::App& app, Commands& out);    // prd/cli.cpp: prd, check
void add_case_commands(CLI::App& app, Commands& out);   // cases/cli.cpp: cases
void add_dem_commands(CLI::App& app, Commands& out);    // dem/cli.cpp: dem
void add_compare_commands(CLI::App& app, Commands& out);  // compare/cli.cpp: compare, demo
void add_sweep_commands(CLI::App& app, Commands& out);    // sweep/cli.cpp: sweep
void add_tradeoff_commands(CLI::App& app, Commands& out); // tradeoff/cli.cpp: tradeoff
void add_validate_commands(CLI::App& app, Commands& out); // validate/cli.cpp: validate

}  // namespace masonry
