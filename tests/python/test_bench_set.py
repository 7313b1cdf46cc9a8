"""octomotion.bench_set: the planning benchmark over a folder, its rows and summary as dicts."""

import os
import re
import shutil
import tempfile
import unittest

import octomotion
from support import SOURCE_DIR

SCENES = os.path.join(SOURCE_DIR, "robots", "scenes")


def copy_scene(name, folder):
    """A shipped scene with its relative robot paths made absolute, so it loads from `folder`."""
    with open(os.path.join(SCENES, name)) as f:
        text = f.read()
    text = re.sub(r"\.\./", os.path.abspath(os.path.join(SCENES, "..")) + "/", text)
    with open(os.path.join(folder, name), "w") as f:
        f.write(text)


class BenchSetTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="octomotion-py-bench-set-")
        # Two sets of one problem each: a folder of sets, summarised per set and over all.
        for folder, name in (("shelf", "bookshelf.yaml"), ("table", "cluttered_table.yaml")):
            os.makedirs(os.path.join(cls.dir, folder))
            copy_scene(name, os.path.join(cls.dir, folder))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_rows_and_summary(self):
        logs = os.path.join(self.dir, "logs")
        result = octomotion.bench_set(self.dir, checkers=["octree-fused", "fcl"], time=2.0,
                                      seed=1, resolution=0.02, log_dir=logs)
        runs = result["runs"]
        # Every problem once per checker.
        pairs = sorted((r["problem"], r["checker"]) for r in runs)
        self.assertEqual(pairs, sorted((p, c) for p in ("bookshelf", "cluttered_table")
                                       for c in ("octree-fused", "fcl")))
        solved = [r for r in runs if r["solved"] == 1]
        self.assertTrue(solved, runs)
        for r in solved:
            # A solved path was re-checked densely by exact FCL and nothing collides.
            self.assertGreater(r["fcl_recheck_states"], 0, r)
            self.assertEqual(r["fcl_recheck_colliding"], 0, r)
        summary = result["summary"]
        self.assertEqual([s["set"] for s in summary],
                         ["shelf", "shelf", "table", "table", "all", "all"])
        for s in summary:
            self.assertEqual(s["problems"], 2 if s["set"] == "all" else 1)
            self.assertLessEqual(s["solved"], s["runs"])
            self.assertLessEqual(s["median_seconds"], s["p90_seconds"])
        total = sum(s["solved"] for s in summary if s["set"] == "all")
        self.assertEqual(total, len(solved))
        self.assertEqual(len(result["logs"]), 4)  # one per set and checker
        for log in result["logs"]:
            self.assertTrue(os.path.isfile(log), log)

    def test_bad_input(self):
        with self.assertRaisesRegex(octomotion.FileError, "no-such-folder"):
            octomotion.bench_set(os.path.join(self.dir, "no-such-folder"))
        with self.assertRaisesRegex(octomotion.Error, "checker"):
            octomotion.bench_set(self.dir, checkers=["octree-typo"])
        with self.assertRaisesRegex(TypeError, "planer"):
            octomotion.bench_set(self.dir, planer="RRT")


if __name__ == "__main__":
    unittest.main()
