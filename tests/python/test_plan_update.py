"""octomotion.plan and the scene updates (add, move, remove, attach, detach objects)."""

import threading
import unittest

import numpy

import octomotion
from support import ARM_SCENE, RESOLUTION, random_states

GOAL = [-2.16, -0.502, 1.442, -1.4, -0.815, -0.618, 1.199, 0.02]  # bookshelf.yaml's goal


class PlanTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.scene = octomotion.load_scene(ARM_SCENE, resolution=RESOLUTION)

    def test_path_is_valid_and_joins_start_and_goal(self):
        path = octomotion.plan(self.scene, time=10.0, seed=1)
        self.assertIsNotNone(path)
        self.assertEqual(path.dtype, numpy.float64)
        self.assertEqual(path.shape[1], self.scene.dof)
        self.assertGreater(len(path), 2)
        numpy.testing.assert_allclose(path[0], numpy.zeros(self.scene.dof), atol=1e-9)
        numpy.testing.assert_allclose(path[-1], GOAL, atol=1e-9)
        self.assertTrue(self.scene.check_many(numpy.ascontiguousarray(path)).all())

    def test_given_start_and_goal(self):
        Q = random_states(self.scene, 200, seed=3, margin=0.0)
        valid = self.scene.check_many(Q)
        free = Q[valid]
        path = octomotion.plan(self.scene, time=10.0, seed=2, start=free[0], goal=GOAL)
        if path is not None:  # a random start may have no path in the time given
            numpy.testing.assert_allclose(path[0], free[0], atol=1e-9)
            self.assertTrue(self.scene.check_many(numpy.ascontiguousarray(path)).all())
        with self.assertRaisesRegex(octomotion.InvalidArgument, "goal is invalid"):
            octomotion.plan(self.scene, time=1.0, start=free[0], goal=Q[~valid][0])
        with self.assertRaisesRegex(octomotion.InvalidArgument, "planner"):
            octomotion.plan(self.scene, planner="NoSuchPlanner")
        with self.assertRaisesRegex(ValueError, "start"):
            octomotion.plan(self.scene, start=[0.0, 0.0])


class UpdateTest(unittest.TestCase):
    def setUp(self):
        self.scene = octomotion.load_scene(ARM_SCENE, resolution=RESOLUTION,
                                           fit_universe_to_reach=True)
        self.q = numpy.zeros(self.scene.dof)
        self.hand = self.scene.forward_kinematics(self.q)["hand"][:3, 3]

    def test_add_move_remove(self):
        self.assertTrue(self.scene.check(self.q))
        self.scene.add_object("crate", box=[0.2, 0.2, 0.2], pose=self.hand)
        self.assertIn("crate", self.scene.object_names)
        self.assertFalse(self.scene.check(self.q))
        self.assertTrue(any(r.other == "crate" for r in self.scene.explain(self.q)))
        away = numpy.eye(4)
        away[:3, 3] = self.hand + [0.6, 0.6, 0.0]
        self.scene.move_object("crate", away)
        self.assertTrue(self.scene.check(self.q))
        self.scene.move_object("crate", self.hand)
        self.assertFalse(self.scene.check(self.q))
        self.scene.remove_object("crate")
        self.assertNotIn("crate", self.scene.object_names)
        self.assertTrue(self.scene.check(self.q))
        with self.assertRaisesRegex(octomotion.InvalidArgument, "crate"):
            self.scene.remove_object("crate")

    def test_attach_detach(self):
        # A ball held in the hand that reaches the forearm: a self-collision while attached.
        self.scene.attach_object("ball", "hand", sphere=0.3)
        self.assertEqual(self.scene.attached_names, ["ball"])
        self.assertFalse(self.scene.check(self.q))
        self.scene.detach_object("ball")
        self.assertEqual(self.scene.attached_names, [])
        self.assertTrue(self.scene.check(self.q))

    def test_updates_while_another_thread_checks(self):
        # The updates wait for a batch in flight: every batch sees the crate or does not, and
        # the answer for q is either the one with it or the one without.
        Q = numpy.repeat(self.q[None, :], 2000, axis=0)
        answers, errors = [], []

        def check():
            try:
                for _ in range(20):
                    answers.append(set(self.scene.check_many(Q, threads=2).tolist()))
            except Exception as e:  # noqa: BLE001 -- reported by the assertion below
                errors.append(e)

        worker = threading.Thread(target=check)
        worker.start()
        for _ in range(10):
            self.scene.add_object("crate", box=[0.2, 0.2, 0.2], pose=self.hand)
            self.scene.remove_object("crate")
        worker.join()
        self.assertEqual(errors, [])
        self.assertTrue(all(a in ({True}, {False}) for a in answers), answers)
        self.assertTrue(self.scene.check(self.q))

    def test_bad_updates(self):
        with self.assertRaisesRegex(octomotion.InvalidArgument, "exactly one"):
            self.scene.add_object("x", box=[0.1, 0.1, 0.1], sphere=0.1)
        with self.assertRaisesRegex(octomotion.InvalidArgument, "rotation"):
            scaled = numpy.eye(4)
            scaled[:3, :3] *= 2
            self.scene.add_object("x", sphere=0.1, pose=scaled)
        with self.assertRaisesRegex(ValueError, "4x4"):
            self.scene.move_object("x", numpy.zeros((3, 3)))


if __name__ == "__main__":
    unittest.main()
