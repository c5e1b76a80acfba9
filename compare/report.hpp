// Reports of a comparison: comparison.json (numbers), report.md (readable on a code-hosting
// site, figures as SVG files beside it) and report.html (one self-contained file: inline SVG,
// inline script, no network; a slider steps through d).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compare/compare.hpp"
#include "compare/slide.hpp"
#include "report/document.hpp"

namespace masonry {

struct ReportRun {
  std::string label;  // "PRD", "DEM phi=35 deg"
  const RunResult* run = nullptr;
  std::string dir;                                    // its results directory, relative to the report (may be empty)
  std::optional<PrdOnRun> prd_on_run = std::nullopt;  // a DEM run: PRD on its deformed configuration (runs/run.hpp)
  std::optional<DampedRerun> rerun = std::nullopt;    // a DEM run compare ran again with contact damping (this run or its rerun)
};

// runs[0] is the reference; comparisons[k] compares runs[0] with runs[k + 1].
struct Report {
  const Case* c = nullptr;
  std::vector<ReportRun> runs;
  std::vector<Comparison> comparisons;
  bool tolerances_checked = false;
  Tolerances tolerances;
  std::vector<std::vector<std::string>> violations;  // per comparison
  std::string command;                               // how the report was made (shown verbatim, escaped)
  int frames = 0;                                    // slider positions in report.html (0: chosen from the scene size)
  std::vector<std::string> notes;                    // the author's paragraphs on the result (plain text), after the checks
};

// Builds the comparisons (and, with `t`, the tolerance checks) of runs[0] against the others.
Report make_report(const Case& c, const std::vector<ReportRun>& runs, const Tolerances* t = nullptr, const CompareOptions& o = {});

struct Figure {
  std::string file;  // relative path, e.g. "figures/thrust-1.svg"
  std::string svg;
  std::string caption;  // plain text
};
std::vector<Figure> report_figures(const Report& r);

// comparison.json: {"format", "case", "runs", "comparisons": [to_json(k) + "tolerances"]}.
nlohmann::ordered_json report_json(const Report& r);
// report.md and report.html hold the same content (one document, two writers); the page inlines
// the figures and adds a slider through d with `frames` positions (0: chosen from the scene size).
std::string report_markdown(const Report& r, const std::vector<Figure>& figures);
std::string report_html(const Report& r, const std::vector<Figure>& figures, int frames = 0);
// What the reports say of PRD on a DEM run's deformed configuration (PrdOnRun), before its
// table: one text for the comparison's report and the DEM studies'. `unit`: d's, x 1000 ("mm").
Text prd_on_run_explained(double tolerance, const std::string& unit);

// Writes DIR/comparison.json, DIR/report.md, DIR/report.html and DIR/figures/*.svg.
void write_report(const std::string& dir, const Report& r);

}  // namespace masonry
