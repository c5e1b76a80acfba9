// `masonry validate`: the catalogue of benchmarks on both methods, one table, an exit code for CI.
//   masonry validate [--quick] [--only NAME...] [--json FILE] [--markdown FILE] [--catalogue FILE]
// Exit code 0 when every row passes, 1 when one fails, 2 for bad input (main()).
#include <cstdio>
#include <iostream>
#include <memory>
#include <set>

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
};

// The benchmarks chosen by --quick and --only, in catalogue order; an unknown name is bad input.
std::vector<const Benchmark*> chosen(const Catalogue& cat, const Opts& o) {
  std::set<std::string> wanted(o.only.begin(), o.only.end());
  for (const std::string& n : wanted) {
    bool known = false;
    for (const Benchmark& b : cat.benchmarks) known = known || b.name == n;
    if (!known) throw CaseError(cat.source + ": no benchmark named '" + n + "' (masonry validate --list)");
  }
  std::vector<const Benchmark*> out;
  for (const Benchmark& b : cat.benchmarks)
    if ((!o.quick || b.quick) && (wanted.empty() || wanted.count(b.name))) out.push_back(&b);
  if (out.empty()) throw CaseError(cat.source + ": no benchmark left to run (--quick and --only exclude them all)");
  return out;
}

std::string command_line(const Opts& o) {
  std::string s = "masonry validate";
  if (o.quick) s += " --quick";
  for (const std::string& n : o.only) s += " --only " + n;
  if (!o.catalogue.empty()) s += " --catalogue " + o.catalogue;
  return s;
}

}  // namespace

void add_validate_commands(CLI::App& app, Commands& out) {
  auto o = std::make_shared<Opts>();
  CLI::App* sub = app.add_subcommand(
      "validate", "Benchmarks with answers from outside the code (closed forms, published results), run on PRD and the DEM");
  sub->add_flag("--quick", o->quick, "Only the benchmarks marked quick (under a minute; CI runs these)");
  sub->add_option("--only", o->only, "Only these benchmarks (names, see --list)");
  sub->add_option("--json", o->json, "Write the rows to this JSON file (masonry-validation/1)");
  sub->add_option("--markdown", o->markdown, "Write the report to this Markdown file");
  sub->add_option("--catalogue", o->catalogue, "A catalogue file (masonry-catalogue/1) instead of the built-in one");
  sub->add_flag("--list", o->list, "List the catalogue's benchmarks and exit");
  sub->add_flag("--quiet", o->quiet, "No progress lines (the table is the command's output, on standard output)");
  out.push_back({sub, [o]() {
                   const Catalogue cat = o->catalogue.empty() ? builtin_catalogue() : load_catalogue(o->catalogue);
                   if (o->list) {
                     for (const Benchmark& b : cat.benchmarks)
                       std::cout << b.name << (b.quick ? " (quick)" : "") << ": " << b.title << "\n";
                     return 0;
                   }
                   const std::vector<const Benchmark*> todo = chosen(cat, *o);
                   std::vector<ValidationRow> rows;
                   RunCache cache;
                   const StudyProgress progress("validate", todo.size());
                   for (size_t k = 0; k < todo.size(); ++k) {
                     const auto part = run_benchmark(cat, *todo[k], cache, [&](const ValidationRow& r) {
                       if (o->quiet) return;
                       char b[48];
                       std::snprintf(b, sizeof b, ": %s in %.2f s", r.pass ? "pass" : "FAIL", r.seconds);
                       std::cerr << progress.line(k + 1, r.benchmark->name + " (" + method_name(r.method) + ")" + b) << "\n" << std::flush;
                     });
                     rows.insert(rows.end(), part.begin(), part.end());
                     // Finished rows are kept even when a later benchmark fails or the run is stopped.
                     if (!o->json.empty()) write_file_atomic(o->json, validation_json(cat, rows).dump(1) + "\n");
                   }
                   std::cout << validation_table(rows);
                   const std::string failures = validation_failures(rows);
                   if (!failures.empty()) std::cout << "\n" << failures;
                   if (!o->markdown.empty()) write_file_atomic(o->markdown, validation_markdown(cat, rows, command_line(*o)));
                   for (const ValidationRow& r : rows)
                     if (!r.pass) return kExitFailed;
                   return 0;
                 }});
}

}  // namespace masonry
