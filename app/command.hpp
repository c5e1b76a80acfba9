// The `masonry` executable is one CLI11 app; each library's subcommands are added by a thin
// front end of its own in app/ (app/<library>_commands.cpp), and main() runs the one chosen.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "model/results.hpp"

namespace masonry {

// The exit codes of every command (README, "Commands"):
//   0  finished: every run located its answer (a collapse or the end of the path) and every
//      check asked for (tolerances, limits, benchmarks) passed;
//   1  finished, but some run ended without an answer (error or undecided: its results.json
//      says why) or a check failed;
//   2  refused or stopped before any result: bad input or options, named on one line of stderr.
constexpr int kExitDone = 0, kExitFailed = 1, kExitRefused = 2;
// A run's exit code: 0 when it located its answer, 1 otherwise.
inline int exit_code(RunStatus s) { return located(s) ? kExitDone : kExitFailed; }

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;  // returns the exit code; throws for bad input or errors
};
using Commands = std::vector<Command>;

void add_prd_commands(CLI::App& app, Commands& out);       // app/prd_commands.cpp: prd, check
void add_case_commands(CLI::App& app, Commands& out);      // app/cases_commands.cpp: cases
void add_dem_commands(CLI::App& app, Commands& out);       // app/dem_commands.cpp: dem
void add_compare_commands(CLI::App& app, Commands& out);   // app/compare_commands.cpp: compare, demo
void add_sweep_commands(CLI::App& app, Commands& out);     // app/sweep_commands.cpp: sweep
void add_tradeoff_commands(CLI::App& app, Commands& out);  // app/tradeoff_commands.cpp: tradeoff
void add_validate_commands(CLI::App& app, Commands& out);  // app/validate_commands.cpp: validate
void add_option_commands(CLI::App& app, Commands& out);    // app/options_commands.cpp: options

// A flag that takes one of `words`, each standing for a value of E: anything else is refused in
// one line naming the flag and the words ("--bond: must be one of header, running, stack, not
// \"flemish\""), where CLI11's own check prints its internal map.
template <class E>
CLI::Option* take_words(CLI::Option* o, const std::map<std::string, E>& words) {
  std::string list;
  for (const auto& [w, e] : words) list += (list.empty() ? "" : ", ") + w;
  // One transform that refuses and converts: CLI11 runs transforms before checks, so a separate
  // check would see the converted value.
  o->type_name("WORD");
  return o->transform(CLI::Validator(
      [words, list](std::string& v) {
        const auto it = words.find(v);
        if (it == words.end()) return "must be one of " + list + ", not \"" + v + "\"";
        v = std::to_string(static_cast<long long>(it->second));
        return std::string();
      },
      ""));
}

}  // namespace masonry
