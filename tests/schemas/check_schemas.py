#!/usr/bin/env python3
"""Every file masonry writes, and every such file checked in, against the published formats
(schemas/*.schema.json, JSON Schema draft 2020-12), with Debian's python3-jsonschema.

    check_schemas.py --exe build/app/masonry --source . --scratch DIR

Checked: the five schemas themselves; what masonry writes, freshly made here (case files from
every generator, a DXF import, PRD and DEM results with their optional parts, a comparison, a
comparison with an outside solver's minimal results); the files checked in (reports/**/results.json
and comparison.json, cases/*.json, the built-in catalogue and its inline cases, the sweep files);
the JSON examples of the READMEs; the example solver's results. And that each schema refuses
what the readers refuse (a test that cannot fail proves nothing). Exit status 1 with one line
per file that does not validate.
"""
import argparse
import glob
import json
import lzma
import os
import re
import shutil
import subprocess
import sys

try:
    import jsonschema
except ImportError:
    print("check_schemas.py: python3-jsonschema is not installed (bash scripts/install-deps.sh)", file=sys.stderr)
    sys.exit(1)

FORMATS = ["case", "results", "comparison", "catalogue", "sweep"]
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


def run(*args, ok=(0,)):
    p = subprocess.run(list(args), capture_output=True, text=True)
    if p.returncode not in ok:
        problems.append(f"{' '.join(args)}: exit {p.returncode}: {p.stderr.strip()[-300:]}")
    return p


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
            m = re.fullmatch(r"masonry-(\w+)/1", doc.get("format", "") if isinstance(doc, dict) else "")
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
    for name, args in runs.items():
        out = os.path.join(tmp, name)
        run(exe, *args, "--out", out)
        path = os.path.join(out, "results.json")
        if os.path.exists(path):
            check("results", load(path), path)
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
    cat = load(catalogue)
    bad = json.loads(json.dumps(cat))
    del bad["benchmarks"][0]["methods"]["prd"]["tolerance"]["why"]
    refuses("catalogue", bad, "a tolerance without its argument")
    refuses("sweep", {"case": "x.json", "vary": {"gravity": [9.81]}}, "a sweep without its format")
    refuses("comparison", {"format": "masonry-comparison/1", "case": "c"}, "a comparison without runs")

    for p in problems:
        print(p)
    print("checked: " + ", ".join(f"{n} {f}" for f, n in checked.items()) + (f"; {len(problems)} problems" if problems else "; all valid"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
