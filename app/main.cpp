#include <exception>
#include <iostream>

#include "app/command.hpp"
#include "app/suggest.hpp"
#include "model/case.hpp"
#include "model/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"masonry: PRD limit analysis and rigid-block DEM of masonry structures, side by side"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Help for every subcommand");
  app.set_version_flag("--version", masonry::version_text(), "The version and the git commit this build was made from");
  masonry::Commands commands;
  masonry::add_prd_commands(app, commands);
  masonry::add_case_commands(app, commands);
  masonry::add_dem_commands(app, commands);
  masonry::add_compare_commands(app, commands);
  masonry::add_sweep_commands(app, commands);
  masonry::add_tradeoff_commands(app, commands);
  masonry::add_validate_commands(app, commands);
  masonry::add_option_commands(app, commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the help (exit 0); a usage error is a refusal like any other bad input
    // (command.hpp), not CLI11's own codes (105-109), said in one line as every refusal is. A
    // subcommand or option that does not exist is named with the nearest one that does.
    if (e.get_exit_code() == 0) return app.exit(e) == 0 ? masonry::kExitDone : masonry::kExitRefused;
    const auto hint = masonry::unknown_name_hint(app, std::vector<std::string>(argv + 1, argv + argc));
    std::cerr << masonry::printable(hint ? *hint : masonry::usage_error_line(app, e.what()), 2000) << "\n";
    return masonry::kExitRefused;
  }
  for (const masonry::Command& c : commands) {
    if (!c.app->parsed()) continue;
    try {
      return c.run();
    } catch (const std::exception& e) {
      // One line, whatever went wrong: the message names the file, block and field.
      // Control characters from a case (an ANSI escape) are escaped, a huge echoed value cut.
      std::string msg = e.what();
      for (char& ch : msg)
        if (ch == '\n') ch = ' ';
      std::cerr << "masonry " << c.app->get_name() << ": " << masonry::printable(msg, 2000) << "\n";
      return masonry::kExitRefused;
    }
  }
  std::cerr << "masonry: no command given (see --help)\n";
  return masonry::kExitRefused;
}
