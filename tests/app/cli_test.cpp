// The command line as one tool (README, "Commands"): a mistyped subcommand or option is refused
// with the nearest name, every subcommand that prints progress takes --quiet and then says
// nothing but warnings and why it failed, and progress lines give the time left.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "common.hpp"
#include "model/options.hpp"

namespace masonry {
namespace {

using test::Scratch;
const std::string kExe = MASONRY_EXE;
const std::string kTilt = std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json";

struct Ran {
  int rc = -1;
  std::string err;
};
Ran run(const std::string& args, const Scratch& dir) {
  const std::string err = (dir.path / "stderr").string();
  Ran r;
  r.rc = test::run(kExe + " " + args + " >/dev/null 2>" + err);
  r.err = test::read(err);
  return r;
}

TEST(CommandLine, AMistypedNameIsRefusedWithTheNearestOne) {
  Scratch dir("cli-typo");
  struct Typo {
    std::string args, needle;
  };
  const std::vector<Typo> typos = {
      {"comapre", "masonry: 'comapre' is not a command; did you mean 'compare'?"},
      {"vaildate --quick", "did you mean 'validate'?"},
      {"cases improt x.dxf --out y.json", "masonry cases: 'improt' is not a command; did you mean 'import'?"},
      {"dem " + kTilt + " --out o --frition 30", "masonry dem: unknown option '--frition'; did you mean '--friction'?"},
      {"prd " + kTilt + " --out o --max-step=0.1 --stpe 0.01", "did you mean '--step'?"},
      {"compare " + kTilt + " --out o --tolerance f.json", "did you mean '--tolerances'?"},
  };
  for (const Typo& t : typos) {
    const Ran r = run(t.args, dir);
    EXPECT_EQ(r.rc, 2) << t.args;
    EXPECT_NE(r.err.find(t.needle), std::string::npos) << t.args << " | " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  }
  // Nothing near: refused all the same, without a guess.
  const Ran far = run("xyzzy", dir);
  EXPECT_EQ(far.rc, 2);
  EXPECT_NE(far.err.find("'xyzzy' is not a command"), std::string::npos) << far.err;
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
  // Help stays help.
  EXPECT_EQ(run("--help", dir).rc, 0);
  EXPECT_EQ(run("dem --help", dir).rc, 0);
}

// Every other usage error CLI11 refuses (a whole number given 1.5, a required option missing, a
// value out of its range) is one line in the harness's form, naming the subcommand, where CLI11
// printed its message and "Run with --help or --help-all for more information." (README,
// "Commands": refused with one line on stderr).
TEST(CommandLine, AUsageErrorIsOneLineNamingTheCommand) {
  Scratch dir("cli-usage");
  const std::string out = (dir.path / "o").string();
  struct Usage {
    std::string args, start, needle;
  };
  const std::vector<Usage> usages = {
      {"dem " + kTilt + " --out " + out + " --max-steps 1.5", "masonry dem: ", "--max-steps = 1.5"},
      {"prd " + kTilt + " --out " + out + " --max-steps 1.5", "masonry prd: ", "--max-steps = 1.5"},
      {"dem " + kTilt, "masonry dem: ", "--out is required"},
      {"prd " + kTilt + " --out " + out + " --friction-angle 100", "masonry prd: ", "--friction-angle"},
      {"cases wall --bond flemish --out -", "masonry cases wall: ", "--bond: must be one of header, running, stack"},
  };
  for (const Usage& u : usages) {
    const Ran r = run(u.args, dir);
    EXPECT_EQ(r.rc, 2) << u.args;
    EXPECT_EQ(r.err.rfind(u.start, 0), 0u) << u.args << " | " << r.err;
    EXPECT_NE(r.err.find(u.needle), std::string::npos) << u.args << " | " << r.err;
    EXPECT_NE(r.err.find("--help lists the options)"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  }
}

// A flag that takes a word names the words it takes, not CLI11's internal map of them.
TEST(CommandLine, AWordOutsideItsListIsRefusedNamingTheWords) {
  Scratch dir("cli-words");
  const Ran bond = run("cases wall --bond flemish --out -", dir);
  EXPECT_EQ(bond.rc, 2);
  EXPECT_NE(bond.err.find("--bond: must be one of header, running, stack, not \"flemish\""), std::string::npos) << bond.err;
  const Ran moving = run("cases wall --moving up --out -", dir);
  EXPECT_NE(moving.err.find("--moving: must be one of left, none, right, not \"up\""), std::string::npos) << moving.err;
  EXPECT_EQ(run("cases wall --bond stack --moving left --courses 2 --bricks 2 --out -", dir).rc, 0);
}

TEST(CommandLine, QuietSaysNothingButWhyItFailed) {
  Scratch dir("cli-quiet");
  const std::string out = (dir.path / "o").string();
  // Every subcommand that prints progress takes --quiet.
  for (const std::string sub : {"prd", "dem", "compare", "demo", "sweep", "tradeoff", "validate"})
    EXPECT_EQ(test::run(kExe + " " + sub + " --help | grep -q -- --quiet"), 0) << sub << " has no --quiet";
  const Ran prd = run("prd " + kTilt + " --out " + out + " --quiet", dir);
  EXPECT_EQ(prd.rc, 0);
  EXPECT_EQ(prd.err, "");
  const Ran loud = run("prd " + kTilt + " --out " + out, dir);
  EXPECT_EQ(loud.rc, 0);
  // The tilting block's d is its support's rotation: 1 degree a step, 60 at most, in rad; it
  // stands at 26 degrees, the last whole degree below atan(b/h) = atan(0.5) = 26.57.
  EXPECT_NE(loud.err.find("prd: step 1, d = 0.0174533 rad of at most 1.0472 rad"), std::string::npos) << loud.err;
  EXPECT_NE(loud.err.find("capacity 0.453786 rad"), std::string::npos) << loud.err;
  EXPECT_NE(loud.err.find(" s, at most "), std::string::npos) << loud.err;
  EXPECT_NE(loud.err.find("collapse, capacity"), std::string::npos) << loud.err;
  // compare --quiet: no progress, no summary (it printed its summary before).
  const Ran cmp = run("compare " + kTilt + " --out " + out + "-c --quiet", dir);
  EXPECT_EQ(cmp.rc, 0) << cmp.err;
  EXPECT_EQ(cmp.err, "");
  // A refusal is said whatever --quiet says.
  const Ran bad = run("prd " + kTilt + " --out " + out + " --quiet --step -1", dir);
  EXPECT_EQ(bad.rc, 2);
  EXPECT_NE(bad.err.find("field 'step'"), std::string::npos) << bad.err;
}

// `check --step` takes the step as the case's motion.step, with its range and refusal: NaN ran
// the other analysis with exit code 0, 1e300 was accepted, 0 printed DBL_MAX's 309 digits. And
// `prd --friction-angle nan` is refused, where CLI11's range let it through.
TEST(CommandLine, CheckStepAndFrictionAngleAreCheckedLikeTheCase) {
  Scratch dir("cli-check-step");
  for (const char* step : {"nan", "0", "1e300", "5"}) {
    const Ran r = run("check " + kTilt + " --step " + step, dir);
    EXPECT_EQ(r.rc, 2) << step;
    EXPECT_NE(r.err.find("field 'step'"), std::string::npos) << step << " | " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  }
  EXPECT_EQ(run("check " + kTilt + " --step 0.01", dir).rc, 0);
  const Ran f = run("prd " + kTilt + " --out " + (dir.path / "o").string() + " --friction-angle nan", dir);
  EXPECT_EQ(f.rc, 2);
  EXPECT_NE(f.err.find("--friction-angle: must be a finite number"), std::string::npos) << f.err;
}

// A switch on by default is turned off by `--name=false`, on `dem` and on `compare`, and the
// results' settings say which was run (dem.confirm_collapse, on by default since 2026-11-27).
TEST(CommandLine, ASwitchOnByDefaultTurnsOffWithEqualsFalse) {
  Scratch dir("cli-switch");
  const auto confirm = [&](const std::string& flags) {
    const std::string out = (dir.path / "o").string();
    const Ran r = run("dem " + kTilt + " --out " + out + " --quiet --max-steps 2" + flags, dir);
    EXPECT_EQ(r.rc, 0) << flags << " | " << r.err;
    return nlohmann::json::parse(test::read(dir.path / "o" / "results.json"))["settings"]["confirm_collapse"].get<bool>();
  };
  EXPECT_TRUE(confirm(""));
  EXPECT_FALSE(confirm(" --confirm-collapse=false"));
  EXPECT_TRUE(confirm(" --confirm-collapse"));
  const Ran c = run("compare " + kTilt + " --out " + (dir.path / "c").string() + " --quiet --max-steps 2 --confirm-collapse=false", dir);
  EXPECT_EQ(c.rc, 0) << c.err;
  const nlohmann::json dem = nlohmann::json::parse(test::read(dir.path / "c" / "dem" / "results.json"));
  EXPECT_FALSE(dem["settings"]["confirm_collapse"].get<bool>());
}

// An option that acts only with another one the run leaves off is accepted and echoed in the
// settings, but ignored: the run says so (the capacity is the same with and without it).
TEST(CommandLine, AnOptionThatActsOnlyWithAnotherSaysSo) {
  Scratch dir("cli-idle");
  const std::string out = (dir.path / "o").string();
  const Ran idle = run("prd " + kTilt + " --out " + out + " --event-tolerance 1e-5", dir);
  EXPECT_EQ(idle.rc, 0) << idle.err;
  EXPECT_NE(idle.err.find("prd: note: prd.event_tolerance (--event-tolerance) has no effect without prd.adaptive"), std::string::npos) << idle.err;
  const double with = nlohmann::json::parse(test::read(dir.path / "o" / "results.json"))["capacity"].get<double>();
  const Ran plain = run("prd " + kTilt + " --out " + out, dir);
  EXPECT_EQ(plain.err.find("note:"), std::string::npos) << plain.err;
  EXPECT_EQ(nlohmann::json::parse(test::read(dir.path / "o" / "results.json"))["capacity"].get<double>(), with);
  const Ran used = run("prd " + kTilt + " --out " + out + " --adaptive --event-tolerance 1e-5", dir);
  EXPECT_EQ(used.err.find("note:"), std::string::npos) << used.err;
  const Ran ramp = run("dem " + kTilt + " --out " + out + " --quiet --max-steps 1 --ramp-fraction 0.1", dir);
  EXPECT_NE(ramp.err.find("dem: note: dem.ramp_fraction (--ramp-fraction) has no effect without dem.move_time"), std::string::npos) << ramp.err;
}

// The DEM's study flags on a plain run (one run, no study) were accepted silently: `dem CASE
// --jobs 3` ran one run on one thread. Each is named as an idle option is (README, the dem
// rows: --jobs, --only and --read-back belong to the studies, the limits to --convergence).
TEST(CommandLine, ADemStudyFlagOnAPlainRunSaysSo) {
  Scratch dir("cli-idle-study");
  const std::string out = (dir.path / "o").string();
  const Ran jobs = run("dem " + kTilt + " --out " + out + " --quiet --max-steps 1 --jobs 3 --spread-limit 0.1", dir);
  EXPECT_EQ(jobs.rc, 0) << jobs.err;
  EXPECT_NE(jobs.err.find("dem: note: --jobs has no effect without a study (--convergence or --stiffness-study)"), std::string::npos) << jobs.err;
  EXPECT_NE(jobs.err.find("dem: note: --spread-limit has no effect without --convergence"), std::string::npos) << jobs.err;
  const Ran plain = run("dem " + kTilt + " --out " + out + " --quiet --max-steps 1", dir);
  EXPECT_EQ(plain.err.find("note:"), std::string::npos) << plain.err;
}

// A case whose supports do not move is refused by the capacity commands (exit 2, one line),
// where `masonry prd` ran 1000 steps to "max_steps, capacity 1 m" with exit code 0.
TEST(CommandLine, SupportsThatDoNotMoveAreRefused) {
  Scratch dir("cli-static");
  std::string text = test::read(kTilt);
  const size_t a = text.find("\"supports\""), b = text.find(']', text.find(']', text.find(']', a) + 1) + 1);
  ASSERT_NE(a, std::string::npos);
  text = text.substr(0, a) + "\"supports\": []" + text.substr(b + 1);
  test::write(dir.path / "still.json", text);
  const Ran r = run("prd " + (dir.path / "still.json").string() + " --out " + (dir.path / "o").string(), dir);
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_NE(r.err.find("no support moves"), std::string::npos) << r.err;
  EXPECT_EQ(run("check " + (dir.path / "still.json").string(), dir).rc, 0);
}

// A DEM refusal comes before PRD runs in `compare` (a large case's PRD takes minutes): nothing
// is written, and the one line names the field.
TEST(CommandLine, CompareRefusesTheDemBeforeRunningPrd) {
  Scratch dir("cli-compare-refusal");
  const std::filesystem::path out = dir.path / "o";
  const Ran r = run("compare " + kTilt + " --out " + out.string() + " --quiet --damping 0", dir);
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_NE(r.err.find("field 'damping' = 0"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out / "prd")) << r.err;
}

// Every flag the options' table gives a command is in that command's help, with the option's key.
TEST(CommandLine, EveryOptionFlagIsOnItsCommands) {
  Scratch dir("cli-option-flags");
  const auto help_of = [&](const std::string& sub) {
    const std::string out = (dir.path / "help").string();
    EXPECT_EQ(test::run(kExe + " " + sub + " --help >" + out + " 2>&1"), 0) << sub;
    return test::read(out);
  };
  std::map<OptionCommand, std::string> help;
  for (OptionCommand k : {OptionCommand::prd, OptionCommand::dem, OptionCommand::compare}) help[k] = help_of(option_command_name(k));
  int flags = 0;
  for (const OptionInfo& i : option_infos())
    for (OptionCommand k : i.commands) {
      ++flags;
      EXPECT_NE(help[k].find(std::string(i.flag) + " "), std::string::npos) << i.flag << " not on " << option_command_name(k);
      EXPECT_NE(help[k].find("case: " + i.key), std::string::npos) << i.key << " not in the help of " << option_command_name(k);
    }
  EXPECT_GE(flags, 20);
  const std::string check = help_of("check");
  EXPECT_NE(check.find("case: " + option_key(&PrdOptions::contact_tolerance)), std::string::npos) << check;
  EXPECT_NE(check.find("case: " + option_key(&PrdOptions::hold_closed)), std::string::npos) << check;
}

}  // namespace
}  // namespace masonry
