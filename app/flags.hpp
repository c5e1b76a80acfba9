// Command-line flags that set case options. A flag such as `--damping 0.6` is the case option
// `dem.damping` = 0.6 applied with with_option, so a setting has one meaning and one validation
// (the case loader's, naming "FILE [dem.damping=1.5]" and the field) whether it comes from a
// case file, a flag, a sweep or a tradeoff plan.
#pragma once

#include <CLI/CLI.hpp>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "model/case.hpp"

namespace masonry {

class CaseFlags {
 public:
  enum class Kind { number, integer, flag, text, texts };
  // Adds `--name VALUE` (or the switch `--name`; for text, one word the case loader checks; for
  // texts, repeatable, the values a list) to `sub`, setting case option `key`.
  void add(CLI::App* sub, const std::string& name, const std::string& key, Kind kind, const std::string& help);
  // The case with every given flag applied, in the order they were added. Throws CaseError.
  Case apply(Case c) const;
  // " --name value" for every given flag: the part of a command line that reproduces them.
  std::string command_line() const;

 private:
  struct Flag {
    std::string name, key;
    Kind kind = Kind::number;
    std::optional<double> number;
    std::optional<long long> integer;
    bool on = false;
    std::optional<std::string> text;
    std::vector<std::string> texts;
  };
  std::deque<Flag> flags_;  // a deque: CLI11 keeps pointers to the values
};

}  // namespace masonry
