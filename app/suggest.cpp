#include "app/suggest.hpp"

#include <algorithm>

namespace masonry {

namespace {

// Every long option of `app` and the apps above it (`--help` included), with its dashes.
std::vector<std::string> long_options(const CLI::App* app) {
  std::vector<std::string> out;
  for (; app; app = app->get_parent())
    for (const CLI::Option* o : app->get_options())
      for (const std::string& n : o->get_lnames()) out.push_back("--" + n);
  return out;
}

std::vector<std::string> subcommand_names(CLI::App* app) {
  std::vector<std::string> out;
  for (const CLI::App* s : app->get_subcommands([](CLI::App*) { return true; })) out.push_back(s->get_name());
  return out;
}

std::string full_name(const CLI::App* app) {
  std::string n;
  for (; app; app = app->get_parent()) n = app->get_parent() ? " " + app->get_name() + n : "masonry" + n;
  return n;
}

}  // namespace

std::string usage_error_line(const CLI::App& app, const std::string& what) {
  const CLI::App* at = &app;
  for (std::vector<CLI::App*> subs = at->get_subcommands(); !subs.empty(); subs = at->get_subcommands()) at = subs.back();
  std::string line = what;
  std::replace(line.begin(), line.end(), '\n', ' ');
  return full_name(at) + ": " + line + " (" + full_name(at) + " --help lists the options)";
}

std::optional<std::string> unknown_name_hint(CLI::App& app, const std::vector<std::string>& args) {
  // Walk the words as CLI11 does: each one that names a subcommand of the current app enters it.
  CLI::App* at = &app;
  bool positional_seen = false;
  for (size_t k = 0; k < args.size(); ++k) {
    const std::string& w = args[k];
    if (w == "--") break;
    if (w.rfind("--", 0) == 0) {
      const std::string name = w.substr(0, w.find('='));
      const std::vector<std::string> known = long_options(at);
      if (std::find(known.begin(), known.end(), name) == known.end())
        return full_name(at) + ": unknown option '" + name + "'" + did_you_mean(name, known) + " (" + full_name(at) + " --help lists them)";
      continue;
    }
    if (w.size() > 1 && w[0] == '-') continue;  // a short option, or a negative number
    CLI::App* sub = nullptr;
    for (CLI::App* s : at->get_subcommands([](CLI::App*) { return true; }))
      if (s->check_name(w)) sub = s;
    if (sub) {
      at = sub;
      positional_seen = false;
      continue;
    }
    // A free word where only a subcommand can stand (an app with subcommands and no positional
    // arguments): a mistyped one.
    const std::vector<std::string> subs = subcommand_names(at);
    const bool positionals = !at->get_options([](CLI::Option* o) { return o->get_positional(); }).empty();
    if (!positional_seen && !subs.empty() && !positionals)
      return full_name(at) + ": '" + w + "' is not a command" + did_you_mean(w, subs) + " (" + full_name(at) + " --help lists them)";
    positional_seen = true;
  }
  return std::nullopt;
}

}  // namespace masonry
