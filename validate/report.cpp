// The validation reports: the terminal table, the failures spelled out, JSON and Markdown.
#include <algorithm>
#include <sstream>

#include "model/version.hpp"
#include "report/escape.hpp"
#include "report/format.hpp"
#include "report/table.hpp"
#include "validate/validate.hpp"

namespace masonry {

namespace {

std::string cell_expected(const ValidationRow& r) {
  if (r.benchmark->quantity == Quantity::stands) return r.expected > 0 ? "stands" : "falls";
  return fmt::g(r.expected, 6);
}

std::string cell_obtained(const ValidationRow& r) {
  if (!r.measured) return "-";
  if (r.benchmark->quantity == Quantity::stands) return r.obtained > 0 ? "stands" : "falls";
  return fmt::g(r.obtained, 6);
}

std::string cell_error(const ValidationRow& r) {
  if (!r.measured || r.benchmark->quantity == Quantity::stands) return "-";
  std::string s = fmt::g(r.error(), 3);
  if (r.expected != 0) s += " (" + fmt::number(100 * r.error() / std::abs(r.expected), "%+.2f%%", 100 * r.error() / std::abs(r.expected)) + ")";
  return s;
}

std::string cell_tolerance(const ValidationRow& r) {
  if (!r.applicable) return "-";
  if (r.benchmark->quantity == Quantity::stands) return "exact";
  return fmt::g(r.tolerance, 3);
}

std::string cell_expected_or_none(const ValidationRow& r) { return r.applicable ? cell_expected(r) : "-"; }

// pass, FAIL (a wrong answer, or none), ERROR (an outside solver failed), n/a.
std::string verdict(const ValidationRow& r) {
  if (!r.applicable) return "n/a";
  if (r.pass) return r.damped_rerun ? "pass (damped rerun)" : "pass";
  return r.solver_error ? "ERROR" : "FAIL";
}

std::string method_cell(const ValidationRow& r) { return r.method_label.empty() ? method_name(r.method) : r.method_label; }

std::string quantity_cell(const ValidationRow& r) {
  std::string q = quantity_name(r.benchmark->quantity);
  if (!r.unit.empty()) q += " (" + r.unit + ")";
  return q;
}

std::vector<std::vector<std::string>> cells(const std::vector<ValidationRow>& rows) {
  std::vector<std::vector<std::string>> out;
  for (const ValidationRow& r : rows)
    out.push_back({r.benchmark->name, method_cell(r), quantity_cell(r), cell_expected_or_none(r), cell_obtained(r), cell_error(r), cell_tolerance(r),
                   verdict(r), fmt::number(r.seconds, "%.2f s", r.seconds), r.expected_from});
  return out;
}

const std::vector<std::string> kHeader = {"benchmark", "method", "quantity", "expected", "obtained", "error", "tolerance", "pass", "time", "source"};

int passed(const std::vector<ValidationRow>& rows) {
  return static_cast<int>(std::count_if(rows.begin(), rows.end(), [](const ValidationRow& r) { return r.pass; }));
}

int not_applicable(const std::vector<ValidationRow>& rows) {
  return static_cast<int>(std::count_if(rows.begin(), rows.end(), [](const ValidationRow& r) { return !r.applicable; }));
}

// "5 of 7 passed", with the rows that do not apply said apart: "5 of 6 passed, 1 not applicable".
std::string tally(const std::vector<ValidationRow>& rows) {
  const int na = not_applicable(rows);
  std::string s = std::to_string(passed(rows)) + " of " + std::to_string(rows.size() - na) + " passed";
  if (na > 0) s += ", " + std::to_string(na) + " not applicable";
  const auto damped = std::count_if(rows.begin(), rows.end(), [](const ValidationRow& r) { return r.pass && r.damped_rerun; });
  if (damped > 0) s += " (" + std::to_string(damped) + " of them by a DEM rerun with contact damping)";
  return s;
}

}  // namespace

std::string validation_table(const std::vector<ValidationRow>& rows) {
  const auto body = cells(rows);
  std::vector<size_t> width(kHeader.size());
  for (size_t k = 0; k < kHeader.size(); ++k) {
    width[k] = kHeader[k].size();
    for (const auto& row : body) width[k] = std::max(width[k], row[k].size());
  }
  std::ostringstream out;
  auto line = [&](const std::vector<std::string>& row) {
    for (size_t k = 0; k < row.size(); ++k) {
      out << row[k];
      if (k + 1 < row.size()) out << std::string(width[k] - row[k].size() + 2, ' ');
    }
    out << "\n";
  };
  line(kHeader);
  for (const auto& row : body) line(row);
  out << tally(rows) << "\n";
  return out.str();
}

std::string validation_failures(const std::vector<ValidationRow>& rows) {
  std::ostringstream out;
  for (const ValidationRow& r : rows) {
    if (!failed(r)) continue;
    const Benchmark& b = *r.benchmark;
    out << verdict(r) << " " << b.name << " (" << method_cell(r) << "): expected " << quantity_name(b.quantity) << " " << cell_expected(r);
    if (b.quantity != Quantity::stands) out << " +- " << fmt::g(r.tolerance, 3);
    if (!r.unit.empty()) out << " " << r.unit;
    out << " (" << r.expected_from << "); ";
    if (r.measured)
      out << "obtained " << cell_obtained(r);
    else
      out << "no result";
    if (!r.note.empty()) out << ": " << r.note;
    out << "\n";
  }
  return out.str();
}

std::string validation_not_applicable(const std::vector<ValidationRow>& rows) {
  std::ostringstream out;
  for (const ValidationRow& r : rows)
    if (!r.applicable) out << "n/a " << r.benchmark->name << " (" << method_cell(r) << "): " << r.note << "\n";
  return out.str();
}

nlohmann::ordered_json validation_json(const Catalogue& cat, const std::vector<ValidationRow>& rows) {
  nlohmann::ordered_json j;
  j["format"] = "masonry-validation/1";
  j["version"] = version_text();
  j["catalogue"] = cat.source;
  j["passed"] = passed(rows);
  j["not_applicable"] = not_applicable(rows);
  j["rows"] = nlohmann::ordered_json::array();
  for (const ValidationRow& r : rows) {
    const Benchmark& b = *r.benchmark;
    nlohmann::ordered_json x = {{"benchmark", b.name},
                                {"title", b.title},
                                {"method", method_cell(r)},
                                {"judged_as", method_name(r.method)},
                                {"quantity", quantity_name(b.quantity)},
                                {"unit", r.unit},
                                {"expected", r.expected},
                                {"expected_from", r.expected_from}};
    // No NaN reaches a report: a row without a number says so.
    x["obtained"] = r.measured ? nlohmann::ordered_json(r.obtained) : nlohmann::ordered_json(nullptr);
    x["error"] = r.measured ? nlohmann::ordered_json(r.error()) : nlohmann::ordered_json(nullptr);
    // Whether a structure stands is a yes or no, as the catalogue writes it (`"expected": true`):
    // true or false, and no difference between them (pass says whether they agree).
    if (b.quantity == Quantity::stands) {
      x["expected"] = r.expected > 0;
      if (r.measured) x["obtained"] = r.obtained > 0;
      x["error"] = nullptr;
    }
    x["tolerance"] = r.tolerance;
    x["pass"] = r.pass;
    x["damped_rerun"] = r.damped_rerun;
    x["applicable"] = r.applicable;
    x["solver_error"] = r.solver_error;
    x["seconds"] = r.seconds;
    x["note"] = r.note;
    for (const MethodRun& m : b.methods)
      if (m.method == r.method) x["tolerance_why"] = m.tolerance.why;
    j["rows"].push_back(x);
  }
  return j;
}

std::string validation_markdown(const Catalogue& cat, const std::vector<ValidationRow>& rows, const std::string& command) {
  std::ostringstream out;
  out << "# Validation: both methods against what is known\n\n";
  out << "Generated by `" << command << "` (" << md_escape(version_text()) << ") from " << md_escape(cat.source) << ". " << tally(rows)
      << ". Times are wall times of one run on a shared machine (indicative only).\n\n";
  Table t;
  t.head.assign(kHeader.begin(), kHeader.end());
  for (const auto& row : cells(rows)) t.rows.emplace_back(row.begin(), row.end());
  out << markdown(t);
  const std::string failures = validation_failures(rows);
  if (!failures.empty()) out << "## Failures\n\n```\n" << failures << "```\n";
  out << (failures.empty() ? "" : "\n") << "## The benchmarks\n";
  const Benchmark* last = nullptr;
  for (const ValidationRow& r : rows) {
    const Benchmark& b = *r.benchmark;
    if (&b != last) {
      out << "\n### " << md_escape(b.name) << "\n\n" << md_escape(b.title) << " Source: " << md_escape(b.source) << ".";
      if (!b.notes.empty()) out << " " << md_escape(b.notes);
      out << "\n\n";
      last = &b;
    }
    out << "- " << md_escape(method_cell(r)) << ": " << (r.pass || !r.applicable ? verdict(r) : "**" + verdict(r) + "**") << ", obtained "
        << md_escape(cell_obtained(r)) << (r.unit.empty() ? "" : " " + r.unit);
    if (!r.note.empty()) out << " (" << md_escape(r.note) << ")";
    for (const MethodRun& m : b.methods)
      if (m.method == r.method && b.quantity != Quantity::stands && r.applicable)
        out << ". Tolerance " << fmt::g(r.tolerance, 3) << (r.unit.empty() ? "" : " " + r.unit) << ": " << md_escape(m.tolerance.why);
    out << "\n";
  }
  return out.str();
}

}  // namespace masonry
