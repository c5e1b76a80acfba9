#!/usr/bin/env python3
"""Every file masonry writes, and every such file checked in, against the published formats
(schemas/*.schema.json, JSON Schema draft 2020-12), with Debian's python3-jsonschema.

    check_schemas.py --exe build/app/masonry --source . --scratch DIR

Checked: the eight schemas themselves; what masonry writes, freshly made here (case files from
every generator, a DXF import, PRD and DEM results with their optional parts, a comparison, a
comparison with an outside solver's minimal results, the sweep.json and sensitivity.json of a
PRD grid with a failed run, of a PRD Latin hypercube and of a small PRD and DEM grid, validation
rows of both methods and of the example outside solver, its errors and rows that do not apply);
the files checked in (reports/**/results.json and comparison.json, every other reports/**/*.json
by its format, cases/*.json, the built-in catalogue and its inline cases, the sweep files); the
JSON examples of the READMEs; the example solver's results. That the fresh outputs reach the
writers' branches the schemas describe (a failed sweep run, an option PRD ignores, a solver
error, a row that does not apply). And that each schema refuses what the readers refuse, and
each output schema what its writer never writes (a test that cannot fail proves nothing). Exit
status 1 with one line per file that does not validate.
"""
import argparse
import glob
import json
import lzma
import os
import re
import shlex
import shutil
import subprocess
import sys

try:
    import jsonschema
except ImportError:
    print("check_schemas.py: python3-jsonschema is not installed (bash scripts/install-deps.sh)", file=sys.stderr)
    sys.exit(1)

FORMATS = ["case", "results", "comparison", "catalogue", "sweep", "sweep-results", "sensitivity", "validation"]
problems = []
checked = {f: 0 for f in FORMATS}


def load(path):
    with open(path) as f:
        return json.load(f)


def check(fmt, doc, where):
    errors = sorted(VALIDATORS[fmt].iter_errors(doc), key=lambda e: list(e.absolute_path))
    checked[fmt] += 1
    for e in errors[:3]:
        problems.append(f"{where}: masonry-{fmt}/1: {e.json_path}: {e.message[:200]}")


def refuses(fmt, doc, what):
    if not list(VALIDATORS[fmt].iter_errors(doc)):
        problems.append(f"masonry-{fmt}/1 schema accepts {what}")


def run(*args, ok=(0,), env=None):
    p = subprocess.run(list(args), capture_output=True, text=True, env=env)
    if p.returncode not in ok:
        problems.append(f"{' '.join(args)}: exit {p.returncode}: {p.stderr.strip()[-300:]}")
    return p


def expect(test, what):
    """The fresh outputs must reach the writer's branch the schema describes (else a schema too
    loose there would never be caught); `test` reads them (a document the schema refused may
    lack what it reads: then it is not covered either)."""
    try:
        ok = test()
    except (KeyError, IndexError, TypeError, AttributeError):
        ok = False
    if not ok:
        problems.append(f"not covered: {what}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--scratch", required=True)
    a = ap.parse_args()
    src, exe, tmp = a.source, a.exe, a.scratch
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)

    global VALIDATORS
    VALIDATORS = {}
    for fmt in FORMATS:
        schema = load(os.path.join(src, "schemas", f"masonry-{fmt}.schema.json"))
        jsonschema.Draft202012Validator.check_schema(schema)
        VALIDATORS[fmt] = jsonschema.Draft202012Validator(schema)

    # Checked in.
    for path in sorted(glob.glob(os.path.join(src, "reports", "**", "results.json"), recursive=True)):
        check("results", load(path), path)
    # The runs kept compressed (reports/README.md): the same format.
    for path in sorted(glob.glob(os.path.join(src, "reports", "**", "results.json.xz"), recursive=True)):
        with lzma.open(path, "rt") as f:
            check("results", json.load(f), path)
    for path in sorted(glob.glob(os.path.join(src, "reports", "**", "comparison.json"), recursive=True)):
        check("comparison", load(path), path)
    # Every other JSON file in reports/ (sweep.json, sensitivity.json, validation.json, the sweep
    # files) by its format; formats without a schema yet are named in the last line.
    unpublished = {}
    for path in sorted(glob.glob(os.path.join(src, "reports", "**", "*.json"), recursive=True)):
        if os.path.basename(path) in ("results.json", "comparison.json"):
            continue
        doc = load(path)
        fmt = doc.get("format", "") if isinstance(doc, dict) else ""
        m = re.fullmatch(r"masonry-([\w-]+)/1", fmt)
        if m and m.group(1) in VALIDATORS:
            check(m.group(1), doc, path)
        else:
            unpublished[fmt or "(no format)"] = unpublished.get(fmt or "(no format)", 0) + 1
    for path in sorted(glob.glob(os.path.join(src, "cases", "**", "*.json"), recursive=True)):
        doc = load(path)
        fmt = doc.get("format", "")
        if fmt == "masonry-case/1":
            check("case", doc, path)
        elif fmt == "masonry-sweep/1":
            check("sweep", doc, path)
    catalogue = os.path.join(src, "validate", "catalogue.json")
    check("catalogue", load(catalogue), catalogue)
    for b in load(catalogue)["benchmarks"]:
        if "inline" in b["case"]:
            check("case", b["case"]["inline"], f"{catalogue}: {b['name']}: case.inline")
    # The READMEs' examples, by their format.
    for readme in [os.path.join(src, "README.md")] + sorted(glob.glob(os.path.join(src, "*", "README.md"))):
        with open(readme) as f:
            text = f.read()
        for k, block in enumerate(re.findall(r"```json\n(.*?)```", text, re.S)):
            try:
                doc = json.loads(block)
            except ValueError:
                continue  # a fragment
            m = re.fullmatch(r"masonry-([\w-]+)/1", doc.get("format", "") if isinstance(doc, dict) else "")
            if m and m.group(1) in VALIDATORS:
                check(m.group(1), doc, f"{readme}: JSON example {k + 1}")

    # Written by masonry, now.
    listing = run(exe, "cases", "--list").stdout
    generators = re.findall(r"^  (\S+)$", listing, re.M)
    if len(generators) < 3:
        problems.append(f"masonry cases --list: no generators found in {listing!r}")
    for name in generators:
        out = os.path.join(tmp, f"{name}.json")
        run(exe, "cases", name, "--out", out)
        if os.path.exists(out):
            check("case", load(out), out)
    drawings = os.path.join(src, "cases", "drawings")
    imported = os.path.join(tmp, "imported.json")
    run(exe, "cases", "import", os.path.join(drawings, "tilting-block.dxf"), "--layers", os.path.join(drawings, "layers.json"),
        "--merge", os.path.join(drawings, "tilting-block.fragment.json"), "--out", imported)
    if os.path.exists(imported):
        check("case", load(imported), imported)
    block = os.path.join(src, "cases", "tilting-block.json")
    runs = {
        "prd": ["prd", block],
        "prd-adaptive-sliding": ["prd", block, "--adaptive", "--sliding"],
        "prd-held": ["prd", block, "--hold", "ground/block:B"],
        "dem": ["dem", block, "--quiet"],
        "dem-stands": ["dem", block, "--quiet", "--max-steps", "0"],
    }
    # A DEM run whose bracket closes on a creep that settles when held on (settled_creeps, and
    # trials marked followed): DemBracket.AHingePassingToAnotherJointIsNotALimitPoint's arch, its
    # holds capped at 1 s.
    passing = os.path.join(src, "tests", "dem", "passing-hinge-arch.json")
    check("case", load(passing), passing)
    runs["dem-passing"] = ["dem", passing, "--quiet", "--hold-time", "1"]
    # A DEM run that lands a snap through (settled_snaps: DemBracket.ASnapLongerThanTheDriftLimit-
    # LandsAndTheRunGoesOn's arch and drift limit), and PRD on the same path: their comparison
    # lists both runs' jumps.
    arch = os.path.join(src, "cases", "pointed-arch.json")
    runs["prd-arch"] = ["prd", arch, "--max-steps", "110"]
    runs["dem-snap"] = ["dem", arch, "--quiet", "--collapse-drift", "0.005", "--max-steps", "110"]
    for name, args in runs.items():
        out = os.path.join(tmp, name)
        run(exe, *args, "--out", out)
        path = os.path.join(out, "results.json")
        if os.path.exists(path):
            check("results", load(path), path)
            if name == "dem-passing":
                expect(lambda: load(path).get("settled_creeps"), "a creep that settled when held on (dem-passing)")
            if name == "dem-snap":
                expect(lambda: load(path).get("settled_snaps"), "a snap through that landed (dem-snap)")
    tolerances = os.path.join(tmp, "tolerances.json")
    with open(tolerances, "w") as f:
        json.dump({"capacity": 0.05, "capacity_abs": 0.02, "thrust": 0.1, "hinges": True}, f)
    outside = os.path.join(tmp, "outside")
    run(sys.executable, os.path.join(src, "examples", "toppling_solver.py"), block, outside)
    check("results", load(os.path.join(outside, "results.json")), "examples/toppling_solver.py's results")
    unsupported = os.path.join(tmp, "unsupported")
    run(sys.executable, os.path.join(src, "examples", "toppling_solver.py"), os.path.join(src, "cases", "pointed-arch.json"), unsupported)
    check("results", load(os.path.join(unsupported, "results.json")), "examples/toppling_solver.py's error results")
    for name, second in [("compare", "dem"), ("compare-outside", "outside")]:
        out = os.path.join(tmp, name)
        run(exe, "compare", block, "--out", out, "--quiet", "--tolerances", tolerances, "--runs", os.path.join(tmp, "prd"),
            os.path.join(tmp, second), ok=(0, 1))
        path = os.path.join(out, "comparison.json")
        if os.path.exists(path):
            check("comparison", load(path), path)
    snaps = os.path.join(tmp, "compare-snap")
    run(exe, "compare", arch, "--out", snaps, "--quiet", "--frames", "2", "--runs", os.path.join(tmp, "prd-arch"), os.path.join(tmp, "dem-snap"))
    path = os.path.join(snaps, "comparison.json")
    if os.path.exists(path):
        check("comparison", load(path), path)
        expect(lambda: load(path)["comparisons"][0]["jumps"]["a"] and load(path)["comparisons"][0]["jumps"]["b"],
               "both runs' jumps (compare-snap)")
    # A comparison whose DEM run is a damped rerun (runs[].damped_rerun): the zoo's jack arch scaled
    # by 0.05, whose undamped DEM slides its skewback where PRD's forces stay within friction
    # (tests/app/compare_rerun_test.cpp).
    jack_path = os.path.join(src, "reports", "unseen-structures", "cases", "jack-scale-0.05.json")
    rerun = os.path.join(tmp, "compare-rerun")
    run(exe, "compare", jack_path, "--out", rerun, "--quiet", "--frames", "2")
    path = os.path.join(rerun, "comparison.json")
    if os.path.exists(path):
        check("comparison", load(path), path)
        expect(lambda: load(path)["runs"][1].get("damped_rerun"), "a damped rerun (compare-rerun)")

    # Sweeps (PRD-only but one, few runs): sweep.json and sensitivity.json of a grid with a failed
    # run (thickness < 0: the generator refuses it) and a DEM option PRD ignores, of a Latin
    # hypercube (base point, one-at-a-time lines, samples), and of a grid with the DEM (the
    # tilting block: diff_prd, the friction angle's boundary, prd_dem).
    arch = {"generator": "circular-arch", "parameters": {"radius": 1, "voussoirs": 10, "step": 0.002}}
    specs = {
        "sweep-grid": {"case": arch, "methods": ["prd"],
                       "vary": {"generator.thickness": [-0.05, 0.09, 0.14, 0.18], "dem.friction_angle": [30, 40]}},
        "sweep-sampled": {"case": arch, "methods": ["prd"],
                          "sample": {"count": 6, "seed": 7, "one_at_a_time": 2,
                                     "ranges": {"generator.thickness": [0.13, 0.18], "generator.radius": [0.9, 1.1]}}},
        "sweep-dem": {"case": os.path.abspath(block), "methods": ["prd", "dem"],
                      "vary": {"motion.step": [0.017453292519943295], "dem.friction_angle": [15, 35]}},
    }
    sweeps = {}
    for name, spec in specs.items():
        spec_path = os.path.join(tmp, f"{name}.json")
        with open(spec_path, "w") as f:
            json.dump(dict({"format": "masonry-sweep/1", "name": name}, **spec), f)
        check("sweep", load(spec_path), spec_path)
        out = os.path.join(tmp, name)
        run(exe, "sweep", spec_path, "--out", out, "--quiet", "--jobs", "1", ok=(0, 1))
        docs = {}
        for fmt, file in [("sweep-results", "sweep.json"), ("sensitivity", "sensitivity.json")]:
            path = os.path.join(out, file)
            if os.path.exists(path):
                docs[fmt] = load(path)
                check(fmt, docs[fmt], path)
            else:
                problems.append(f"masonry sweep {spec_path}: wrote no {file}")
        sweeps[name] = docs
    grid, sampled, dem = (sweeps[n] for n in specs)
    if "sweep-results" in grid and "sensitivity" in grid:
        expect(lambda: any(r["stopped"] == "error" and r["capacity"] is None for r in grid["sweep-results"]["runs"]), "a failed sweep run")
        expect(lambda: grid["sweep-results"]["failed"] >= 1 and grid["sweep-results"]["curves"], "a grid's curves beside a failed run")
        expect(lambda: grid["sensitivity"]["prd_ignores"] and grid["sensitivity"]["note"], "a PRD-only sweep over a DEM option")
        expect(lambda: {"ignored": True} in grid["sensitivity"]["methods"]["prd"]["parameters"].values(), "an option PRD ignores")
        expect(lambda: grid["sensitivity"]["methods"]["prd"]["zero_capacity"] >= 1, "a run with capacity 0")
    if "sweep-results" in sampled and "sensitivity" in sampled:
        expect(lambda: {r["point"] for r in sampled["sweep-results"]["runs"]} == {"base", "one-at-a-time", "sample"}, "a sampled design's points")
        expect(lambda: sampled["sensitivity"]["methods"]["prd"]["r2"] is not None
               and set(sampled["sensitivity"]["methods"]["prd"]["percentiles"]) == {"5", "50", "95"}, "a sampled sweep's regression and percentiles")
    if "sweep-results" in dem and "sensitivity" in dem:
        expect(lambda: any(r["diff_prd"] is not None for r in dem["sweep-results"]["runs"]), "a DEM run against its PRD run")
        expect(lambda: any(c["boundary"] is not None for c in dem["sweep-results"]["curves"]), "a friction angle boundary")
        expect(lambda: dem["sensitivity"]["prd_dem"], "PRD against DEM per point")

    # Validation: both methods on fast benchmarks (a capacity in rad, a reaction, a threshold,
    # stands, the duality gap, the least friction angle); the example outside solver as the
    # README runs it (pass, not applicable, and a case outside its model: a solver error); and
    # the solver judged as a method a benchmark does not name (no tolerance_why).
    solver = shlex.join([sys.executable, os.path.join(src, "examples", "toppling_solver.py")]) + " {case} {out}"
    solver_env = dict(os.environ, TMPDIR=tmp)  # the solver's kept runs go to the scratch directory
    validations = {
        "validation": ["--only", "block-topples", "block-reaction", "block-least-friction", "milankovitch-n10", "arch-stands", "duality-pointed-arch"],
        "validation-solver": ["--solver", solver, "--solver-name", "toppling-py", "--only", "block-topples", "block-reaction",
                              "block-least-friction", "pointed-arch-test"],
        "validation-solver-as-dem": ["--solver", solver, "--solver-name", "toppling-py", "--solver-as", "dem", "--only", "block-least-friction"],
    }
    rows, validation = [], None
    for name, args in validations.items():
        path = os.path.join(tmp, f"{name}.json")
        run(exe, "validate", *args, "--json", path, "--quiet", ok=(0, 1), env=solver_env)
        if os.path.exists(path):
            doc = load(path)
            check("validation", doc, path)
            rows += doc.get("rows", []) if isinstance(doc, dict) else []
            if name == "validation":
                validation = doc
        else:
            problems.append(f"masonry validate {' '.join(args)}: wrote no {path}")
    expect(lambda: any(r["unit"] == "rad" and r["quantity"] == "capacity" for r in rows), "a capacity in rad")
    expect(lambda: any(r["method"] == "toppling-py" and r["pass"] for r in rows), "an outside solver's row that passes")
    expect(lambda: any(r["solver_error"] for r in rows), "an outside solver's error")
    expect(lambda: any(not r["applicable"] and "tolerance_why" in r for r in rows), "a row that does not apply")
    expect(lambda: any(not r["applicable"] and "tolerance_why" not in r for r in rows), "a solver judged as a method the benchmark does not name")

    # Each schema refuses what its reader refuses.
    minimal = {"format": "masonry-results/1", "method": "m", "case": "c", "capacity": 0.0, "stopped": "collapse", "steps": [{"step": 0, "d": 0.0}]}
    check("results", minimal, "the minimal results")
    refuses("results", {k: v for k, v in minimal.items() if k != "capacity"}, "results without a capacity")
    refuses("results", dict(minimal, stopped="xyz"), "stopped \"xyz\"")
    refuses("results", dict(minimal, capacity=-5), "a negative capacity")
    refuses("results", dict(minimal, capcity=1), "an unknown field")
    refuses("results", dict(minimal, steps=[{"step": 0}]), "a step without d")
    refuses("results", dict(minimal, steps=[{"step": 0, "d": 0, "cycles": 3}]), "a DEM hold field without hold_end")
    case = load(block)
    refuses("case", dict(case, colour="red"), "an unknown field")
    refuses("case", {k: v for k, v in case.items() if k != "format"}, "a case without its format")
    refuses("case", dict(case, blocks=[{"id": "b", "vertices": [[0, 0], [1, 0], [1, 1]]}]), "a free block without density")
    for sep in "/:":
        refuses("case", dict(case, blocks=[dict(case["blocks"][0], id="a" + sep + "b")] + case["blocks"][1:]), "an id holding '" + sep + "'")
    # hold_closed: a corner as corner_name writes it (the loader's is_joint_corner refuses these too)
    for corner in ("a/b/c:A", "a:x/b:A", "a/b:c:A", "a/b:A0", "a/b:B13", "a/b:a"):
        refuses("case", dict(case, prd=dict(case.get("prd", {}), hold_closed=[corner])), "hold_closed " + corner)
    cat = load(catalogue)
    bad = json.loads(json.dumps(cat))
    del bad["benchmarks"][0]["methods"]["prd"]["tolerance"]["why"]
    refuses("catalogue", bad, "a tolerance without its argument")
    refuses("sweep", {"case": "x.json", "vary": {"gravity": [9.81]}}, "a sweep without its format")
    refuses("comparison", {"format": "masonry-comparison/1", "case": "c"}, "a comparison without runs")
    # The output schemas refuse what their writers never write.
    if grid.get("sweep-results", {}).get("runs"):
        doc = grid["sweep-results"]
        failed_run = next((r for r in doc["runs"] if r["stopped"] == "error"), doc["runs"][0])
        refuses("sweep-results", dict(doc, format="masonry-sweep/1"), "a sweep file's format")
        refuses("sweep-results", {k: v for k, v in doc.items() if k != "runs"}, "sweep results without runs")
        refuses("sweep-results", dict(doc, units="SI: capacity in mm"), "a capacity in mm")
        refuses("sweep-results", dict(doc, runs=[dict(doc["runs"][0], stopped="running")]), "a sweep run still running")
        refuses("sweep-results", dict(doc, runs=[dict(failed_run, capacity=0.01)]), "a failed sweep run with a capacity")
        refuses("sweep-results", dict(doc, runs=[dict(doc["runs"][0], diff_prd=0.1)]), "a PRD run with a difference from PRD")
        refuses("sweep-results", dict(doc, runs=[dict(doc["runs"][0], point="sample")]), "a sample without its number")
        refuses("sweep-results", dict(doc, runs=[{k: v for k, v in doc["runs"][0].items() if k != "hinges"}]), "a run without hinges")
        refuses("sweep-results", dict(doc, sweep_time=1), "an unknown field")
    if grid.get("sensitivity", {}).get("methods", {}).get("prd") and sampled.get("sensitivity", {}).get("methods", {}).get("prd"):
        doc = grid["sensitivity"]
        refuses("sensitivity", dict(doc, format="masonry-sweep-results/1"), "sweep results' format")
        refuses("sensitivity", {k: v for k, v in doc.items() if k != "methods"}, "a sensitivity without methods")
        refuses("sensitivity", dict(doc, methods={"prd": dict(doc["methods"]["prd"], r2=0.5)}), "a grid's R²")
        refuses("sensitivity", dict(doc, methods={"fem": doc["methods"]["prd"]}), "an unknown method")
        refuses("sensitivity", dict(doc, methods={"prd": dict(doc["methods"]["prd"], parameters={"x": {"ignored": False}})}), "ignored false")
        prd = sampled["sensitivity"]["methods"]["prd"]
        refuses("sensitivity", dict(sampled["sensitivity"], methods={"prd": {k: v for k, v in prd.items() if k != "percentiles"}}),
                "a sampled sweep without percentiles")
        refuses("sensitivity", dict(doc, design={"kind": "latin-hypercube"}), "a sampled design without its ranges")
    row = next((r for r in rows if r["pass"]), None)
    if validation and row:
        refuses("validation", dict(validation, format="masonry-catalogue/1"), "a catalogue's format")
        refuses("validation", {k: v for k, v in validation.items() if k != "rows"}, "a validation without rows")
        refuses("validation", dict(validation, rows=[{k: v for k, v in row.items() if k != "pass"}]), "a row without pass")
        refuses("validation", dict(validation, rows=[dict(row, applicable=False)]), "a row that passes and does not apply")
        refuses("validation", dict(validation, rows=[dict(row, obtained=None)]), "a row that passes without a number")
        refuses("validation", dict(validation, rows=[dict(row, quantity="capacity", unit="N")]), "a capacity in N")
        refuses("validation", dict(validation, rows=[dict(row, judged_as="toppling-py")]), "a row judged as no method")
        # A threshold is in its parameter's unit: every unit an option has (`masonry options
        # --markdown`, the unit column) is one the schema takes for a threshold.
        for line in run(exe, "options", "--markdown").stdout.splitlines():
            cells = [c.strip() for c in line.split("|")]
            if len(cells) > 6 and cells[1].startswith("`") and cells[5] != "-":
                check("validation", dict(validation, rows=[dict(row, quantity="threshold", unit=cells[5])]), f"a threshold in {cells[5]}")

    for p in problems:
        print(p)
    print("checked: " + ", ".join(f"{n} {f}" for f, n in checked.items()) + (f"; {len(problems)} problems" if problems else "; all valid"))
    if unpublished:
        print("in reports/ without a schema: " + ", ".join(f"{f} ({n})" for f, n in sorted(unpublished.items())))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
