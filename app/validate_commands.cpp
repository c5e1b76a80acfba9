// `masonry validate`: the catalogue of benchmarks on both methods, or on an outside solver, one
// table, an exit code for CI.
//   masonry validate [--quick] [--only NAME...] [--json FILE] [--markdown FILE] [--catalogue FILE]
//                    [--solver 'COMMAND' [--solver-name NAME] [--solver-as prd|dem] [--solver-timeout S] [--solver-keep DIR]]
// Exit code 0 when every row passes, 1 when one fails or errors, 2 for bad input (main()).
#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "app/command.hpp"
#include "model/results.hpp"
#include "runs/progress.hpp"
#include "validate/validate.hpp"

namespace masonry {

namespace {

struct Opts {
  bool quick = false, quiet = false, list = false;
  std::vector<std::string> only;
  std::string json, markdown, catalogue;
  std::string solver, solver_name = "solver", solver_as = "prd", solver_keep;
  double solver_timeout = 600;
};

// The outside solver's working directory: the user's --solver-keep DIR (made if missing), else a
// fresh one under the system's temporary directory. The paths replace {case} and {out} in a
// shell command as they are, so they must need no quoting.
std::string solver_workdir(const std::string& keep) {
  namespace fs = std::filesystem;
  std::string dir = keep.empty() ? (fs::temp_directory_path() / "masonry-solver-XXXXXX").string() : keep;
  const std::string what = keep.empty() ? "--solver: the temporary directory " : "--solver-keep: ";
  for (char ch : dir)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && std::string("/._-+").find(ch) == std::string::npos)
      throw CaseError(what + dir + " has characters a shell command would need quoted" + (keep.empty() ? " (set TMPDIR)" : ""));
  if (!keep.empty()) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw CaseError("--solver-keep: cannot make the directory " + dir + (ec ? ": " + ec.message() : ""));
    return dir;
  }
  if (!mkdtemp(dir.data())) throw CaseError("--solver: cannot make a working directory under " + fs::temp_directory_path().string());
  return dir;
}

// The temporary working directory goes when the command ends, however it ends (every row passed,
// one failed, or a refusal thrown mid-way): a failing solver left one under /tmp per run. The
// user's --solver-keep DIR is never removed.
struct RemovedAtExit {
  std::string dir;
  void remove() {
    std::error_code ec;
    if (!dir.empty()) std::filesystem::remove_all(dir, ec);
    dir.clear();
  }
  ~RemovedAtExit() { remove(); }
};

// A process that removes the temporary directory once this one has ended, however it ends:
// stopped by Ctrl-C during masonry's own work between the solver's runs (the solver's wait
// catches the signal and cleans up itself, nothing else does) or killed, no destructor runs.
// It waits on a pipe whose only writer is this process (close-on-exec, so no solver holds it), in
// a process group of its own (a signal to masonry's group, a terminal's Ctrl-C or a CI's kill,
// does not reach it; the terminal's signals are blocked across the fork and then ignored), and
// holds none of the caller's streams or descriptors. Called before any thread starts: the child
// of a single-threaded process may allocate (remove_all). Without it (no pipe or fork) the
// ordinary ends still remove the directory.
void remove_when_this_process_ends(const std::string& dir) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return;
  sigset_t stops, before;
  sigemptyset(&stops);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaddset(&stops, sig);
  sigprocmask(SIG_BLOCK, &stops, &before);
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) std::signal(sig, SIG_IGN);
    sigprocmask(SIG_SETMASK, &before, nullptr);
    if (const int null = open("/dev/null", O_RDWR); null >= 0) {
      for (const int fd : {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO}) dup2(null, fd);
      if (null > STDERR_FILENO) close(null);
    }
    close_range(STDERR_FILENO + 1, unsigned(fds[0]) - 1, 0);  // every inherited descriptor but the pipe's read end
    close_range(unsigned(fds[0]) + 1, ~0U, 0);
    char ch;
    while (read(fds[0], &ch, 1) < 0 && errno == EINTR) {
    }
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    _exit(0);
  }
  sigprocmask(SIG_SETMASK, &before, nullptr);
  close(fds[0]);  // the write end stays open until this process ends
  if (pid < 0) close(fds[1]);
}

std::string command_line(const Opts& o) {
  std::string s = "masonry validate";
  if (o.quick) s += " --quick";
  for (const std::string& n : o.only) s += " --only " + n;
  if (!o.catalogue.empty()) s += " --catalogue " + o.catalogue;
  if (!o.solver.empty()) s += " --solver '" + o.solver + "' --solver-name " + o.solver_name + " --solver-as " + o.solver_as;
  if (!o.solver_keep.empty()) s += " --solver-keep " + o.solver_keep;
  return s;
}

}  // namespace

void add_validate_commands(CLI::App& app, Commands& out) {
  auto o = std::make_shared<Opts>();
  CLI::App* sub =
      app.add_subcommand("validate", "Benchmarks with answers from outside the code (closed forms, published results), run on PRD and the DEM");
  sub->add_flag("--quick", o->quick, "Only the benchmarks marked quick (under a minute; CI runs these)");
  sub->add_option("--only", o->only, "Only these benchmarks (names, see --list)");
  sub->add_option("--json", o->json, "Write the rows to this JSON file (masonry-validation/1)");
  sub->add_option("--markdown", o->markdown, "Write the report to this Markdown file");
  sub->add_option("--catalogue", o->catalogue, "A catalogue file (masonry-catalogue/1) instead of the built-in one");
  sub->add_flag("--list", o->list, "List the catalogue's benchmarks and exit");
  sub->add_flag("--quiet", o->quiet, "No progress lines (the table is the command's output, on standard output)");
  sub->add_option("--solver", o->solver,
                  "Judge an outside solver instead: a shell command with {case} (a masonry-case/1 file it reads) and {out} (an empty "
                  "directory where it writes results.json, masonry-results/1); README, \"Gate your own solver in CI\"");
  sub->add_option("--solver-name", o->solver_name, "The outside solver's name in the table (default: solver)")->needs("--solver");
  sub->add_option("--solver-as", o->solver_as, "Judge it by this method's expected values and tolerances (default prd: a limit-analysis code)")
      ->check(CLI::IsMember({"prd", "dem"}))
      ->needs("--solver");
  sub->add_option("--solver-timeout", o->solver_timeout, "Seconds one run of the solver may take (default 600); past it the run is an error")
      ->check(CLI::PositiveNumber)
      ->needs("--solver");
  sub->add_option("--solver-keep", o->solver_keep,
                  "Write the solver's runs (each benchmark's case.json, out/ and solver.log) under this directory and keep them; without it "
                  "they go to a temporary directory removed at the end")
      ->needs("--solver");
  out.push_back({sub, [o]() {
                   const Catalogue cat = o->catalogue.empty() ? builtin_catalogue() : load_catalogue(o->catalogue);
                   if (o->list) {
                     for (const Benchmark& b : cat.benchmarks) std::cout << b.name << (b.quick ? " (quick)" : "") << ": " << b.title << "\n";
                     return 0;
                   }
                   const std::vector<const Benchmark*> todo = chosen_benchmarks(cat, o->quick, o->only);
                   std::optional<OutsideSolver> solver;
                   RemovedAtExit temporary;
                   if (!o->solver.empty()) {
                     solver.emplace();
                     solver->command = o->solver;
                     solver->name = o->solver_name;
                     solver->as = *parse_method(o->solver_as);
                     solver->timeout_s = o->solver_timeout;
                     solver->workdir = solver_workdir(o->solver_keep);
                     solver->kept = !o->solver_keep.empty();
                     if (!solver->kept) {
                       temporary.dir = solver->workdir;
                       remove_when_this_process_ends(solver->workdir);
                     }
                   }
                   std::vector<ValidationRow> rows;
                   RunCache cache;
                   const StudyProgress progress("validate", todo.size());
                   for (size_t k = 0; k < todo.size(); ++k) try {
                     const auto part = run_benchmark(
                         cat, *todo[k], cache,
                         [&](const ValidationRow& r) {
                           if (o->quiet) return;
                           const char* verdict = !r.applicable ? "n/a" : r.pass ? (r.damped_rerun ? "pass (damped rerun)" : "pass") : r.solver_error ? "ERROR" : "FAIL";
                           char b[64];
                           std::snprintf(b, sizeof b, ": %s in %.2f s", verdict, r.seconds);
                           std::cerr << progress.line(k + 1, r.benchmark->name + " (" + r.method_label + ")" + b) << "\n" << std::flush;
                         },
                         solver ? &*solver : nullptr);
                     rows.insert(rows.end(), part.begin(), part.end());
                     // Finished rows are kept even when a later benchmark fails or the run is stopped.
                     if (!o->json.empty()) write_file_atomic(o->json, validation_json(cat, rows).dump(1) + "\n");
                   } catch (const SolverInterrupted& e) {
                     // Stopped (Ctrl-C) while the solver ran: it is killed; the temporary
                     // directory goes, and the command ends by the same signal.
                     temporary.remove();
                     std::signal(e.signal, SIG_DFL);
                     std::raise(e.signal);
                     return 128 + e.signal;
                   }
                   std::cout << validation_table(rows);
                   const std::string failures = validation_failures(rows);
                   if (!failures.empty()) std::cout << "\n" << failures;
                   const std::string skipped = validation_not_applicable(rows);
                   if (!skipped.empty()) std::cout << "\n" << skipped;
                   if (!o->markdown.empty()) write_file_atomic(o->markdown, validation_markdown(cat, rows, command_line(*o)));
                   bool any_failed = false;
                   for (const ValidationRow& r : rows) any_failed = any_failed || failed(r);
                   // Where the runs are, where they are kept; else, after a failure, how to keep them.
                   if (solver && solver->kept) std::cout << "\nThe solver's runs (case.json, out/, solver.log): " << solver->workdir << "\n";
                   if (solver && !solver->kept && any_failed)
                     std::cout << "\nThe solver's runs were in a temporary directory, now removed: --solver-keep DIR keeps them (case.json, out/, "
                                  "solver.log)\n";
                   return any_failed ? kExitFailed : kExitDone;
                 }});
}

}  // namespace masonry
