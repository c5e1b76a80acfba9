// The compiled half of `import masonry` (python/masonry/__init__.py is the other, README "From
// Python"): thin bindings over the libraries the command line uses. Cases cross as Case values
// (options through with_option, so the loader's validation), runs run through run_case (the one
// way the command line runs a case), results stay a RunResult with its Case (so save() writes
// what `masonry prd|dem --out` writes), studies run through their commands' library calls and
// come back as the JSON documents the commands write. Bad input raises MasonryError with the
// library's one-line message.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cases/generators.hpp"
#include "cases/parameters.hpp"
#include "cases/wall_fields.hpp"
#include "compare/compare.hpp"
#include "compare/report.hpp"
#include "model/case.hpp"
#include "model/io.hpp"
#include "model/method.hpp"
#include "model/names.hpp"
#include "model/options.hpp"
#include "model/results.hpp"
#include "runs/run.hpp"
#include "sweep/sweep.hpp"
#include "validate/validate.hpp"

namespace py = pybind11;

namespace masonry {

namespace {

// A finished (or interrupted) run: the results and the case they belong to.
struct PyResult {
  RunResult run;
  Case c;
};

// Thrown from a run's per-step callback to stop it (Ctrl-C, or an exception in the Python
// callback). Not a std::exception: the solvers turn those into a run stopped by "error", which is
// not what stopping from outside is.
struct Stop {};

// "35", "0.5": a number as the command line's labels write it (app/compare_commands.cpp).
std::string number_text(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

// A JSON document as Python objects, through Python's own json module: it crosses as text, as it
// crosses between the command line's files.
py::object from_json(const nlohmann::ordered_json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

// What a step's callback does, with the GIL held again: the progress callable, then Python's
// signal handlers (Ctrl-C raises KeyboardInterrupt there). Any Python error stops the run; the
// error is kept to raise once the run has returned.
class StepHook {
 public:
  explicit StepHook(py::object progress) : progress_(std::move(progress)) {}
  template <class Partial>
  void operator()(const Partial& keep) {
    py::gil_scoped_acquire gil;
    try {
      if (!progress_.is_none()) keep.call(progress_);
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    } catch (py::error_already_set& e) {
      error_.emplace(std::move(e));
      keep.save();
      throw Stop{};
    }
  }
  // With the GIL held: whether the run was stopped by KeyboardInterrupt (Ctrl-C); any other
  // Python error is raised again.
  bool interrupted() {
    if (!error_) return false;
    if (error_->matches(PyExc_KeyboardInterrupt)) {
      error_.reset();
      return true;
    }
    py::error_already_set e = std::move(*error_);
    error_.reset();
    throw e;
  }

 private:
  py::object progress_;
  std::optional<py::error_already_set> error_;
};

// Runs case `c` by method `m` as `masonry prd|dem --out DIR` does. Returns the result and whether
// Ctrl-C stopped it (then the result is the run as it stood after its last recorded step, status
// "running", and DIR holds those steps).
py::tuple run_one(const Case& c, const std::string& method, const std::string& dir, py::object progress) {
  const std::optional<Method> m = parse_method(method);
  if (!m) throw CaseError("method '" + printable(method) + "': prd or dem");
  PyResult out{{}, c};
  StepHook hook(std::move(progress));
  struct Partial {
    const RunResult& r;
    PyResult& out;
    void call(const py::object& f) const { f(r.steps.empty() ? 0.0 : r.steps.back().d, static_cast<int>(r.steps.size())); }
    void save() const { out.run = r; }
  };
  bool stopped = false;
  {
    py::gil_scoped_release release;
    try {
      out.run = run_case(c, *m, {dir, [&](const RunResult& r) { hook(Partial{r, out}); }});
    } catch (const Stop&) {
      stopped = true;
      // Every recorded step on disk, not only those the writing rule had written by then.
      if (!dir.empty()) write_results(dir, out.run, c);
    }
  }
  const bool interrupted = stopped && hook.interrupted();
  return py::make_tuple(out, interrupted);
}

// The records' d (m, or rad where the supports only turn).
py::array_t<double> d_array(const RunResult& r) {
  py::array_t<double> a(static_cast<py::ssize_t>(r.steps.size()));
  auto v = a.mutable_unchecked<1>();
  for (size_t k = 0; k < r.steps.size(); ++k) v(k) = r.steps[k].d;
  return a;
}

std::vector<int> support_blocks(const Case& c) {
  std::vector<int> s;
  for (size_t k = 0; k < c.blocks.size(); ++k)
    if (c.blocks[k].support) s.push_back(static_cast<int>(k));
  return s;
}

// (n_steps, n_supports, 3): Fx, Fy (N) and the moment (N m) each support gives the structure, in
// the case's order of support blocks; NaN where a record gives none.
py::array_t<double> reactions_array(const PyResult& p) {
  const std::vector<int> sup = support_blocks(p.c);
  std::map<std::string, size_t> at;
  for (size_t k = 0; k < sup.size(); ++k) at[p.c.blocks[sup[k]].id] = k;
  py::array_t<double> a({p.run.steps.size(), sup.size(), size_t{3}});
  auto v = a.mutable_unchecked<3>();
  for (size_t s = 0; s < p.run.steps.size(); ++s) {
    for (size_t k = 0; k < sup.size(); ++k)
      for (int q = 0; q < 3; ++q) v(s, k, q) = NAN;
    for (const Reaction& rc : p.run.steps[s].reactions) {
      const auto it = at.find(rc.support);
      if (it == at.end()) continue;
      v(s, it->second, 0) = rc.force.x();
      v(s, it->second, 1) = rc.force.y();
      v(s, it->second, 2) = rc.moment;
    }
  }
  return a;
}

// (n_steps, n_blocks, 3): every block's centroid x, y (m) and rotation since the start (rad), in
// case order, supports included; NaN where a record gives no poses.
py::array_t<double> poses_array(const PyResult& p) {
  const size_t n = p.c.blocks.size();
  py::array_t<double> a({p.run.steps.size(), n, size_t{3}});
  auto v = a.mutable_unchecked<3>();
  for (size_t s = 0; s < p.run.steps.size(); ++s) {
    const std::vector<Pose>& poses = p.run.steps[s].poses;
    for (size_t b = 0; b < n; ++b) {
      const bool given = poses.size() == n;
      v(s, b, 0) = given ? poses[b].x : NAN;
      v(s, b, 1) = given ? poses[b].y : NAN;
      v(s, b, 2) = given ? poses[b].angle : NAN;
    }
  }
  return a;
}

py::list open_corners_list(const RunResult& r) {
  py::list steps;
  for (const StepRecord& s : r.steps) {
    py::list open;
    for (const OpenCorner& o : s.open_corners) open.append(py::make_tuple(o.joint, o.corner == 0 ? "A" : "B", o.gap));
    steps.append(open);
  }
  return steps;
}

py::list joints_list(const PyResult& p) {
  py::list joints;
  for (const JointInfo& j : p.run.joints) joints.append(py::make_tuple(p.c.blocks.at(j.i).id, p.c.blocks.at(j.j).id));
  return joints;
}

py::array_t<bool> settled_array(const RunResult& r) {
  py::array_t<bool> a(static_cast<py::ssize_t>(r.steps.size()));
  auto v = a.mutable_unchecked<1>();
  for (size_t k = 0; k < r.steps.size(); ++k) v(k) = is_equilibrium(r, r.steps[k]);
  return a;
}

// The case's masonry-case/1 document with every option that has a value, as case[key] reads it:
// the case writer leaves out the options that hold their unset value (prd.hold_closed [],
// dem.hold_damping "local"), and case[key] = [] then read back as a KeyError. An optional
// number left absent (dem.kn, derived from the case when a run starts) stays absent.
std::string options_json(const Case& c) {
  nlohmann::ordered_json doc = nlohmann::ordered_json::parse(case_to_json(c));
  doc.update(valued_options(c));
  doc["motion"].update(valued_options(c.motion));
  doc["prd"].update(valued_options(c.prd));
  doc["dem"].update(valued_options(c.dem));
  return doc.dump();
}

py::list blocks_list(const Case& c) {
  py::list out;
  for (const Block& b : c.blocks) {
    py::array_t<double> v({b.vertices.size(), size_t{2}});
    auto w = v.mutable_unchecked<2>();
    for (size_t k = 0; k < b.vertices.size(); ++k) w(k, 0) = b.vertices[k].x(), w(k, 1) = b.vertices[k].y();
    py::dict d;
    d["id"] = b.id;
    d["vertices"] = v;
    // A support's density is read (and range-checked) but used by neither method, its motion
    // being given, and the case writer leaves it out: given here, it read 2500 until any change
    // went through the writer and made it 0. A support has none, as in the file the case writes.
    if (!b.support) d["density"] = b.density;
    d["depth"] = b.depth;
    d["support"] = b.support;
    out.append(d);
  }
  return out;
}

// The comparison of two runs of case c: `masonry compare --runs A B [--tolerances FILE]`'s
// comparison.json (without PRD on the DEM's deformed configuration, which reruns PRD), and with
// `dir` its report too. A run of another case is refused as the command line refuses it.
py::object compare_two(const Case& c, const PyResult& a, const PyResult& b, const std::string& tolerances, const std::string& source,
                       const std::string& dir) {
  std::optional<Tolerances> tol;
  if (!tolerances.empty()) tol = parse_tolerances(tolerances, source);
  const auto label = [](const RunResult& r) {
    if (known_method(r) == Method::dem && r.settings.contains("friction_angle") && r.settings["friction_angle"].is_number())
      return "DEM phi=" + number_text(r.settings["friction_angle"].get<double>());
    return method_label(r);
  };
  // Each run as `masonry compare --runs` reads it: its results.json read against case c
  // (load_results), whose checks refuse a run of another case (its blocks, supports or joints are
  // not c's). Without them a tilting block's run in rad was compared with an arch's in m, and two
  // runs were judged against a case they did not run.
  const auto read = [&](const PyResult& p, const std::string& which) {
    return parse_results(to_json(p.run, p.c).dump(1), c, "run " + which + " (" + p.run.method + " of case '" + printable(p.c.name) + "')");
  };
  const RunResult ra = read(a, "a"), rb = read(b, "b");
  std::string la = label(ra), lb = label(rb);
  if (la == lb) la += " a", lb += " b";
  const Report rep = make_report(c, {{la, &ra, ""}, {lb, &rb, ""}}, tol ? &*tol : nullptr);
  if (!dir.empty()) write_report(dir, rep);
  nlohmann::ordered_json j = report_json(rep);
  j["pass"] = rep.violations[0].empty();
  j["violations"] = rep.violations[0];
  return from_json(j);
}

// `masonry validate [--quick] [--only NAME...]` on the built-in catalogue: the rows its --json
// file holds. Ctrl-C between rows stops it; the rows finished so far come back with the flag.
py::tuple validate_builtin(bool quick, const std::vector<std::string>& only) {
  const Catalogue cat = builtin_catalogue();
  const std::vector<const Benchmark*> todo = chosen_benchmarks(cat, quick, only);
  std::vector<ValidationRow> rows;
  RunCache cache;
  StepHook hook{py::none()};
  struct Partial {
    void call(const py::object&) const {}
    void save() const {}
  };
  bool stopped = false;
  {
    py::gil_scoped_release release;
    try {
      for (const Benchmark* b : todo) {
        const auto part = run_benchmark(cat, *b, cache, [&](const ValidationRow&) { hook(Partial{}); });
        rows.insert(rows.end(), part.begin(), part.end());
      }
    } catch (const Stop&) {
      stopped = true;
    }
  }
  const bool interrupted = stopped && hook.interrupted();
  return py::make_tuple(from_json(validation_json(cat, rows)), interrupted);
}

// `masonry sweep SPEC --out DIR --jobs N --quiet`: writes what the command writes and returns its
// sweep.json and sensitivity.json.
py::dict run_sweep_file(const std::string& spec, const std::string& dir, int jobs, bool restart, bool keep_runs, bool quiet) {
  SweepOptions o;
  o.out_dir = dir;
  o.jobs = jobs;
  o.restart = restart;
  o.keep_runs = keep_runs;
  o.quiet = quiet;
  o.command = "masonry sweep " + spec + " --out " + dir + (keep_runs ? " --keep-runs" : "");
  {
    py::gil_scoped_release release;
    run_sweep(read_sweep_input(spec), o);
  }
  py::dict out;
  const auto read = [&](const std::string& name) {
    const std::optional<std::string> text = read_text(dir + "/" + name);
    if (!text) throw std::runtime_error(dir + "/" + name + ": not written by the sweep");
    return py::module_::import("json").attr("loads")(*text);
  };
  out["sweep"] = read("sweep.json");
  out["sensitivity"] = read("sensitivity.json");
  return out;
}

// The case `masonry cases NAME --out FILE` writes, as the loader reads that file back. The
// command line refuses to write a case its loader would refuse (app/cases_commands.cpp, emit): a
// generator checks its geometry, not the loader's ranges, so radius=1e6 or step=10 built a case
// that ran here and that no case file can hold. Through the loader, the same refusal with the
// same message (the source "generator NAME" where the command line names its file), and the
// case the command line's file gives. `masonry cases wall` has parameters that are words and
// lists as well as numbers: a table of its own (cases/wall_fields.hpp), read as the command line
// reads it.
Case generated_case(const std::string& name, const nlohmann::json& values) {
  if (name != "wall" && !find_case_generator(name)) {
    // As `masonry cases wal` does: the nearest name, by the command line's rule (model/names.hpp).
    std::vector<std::string> names;
    for (const CaseGenerator& g : case_generators()) names.push_back(g.name);
    names.push_back("wall");
    throw CaseError("no case generator '" + printable(name) + "'" + did_you_mean(name, names) + " (masonry.generators(), and 'wall')");
  }
  const Case c = name == "wall" ? brick_wall(wall_parameters(values, "generate('wall')")) : generate_case(name, values);
  return parse_case(case_to_json(c), "generator " + name);
}

py::list generator_list() {
  py::list out;
  for (const CaseGenerator& g : case_generators()) {
    py::list params;
    for (const GeneratorParameter& p : g.parameters) {
      py::dict d;
      d["name"] = p.name;
      d["kind"] = p.kind == ParameterKind::number ? "number" : p.kind == ParameterKind::integer ? "integer" : "flag";
      d["help"] = parameter_help(p);
      d["default"] = p.kind == ParameterKind::flag      ? py::object(py::bool_(p.value != 0))
                     : p.kind == ParameterKind::integer ? py::object(py::int_(static_cast<long long>(p.value)))
                                                        : py::object(py::float_(p.value));
      params.append(d);
    }
    py::dict d;
    d["name"] = g.name;
    d["summary"] = g.summary;
    d["parameters"] = params;
    out.append(d);
  }
  return out;
}

}  // namespace

}  // namespace masonry

PYBIND11_MODULE(_masonry, m) {
  using namespace masonry;
  m.doc() = "masonry's compiled core; use the package masonry (README, \"From Python\")";
  static py::exception<CaseError> error(m, "MasonryError", PyExc_Exception);
  // Every one-line message of bad input the libraries throw (CaseError, SweepError, a results or
  // tolerances file the reader refuses) becomes MasonryError.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (cast_error, ...): its translator
    } catch (const std::runtime_error& e) {
      error(e.what());
    }
  });

  // Every CaseData is one the loader made (parse_case, load_case, generate, with_option; a
  // Result's is the case it ran), and it has no constructor of its own: a run given no settings
  // runs it as it is, so a case the loader would refuse must never become one.
  py::class_<Case>(m, "CaseData", "A case as the loader validated it (masonry.Case wraps it)")
      .def_readonly("name", &Case::name)
      .def_readonly("source", &Case::source)
      .def("blocks", &blocks_list)
      .def("to_json", &case_to_json)
      .def("options_json", &options_json)
      .def("with_option", [](const Case& c, const std::string& key,
                             const std::string& value_json) { return with_option(c, key, nlohmann::json::parse(value_json)); })
      .def("d_unit", &path_unit);
  m.def("parse_case", &parse_case, py::arg("text"), py::arg("source"));
  m.def("load_case", &load_case, py::arg("path"));
  m.def("generate", [](const std::string& name, const std::string& values_json) { return generated_case(name, nlohmann::json::parse(values_json)); });
  m.def("generators", &generator_list);

  py::class_<PyResult>(m, "Result", "One run's results and its case (masonry.run_prd, masonry.run_dem)")
      .def_property_readonly("method", [](const PyResult& p) { return p.run.method; })
      .def_property_readonly("case_name", [](const PyResult& p) { return p.run.case_name; })
      .def_property_readonly("capacity", [](const PyResult& p) { return p.run.capacity; })
      .def_property_readonly("d_unit", [](const PyResult& p) { return path_unit(p.c); })
      .def_property_readonly("status", [](const PyResult& p) { return std::string(status_name(p.run.status)); })
      .def_property_readonly("located", [](const PyResult& p) { return located(p.run.status); })
      .def_property_readonly("message", [](const PyResult& p) { return p.run.message; })
      .def_property_readonly("stable_steps", [](const PyResult& p) { return p.run.stable_steps; })
      .def_property_readonly("total_weight", [](const PyResult& p) { return p.run.total_weight; })
      .def_property_readonly("time_s", [](const PyResult& p) { return p.run.timing.total_s; })
      .def_property_readonly("d", [](const PyResult& p) { return d_array(p.run); })
      .def_property_readonly("settled", [](const PyResult& p) { return settled_array(p.run); })
      .def_property_readonly("supports",
                             [](const PyResult& p) {
                               std::vector<std::string> ids;
                               for (int k : support_blocks(p.c)) ids.push_back(p.c.blocks[k].id);
                               return ids;
                             })
      .def_property_readonly("blocks",
                             [](const PyResult& p) {
                               std::vector<std::string> ids;
                               for (const Block& b : p.c.blocks) ids.push_back(b.id);
                               return ids;
                             })
      .def_property_readonly("reactions", &reactions_array)
      .def_property_readonly("poses", &poses_array)
      .def_property_readonly("joints", &joints_list)
      .def_property_readonly("open_corners", [](const PyResult& p) { return open_corners_list(p.run); })
      .def_property_readonly("settings", [](const PyResult& p) { return from_json(p.run.settings); })
      .def_property_readonly("_case", [](const PyResult& p) { return p.c; })
      .def("to_json", [](const PyResult& p) { return to_json(p.run, p.c).dump(1) + "\n"; })
      .def(
          "save", [](const PyResult& p, const std::string& dir) { write_results(dir, p.run, p.c); }, py::arg("dir"))
      .def("__repr__", [](const PyResult& p) {
        return "<masonry.Result " + p.run.method + " " + p.run.case_name + ": " + status_name(p.run.status) + ", capacity " +
               py::repr(py::float_(p.run.capacity)).cast<std::string>() + " " + path_unit(p.c) + ">";
      });
  m.def("load_results", [](const std::string& path, const Case& c) { return PyResult{load_results(path, c), c}; });

  m.def("run", &run_one, py::arg("case"), py::arg("method"), py::arg("out"), py::arg("progress"));
  m.def("compare", &compare_two);
  m.def("validate", &validate_builtin);
  m.def("sweep", &run_sweep_file);
}
