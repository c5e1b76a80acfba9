// `masonry options [--markdown]`: every case option from its row (model/options.cpp); the
// Markdown table is README.md's ("Options"), which a test holds to it.
#include <iostream>
#include <memory>

#include "app/command.hpp"
#include "model/options.hpp"

namespace masonry {

namespace {

void print_options() {
  for (const OptionInfo& i : option_infos()) {
    std::cout << i.key << ": " << option_type_name(i.type);
    if (*i.unit) std::cout << ", " << i.unit;
    std::cout << ", default " << (i.default_text.empty() ? "none" : i.default_text) << ", " << i.range_text;
    if (*i.flag) {
      std::cout << ", flag " << i.flag << " (";
      for (size_t k = 0; k < i.commands.size(); ++k) std::cout << (k ? ", " : "") << option_command_name(i.commands[k]);
      std::cout << ")";
    }
    std::cout << "\n    " << i.help << (*i.note ? std::string(" (") + i.note + ")" : "") << "\n";
  }
}

}  // namespace

void add_option_commands(CLI::App& app, Commands& out) {
  auto markdown = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("options", "Every case option: key, type, default, range, unit, flag and meaning");
  sub->add_flag("--markdown", *markdown, "As the Markdown table of README.md (\"Options\")");
  out.push_back({sub, [markdown]() {
                   if (*markdown)
                     std::cout << options_markdown();
                   else
                     print_options();
                   return kExitDone;
                 }});
}

}  // namespace masonry
