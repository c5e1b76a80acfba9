// What a mistyped command line most likely meant: `masonry comapre` -> "did you mean 'compare'?",
// `masonry dem case.json --frition 30` -> "did you mean '--friction'?" (README, "Commands").
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/names.hpp"  // nearest_name, did_you_mean: the rule

namespace masonry {

// One line for a command line that names a subcommand or an option that does not exist, with
// the nearest existing name; nothing when every name exists (another usage error, left to
// CLI11). `app` is the top-level app after a parse that failed (or before any parse, for the
// first word).
std::optional<std::string> unknown_name_hint(CLI::App& app, const std::vector<std::string>& args);

// Any other usage error CLI11 refuses (a value that is not a number, a required option missing,
// a value out of its range) as one line in the harness's form, "masonry dem: WHAT (masonry dem
// --help lists the options)", naming the subcommand the parse had entered, where CLI11 prints
// its message and a second line of its own.
std::string usage_error_line(const CLI::App& app, const std::string& what);

}  // namespace masonry
