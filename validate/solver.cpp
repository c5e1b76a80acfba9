// An outside solver's run (`masonry validate --solver`): the case written to a file, the command
// run through the shell with a time limit, its results read back through the results reader.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "model/io.hpp"
#include "validate/validate.hpp"

namespace masonry {

namespace {

namespace fs = std::filesystem;

// Every "{key}" in `text` replaced by `value`.
std::string substitute(std::string text, const std::string& key, const std::string& value) {
  for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size())) text.replace(at, key.size(), value);
  return text;
}

// A file or directory name from a benchmark's name: letters, digits, '.', '-' and '_' only.
std::string file_name(const std::string& label) {
  std::string out;
  for (char ch : label) out += std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == '_' ? ch : '_';
  return out.empty() || out[0] == '.' ? "run" + out : out;
}

struct Exit {
  bool timed_out = false;
  int status = 0;  // the exit status, or 128 + the signal that ended it
};

// The signal that asked the command to stop while a solver ran (0: none). A handler may only set
// it; the wait below reads it.
volatile sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int sig) { stop_signal = sig; }

// SIGINT, SIGTERM and SIGHUP caught while the solver runs, the previous handlers back after.
struct StopSignals {
  static constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction old[3];
  StopSignals() {
    stop_signal = 0;
    struct sigaction a {};
    a.sa_handler = on_stop_signal;
    sigemptyset(&a.sa_mask);
    for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &a, &old[k]);
  }
  ~StopSignals() {
    for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &old[k], nullptr);
  }
};

// Runs `command` through /bin/sh in a process group of its own, stdin from /dev/null, stdout and
// stderr to `log`; past `timeout_s` the whole group is killed (a solver's own child processes too).
Exit run_shell(const std::string& command, const std::string& log, double timeout_s) {
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("cannot start the solver: ") + std::strerror(errno));
  if (pid == 0) {
    setpgid(0, 0);
    const int in = open("/dev/null", O_RDONLY);
    const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in >= 0) dup2(in, STDIN_FILENO);
    if (out >= 0) {
      dup2(out, STDOUT_FILENO);
      dup2(out, STDERR_FILENO);
    }
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);  // as the child does: whichever runs first, the group exists before a kill
  const StopSignals stops;
  using clock = std::chrono::steady_clock;
  const auto deadline = clock::now() + std::chrono::duration<double>(timeout_s);
  // Polled, from 1 ms up to 50 ms: a quick solver is not kept waiting, a slow one costs nothing.
  auto pause = std::chrono::milliseconds(1);
  for (;;) {
    int st = 0;
    const pid_t done = waitpid(pid, &st, WNOHANG);
    if (done == pid) return {false, WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st)};
    if (done < 0 && errno != EINTR) throw std::runtime_error(std::string("lost the solver's process: ") + std::strerror(errno));
    if (stop_signal != 0) {
      kill(-pid, SIGKILL);
      waitpid(pid, &st, 0);
      throw SolverInterrupted{stop_signal};
    }
    if (clock::now() >= deadline) {
      kill(-pid, SIGKILL);
      waitpid(pid, &st, 0);
      return {true, 0};
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
}

// The last non-empty line of the solver's output, cut to 300 characters: what a failing row shows.
std::string last_line(const std::string& log) {
  const std::optional<std::string> text = read_text(log);
  if (!text) return "";
  std::istringstream in(*text);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  if (last.size() > 300) last = last.substr(0, 300) + "...";
  return printable(last);
}

}  // namespace

RunResult run_outside(const OutsideSolver& s, const Case& c, const std::string& label) {
  const fs::path dir = fs::path(s.workdir) / file_name(label);
  const fs::path out = dir / "out";
  fs::remove_all(dir);
  fs::create_directories(out);
  const std::string case_path = (dir / "case.json").string();
  write_file_atomic(case_path, case_to_json(c) + "\n");
  const std::string log = (dir / "solver.log").string();
  const std::string command = substitute(substitute(s.command, "{case}", case_path), "{out}", out.string());
  const Exit e = run_shell(command, log, s.timeout_s);
  const std::string said = last_line(log);
  const std::string tail = said.empty() ? "" : " (last line of its output: " + said + ")";
  // Where to look: the run's folder where the user keeps the runs; else how to keep them (the
  // temporary folder is gone when the command ends).
  const std::string files = s.kept ? "; its files: " + dir.string() : "; --solver-keep DIR keeps its case.json, out/ and solver.log";
  if (e.timed_out) {
    std::ostringstream m;
    m << "the solver ran past " << s.timeout_s << " s (--solver-timeout) and was stopped" << files;
    throw std::runtime_error(m.str());
  }
  if (e.status != 0) throw std::runtime_error("the solver exited with status " + std::to_string(e.status) + tail + files);
  const fs::path results = out / "results.json";
  if (!fs::exists(results)) throw std::runtime_error("the solver wrote no {out}/results.json" + tail + files);
  RunResult r = load_results(results.string(), c);
  // A results file of another case (a copy left from an earlier run, a hard-coded name) would
  // be judged as this case's answer.
  if (r.case_name != c.name)
    throw std::runtime_error(results.string() + ": field 'case' is '" + printable(r.case_name) + "', not the case the solver was given ('" + c.name +
                             "')");
  return r;
}

}  // namespace masonry
