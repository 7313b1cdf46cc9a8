"""Scene.check / check_many / explain / clearance / forward_kinematics against each other and
against the `octomotion check` command."""

import csv
import io
import os
import subprocess
import tempfile
import unittest

import numpy

import octomotion
from support import ARM_SCENE, CLI, RESOLUTION, RIGID_SCENE, random_poses, random_states


class CheckTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.scene = octomotion.load_scene(ARM_SCENE, resolution=RESOLUTION)
        cls.Q = random_states(cls.scene, 400, seed=7)
        cls.Q[5, 2] = numpy.nan  # a NaN state is invalid, not a crash
        cls.Q[6, 0] = numpy.inf

    def test_scene_description(self):
        self.assertEqual(self.scene.dof, len(self.scene.joint_names))
        self.assertEqual(self.scene.joint_names[:2], ["joint1", "joint2"])
        self.assertFalse(self.scene.free_flying)
        self.assertAlmostEqual(self.scene.resolution, RESOLUTION)
        low, high = self.scene.bounds
        self.assertTrue(numpy.all(low < high))

    def test_check_many_equals_check(self):
        valid = self.scene.check_many(self.Q)
        self.assertEqual(valid.dtype, numpy.bool_)
        self.assertEqual(valid.shape, (len(self.Q),))
        self.assertEqual(list(valid), [self.scene.check(q) for q in self.Q])
        # Both answers occur, so the comparison means something.
        self.assertTrue(valid.any() and not valid.all())
        self.assertFalse(valid[5] or valid[6])

    def test_threads_give_the_same_answers(self):
        one = self.scene.check_many(self.Q)
        for threads in (2, 3, 0):
            numpy.testing.assert_array_equal(self.scene.check_many(self.Q, threads=threads), one)

    @unittest.skipUnless(os.path.exists(CLI), "the octomotion command is not built")
    def test_check_many_equals_the_command(self):
        command = command_answers(self.scene, ARM_SCENE, self.Q, "--resolution", str(RESOLUTION))
        self.assertEqual(len(command), len(self.Q))
        self.assertEqual(list(self.scene.check_many(self.Q)), command)

    def test_bad_arrays_name_the_shape(self):
        dof = self.scene.dof
        with self.assertRaisesRegex(TypeError, "float64"):
            self.scene.check_many(self.Q.astype(numpy.float32))
        with self.assertRaisesRegex(TypeError, "float64"):
            self.scene.check_many(self.Q.tolist())
        with self.assertRaisesRegex(ValueError, r"\(N, %d\).*\(400, %d\)" % (dof, dof + 1)):
            self.scene.check_many(numpy.zeros((400, dof + 1)))
        with self.assertRaisesRegex(ValueError, r"\(%d,\)" % dof):
            self.scene.check_many(numpy.zeros(dof))
        with self.assertRaisesRegex(ValueError, "non-contiguous"):
            self.scene.check_many(numpy.asfortranarray(self.Q))
        with self.assertRaisesRegex(ValueError, "non-contiguous"):
            self.scene.check_many(self.Q[::2])
        with self.assertRaisesRegex(ValueError, r"shape \(%d,\)" % dof):
            self.scene.check(numpy.zeros(dof + 1))
        with self.assertRaises(ValueError):
            self.scene.check_many(self.Q, threads=-1)

    def test_empty_batch(self):
        self.assertEqual(self.scene.check_many(numpy.zeros((0, self.scene.dof))).shape, (0,))

    def test_explain_names_a_pair(self):
        valid = self.scene.check_many(self.Q)
        links = set(self.scene.forward_kinematics(numpy.zeros(self.scene.dof)))
        contacts = 0
        for q, ok in zip(self.Q, valid):
            reasons = self.scene.explain(q)
            self.assertEqual(ok, not reasons, [str(r) for r in reasons])
            for r in reasons:
                if r.kind in ("environment", "self"):
                    contacts += 1
                    self.assertIn(r.link, links)
                    if r.kind == "self":
                        self.assertIn(r.other, links)
                    else:
                        self.assertIn(r.other, self.scene.object_names)
                    self.assertIn(r.link, r.text)
        self.assertGreater(contacts, 0)
        self.assertEqual(self.scene.explain(self.Q[5])[0].kind, "non-finite")

    def test_clearance(self):
        valid = self.scene.check_many(self.Q)
        for q, ok in list(zip(self.Q, valid))[:40]:
            c = self.scene.clearance(q)
            if ok:
                self.assertGreaterEqual(c, 0.0)
            else:
                self.assertEqual(c, 0.0)

    def test_forward_kinematics(self):
        q0 = numpy.zeros(self.scene.dof)
        q0[1] = 0.8  # leans the arm forward, off joint1's axis
        q1 = q0.copy()
        q1[0] = 1.0
        X0 = self.scene.forward_kinematics(q0)
        X1 = self.scene.forward_kinematics(q1)
        for X in X0.values():
            self.assertEqual(X.shape, (4, 4))
            numpy.testing.assert_allclose(X[3], [0, 0, 0, 1])
            R = X[:3, :3]
            numpy.testing.assert_allclose(R @ R.T, numpy.eye(3), atol=1e-12)
        # joint1 turns about the base's z axis: the hand turns by 1 rad about it too.
        p0, p1 = X0["hand"][:3, 3], X1["hand"][:3, 3]
        self.assertAlmostEqual(p0[2], p1[2])
        angle = numpy.arctan2(p1[1], p1[0]) - numpy.arctan2(p0[1], p0[0])
        self.assertAlmostEqual(angle, 1.0, places=9)
        with self.assertRaises(octomotion.InvalidArgument):
            self.scene.forward_kinematics(numpy.full(self.scene.dof, numpy.nan))


def command_answers(scene, scene_path, Q, *flags):
    """`octomotion check`'s valid column for the states Q."""
    with tempfile.TemporaryDirectory() as tmp:
        states = os.path.join(tmp, "states.csv")
        with open(states, "w") as f:
            f.write(",".join(scene.joint_names) + "\n")
            for q in Q:
                f.write(",".join(repr(float(v)) for v in q) + "\n")
        out = subprocess.run([CLI, "check", scene_path, "--states", states, *flags],
                             check=True, capture_output=True, text=True).stdout
    return [row["valid"] == "1" for row in csv.DictReader(io.StringIO(out))]


class RigidBodyTest(unittest.TestCase):
    """A free-flying body: seven columns, the pose's quaternion normalised, a zero one invalid."""

    @classmethod
    def setUpClass(cls):
        cls.scene = octomotion.load_scene(RIGID_SCENE)
        cls.Q = random_poses(cls.scene, 300, seed=5)
        cls.Q[3, 3:] = 0.0  # a zero quaternion

    def test_columns(self):
        self.assertTrue(self.scene.free_flying)
        self.assertEqual(self.scene.joint_names, ["x", "y", "z", "qx", "qy", "qz", "qw"])

    def test_answers(self):
        valid = self.scene.check_many(self.Q, threads=2)
        self.assertEqual(list(valid), [self.scene.check(q) for q in self.Q])
        self.assertTrue(valid.any() and not valid.all())
        self.assertFalse(valid[3])
        self.assertEqual(self.scene.explain(self.Q[3])[0].kind, "non-finite")
        if os.path.exists(CLI):
            self.assertEqual(list(valid), command_answers(self.scene, RIGID_SCENE, self.Q))

    def test_pose(self):
        q = self.Q[0]
        X = next(iter(self.scene.forward_kinematics(q).values()))
        numpy.testing.assert_allclose(X[:3, 3], q[:3], atol=1e-12)


class LoadErrorsTest(unittest.TestCase):
    def test_missing_file(self):
        with self.assertRaisesRegex(octomotion.FileError, "no_such_scene.yaml"):
            octomotion.load_scene("/nonexistent/no_such_scene.yaml")

    def test_bad_override(self):
        with self.assertRaisesRegex(octomotion.InvalidArgument, "resolution"):
            octomotion.load_scene(ARM_SCENE, resolution=-1)
        with self.assertRaisesRegex(octomotion.Error, "checker"):
            octomotion.load_scene(ARM_SCENE, checker="nonsense")
        with self.assertRaisesRegex(TypeError, "resolutoin"):
            octomotion.load_scene(ARM_SCENE, resolutoin=0.02)

    def test_hierarchy(self):
        self.assertTrue(issubclass(octomotion.FileError, octomotion.Error))
        self.assertTrue(issubclass(octomotion.InvalidArgument, octomotion.Error))
        self.assertTrue(issubclass(octomotion.InvalidArgument, ValueError))


if __name__ == "__main__":
    unittest.main()
