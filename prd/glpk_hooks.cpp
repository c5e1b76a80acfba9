#include "prd/glpk_hooks.hpp"

#include <glpk.h>

#include <csetjmp>
#include <cstdio>
#include <string>

namespace masonry::prd {

namespace {

// GLPK's last lines of terminal output: an error's text arrives here before the error hook runs.
thread_local std::string glpk_text;
thread_local bool installed = false;
// The innermost glpk_guarded's return point on this thread (none outside a guarded call).
thread_local std::jmp_buf* target = nullptr;
thread_local unsigned generation = 0;

int on_terminal(void*, const char* s) {
  glpk_text += s;
  if (glpk_text.size() > 2000) glpk_text.erase(0, glpk_text.size() - 2000);
  return 1;  // handled: nothing reaches stdout
}

// GLPK's text, one line.
std::string error_line() {
  std::string line;
  for (char ch : glpk_text) line += (ch == '\n' || ch == '\r') ? ' ' : ch;
  while (!line.empty() && line.back() == ' ') line.pop_back();
  while (!line.empty() && line.front() == ' ') line.erase(0, 1);
  return line;
}

void on_error(void*) {
  if (target) std::longjmp(*target, 1);
  std::fprintf(stderr, "masonry: GLPK refused a call outside the guarded solves (a bug in masonry): %s\n", error_line().c_str());
  std::fflush(stderr);
  // Returning, GLPK aborts.
}

}  // namespace

// GLPK keeps one environment per thread (thread-local storage) and nothing frees it when the
// thread ends: every worker thread of a sweep would leave its own behind (LeakSanitizer found
// the one of a test's second thread). Each thread that installs the hooks frees its environment
// when it exits; by then every problem it made is gone (GlpProblem is scoped to a run).
struct FreeEnvAtThreadExit {
  ~FreeEnvAtThreadExit() { glp_free_env(); }
};

void install_glpk_hooks() {
  thread_local FreeEnvAtThreadExit free_at_exit;
  (void)free_at_exit;
  if (installed) return;
  glp_term_hook(on_terminal, nullptr);
  glp_error_hook(on_error, nullptr);
  installed = true;
}

int glpk_guarded(int (*call)(void*), void* context) {
  install_glpk_hooks();
  glpk_text.clear();  // an error's text is this call's
  std::jmp_buf here;
  std::jmp_buf* const outer = target;
  target = &here;
  if (setjmp(here) != 0) {
    target = outer;
    const std::string line = error_line();
    glpk_text.clear();
    glp_free_env();
    ++generation;
    installed = false;  // the hooks went with the environment
    throw GlpkError("the LP solver (GLPK) stopped on an internal error: " + line +
                    ". The case's numbers are probably outside what it can scale (see the README's ranges)");
  }
  const int rc = call(context);
  target = outer;
  return rc;
}

unsigned glpk_generation() { return generation; }

}  // namespace masonry::prd
