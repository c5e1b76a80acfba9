// `masonry prd` and `masonry check`: thin front ends over prd_run and prd_check.
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/command.hpp"
#include "app/flags.hpp"
#include "prd/prd.hpp"
#include "runs/progress.hpp"
#include "runs/run.hpp"

namespace masonry {

namespace {

// With corners held closed: the least force the LP's force state gives a held corner over the
// run. Negative means the held path is carried by a tension there; where the held run's first
// step also releases less energy than the free run's, no compressive force state can carry it
// (LP duality), so a no-tension structure leaves that path (dem/README.md, "The branch X").
void report_held(const RunResult& r, const std::string& unit) {
  double least = INFINITY, at = 0;
  std::string which;
  for (const StepRecord& s : r.steps)
    for (const HeldCorner& h : s.held_corners)
      if (h.force < least) least = h.force, at = s.d, which = h.corner;
  if (which.empty()) return;
  std::cerr << "prd: held corners: the least force in the LP's force state is " << least << " N (" << which << ", d = " << at << " " << unit << ")"
            << (least < 0 ? ": negative, the force state pulls there (a tension)" : "") << "\n";
}

// Warns, before the LP is built, when the case is large enough for the analysis to take a
// while: the simplex makes one to two pivots per free block on a fresh LP, each costing in
// proportion to the rows, so the time grows with the square of the blocks (measured on the
// 2-core reference machine: 1.9 s for a wall of 4000 blocks with `check`; the first step of
// `prd` on running-bond walls 4.1 s at 2,049 blocks and 14.3 s at 4,130, prd/README.md).
void warn_lp_cost(const Case& c, const char* cmd, double seconds_per_block_squared, bool as_it_stands = false) {
  double n = 0;
  for (const Block& b : c.blocks) n += !b.support;
  // A fixed-step run of that many blocks solves by the interior point instead (prd/interior.hpp):
  // 0.45 s at 2,049 blocks and 5 s at 10,052, each of the run's LPs that the last solution does
  // not solve (prd/README.md, "The interior point"), as the blocks to the power 1.5.
  if (std::string(cmd) == "prd" && !c.prd.adaptive && n >= kInteriorPointBlocks) {
    const double estimate = 5.0 * std::pow(n / 10052.0, 1.5);
    // An unbounded LP (the collapse) has no optimum for the interior point: GLPK's simplex proves
    // it, from a fresh start (6,442 blocks: 130 s; prd/README.md, "Known limits").
    if (estimate >= 5 || n >= 6000)
      std::cerr << "masonry prd: " << n << " free blocks: the interior point takes about " << std::max(1L, std::lround(estimate))
                << " s for each LP that the last one's solution does not solve (it grows as the blocks to the power 1.5); the step "
                   "that collapses is GLPK's, which takes minutes at this size\n";
    return;
  }
  const double estimate = seconds_per_block_squared * n * n;
  if (estimate < 5) return;
  std::cerr << "masonry " << cmd << ": " << n << " free blocks: the first LP alone takes about " << static_cast<long>(estimate)
            << " s (it grows with the square of the blocks)";
  // From about 6,000 blocks GLPK's simplex has failed from the advanced basis on walls, and its
  // standard basis then took minutes (6,442 blocks: 130 s; prd/README.md, "Known limits").
  if (n >= 6000) std::cerr << ", or minutes where GLPK must fall back on its standard basis";
  // The structure as it stands: where each block's loads go down through the joints below it,
  // that load path is the LP's optimum (prd/static_basis.cpp; a 10,052-block wall: 0.5 s).
  if (as_it_stands) std::cerr << "; under a second where the loads go down through the joints to the supports";
  std::cerr << "\n";
}

// `masonry check --step H [--hold CORNER ...]`: at the case's contact tolerance, holding its corners.
int print_first_step(const Case& c, double h, bool as_json) {
  const std::vector<std::string>& held = c.prd.hold_closed;
  const FirstStep f = prd_first_step(c, c.prd.contact_tolerance, h, held);
  nlohmann::ordered_json j;
  j["case"] = c.name;
  j["step"] = h;
  j["held_closed"] = held;
  j["bounded"] = f.bounded;
  if (f.bounded) {
    j["energy_change"] = f.energy_change;
    j["opening"] = nlohmann::ordered_json::array();
    for (const FirstStep::Opening& o : f.opening) j["opening"].push_back({{"corner", o.corner}, {"opening", o.opening}});
  }
  if (as_json) {
    std::cout << j.dump(1) << "\n";
    return kExitDone;
  }
  if (!f.bounded) {
    std::cout << printable(c.name) << ": unbounded: the structure collapses at d = 0\n";
    return kExitDone;
  }
  std::cout << printable(c.name) << ": a first step of " << h << " " << path_unit(c) << " changes the loads' potential energy by "
            << f.energy_change << " J; it opens " << (f.opening.empty() ? "no corner\n" : "these corners:\n");
  for (const FirstStep::Opening& o : f.opening) std::cout << "  " << printable(o.corner) << "  " << o.opening * 1e3 << " mm\n";
  return kExitDone;
}

// The start configuration of `masonry prd --from`: the last equilibrium record of that run at or
// before d (NaN: its capacity).
PrdStart start_of(const Case& c, const std::string& path, double d, StartOffsets offsets) {
  const RunResult src = load_results(path, c);
  const double at = std::isnan(d) ? src.capacity : d;
  const StepRecord* rec = last_equilibrium(src, at);
  std::ostringstream what;
  if (!rec) {
    what << path << ": no equilibrium record at or before d = " << at << " " << path_unit(c);
    throw std::runtime_error(what.str());
  }
  what << path << ", " << src.method << " record " << rec->index << " (d = " << rec->d << " " << path_unit(c) << ")";
  // A results file need not give poses (an outside solver's); a start needs every block's.
  if (rec->poses.empty()) throw std::runtime_error(what.str() + ": no poses (steps[].poses), which a start needs");
  return {rec->d, rec->poses, offsets, what.str()};
}

}  // namespace

void add_prd_commands(CLI::App& app, Commands& out) {
  {
    auto* sub = app.add_subcommand("prd", "PRD capacity run: a sequence of LPs until the structure collapses");
    auto path = std::make_shared<std::string>();
    auto dir = std::make_shared<std::string>();
    auto settings = std::make_shared<CaseFlags>();  // the flags that set case options
    auto friction = std::make_shared<double>(-1.0);
    auto quiet = std::make_shared<bool>(false);
    sub->add_option("case", *path, "Case file (JSON, masonry-case/1)")->required();
    sub->add_flag("--quiet", *quiet, "No progress lines and no summary: only warnings, the answers asked for and why a run failed");
    sub->add_option("--out", *dir, "Output directory: results.json and steps.csv")->required();
    settings->add(sub, OptionCommand::prd);
    sub->add_option("--friction-angle", *friction,
                    "Report the first step and joint where the friction demand exceeds this angle, deg (implies --sliding)")
        ->check(CLI::Validator(
            [](std::string& v) {
              // CLI11's range lets NaN through (every comparison with it is false).
              const double x = std::strtod(v.c_str(), nullptr);
              return std::isfinite(x) ? std::string() : "must be a finite number, not \"" + v + "\"";
            },
            ""))
        ->check(CLI::Range(0.0, 90.0));
    auto from = std::make_shared<std::string>();
    auto from_d = std::make_shared<double>(NAN);
    auto offsets = std::make_shared<StartOffsets>(StartOffsets::keep);
    auto* from_opt = sub->add_option("--from", *from,
                                     "Start from a configuration another run of this case recorded (its results.json, PRD or DEM): "
                                     "the blocks where it left them, d going on from there (dem/README.md, \"Joint stiffness\")");
    sub->add_option("--from-d", *from_d, "With --from: the last equilibrium record at or before this d, m (default: the run's capacity)")
        ->needs(from_opt);
    take_words(sub->add_option("--elastic", *offsets,
                               "With --from: a closed corner's offset there (a DEM's elastic overlap and shear) is kept as the joint's geometry "
                               "(keep, the default) or taken back over the first step (take-back)"),
               std::map<std::string, StartOffsets>{{"keep", StartOffsets::keep}, {"take-back", StartOffsets::take_back}})
        ->needs(from_opt);
    out.push_back({sub, [=]() {
                     const Case c = settings->apply(load_case(*path));
                     PrdSettings s = PrdSettings::from_case(c);
                     if (*friction >= 0) {
                       s.sliding_check = true;
                       s.friction_angle = *friction;
                     }
                     if (!from->empty()) s.start = start_of(c, *from, *from_d, *offsets);
                     warn_lp_cost(c, "prd", 1e-6);
                     for (const std::string& line : idle_options(c.prd)) std::cerr << "prd: note: " << line << "\n";
                     RunProgress progress("prd", (s.start ? s.start->d : 0.0) + s.step * s.max_steps, 1.0, {}, path_unit(c));
                     const RunResult r = run_prd(c, s, {*dir, *quiet ? std::function<void(const RunResult&)>() : std::ref(progress)});
                     if (!*quiet || !located(r.status))
                       std::cerr << "prd: " << printable(c.name) << ": " << status_name(r.status) << (r.message.empty() ? "" : " (" + r.message + ")")
                                 << ", capacity " << r.capacity << " " << path_unit(c) << " after " << r.stable_steps << " steps, "
                                 << r.timing.total_s << " s (" << r.timing.lp_solves << " LPs); results in " << *dir << "\n";
                     if (r.sliding && r.sliding->any) {
                       std::cerr << "prd: sliding check: some admissible force state avoids sliding at every step for friction angles above "
                                 << r.sliding->required_friction_angle << " deg (the most demanding: d = " << r.sliding->d << " " << path_unit(c) << ", joint "
                                 << r.sliding->joint << ")\n";
                     }
                     report_held(r, path_unit(c));
                     if (*friction >= 0) {
                       // Two answers: where the dual's own forces need more friction than the
                       // angle, and where every admissible force state does (sliding is then
                       // certain, whatever the force distribution).
                       for (bool required : {false, true}) {
                         const auto e = first_sliding(c, r, *friction, required);
                         std::cerr << "prd: " << (required ? "every admissible force state" : "the dual force state") << " needs more than "
                                   << *friction << " deg of friction ";
                         if (e)
                           std::cerr << "first at step " << e->step << ", d = " << e->d << " " << path_unit(c) << ", joint " << e->blocks << " (" << e->angle << " deg)\n";
                         else
                           std::cerr << "at no step\n";
                       }
                     }
                     return exit_code(r.status);
                   }});
  }
  {
    auto* sub = app.add_subcommand("check", "Single PRD analysis: is the structure stable as it stands?");
    auto path = std::make_shared<std::string>();
    auto as_json = std::make_shared<bool>(false);
    auto settings = std::make_shared<CaseFlags>();  // the flags that set case options
    sub->add_option("case", *path, "Case file (JSON, masonry-case/1)")->required();
    sub->add_flag("--json", *as_json, "Print one JSON object (stable, forces, reactions)");
    settings->add(sub, &PrdOptions::contact_tolerance);
    auto step = std::make_shared<std::optional<double>>();
    sub->add_option("--step", *step,
                    "Instead: the run's first LP, the mechanism the support motion over this step (m, or rad where the supports only "
                    "turn) drives from the start, the potential energy it releases and the corners it opens (checked as the case's "
                    "motion.step)");
    // With --step, the corners the run holds closed (the case's and these) are held in its first LP.
    settings->add(sub, &PrdOptions::hold_closed)->needs("--step");
    out.push_back({sub, [=]() {
                     Case c = settings->apply(load_case(*path));
                     // The step as the case's own: one range and one refusal (a NaN or a step
                     // outside the scene's range named like a case file's).
                     if (*step) c = with_option(c, "motion.step", **step);
                     warn_lp_cost(c, "check", 1.2e-7, !*step);
                     if (*step) return print_first_step(c, c.motion.step, *as_json);
                     const PrdCheck k = prd_check(c, c.prd.contact_tolerance);
                     RunResult r;
                     r.method = method_name(Method::prd);
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
                     if (!k.stable) j["mechanism"] = mechanism_json(k.collapse, c);
                     if (*as_json) {
                       std::cout << j.dump(1) << "\n";
                     } else {
                       std::cout << printable(c.name) << ": " << (k.stable ? "stable" : "unstable (a collapse mechanism exists)") << "\n";
                     }
                     return 0;
                   }});
  }
}

}  // namespace masonry
