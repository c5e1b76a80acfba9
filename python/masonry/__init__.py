"""masonry from Python: cases, PRD and DEM runs, comparisons, validation and sweeps.

A thin layer over the C++ libraries the command line uses (README, "From Python"):

    import masonry
    case = masonry.load_case("cases/tilting-block.json")     # or masonry.generate("circular-arch", thickness=0.1)
    case["dem.friction_angle"] = 30                            # an option by its case-file key, checked by the loader
    prd = masonry.run_prd(case)                                # what `masonry prd CASE --out DIR` runs
    dem = masonry.run_dem(case, out="dem", progress=print)     # results.json and steps.csv written as it goes
    print(prd.capacity, prd.d_unit, dem.status)
    report = masonry.compare(prd, dem, tolerances={"capacity": 0.05})

Units are SI throughout (m, N, kg/m^3, rad; friction angles in degrees, as case files write
them). The path parameter d, and so a capacity, is in metres, or in radians where every moving
support only turns (Result.d_unit, Case.d_unit).

Result arrays (numpy, one row per recorded step, in the order of Result.d):
    d             (n_steps,)                 the path parameter, d_unit
    settled       (n_steps,)                 bool: the record is an equilibrium (the DEM's last record of a
                                             collapse is not)
    reactions     (n_steps, n_supports, 3)   Fx, Fy [N] and the moment [N m] each support (Result.supports,
                                             the case's support blocks in order) gives the structure
    poses         (n_steps, n_blocks, 3)     x, y [m] of every block's centroid (Result.blocks, case order,
                                             supports included) and its rotation since the start [rad]
    open_corners  list per step of (joint, "A" | "B", gap [m]); joint indexes Result.joints, a list of
                                             (block id, block id)
A value a record does not give is NaN.

Bad input raises MasonryError with the loader's one-line message (file, block, field). Runs
release the GIL; Ctrl-C stops a run after its current step and raises Interrupted (a
KeyboardInterrupt) whose .result holds the steps finished so far (status "running"); with
out=DIR they are on disk too.
"""

import json as _json
import math as _math
import os as _os

from . import _masonry
from ._masonry import MasonryError, Result

__all__ = [
    "Case", "Result", "MasonryError", "Interrupted", "load_case", "parse_case", "generate", "generators",
    "run_prd", "run_dem", "load_results", "compare", "validate", "sweep",
]


class Interrupted(KeyboardInterrupt):
    """Ctrl-C stopped a run or a study; .result holds what it finished (a Result, or validate's rows)."""

    def __init__(self, result, what="run"):
        super().__init__(f"masonry: the {what} was interrupted; .result holds what it finished")
        self.result = result


def _plain(value):
    # numpy arrays and scalars (numpy itself is imported only where an array is made)
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"masonry: {type(value).__name__} is not a JSON value")


def _dumps(value):
    return _json.dumps(value, default=_plain, allow_nan=False)


def _nonfinite(value, path=()):
    """The first number in `value` that is nan or infinite, and where it sits (keys and indexes), or None."""
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, float):
        return None if _math.isfinite(value) else (value, path)
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, (list, tuple)) else ()
    for key, item in items:
        found = _nonfinite(item, path + (key,))
        if found:
            return found
    return None


def _json_text(value, where):
    """`value` as JSON text for the loader. JSON has no nan or inf, so the loader never sees one
    (json.dumps raised a ValueError naming nothing): a nan or inf (1e400 is inf) raises
    MasonryError instead, "WHERE = nan must be a finite number", where(path) naming the field as
    the loader's messages do."""
    found = _nonfinite(value)
    if found:
        raise MasonryError(f"{where(found[1])} = {found[0]!r} must be a finite number")
    return _dumps(value)


def _option_json(source, key, value):
    """An option's value as JSON text, a nan refused as the loader words its refusals."""
    section, _, name = key.rpartition(".")
    return _json_text(value, lambda path: f"{source} [{key}={value!r}]: {section or 'case'}: field '{name}'")


def _block_field(blocks, path):
    """ "block 'ID': field 'vertices'": the field at `path` in a list of blocks, as the loader names it."""
    block = blocks[path[0]]
    bid = block.get("id") if isinstance(block, dict) else None
    who = f"block '{bid}'" if isinstance(bid, str) and bid else f"block #{path[0]}"
    return f"{who}: field '{path[1]}'" if len(path) > 1 else who


class Case:
    """A case as the loader validated it (masonry-case/1). Every change goes through the loader again.

    case.name, case.blocks (list of dicts: id, vertices (n, 2) array in m, counter-clockwise,
    density kg/m^3 (free blocks only: neither method uses a support's), depth m, support), case.motion (dict: step, max_steps, supports), options by
    their case-file keys: case["dem.friction_angle"], case["motion.step"] = 0.002.
    """

    __slots__ = ("_c",)

    def __init__(self, data):
        if not isinstance(data, _masonry.CaseData):
            raise TypeError("masonry.Case: use masonry.load_case, parse_case or generate")
        self._c = data

    def _doc(self):
        return _json.loads(self._c.to_json())

    def _replace(self, section, value, where):
        """The case with doc[section] = value, through the loader; where(value, path) names the
        field at `path` within value for a nan's message (the rest of the document is the loader's)."""
        doc = self._doc()
        doc[section] = value
        self._c = _masonry.parse_case(_json_text(doc, lambda path: f"{self.source}: {where(value, path[1:])}"), self._c.source)

    @property
    def name(self):
        return self._c.name

    @property
    def source(self):
        """The file the case came from (or what made it), as messages name it."""
        return self._c.source

    @property
    def d_unit(self):
        """"m", or "rad" where every moving support only turns: the unit of d and of capacities."""
        return self._c.d_unit()

    @property
    def blocks(self):
        return self._c.blocks()

    @blocks.setter
    def blocks(self, blocks):
        # A support's density goes to the loader too, which checks its range (it was dropped unread).
        self._replace("blocks", list(blocks), _block_field)

    @property
    def motion(self):
        return self._doc()["motion"]

    @motion.setter
    def motion(self, motion):
        self._replace("motion", motion, lambda motion, path: f"motion: field '{path[0]}'")

    def __getitem__(self, key):
        # Options the case file leaves out while unset (prd.hold_closed []) read as their value.
        at = _json.loads(self._c.options_json())
        for name in key.split("."):
            if not isinstance(at, dict) or name not in at:
                raise KeyError(key)
            at = at[name]
        return at

    def get(self, key, default=None):
        try:
            return self[key]
        except KeyError:
            return default

    def __setitem__(self, key, value):
        self._c = self._c.with_option(key, _option_json(self.source, key, value))

    def copy(self):
        return Case(self._c)

    def to_json(self):
        """The masonry-case/1 text, as `masonry cases NAME --out FILE` writes it."""
        return self._c.to_json()

    def save(self, path):
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.to_json())

    def __repr__(self):
        return f"<masonry.Case {self.name!r}: {len(self.blocks)} blocks, from {self.source}>"


def load_case(path):
    return Case(_masonry.load_case(_os.fspath(path)))


def parse_case(text, source="<text>"):
    return Case(_masonry.parse_case(text, source))


def generators():
    """The case generators of `masonry cases`: name, summary and parameters (name, kind, help, default)."""
    return _masonry.generators()


def generate(name, **parameters):
    """The case `masonry cases NAME --out FILE --PARAM VALUE ...` writes, as the loader reads it back
    (what it refuses raises MasonryError); a parameter's '-' is '_' here."""
    values = {k.replace("_", "-"): v for k, v in parameters.items()}
    return Case(_masonry.generate(name, _json_text(values, lambda path: f"generator {name}: parameter '{path[0]}'")))


def _configured(case, method, options, settings):
    """The case with `options` (case-file keys) and `settings` (names within the method's section,
    or motion's step and max_steps, or gravity) applied through the loader."""
    if not isinstance(case, Case):
        raise TypeError("masonry: a run needs a masonry.Case (load_case, parse_case, generate)")
    motion = set(case.motion) - {"supports"}
    keys = dict(options or {})
    for name, value in settings.items():
        keys[name if "." in name or name == "gravity" else ("motion." if name in motion else method + ".") + name] = value
    c = case._c
    for key, value in keys.items():
        c = c.with_option(key, _option_json(case.source, key, value))
    return c


def _run(case, method, out, progress, options, settings):
    c = _configured(case, method, options, settings)
    result, interrupted = _masonry.run(c, method, "" if out is None else _os.fspath(out), progress)
    if interrupted:
        raise Interrupted(result)
    return result


def run_prd(case, out=None, progress=None, options=None, **settings):
    """PRD's capacity run, as `masonry prd CASE --out DIR`. Settings by their names in the case's prd
    section (contact_tolerance=1e-6, adaptive=True), step= and max_steps= for the motion, or
    options={"motion.step": 0.001}. progress(d, n_steps) is called after every recorded step."""
    return _run(case, "prd", out, progress, options, settings)


def run_dem(case, out=None, progress=None, options=None, **settings):
    """The DEM's capacity run, as `masonry dem CASE --out DIR`; settings as run_prd's, in the dem
    section (friction_angle=30 sets dem.friction_angle)."""
    return _run(case, "dem", out, progress, options, settings)


def load_results(path, case):
    """A results.json (masonry-results/1) written for `case`, as a Result."""
    return _masonry.load_results(_os.fspath(path), case._c)


def _case_of(result):
    return Case(result._case)


Result.case = property(_case_of, doc="The case the run ran (with the settings it was given)")


def compare(a, b, *more, tolerances=None, out=None):
    """Compares two runs of one case as `masonry compare --runs A B [--tolerances FILE]` does:
    compare(a, b) or compare(case, a, b). Returns comparison.json as a dict, with "pass" and
    "violations" (the limits exceeded, one line each) at the top. tolerances: a dict
    ({"capacity": 0.05, "thrust": 0.1, "hinges": True}) or a file; out=DIR also writes the report.
    A run of another case raises MasonryError, as the command line refuses its results.json."""
    if isinstance(a, Case):
        if len(more) != 1:
            raise TypeError("masonry.compare(case, a, b) or compare(a, b)")
        case, a, b = a, b, more[0]
    elif more:
        raise TypeError("masonry.compare(case, a, b) or compare(a, b)")
    else:
        case = a.case
    text, source = "", "tolerances"
    if isinstance(tolerances, (str, _os.PathLike)):
        source = _os.fspath(tolerances)
        with open(source, encoding="utf-8") as f:
            text = f.read()
    elif tolerances is not None:
        text = _json_text(tolerances, lambda path: f"tolerances: \"{path[0]}\"")
    return _masonry.compare(case._c, a, b, text, source, "" if out is None else _os.fspath(out))


def validate(quick=True, names=None):
    """The built-in catalogue's benchmarks, as `masonry validate [--quick] [--only NAME ...]`: one
    dict per benchmark and method (the rows of its --json file: benchmark, method, expected,
    obtained, error, tolerance, pass, ...)."""
    doc, interrupted = _masonry.validate(bool(quick), list(names or []))
    if interrupted:
        raise Interrupted(doc["rows"], "validation")
    return doc["rows"]


def sweep(spec, out, jobs=1, restart=False, keep_runs=False, quiet=True):
    """Runs a sweep file (masonry-sweep/1) exactly as `masonry sweep SPEC --out OUT --jobs N`,
    writing everything the command writes to OUT (a sweep.csv there is resumed unless restart).
    Returns {"sweep": sweep.json, "sensitivity": sensitivity.json} as dicts. Ctrl-C takes effect
    when the sweep ends (its finished rows are in OUT/sweep.csv, and a rerun resumes them)."""
    return _masonry.sweep(_os.fspath(spec), _os.fspath(out), int(jobs), bool(restart), bool(keep_runs), bool(quiet))
