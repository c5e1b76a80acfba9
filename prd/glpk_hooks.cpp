#include "prd/glpk_hooks.hpp"

#include <glpk.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace masonry::prd {

namespace {

// GLPK's last lines of terminal output: an error's text arrives here before the error hook runs.
thread_local std::string glpk_text;

int on_terminal(void*, const char* s) {
  glpk_text += s;
  if (glpk_text.size() > 2000) glpk_text.erase(0, glpk_text.size() - 2000);
  return 1;  // handled: nothing reaches stdout
}

[[noreturn]] void on_error(void*) {
  std::string line;
  for (char ch : glpk_text) line += (ch == '\n' || ch == '\r') ? ' ' : ch;
  while (!line.empty() && line.back() == ' ') line.pop_back();
  std::fprintf(stderr,
               "masonry: the LP solver (GLPK) stopped on an internal error: %s. The case's numbers are probably outside "
               "what it can scale (see the README's ranges); steps finished before it were written.\n",
               line.c_str());
  std::fflush(stderr);
  std::_Exit(2);  // GLPK's state is broken: it would abort() on return
}

thread_local bool installed = false;

}  // namespace

void install_glpk_hooks() {
  if (installed) return;
  glp_term_hook(on_terminal, nullptr);
  glp_error_hook(on_error, nullptr);
  installed = true;
}

}  // namespace masonry::prd
