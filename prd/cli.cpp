// `masonry prd` and `masonry check`: thin front ends over prd_run and prd_check.
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "prd.hpp"

namespace masonry {

namespace {

// Rewrites the results after each step, but spends at most about a fifth of the run's time on
// it: a long run with large files is written less often, a short one every step. The final
// call always writes.
struct ThrottledWriter {
  std::string dir;
  const Case* c;
  std::chrono::steady_clock::time_point last{};
  double last_cost = 0;
  void operator()(const RunResult& r, bool force) {
    const auto now = std::chrono::steady_clock::now();
    if (!force && std::chrono::duration<double>(now - last).count() < 4 * last_cost) return;
    write_results(dir, r, *c);
    last = std::chrono::steady_clock::now();
    last_cost = std::chrono::duration<double>(last - now).count();
  }
};

}  // namespace

void add_prd_commands(CLI::App& app, Commands& out) {
  {
    auto* sub = app.add_subcommand("prd", "PRD capacity run: a sequence of LPs until the structure collapses");
    auto path = std::make_shared<std::string>();
    auto dir = std::make_shared<std::string>();
    auto step = std::make_shared<double>(0.0);
    auto max_steps = std::make_shared<int>(-1);
    auto tol = std::make_shared<double>(0.0);
    sub->add_option("case", *path, "Case file (JSON, masonry-case/1)")->required();
    sub->add_option("--out", *dir, "Output directory: results.json and steps.csv")->required();
    sub->add_option("--step", *step, "Increment of d per step, m (default: the case's motion.step)")->check(CLI::PositiveNumber);
    sub->add_option("--max-steps", *max_steps, "Largest number of steps (default: the case's motion.max_steps)")->check(CLI::NonNegativeNumber);
    sub->add_option("--tolerance", *tol, "Contact tolerance, m (default: the case's prd.contact_tolerance)")->check(CLI::PositiveNumber);
    out.push_back({sub, [=]() {
                     Case c = load_case(*path);
                     PrdSettings s = PrdSettings::from_case(c);
                     if (*step > 0) s.step = *step;
                     if (*max_steps >= 0) s.max_steps = *max_steps;
                     if (*tol > 0) s.contact_tolerance = *tol;
                     ThrottledWriter w{*dir, &c};
                     RunResult r = prd_run(c, s, [&](const RunResult& x) { w(x, false); });
                     w(r, true);
                     std::cerr << "prd: " << c.name << ": " << r.stopped << (r.message.empty() ? "" : " (" + r.message + ")")
                               << ", capacity " << r.capacity << " m after " << r.stable_steps << " steps, "
                               << r.timing.total_s << " s (" << r.timing.lp_solves << " LPs); results in " << *dir << "\n";
                     return r.stopped == "error" ? 1 : 0;
                   }});
  }
  {
    auto* sub = app.add_subcommand("check", "Single PRD analysis: is the structure stable as it stands?");
    auto path = std::make_shared<std::string>();
    auto as_json = std::make_shared<bool>(false);
    auto tol = std::make_shared<double>(0.0);
    sub->add_option("case", *path, "Case file (JSON, masonry-case/1)")->required();
    sub->add_flag("--json", *as_json, "Print one JSON object (stable, forces, reactions)");
    sub->add_option("--tolerance", *tol, "Contact tolerance, m (default: the case's prd.contact_tolerance)")->check(CLI::PositiveNumber);
    out.push_back({sub, [=]() {
                     Case c = load_case(*path);
                     const PrdCheck k = prd_check(c, *tol > 0 ? *tol : c.prd.contact_tolerance);
                     RunResult r;
                     r.method = "prd";
                     r.case_name = c.name;
                     r.joints = k.joints;
                     r.steps.push_back(k.state);
                     nlohmann::ordered_json full = to_json(r, c);
                     nlohmann::ordered_json j;
                     j["case"] = c.name;
                     j["stable"] = k.stable;
                     j["total_weight"] = k.total_weight;
                     j["joints"] = full["joints"];
                     j["forces"] = full["steps"][0]["forces"];
                     j["reactions"] = full["steps"][0]["reactions"];
                     if (!k.stable) j["mechanism"] = k.state.extra["collapse"];
                     if (*as_json) {
                       std::cout << j.dump(1) << "\n";
                     } else {
                       std::cout << c.name << ": " << (k.stable ? "stable" : "unstable (a collapse mechanism exists)") << "\n";
                     }
                     return 0;
                   }});
  }
}

}  // namespace masonry
