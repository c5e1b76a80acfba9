// What a mistyped command line most likely meant: `masonry comapre` -> "did you mean 'compare'?",
// `masonry dem case.json --frition 30` -> "did you mean '--friction'?" (README, "Commands").
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace masonry {

// The name among `names` that `typed` most likely misspells: the nearest by edits (an inserted,
// dropped or changed letter, or two letters swapped), within 2 edits and fewer than half its
// letters, or the one name it begins (an abbreviation of at least 3 letters); empty when none.
std::string nearest_name(const std::string& typed, const std::vector<std::string>& names);

// One line for a command line that names a subcommand or an option that does not exist, with
// the nearest existing name; nothing when every name exists (another usage error, left to
// CLI11). `app` is the top-level app after a parse that failed (or before any parse, for the
// first word).
std::optional<std::string> unknown_name_hint(CLI::App& app, const std::vector<std::string>& args);

}  // namespace masonry
