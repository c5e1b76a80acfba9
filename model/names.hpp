// What a mistyped name most likely meant, by one rule for every place that names things: the
// command line's subcommands and options (app/suggest.hpp), the case generators (`masonry cases
// wal`, Python's generate("wal")).
#pragma once

#include <string>
#include <vector>

namespace masonry {

// The name among `names` that `typed` most likely misspells: the nearest by edits (an inserted,
// dropped or changed letter, or two letters swapped), within 2 edits and fewer than half its
// letters, or the one name it begins (an abbreviation of at least 3 letters); empty when none.
std::string nearest_name(const std::string& typed, const std::vector<std::string>& names);

// "; did you mean 'NAME'?" for that name, or "" when there is none.
std::string did_you_mean(const std::string& typed, const std::vector<std::string>& names);

}  // namespace masonry
