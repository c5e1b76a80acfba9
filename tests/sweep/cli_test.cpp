// `masonry sweep` as a command: a failing run is a row and the sweep goes on; a sweep killed half
// way resumes with the missing runs only; a table of another sweep is refused unless --restart;
// and the same sweep on 1 and 2 MPI ranks (mpirun on this machine) gives the same table.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>

#include <chrono>
#include <map>
#include <set>
#include <thread>

#include "util.hpp"

extern char** environ;

namespace masonry {
namespace {

namespace fs = std::filesystem;
const std::string kExe = MASONRY_EXE;

std::string spec(const std::string& body) { return R"({"format": "masonry-sweep/1", "case": ")" + test::kTiltCase + R"(", )" + body + "}"; }

// Data lines of a sweep.csv (complete lines only).
std::vector<std::string> data_lines(const std::string& csv) {
  std::vector<std::string> out;
  size_t pos = csv.find('\n');
  while (pos != std::string::npos && pos + 1 < csv.size()) {
    const size_t nl = csv.find('\n', pos + 1);
    if (nl == std::string::npos) break;
    out.push_back(csv.substr(pos + 1, nl - pos - 1));
    pos = nl;
  }
  return out;
}

TEST(SweepCommand, AFailedRunIsARowAndTheSweepGoesOn) {
  test::Scratch d("fail");
  // A friction angle and a time step (above the stability limit) the case refuses: three of four
  // runs fail, each with the first refusal of its values.
  test::write(d.path / "s.json", spec(R"("methods": ["dem"], "vary": {"dem.timestep_factor": [2.0, 0.2], "dem.friction_angle": [95, 30.5]})"));
  const fs::path out = d.path / "out", err = d.path / "err.txt";
  EXPECT_EQ(test::run(kExe + " sweep " + (d.path / "s.json").string() + " --out " + out.string() + " 2>" + err.string()), 1) << test::read(err);
  const auto rows = test::csv_rows(test::read(out / "sweep.csv"));
  ASSERT_EQ(rows.size(), 5u) << test::read(out / "sweep.csv");
  const size_t st = test::column(rows[0], "stopped"), msg = test::column(rows[0], "message"), cap = test::column(rows[0], "capacity");
  ASSERT_LT(msg, rows[0].size());
  // Runs: (2, 95), (2, 30.5), (0.2, 95), (0.2, 30.5).
  for (int i : {1, 3}) {
    EXPECT_EQ(rows[i][st], "error");
    EXPECT_NE(rows[i][msg].find(i == 1 ? "timestep_factor" : "friction_angle"), std::string::npos) << rows[i][msg];
    EXPECT_EQ(rows[i][cap], "");
  }
  EXPECT_EQ(rows[2][st], "error");
  EXPECT_NE(rows[2][msg].find("stability limit"), std::string::npos) << rows[2][msg];
  EXPECT_EQ(rows[4][st], "collapse") << rows[4][msg];
  EXPECT_FALSE(rows[4][cap].empty());
  const auto j = nlohmann::json::parse(test::read(out / "sweep.json"));
  EXPECT_EQ(j["failed"], 3);
  EXPECT_TRUE(j["complete"].get<bool>());
  EXPECT_NE(test::read(out / "report.md").find("stability limit"), std::string::npos);
  // Bad input is exit code 2 with one line naming the file and the field.
  test::write(d.path / "bad.json", spec(R"("vary": {"dem.friction_angle": {"from": 1}})"));
  EXPECT_EQ(test::run(kExe + " sweep " + (d.path / "bad.json").string() + " --out " + out.string() + " 2>" + err.string()), 2);
  const std::string e = test::read(err);
  EXPECT_NE(e.find((d.path / "bad.json").string()), std::string::npos) << e;
  EXPECT_NE(e.find("vary 'dem.friction_angle'"), std::string::npos) << e;
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
}

// The tilting block's support only turns, so its path parameter and capacities are in rad:
// the progress lines, the report and its figures say so, and never call them m.
TEST(SweepCommand, ATurningSupportsCapacitiesAreInRad) {
  test::Scratch d("rad");
  test::write(d.path / "s.json", spec(R"("methods": ["prd"], "vary": {"motion.step": [0.017453292519943295, 0.008726646259971648]})"));
  const fs::path out = d.path / "out", err = d.path / "err.txt";
  ASSERT_EQ(test::run(kExe + " sweep " + (d.path / "s.json").string() + " --out " + out.string() + " 2>" + err.string()), 0) << test::read(err);
  const std::string progress = test::read(err), report = test::read(out / "report.md"), figure = test::read(out / "figures" / "capacity.svg");
  EXPECT_NE(progress.find(" rad in "), std::string::npos) << progress;
  EXPECT_NE(report.find("capacity (rad)"), std::string::npos) << report;
  EXPECT_NE(figure.find("last stable d (rad)"), std::string::npos) << figure;
  for (const std::string* text : {&progress, &report, &figure}) {
    EXPECT_EQ(text->find("(m)"), std::string::npos) << *text;
    EXPECT_EQ(text->find(" m in "), std::string::npos) << *text;
  }
}

// A DEM run whose hold neither settles nor runs away (an equilibrium tolerance of 1e-16 of the
// weight, below the round-off of the joint forces, so the settled block never counts as at rest
// while its motion dies out) is listed as undecided with the DEM's reason, not turned into an
// error, and is neither compared nor counted as done.
TEST(SweepCommand, AnUndecidedDemRunIsAnUndecidedRow) {
  test::Scratch d("undecided");
  test::write(d.path / "s.json", spec(R"("methods": ["dem"], "set": {"dem.equilibrium_tolerance": 1e-16, "dem.hold_time": 1},
                      "vary": {"dem.friction_angle": [35]})"));
  const fs::path out = d.path / "out", err = d.path / "err.txt";
  EXPECT_EQ(test::run(kExe + " sweep " + (d.path / "s.json").string() + " --out " + out.string() + " 2>" + err.string()), 1) << test::read(err);
  const auto rows = test::csv_rows(test::read(out / "sweep.csv"));
  ASSERT_EQ(rows.size(), 2u) << test::read(out / "sweep.csv");
  const size_t st = test::column(rows[0], "stopped"), msg = test::column(rows[0], "message");
  ASSERT_LT(msg, rows[0].size());
  EXPECT_EQ(rows[1][st], "undecided");
  EXPECT_NE(rows[1][msg].find("neither settled nor ran away"), std::string::npos) << rows[1][msg];
  const auto j = nlohmann::json::parse(test::read(out / "sweep.json"));
  EXPECT_EQ(j["failed"], 1);
}

TEST(SweepCommand, AKilledSweepResumesWithTheMissingRunsOnly) {
  test::Scratch d("resume");
  // One run at a time, each slowed down (seconds of model time per degree of tilt), and enough
  // of them that the sweep can be caught half way; the sanitized build is slow as it is.
#ifdef __SANITIZE_ADDRESS__
  const std::string vary = R"("dem.friction_angle": {"from": 10.5, "to": 18.5, "step": 2})", move_time = "1.0";
#else
  const std::string vary = R"("dem.friction_angle": {"from": 10.5, "to": 32.5, "step": 2})", move_time = "3.0";
#endif
  test::write(d.path / "s.json", spec(R"("vary": {)" + vary + R"(}, "set": {"dem.move_time": )" + move_time + "}"));
  const size_t n = plan_sweep(read_sweep_input((d.path / "s.json").string())).runs.size();
  const std::string out = (d.path / "out").string(), csv = out + "/sweep.csv";
  const std::string spec_path = (d.path / "s.json").string();
  const std::vector<std::string> args = {kExe, "sweep", spec_path, "--out", out, "--jobs", "1", "--quiet"};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, kExe.c_str(), nullptr, nullptr, argv.data(), environ), 0);
  // Kill it (SIGKILL: no chance to tidy up) once the PRD row and two DEM rows are in.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (data_lines(test::read(csv)).size() < 3 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep finished before it could be killed: make its runs slower";
  const std::vector<std::string> before = data_lines(test::read(csv));
  ASSERT_GE(before.size(), 3u);
  ASSERT_LT(before.size(), n);
  std::set<int> had;
  for (const std::string& l : before) had.insert(std::stoi(l));

  // Resume: only the runs that have no row.
  const std::string err = (d.path / "err.txt").string();
  ASSERT_EQ(test::run(kExe + " sweep " + spec_path + " --out " + out + " --jobs 1 2>" + err), 0) << test::read(err);
  const std::string progress = test::read(err);
  std::set<int> missing;
  for (int i = 0; i < int(n); ++i)
    if (!had.count(i)) missing.insert(i);
  EXPECT_EQ(test::runs_done(progress), missing) << progress;
  EXPECT_NE(progress.find(std::to_string(had.size()) + " in " + csv + " already, " + std::to_string(missing.size()) + " to run"), std::string::npos)
      << progress;
  // The rows from before the kill are kept as they were, run times included (a rerun would
  // have measured another time).
  const std::string final_csv = test::read(csv);
  const std::vector<std::string> after = data_lines(final_csv);
  ASSERT_EQ(after.size(), n);
  for (const std::string& l : before) EXPECT_EQ(after.at(std::stoi(l)), l);
  for (int i = 0; i < int(n); ++i) EXPECT_EQ(std::stoi(after[i]), i);  // sorted by run

  // A finished sweep run again does nothing and leaves the table as it was.
  ASSERT_EQ(test::run(kExe + " sweep " + spec_path + " --out " + out + " 2>" + err), 0) << test::read(err);
  EXPECT_NE(test::read(err).find(", 0 to run"), std::string::npos) << test::read(err);
  EXPECT_EQ(test::read(csv), final_csv);
}

TEST(SweepCommand, RefusesToResumeAnotherSweepUnlessRestarted) {
  test::Scratch d("restart");
  const std::string out = (d.path / "out").string(), err = (d.path / "err.txt").string();
  test::write(d.path / "a.json", spec(R"("methods": ["prd"], "vary": {"motion.step": [0.0174532925199433, 0.0349065850398866]})"));
  test::write(d.path / "b.json", spec(R"("methods": ["prd"], "vary": {"motion.step": [0.0174532925199433, 0.0349065850398866]},
      "set": {"prd.contact_tolerance": 2e-5})"));
  ASSERT_EQ(test::run(kExe + " sweep " + (d.path / "a.json").string() + " --out " + out + " 2>" + err), 0) << test::read(err);
  const std::string first = test::read(out + "/sweep.csv");
  EXPECT_EQ(test::run(kExe + " sweep " + (d.path / "b.json").string() + " --out " + out + " 2>" + err), 2);
  const std::string e = test::read(err);
  EXPECT_NE(e.find("--restart"), std::string::npos) << e;
  EXPECT_NE(e.find(out + "/sweep.csv"), std::string::npos) << e;
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
  EXPECT_EQ(test::read(out + "/sweep.csv"), first) << "a refused sweep leaves the table alone";
  ASSERT_EQ(test::run(kExe + " sweep " + (d.path / "b.json").string() + " --out " + out + " --restart 2>" + err), 0) << test::read(err);
  EXPECT_EQ(test::runs_done(test::read(err)), (std::set<int>{0, 1}));
}

TEST(SweepCommand, OneAndTwoMpiRanksGiveTheSameTable) {
  if (test::run("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun is not on PATH (scripts/install-deps.sh installs it)";
  test::Scratch d("mpi");
  const std::string s = (d.path / "s.json").string();
  test::write(s, spec(R"("vary": {"motion.step": [0.0174532925199433, 0.0349065850398866], "dem.friction_angle": [20.5, 30.5]})"));
  std::map<std::string, std::string> tables;
  for (const auto& [name, launcher] :
       std::map<std::string, std::string>{{"local", ""}, {"np1", test::mpirun(1, d.path)}, {"np2", test::mpirun(2, d.path)}}) {
    const std::string out = (d.path / name).string(), err = (d.path / (name + ".err")).string();
    ASSERT_EQ(test::run(launcher + kExe + " sweep " + s + " --out " + out + " </dev/null 2>" + err + " >/dev/null"), 0)
        << name << ": " << test::read(err);
    tables[name] = test::read(out + "/sweep.csv");
    if (name == "np2") {
      EXPECT_NE(test::read(err).find("on 2 MPI ranks"), std::string::npos) << test::read(err);
    }
  }
  // Every column but the run time, which is measured and so differs from one run to the next.
  const auto without_time = [](const std::string& csv) {
    auto rows = test::csv_rows(csv);
    const size_t tc = test::column(rows.at(0), "time_s");
    for (auto& r : rows) r.at(tc) = "";
    return rows;
  };
  const auto local = without_time(tables["local"]);
  EXPECT_EQ(local.size(), 7u);  // header, 2 PRD runs, 4 DEM runs
  EXPECT_EQ(without_time(tables["np1"]), local);
  EXPECT_EQ(without_time(tables["np2"]), local);
}

}  // namespace
}  // namespace masonry
