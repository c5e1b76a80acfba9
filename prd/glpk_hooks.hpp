// GLPK's terminal and error hooks, and the guard that turns an internal error of GLPK into the
// error of the one run that made the call.
#pragma once

#include <stdexcept>
#include <type_traits>

namespace masonry::prd {

// GLPK reports an internal error (a failed assertion on numbers it cannot handle, or a call it
// refuses) by printing the text and calling abort(): exit code 134, the text on stdout, and in a
// threaded sweep every other run lost with it. Inside glpk_guarded it is this exception instead,
// with GLPK's text on one line: the run that made the call stops with an error (runs/ writes it
// as that run's result), the process and the other threads go on.
struct GlpkError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Installs the hooks on this thread (GLPK's environment is per thread; cheap and idempotent):
// GLPK's terminal output is dropped (the harness prints its own), its error hook jumps back to
// the innermost glpk_guarded. An error outside any guard is a wrong call of ours, not a case's
// numbers: its text goes to stderr and GLPK aborts as it would.
void install_glpk_hooks();

// Runs call(context), one GLPK call, so that GLPK's internal error in it throws GlpkError. The
// error hook leaves GLPK by longjmp, GLPK's documented way back (its reference manual,
// glp_error_hook): the jump skips no C++ destructor, since only `call` and GLPK's own C frames
// lie between here and the hook, and `call` must hold no object with one. GLPK's state after an
// error is broken, so the thread's whole GLPK environment is freed (glp_free_env, as the manual
// requires) before the throw: every GLPK problem of this thread is gone with it (GlpProblem
// knows not to delete it again), which is why a thread runs one PRD run at a time.
int glpk_guarded(int (*call)(void*), void* context);
template <class F>
int glpk_guarded(F&& f) {
  return glpk_guarded([](void* c) { return (*static_cast<std::remove_reference_t<F>*>(c))(); }, static_cast<void*>(&f));
}

// How many times this thread's GLPK environment has been freed after an error: a problem made
// before the latest one no longer exists.
unsigned glpk_generation();

}  // namespace masonry::prd
