"""The Python module (python/, README "From Python"), run by ctest with PYTHONPATH at the build's
python/ directory, MASONRY_EXE the command line and MASONRY_SOURCE_DIR the repository. Expected
values come from the case files (closed forms), the command line's own output (the module must
give what it gives, bit for bit) and equilibrium; PRD runs only, and two DEM steps."""

import json
import math
import os
import signal
import subprocess
import tempfile
import unittest

import numpy as np

import masonry

SOURCE = os.environ.get("MASONRY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
EXE = os.environ.get("MASONRY_EXE", "masonry")
TILT = os.path.join(SOURCE, "cases", "tilting-block.json")
POINTED = os.path.join(SOURCE, "cases", "pointed-arch.json")


def cli(*args):
    return subprocess.run([EXE, *args], check=True, capture_output=True, text=True)


def tilting_block_dimensions():
    """b, h and the centroid of the free block, from the case file's vertices."""
    with open(TILT, encoding="utf-8") as f:
        doc = json.load(f)
    (block,) = [b for b in doc["blocks"] if not b.get("support")]
    v = np.array(block["vertices"])
    return v[:, 0].ptp(), v[:, 1].ptp(), v.mean(axis=0), block["density"] * v[:, 0].ptp() * v[:, 1].ptp() * block["depth"]


class TiltingBlock(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.case = masonry.load_case(TILT)
        cls.prd = masonry.run_prd(cls.case)

    def test_topples_at_atan_b_over_h(self):
        b, h, _, _ = tilting_block_dimensions()
        step = self.case["motion.step"]
        r = self.prd
        self.assertEqual(r.status, "collapse")
        self.assertEqual(r.d_unit, "rad")  # the slab only turns: d is its tilt
        # The capacity is the last stable tilt: toppling lies within the next step.
        self.assertLessEqual(r.capacity, math.atan(b / h))
        self.assertLess(math.atan(b / h), r.capacity + step)

    def test_capacity_as_the_command_line_prints_it(self):
        with tempfile.TemporaryDirectory() as tmp:
            cli("prd", TILT, "--out", tmp, "--quiet")
            with open(os.path.join(tmp, "results.json"), encoding="utf-8") as f:
                self.assertEqual(json.load(f)["capacity"], self.prd.capacity)

    def test_arrays_have_their_shapes_and_units(self):
        r = self.prd
        n = len(r.d)
        self.assertGreater(n, 2)
        self.assertEqual(r.d.shape, (n,))
        self.assertEqual(r.settled.shape, (n,))
        self.assertEqual(r.supports, ["ground"])
        self.assertEqual(r.blocks, ["ground", "block"])
        self.assertEqual(r.reactions.shape, (n, 1, 3))
        self.assertEqual(r.poses.shape, (n, 2, 3))
        self.assertEqual(len(r.open_corners), n)
        _, _, centroid, mass = tilting_block_dimensions()
        weight = mass * self.case["gravity"]
        # N: at rest the slab carries the block's weight, straight up.
        np.testing.assert_allclose(r.reactions[0, 0, :2], [0.0, weight], rtol=1e-9, atol=1e-9 * weight)
        # m: the block's centroid at the start, from its vertices; rad: its rotation since the start.
        np.testing.assert_allclose(r.poses[0, 1], [centroid[0], centroid[1], 0.0], atol=1e-12)
        # At every tilt d (rad) the resting block has turned with the slab.
        np.testing.assert_allclose(r.poses[:, 1, 2], r.d, atol=1e-9)
        for step in r.open_corners:
            for joint, corner, gap in step:
                self.assertIn(corner, ("A", "B"))
                self.assertLess(joint, len(r.joints))
                self.assertGreaterEqual(gap, 0.0)
        self.assertEqual(r.joints, [("ground", "block")])

    def test_an_option_set_on_the_case_reaches_the_run(self):
        case = masonry.load_case(TILT)
        case["dem.friction_angle"] = 30
        self.assertEqual(case["dem.friction_angle"], 30)
        r = masonry.run_dem(case, max_steps=2)
        self.assertEqual(r.settings["friction_angle"], 30)
        self.assertEqual(len(r.d), 3)  # the settled start and two steps
        r = masonry.run_prd(case, contact_tolerance=2e-5, options={"motion.step": 0.01})
        self.assertEqual(r.settings["contact_tolerance"], 2e-5)
        np.testing.assert_allclose(np.diff(r.d), 0.01, rtol=1e-12)

    def test_an_option_reads_back_what_was_set(self):
        case = masonry.load_case(TILT)
        # The case file leaves these out while they hold their unset value: reading one raised KeyError.
        self.assertEqual(case["prd.hold_closed"], [])
        case["prd.hold_closed"] = []
        self.assertEqual(case["prd.hold_closed"], [])
        case["dem.hold_damping"] = "local"
        self.assertEqual(case["dem.hold_damping"], "local")
        case["prd.hold_closed"] = ["ground/block:A"]
        self.assertEqual(case["prd.hold_closed"], ["ground/block:A"])
        # An optional number left absent is derived when a run starts: it has no value to read.
        self.assertIsNone(case.get("dem.open_gap"))

    def test_save_writes_what_the_command_line_writes(self):
        with tempfile.TemporaryDirectory() as tmp:
            self.prd.save(tmp)
            with open(os.path.join(tmp, "results.json"), encoding="utf-8") as f:
                self.assertEqual(f.read(), self.prd.to_json())
            self.assertTrue(os.path.exists(os.path.join(tmp, "steps.csv")))
            back = masonry.load_results(os.path.join(tmp, "results.json"), self.case)
            np.testing.assert_array_equal(back.d, self.prd.d)

    def test_ctrl_c_keeps_the_finished_steps(self):
        seen = []

        def progress(d, steps):
            seen.append(steps)
            if steps == 4:
                os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C

        with tempfile.TemporaryDirectory() as tmp:
            with self.assertRaises(masonry.Interrupted) as stop:
                masonry.run_prd(self.case, out=tmp, progress=progress)
            self.assertIsInstance(stop.exception, KeyboardInterrupt)
            partial = stop.exception.result
            self.assertEqual(partial.status, "running")
            self.assertEqual(len(partial.d), 4)
            np.testing.assert_array_equal(partial.d, self.prd.d[:4])
            with open(os.path.join(tmp, "results.json"), encoding="utf-8") as f:
                self.assertEqual(len(json.load(f)["steps"]), 4)
        self.assertEqual(seen[-1], 4)

    def test_an_error_in_progress_stops_the_run_and_is_raised(self):
        def progress(d, steps):
            if steps == 3:
                raise ValueError("enough")

        with self.assertRaisesRegex(ValueError, "enough"):
            masonry.run_prd(self.case, progress=progress)

    def test_compare(self):
        same = masonry.compare(self.prd, masonry.run_prd(self.case), tolerances={"capacity": 1e-12})
        self.assertTrue(same["pass"])
        self.assertEqual(same["violations"], [])
        self.assertEqual(same["d_unit"], "rad")
        # Half the tilt increment locates the toppling half a degree closer: a capacity difference
        # beyond a 1e-6 limit.
        finer = masonry.run_prd(self.case, step=self.case["motion.step"] / 2)
        k = masonry.compare(self.case, self.prd, finer, tolerances={"capacity": 1e-6})
        self.assertFalse(k["pass"])
        self.assertEqual(len(k["violations"]), 1)
        self.assertIn("capacity", k["violations"][0])

    def test_compare_refuses_runs_of_another_case(self):
        # As `masonry compare --runs` does: each run is read against the case compared (an arch's
        # run, d in m, was compared with the tilting block's, d in rad, and could pass).
        arch = masonry.run_prd(masonry.generate("circular-arch"), max_steps=1)
        with tempfile.TemporaryDirectory() as tmp:
            self.prd.save(os.path.join(tmp, "tb"))
            arch.save(os.path.join(tmp, "arch"))
            done = subprocess.run([EXE, "compare", TILT, "--runs", os.path.join(tmp, "tb"), os.path.join(tmp, "arch"), "--out",
                                   os.path.join(tmp, "cmp")], capture_output=True, text=True)
        self.assertEqual(done.returncode, 2)
        reason = done.stderr.strip().split("results.json: ", 1)[1]  # "blocks: 22 blocks, the case has 2"
        with self.assertRaises(masonry.MasonryError) as e:
            masonry.compare(self.prd, arch)
        self.assertEqual(str(e.exception), f"run b (prd of case '{arch.case.name}'): {reason}")
        for args in [(self.case, self.prd, arch), (arch.case, self.prd, self.prd)]:
            with self.assertRaisesRegex(masonry.MasonryError, "blocks: "):
                masonry.compare(*args)


class PointedArch(unittest.TestCase):
    def test_capacity_and_every_d_equal_the_command_line(self):
        r = masonry.run_prd(masonry.load_case(POINTED))
        with tempfile.TemporaryDirectory() as tmp:
            cli("prd", POINTED, "--out", tmp, "--quiet")
            with open(os.path.join(tmp, "results.json"), encoding="utf-8") as f:
                doc = json.load(f)
        self.assertEqual(r.status, doc["stopped"])
        self.assertEqual(r.capacity, doc["capacity"])
        self.assertEqual(r.d.tolist(), [s["d"] for s in doc["steps"]])
        self.assertEqual(r.d_unit, "m")
        for k, s in enumerate(doc["steps"]):
            for j, rc in enumerate(s["reactions"]):
                self.assertEqual(rc["support"], r.supports[j])
                self.assertEqual(r.reactions[k, j].tolist(), [rc["force"][0], rc["force"][1], rc["moment"]])


class BadInput(unittest.TestCase):
    def test_a_malformed_case_names_the_field(self):
        with open(TILT, encoding="utf-8") as f:
            doc = json.load(f)
        doc["blocks"][1]["density"] = -2000
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "bad.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump(doc, f)
            with self.assertRaises(masonry.MasonryError) as e:
                masonry.load_case(path)
        self.assertIsInstance(e.exception, Exception)
        self.assertIn("bad.json", str(e.exception))
        self.assertIn("density", str(e.exception))
        self.assertNotIn("\n", str(e.exception))

    def test_a_bad_option_gets_the_loaders_message(self):
        case = masonry.load_case(TILT)
        with self.assertRaises(masonry.MasonryError) as e:
            case["dem.friction_angle"] = -5
        self.assertIn("friction_angle", str(e.exception))
        self.assertEqual(case["dem.friction_angle"], 35.0)  # unchanged
        with self.assertRaises(masonry.MasonryError) as e:
            masonry.run_dem(case, no_such_setting=1)
        self.assertIn("no_such_setting", str(e.exception))
        with self.assertRaises(masonry.MasonryError):
            masonry.parse_case("{", "inline")
        with self.assertRaises(masonry.MasonryError) as e:
            masonry.generate("circular-arch", thickness=-1)
        self.assertIn("thickness", str(e.exception))
        with self.assertRaises(masonry.MasonryError):
            masonry.compare(masonry.run_prd(case, max_steps=1), masonry.run_prd(case, max_steps=1), tolerances={"capacityy": 1})

    def test_a_nan_or_inf_names_the_field(self):
        # JSON has no nan or inf, so they never reached the loader: json.dumps raised a ValueError
        # that named nothing.
        case = masonry.load_case(TILT)
        run = masonry.run_prd(case, max_steps=1)
        blocks = case.blocks
        blocks[1]["vertices"][0, 0] = float("nan")
        motion = case.motion
        motion["step"] = float("inf")
        for call, says in [(lambda: masonry.run_prd(case, step=float("nan")), "[motion.step=nan]: motion: field 'step' = nan"),
                           (lambda: masonry.run_prd(case, gravity=1e400), "case: field 'gravity' = inf"),
                           (lambda: case.__setitem__("dem.kn", np.float64("nan")), "dem: field 'kn' = nan"),
                           (lambda: setattr(case, "blocks", blocks), "block 'block': field 'vertices' = nan"),
                           (lambda: setattr(case, "motion", motion), "motion: field 'step' = inf"),
                           (lambda: masonry.generate("circular-arch", step=float("nan")), "parameter 'step' = nan"),
                           (lambda: masonry.compare(run, run, tolerances={"capacity": float("nan")}), '"capacity" = nan')]:
            with self.assertRaises(masonry.MasonryError) as e:
                call()
            self.assertIn(says, str(e.exception))
            self.assertIn("must be a finite number", str(e.exception))
        self.assertEqual(case.to_json(), masonry.load_case(TILT).to_json())  # unchanged


class Generators(unittest.TestCase):
    def test_generate_equals_the_command_line(self):
        names = [g["name"] for g in masonry.generators()]
        self.assertIn("circular-arch", names)
        (arch,) = [g for g in masonry.generators() if g["name"] == "circular-arch"]
        self.assertIn("embrace-deg", [p["name"] for p in arch["parameters"]])
        case = masonry.generate("circular-arch", thickness=0.1, voussoirs=9, embrace_deg=160)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "arch.json")
            cli("cases", "circular-arch", "--out", path, "--thickness", "0.1", "--voussoirs", "9", "--embrace-deg", "160")
            with open(path, encoding="utf-8") as f:
                self.assertEqual(case.to_json(), f.read())
        self.assertEqual(len(case.blocks), 11)  # 9 voussoirs and two supports
        self.assertEqual(case.blocks[1]["vertices"].shape[1], 2)

    def test_generate_refuses_what_the_command_line_refuses(self):
        # A generator checks its geometry, not the loader's ranges: these built cases that ran
        # from Python and that `masonry cases` refuses to write (exit 2, the loader's message).
        for param, value, text in [("radius", 1e6, "1e6"), ("step", 10.0, "10"), ("step", 1e-12, "1e-12"), ("density", 1e6, "1e6"),
                                   ("max_steps", 2e8, "200000000"), ("depth", 1e6, "1e6")]:
            with self.assertRaises(masonry.MasonryError) as e:
                masonry.generate("circular-arch", **{param: value})
            with tempfile.TemporaryDirectory() as tmp:
                path = os.path.join(tmp, "x.json")
                done = subprocess.run([EXE, "cases", "circular-arch", "--out", path, "--" + param.replace("_", "-"), text],
                                      capture_output=True, text=True)
            self.assertEqual(done.returncode, 2)
            # The same message, naming the generator where the command line names its file.
            self.assertEqual(str(e.exception), done.stderr.strip().replace("masonry cases: " + path, "generator circular-arch"))

    def test_a_mistyped_generator_gets_the_command_lines_suggestion(self):
        for typed, meant in [("wal", "wall"), ("circular-ach", "circular-arch")]:
            with self.assertRaises(masonry.MasonryError) as e:
                masonry.generate(typed)
            hint = f"did you mean '{meant}'?"
            self.assertIn(hint, str(e.exception))
            with tempfile.TemporaryDirectory() as tmp:
                done = subprocess.run([EXE, "cases", typed, "--out", os.path.join(tmp, "x.json")], capture_output=True, text=True)
            self.assertIn(hint, done.stderr)
        with self.assertRaises(masonry.MasonryError) as e:
            masonry.generate("colonnade")
        self.assertNotIn("did you mean", str(e.exception))

    def test_the_wall_generator_equals_the_command_line(self):
        # Its parameters are words and lists as well as numbers (cases/wall_fields.hpp), read by their names.
        case = masonry.generate("wall", courses=12, bricks=8, bond="stack", opening=["0.75,0.25,0.5,0.5,arch"], moving="left")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "wall.json")
            cli("cases", "wall", "--out", path, "--courses", "12", "--bricks", "8", "--bond", "stack",
                "--opening", "0.75,0.25,0.5,0.5,arch", "--moving", "left")
            with open(path, encoding="utf-8") as f:
                self.assertEqual(case.to_json(), f.read())
        for bad, field in [({"bond": "flemish"}, "bond"), ({"courses": 2.5}, "courses"), ({"colour": 1}, "colour")]:
            with self.assertRaises(masonry.MasonryError) as e:
                masonry.generate("wall", **bad)
            self.assertIn(field, str(e.exception))

    def test_blocks_and_motion_are_settable(self):
        case = masonry.load_case(TILT)
        blocks = case.blocks
        blocks[1]["vertices"] = blocks[1]["vertices"] * [1.0, 0.5]  # half as tall
        case.blocks = blocks
        self.assertAlmostEqual(case.blocks[1]["vertices"][:, 1].max(), 0.2)
        motion = case.motion
        motion["max_steps"] = 5
        case.motion = motion
        self.assertEqual(case["motion.max_steps"], 5)
        bad = case.blocks
        bad[1]["vertices"] = bad[1]["vertices"][:2]
        with self.assertRaises(masonry.MasonryError) as e:
            case.blocks = bad
        self.assertIn("block", str(e.exception))

    def test_a_supports_density_is_neither_shown_nor_dropped_unchecked(self):
        # The loader takes a support's density ([0, 1e5]); neither method uses it and the case
        # writer leaves it out. case.blocks gave 2500 until a change made it 0.
        with open(TILT, encoding="utf-8") as f:
            doc = json.load(f)
        doc["blocks"][0]["density"] = 2500
        case = masonry.parse_case(json.dumps(doc), "support-density.json")
        self.assertTrue(case.blocks[0]["support"])
        self.assertNotIn("density", case.blocks[0])
        self.assertNotIn("density", json.loads(case.to_json())["blocks"][0])
        text = case.to_json()
        case.blocks = case.blocks
        self.assertEqual(case.to_json(), text)
        # Given on a support through case.blocks, it goes to the loader (it was dropped unread).
        bad = case.blocks
        bad[0]["density"] = -1
        with self.assertRaises(masonry.MasonryError) as e:
            case.blocks = bad
        self.assertIn("block 'ground': field 'density'", str(e.exception))


class Studies(unittest.TestCase):
    def test_validate_one_benchmark(self):
        rows = masonry.validate(names=["block-least-friction"])
        self.assertEqual([(r["benchmark"], r["method"]) for r in rows], [("block-least-friction", "prd")])
        self.assertTrue(rows[0]["pass"])
        with self.assertRaises(masonry.MasonryError):
            masonry.validate(names=["no-such-benchmark"])

    def test_sweep_returns_what_it_writes(self):
        with tempfile.TemporaryDirectory() as tmp:
            spec = os.path.join(tmp, "sweep.json")
            with open(spec, "w", encoding="utf-8") as f:
                json.dump({"format": "masonry-sweep/1", "name": "tilt steps", "case": TILT, "methods": ["prd"],
                           "vary": {"motion.step": [0.017453292519943295, 0.008726646259971648]}}, f)
            out = os.path.join(tmp, "out")
            got = masonry.sweep(spec, out)
            with open(os.path.join(out, "sweep.json"), encoding="utf-8") as f:
                self.assertEqual(got["sweep"], json.load(f))
            with open(os.path.join(out, "sensitivity.json"), encoding="utf-8") as f:
                self.assertEqual(got["sensitivity"], json.load(f))
            self.assertEqual(len(got["sweep"]["runs"]), 2)


if __name__ == "__main__":
    unittest.main()
