#!/usr/bin/env python3
"""A deliberately wrong copy of examples/toppling_solver.py, for tests/validate/solver_test.cpp:
the same closed form with every d, and so the capacity, 10% too large. `masonry validate
--solver` must fail it (exit status 1)."""
import json
import os
import subprocess
import sys

example = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "toppling_solver.py")
case, out = sys.argv[1], sys.argv[2]
subprocess.run([sys.executable, example, case, out, "--name", "wrong"], check=True)
path = os.path.join(out, "results.json")
with open(path) as f:
    results = json.load(f)
results["capacity"] *= 1.1
for step in results["steps"]:
    step["d"] *= 1.1
with open(path, "w") as f:
    json.dump(results, f)
