// Helpers of the sweep tests: the tilting block's closed form (files, scratch directories and
// commands: common.hpp).
#pragma once

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common.hpp"
#include "model/case.hpp"
#include "sweep/sweep.hpp"

namespace masonry::test {

inline const std::string kTiltCase = std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json";

// The tilting block's closed form, from the case file's own geometry: a block b wide and h high
// slides when the tilt reaches phi if tan(phi) < b/h and topples at atan(b/h) otherwise.
struct TiltBlock {
  double b = 0, h = 0;   // m
  double rate = 0;       // rad of tilt per m of d (the slab's rotation rate)
  double increment = 0;  // rad of tilt per step
  double topple() const { return std::atan(b / h); }
  // The collapse tilt for friction angle phi (rad): the smaller of phi and the toppling angle.
  double collapse(double phi) const { return std::tan(phi) < b / h ? phi : topple(); }
};

inline TiltBlock tilt_block() {
  const Case c = load_case(kTiltCase);
  TiltBlock t;
  const Block& blk = c.blocks.at(c.block_index("block"));
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const Vec2& v : blk.vertices) {
    x0 = std::min(x0, v.x()), x1 = std::max(x1, v.x());
    y0 = std::min(y0, v.y()), y1 = std::max(y1, v.y());
  }
  t.b = x1 - x0;
  t.h = y1 - y0;
  t.rate = c.motion.supports.at(0).rotation;
  t.increment = c.motion.step * t.rate;
  return t;
}

// The lines of a CSV text split into fields (no quoted commas in the columns the tests read).
inline std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> f(1);
    bool quoted = false;
    for (char ch : line) {
      if (ch == '"')
        quoted = !quoted;
      else if (ch == ',' && !quoted)
        f.emplace_back();
      else
        f.back() += ch;
    }
    rows.push_back(f);
  }
  return rows;
}

// Whether a text has the word "nan" (any case): the reports never show one.
inline bool says_nan(const std::string& text) {
  const auto letter = [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) != 0; };
  for (size_t i = 0; i + 3 <= text.size(); ++i) {
    const bool n = std::tolower(static_cast<unsigned char>(text[i])) == 'n' && std::tolower(static_cast<unsigned char>(text[i + 1])) == 'a' &&
                   std::tolower(static_cast<unsigned char>(text[i + 2])) == 'n';
    if (n && (i == 0 || !letter(text[i - 1])) && (i + 3 == text.size() || !letter(text[i + 3]))) return true;
  }
  return false;
}

// "sweep: [k/n] run I ..." progress lines: the runs an invocation did.
inline std::set<int> runs_done(const std::string& progress) {
  std::set<int> s;
  std::istringstream in(progress);
  for (std::string line; std::getline(in, line);) {
    const size_t at = line.find("] run ");
    if (line.rfind("sweep: [", 0) == 0 && at != std::string::npos) s.insert(std::stoi(line.substr(at + 6)));
  }
  return s;
}

// mpirun as the tests need it: as root (CI runs as root), more ranks than cores allowed, and
// every byte on this machine (shared memory between ranks, no cross-memory attach, which
// containers forbid; loopback for the launcher).
//
// In the sanitized build, Open MPI's runtime keeps memory to the end of the process that
// LeakSanitizer reports as leaks (libmpi, libopen-rte, libopen-pal, its libevent and its
// components, mca_*.so): those are suppressed, for the ranks only. Full stack unwinding and
// components kept loaded are what let the suppressions see Open MPI's frames; any leak without
// one of them in its stack is still reported.
inline std::string mpirun(int ranks, const std::filesystem::path& scratch) {
  const std::filesystem::path supp = scratch / "openmpi-lsan.supp";
  write(supp, "leak:libmpi.so\nleak:libopen-rte.so\nleak:libopen-pal.so\nleak:libevent_core\nleak:mca_\n");
  const char* asan = std::getenv("ASAN_OPTIONS");
  return "ASAN_OPTIONS='" + std::string(asan ? asan : "") + ":fast_unwind_on_malloc=0' LSAN_OPTIONS='suppressions=" + supp.string() +
         "' mpirun --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) +
         " --mca btl self,vader --mca btl_vader_single_copy_mechanism none --mca oob_tcp_if_include lo"
         " --mca mca_base_component_disable_dlclose 1 ";
}

inline size_t column(const std::vector<std::string>& header, const std::string& name) {
  for (size_t k = 0; k < header.size(); ++k)
    if (header[k] == name) return k;
  return header.size();
}

}  // namespace masonry::test
