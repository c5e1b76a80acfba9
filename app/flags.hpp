// Command-line flags that set case options. A flag such as `--damping 0.6` is the case option
// `dem.damping` = 0.6 applied with with_option, so a setting has one meaning and one validation
// (the case loader's, naming "FILE [dem.damping=1.5]" and the field) whether it comes from a
// case file, a flag, a sweep or a tradeoff plan. The flags, their help and the commands that
// offer them are the options' rows (model/options.cpp): none is declared here by hand.
#pragma once

#include <CLI/CLI.hpp>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/options.hpp"

namespace masonry {

class CaseFlags {
 public:
  // Adds to `sub` the flag of every option whose row offers one on `command`, in the table's
  // order. On compare, which runs both methods, each help says which method reads it.
  void add(CLI::App* sub, OptionCommand command);
  // Adds one option's flag, for a command that takes only some (`check --tolerance`).
  template <class S, class T>
  CLI::Option* add(CLI::App* sub, T S::*member) {
    return add(sub, info(option_key(member)), "");
  }
  // The case with every given flag applied, in the order they were added. Throws CaseError.
  Case apply(Case c) const;
  // " --name value" for every given flag: the part of a command line that reproduces them.
  std::string command_line() const;

 private:
  struct Flag {
    std::string name, key;
    std::optional<double> number;
    std::optional<long long> integer;
    bool on = false;  // a boolean option: `--name` is true, `--name=false` false
    CLI::Option* flag = nullptr;  // the boolean's flag, whose count says whether it was given
    bool switch_given() const { return flag && flag->count() > 0; }
    std::optional<std::string> text;
    std::vector<std::string> texts;
  };
  static OptionInfo info(const std::string& key);
  CLI::Option* add(CLI::App* sub, const OptionInfo& option, const std::string& prefix);
  std::deque<Flag> flags_;  // a deque: CLI11 keeps pointers to the values
};

}  // namespace masonry
