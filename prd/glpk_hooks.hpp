// GLPK's terminal and error hooks, installed before the solver's first GLPK call on a thread.
#pragma once

namespace masonry::prd {

// GLPK reports an internal error (a failed assertion on numbers it cannot handle) by printing
// the text and calling abort(): exit code 134, the text on stdout, no word of what to do. With
// these hooks its text goes to one line on stderr and the process exits with code 2, as for any
// other error; the results a run wrote as it went stay on disk. Its other terminal output is
// dropped (the harness prints its own). GLPK's environment is per thread, so each thread that
// solves LPs installs them (cheap and idempotent).
void install_glpk_hooks();

}  // namespace masonry::prd
