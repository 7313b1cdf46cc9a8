"""octomotion.trade_study: the study's rows as dicts, with the study's own guarantees."""

import unittest

import octomotion
from support import ARM_SCENE


class TradeStudyTest(unittest.TestCase):
    def test_rows(self):
        study = octomotion.trade_study(ARM_SCENE, states=300, resolutions=[0.04],
                                       roundings=["conservative"], paths=["octree-fused"],
                                       fcl_octomap=False)
        self.assertEqual(study["planning"], [])  # runs=0: no planning
        by_checker = {row["checker"]: row for row in study["checks"]}
        self.assertEqual(set(by_checker), {"octree-fused", "fcl"})
        octree, fcl = by_checker["octree-fused"], by_checker["fcl"]
        self.assertEqual(octree["states"], 300)
        self.assertAlmostEqual(octree["resolution_m"], 0.04)
        self.assertEqual(octree["free_states"] + octree["colliding_states"], 300)
        # Conservative rounding never misses a contact FCL finds (docs/validation.md).
        self.assertEqual(octree["false_negatives"], 0)
        self.assertGreaterEqual(octree["colliding_states"], fcl["colliding_states"])

    def test_bad_options(self):
        with self.assertRaisesRegex(TypeError, "statse"):
            octomotion.trade_study(ARM_SCENE, statse=10)
        with self.assertRaises(octomotion.Error):
            octomotion.trade_study(ARM_SCENE, states=10, resolutions=[-1.0], runs=0)


if __name__ == "__main__":
    unittest.main()
