// Reports and the command: the tolerance gate's exit code through `masonry compare --runs`, the
// reports' escaping of case text, and report.html in headless Chromium (no console errors, the
// slider's test hook changes the drawn step, markup in a case name does not run).
#include "compare/report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <utility>
#include <vector>

#include "common.hpp"
#include "compare/compare.hpp"
#include "prd/prd.hpp"
#include "xml.hpp"

namespace masonry {
namespace {

namespace fs = std::filesystem;

using test::read;
using test::run;
using test::write;

const std::string kArch = std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json";

// A case whose name and a block id try to run script in the HTML report: each payload, if it
// ever ran, would set data-pwned="yes" on <body>; the string "yes" appears nowhere in the payload.
const std::string kPayload =
    "<script>document.body.setAttribute('data-pwned','y'+'es')</script>"
    "<img src=x onerror=\"document.body.setAttribute('data-pwned','y'+'es')\">";

TEST(CompareCommand, ToleranceGateSetsTheExitCode) {
  const test::Scratch scratch("compare-gate");
  const fs::path d = scratch.path;
  ASSERT_EQ(run(std::string(MASONRY_EXE) + " prd " + kArch + " --out " + (d / "a").string() + " 2>/dev/null"), 0);
  // b: the same run with its capacity doctored to 1.2 times, and its steps' d with it (the
  // reader refuses a capacity beyond the last step).
  fs::create_directories(d / "b");
  auto j = nlohmann::ordered_json::parse(read(d / "a" / "results.json"));
  j["capacity"] = j["capacity"].get<double>() * 1.2;
  for (auto& s : j["steps"]) s["d"] = s["d"].get<double>() * 1.2;
  write(d / "b" / "results.json", j.dump());
  write(d / "tol.json", R"({"capacity": 0.05, "thrust": 0.10, "hinges": true})");
  const std::string base = std::string(MASONRY_EXE) + " compare " + kArch + " --quiet --tolerances " + (d / "tol.json").string();
  EXPECT_EQ(run(base + " --runs " + (d / "a").string() + " " + (d / "a").string() + " --out " + (d / "same").string() + " 2>/dev/null"), 0);
  EXPECT_NE(run(base + " --runs " + (d / "a").string() + " " + (d / "b").string() + " --out " + (d / "doctored").string() + " 2>/dev/null"), 0);
  const std::string md = read(d / "doctored" / "report.md");
  EXPECT_NE(md.find("**FAIL**"), std::string::npos);
  EXPECT_NE(md.find("capacity: PRD a"), std::string::npos) << "the report names the violated limit";
  const auto cj = nlohmann::json::parse(read(d / "doctored" / "comparison.json"));
  EXPECT_FALSE(cj["comparisons"][0]["tolerances"]["pass"].get<bool>());
  EXPECT_NEAR(cj["comparisons"][0]["capacity"]["relative_difference"].get<double>(), 0.2, 1e-12);
  const auto sj = nlohmann::json::parse(read(d / "same" / "comparison.json"));
  EXPECT_TRUE(sj["comparisons"][0]["tolerances"]["pass"].get<bool>());
  EXPECT_EQ(sj["comparisons"][0]["thrust"]["max_difference"].get<double>(), 0.0);
  // The author's notes (why a check fails) come after the checks in both media, one paragraph
  // per blank-line-separated block, escaped as any text; a notes file that is not there is
  // refused with its name.
  write(d / "notes.txt", "The DEM takes another mechanism:\nnave-24/25 opens <first>.\n\n  \nSecond paragraph.\n");
  EXPECT_NE(run(base + " --runs " + (d / "a").string() + " " + (d / "b").string() + " --notes " + (d / "notes.txt").string() + " --out " +
                (d / "noted").string() + " 2>/dev/null"),
            0);
  const std::string noted = read(d / "noted" / "report.md");
  const size_t checks = noted.find("## Tolerance checks"), notes = noted.find("## Notes"), caps = noted.find("## Capacities");
  ASSERT_NE(notes, std::string::npos) << noted;
  EXPECT_LT(checks, notes);
  EXPECT_LT(notes, caps);
  EXPECT_NE(noted.find("The DEM takes another mechanism: nave-24/25 opens \\<first>.\n\nSecond paragraph."), std::string::npos) << noted;
  EXPECT_NE(read(d / "noted" / "report.html").find("nave-24/25 opens &lt;first&gt;."), std::string::npos);
  EXPECT_EQ(run(base + " --runs " + (d / "a").string() + " " + (d / "b").string() + " --notes " + (d / "missing.txt").string() + " --out " +
                (d / "nonotes").string() + " 2>" + (d / "err.txt").string()),
            2);
  EXPECT_NE(read(d / "err.txt").find("missing.txt: cannot read the notes file"), std::string::npos) << read(d / "err.txt");
  fs::remove_all(d);
}

// PRD on the DEM's deformed configuration, in the comparison of the tilting block on joints ten
// times softer than the case's: PRD from the case and PRD with the DEM's elastic offsets taken
// back topple at the rigid block's atan(b/h) (closed form); with the offsets kept, PRD topples
// near the DEM's own tilt, which the soft joint lowers (dem/README.md, "Joint stiffness").
TEST(CompareCommand, ADemRunIsHandedToPrdOnItsDeformedConfiguration) {
  const test::Scratch scratch("compare-deformed");
  const fs::path d = scratch.path;
  const std::string block = std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json";
  ASSERT_EQ(run(std::string(MASONRY_EXE) + " compare " + block + " --stiffness-reduction 10 --quiet --out " + (d / "c").string() + " 2>/dev/null"),
            0);
  const auto j = nlohmann::json::parse(read(d / "c" / "comparison.json"));
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_FALSE(j["runs"][0].contains("prd_on_run")) << "PRD's own run is not handed to PRD";
  const auto& dem = j["runs"][1];
  ASSERT_EQ(dem["method"], "dem");
  ASSERT_TRUE(dem.contains("prd_on_run")) << dem.dump();
  const auto& p = dem["prd_on_run"];
  const double rigid = std::atan(0.2 / 0.4), tol = p["tolerance"].get<double>(), cap = dem["capacity"].get<double>();
  EXPECT_GT(tol, 0.0);
  EXPECT_LE(p["from_d"].get<double>(), 0.9 * cap + 1e-12);
  EXPECT_NEAR(p["own"].get<double>(), rigid, 2 * tol);
  EXPECT_NEAR(p["taken_back"].get<double>(), rigid, 2 * tol);
  ASSERT_GT(rigid - cap, 20 * tol) << "the soft block topples visibly early";
  EXPECT_LT(std::abs(p["kept"].get<double>() - cap), 0.25 * (rigid - cap)) << p.dump();
  const std::string md = read(d / "c" / "report.md");
  EXPECT_NE(md.find("PRD on the DEM's deformed configuration"), std::string::npos);
  // The block's support only turns: d is its tilt, an angle, in every table and axis.
  EXPECT_EQ(j["d_unit"], "rad");
  EXPECT_NE(md.find("| capacity (mrad) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| step (mrad) |"), std::string::npos);
  EXPECT_EQ(md.find("capacity (mm)"), std::string::npos);
  EXPECT_EQ(md.find("d (mm)"), std::string::npos);
  EXPECT_NE(read(d / "c" / "figures" / "thrust-1.svg").find("support rotation d (mrad)"), std::string::npos);
  EXPECT_NE(read(d / "c" / "figures" / "capacity.svg").find(" mrad</text>"), std::string::npos);
  const std::string html = read(d / "c" / "report.html");
  EXPECT_NE(html.find("data-unit=\"mrad\""), std::string::npos);
  // Code in the text is code in both media, never a literal backtick in the page.
  EXPECT_NE(html.find("<code>masonry prd --from</code>"), std::string::npos);
  EXPECT_NE(md.find("(`masonry prd --from`)"), std::string::npos);
  EXPECT_EQ(html.find('`'), std::string::npos);
}

// A run that ended undecided says why in the report (its message), and the settings are a table
// of their own, one row per setting, not one line of JSON running off the page.
TEST(CompareReport, AnUndecidedRunSaysWhyAndSettingsAreATable) {
  const Case c = load_case(kArch);
  RunResult a = prd_run(c, PrdSettings::from_case(c)), b = a;
  b.status = RunStatus::undecided;
  b.collapsed = false;
  b.message = "the hold at d = 0.27 m reached its 30 s cap with a block still moving at 0.02 m/s";
  const Report r = make_report(c, {{"PRD", &a, "a"}, {"other", &b, "b"}});
  const auto figs = report_figures(r);
  const std::string md = report_markdown(r, figs), html = report_html(r, figs, 4);
  for (const std::string* text : {&md, &html}) {
    EXPECT_NE(text->find(b.message), std::string::npos);
    EXPECT_NE(text->find("(undecided: last equilibrium)"), std::string::npos);
    EXPECT_EQ(text->find("{\"step\""), std::string::npos) << "no settings JSON";
  }
  EXPECT_NE(md.find("| `contact_tolerance` | 1e-05 | 1e-05 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `max_steps` | 400 | 400 |"), std::string::npos) << md;
}

// A PRD-against-PRD report (1 mm and 2 mm steps) of the arch, with markup in its name and ids.
Report markup_report(Case& c, RunResult& a, RunResult& b) {
  c = load_case(kArch);
  c.name = kPayload;
  c.blocks[c.block_index("v3")].id = "v3" + kPayload;
  c.blocks[c.block_index("right")].id = "right<b>|*";
  PrdSettings s = PrdSettings::from_case(c);
  a = prd_run(c, s);
  s.step = 0.002;
  b = prd_run(c, s);
  return make_report(c, {{"PRD 1mm", &a, "a"}, {"PRD 2mm<i>", &b, "b"}});
}

TEST(CompareReport, CaseTextIsEscapedEverywhere) {
  Case c;
  RunResult a, b;
  const Report r = markup_report(c, a, b);
  const auto figs = report_figures(r);
  const std::string md = report_markdown(r, figs), html = report_html(r, figs, 10);
  // The page: as entities. The Markdown: each '<' that would open a tag behind a backslash
  // (CommonMark reads "\<" as the character), no entity a reader of the text would see.
  for (const char* tag : {"<script>document", "<img", "<b>", "<i>"}) {
    EXPECT_EQ(html.find(tag), std::string::npos) << tag;
    for (size_t at = md.find(tag); at != std::string::npos; at = md.find(tag, at + 1)) EXPECT_EQ(md[at - 1], '\\') << tag;
  }
  EXPECT_EQ(md.find("&lt;"), std::string::npos);
  for (const Figure& f : figs) {
    EXPECT_EQ(f.svg.find("<script"), std::string::npos) << f.file;
    EXPECT_EQ(f.svg.find("<img"), std::string::npos) << f.file;
  }
  EXPECT_NE(html.find("&lt;script&gt;"), std::string::npos);  // shown as text
}

// Every figure (figures/structure-*.svg, thrust, capacity) is well-formed XML whatever the ids
// and names hold: an ESC byte, a quote, a comma, a line break, bytes that are not UTF-8, U+FFFF
// (expat, an XML parser independent of the writers, reads each).
TEST(CompareReport, EveryFigureIsWellFormedXmlWhateverTheIds) {
  Case c = load_case(kArch);
  c.name = "arch\x1b[31m \"q\", \xff";
  c.blocks[c.block_index("v3")].id = "v3\x1b[0m,\"x\"\n<&>";
  c.blocks[c.block_index("right")].id = "right \xef\xbf\xbf \xc3";
  c.blocks[c.block_index("left")].id = "left\r\x01";
  PrdSettings s = PrdSettings::from_case(c);
  const RunResult a = prd_run(c, s);
  s.step = 0.002;
  const RunResult b = prd_run(c, s);
  const Report r = make_report(c, {{"PRD 1mm\x1b", &a, "a"}, {"PRD 2mm \xfe", &b, "b"}});
  const auto figs = report_figures(r);
  ASSERT_GE(figs.size(), 3u);
  for (const Figure& f : figs) {
    std::string why;
    EXPECT_TRUE(test::xml_well_formed(f.svg, why)) << f.file << ": " << why;
  }
}

bool have_chromium() { return run("command -v chromium >/dev/null 2>&1") == 0; }

// Loads the page in headless Chromium and returns the DOM after the page's own script ran.
std::string dump_dom(const fs::path& html, const std::string& fragment, const fs::path& work) {
  const fs::path profile = work / "profile", out = work / "dom.html";
  const std::string cmd =
      "timeout 90 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync --user-data-dir=" +
      profile.string() + " --virtual-time-budget=5000 --dump-dom 'file://" + html.string() + fragment + "' > " + out.string() + " 2>/dev/null";
  EXPECT_EQ(run(cmd), 0) << cmd;
  return read(out);
}

TEST(CompareReport, HtmlRunsInHeadlessChromium) {
  if (!have_chromium()) GTEST_SKIP() << "chromium is not installed (scripts/install-deps.sh installs it; CI runs this test)";
  const test::Scratch scratch("compare-chromium");
  const fs::path d = scratch.path;
  Case c;
  RunResult a, b;
  Report r = markup_report(c, a, b);
  r.frames = 12;
  write_report(d.string(), r);
  const fs::path html = d / "report.html";

  const std::string dom0 = dump_dom(html, "", d);
  const std::string dom5 = dump_dom(html, "#step=5", d);
  for (const std::string* dom : {&dom0, &dom5}) {
    ASSERT_NE(dom->find("data-ready=\"1\""), std::string::npos) << "the page's script did not finish";
    // No error, console error or blocked script was recorded.
    const size_t pre = dom->find("<pre id=\"errors\"");
    ASSERT_NE(pre, std::string::npos);
    const size_t open = dom->find('>', pre), close = dom->find("</pre>", pre);
    ASSERT_TRUE(open != std::string::npos && close != std::string::npos && open < close);
    EXPECT_EQ(dom->substr(open + 1, close - open - 1), "") << "errors in the page";
    EXPECT_EQ(dom->find("data-pwned=\"yes\""), std::string::npos) << "markup from the case ran";
  }
  // The slider position drawn: frame 0 without the hook, frame 5 with it, at a larger d.
  // (d, index) of the frames without the hidden attribute: exactly one is expected.
  const auto shown = [](const std::string& dom) {
    std::vector<std::pair<double, int>> out;
    const std::string tag = "<div class=\"frame\" data-d=\"";
    for (size_t at = dom.find(tag); at != std::string::npos; at = dom.find(tag, at + 1)) {
      const std::string head = dom.substr(at, dom.find('>', at) - at);
      if (head.find(" hidden") != std::string::npos) continue;
      const size_t d0 = tag.size(), i0 = head.find("data-index=\"") + 12;
      out.emplace_back(std::stod(head.substr(d0)), std::stoi(head.substr(i0)));
    }
    EXPECT_EQ(out.size(), 1u) << "exactly one frame drawn";
    return out.empty() ? std::make_pair(-1.0, -1) : out.front();
  };
  EXPECT_NE(dom0.find("data-frame=\"0\""), std::string::npos);
  EXPECT_NE(dom5.find("data-frame=\"5\""), std::string::npos);
  const auto f0 = shown(dom0), f5 = shown(dom5);
  EXPECT_EQ(f0.second, 0);
  EXPECT_EQ(f5.second, 5);
  EXPECT_GT(f5.first, f0.first);
  // The cursor of the thrust curves moved with it.
  EXPECT_NE(dom0.find("class=\"cursor\" x1=\"70"), std::string::npos);
  EXPECT_EQ(dom5.find("class=\"cursor\" x1=\"70\""), std::string::npos);
  fs::remove_all(d);
}

}  // namespace
}  // namespace masonry
