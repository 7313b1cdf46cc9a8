"""Shared by the Python tests: the shipped arm scene, seeded states, the CLI."""

import os
import numpy

SOURCE_DIR = os.environ.get(
    "OCTOMOTION_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")
)
# The octo7 arm in front of a bookshelf (robots/scenes/bookshelf.yaml), at a coarse resolution
# so that the tests build it quickly.
ARM_SCENE = os.path.join(SOURCE_DIR, "robots", "scenes", "bookshelf.yaml")
RESOLUTION = 0.02
CLI = os.environ.get("OCTOMOTION_CLI", "")


def random_states(scene, count, seed, margin=0.1):
    """Uniform states over the space's bounds widened by `margin` (some fall outside them)."""
    rng = numpy.random.default_rng(seed)
    low, high = scene.bounds
    span = high - low
    return rng.uniform(low - margin * span, high + margin * span, size=(count, scene.dof))

# A free-flying drone in three rooms (robots/scenes/rooms.yaml): states are x y z qx qy qz qw.
RIGID_SCENE = os.path.join(SOURCE_DIR, "robots", "scenes", "rooms.yaml")


def random_poses(scene, count, seed):
    """Positions uniform in the bounds, unit quaternions uniform over rotations."""
    rng = numpy.random.default_rng(seed)
    low, high = scene.bounds
    xyz = rng.uniform(low[:3], high[:3], size=(count, 3))
    quat = rng.normal(size=(count, 4))
    quat /= numpy.linalg.norm(quat, axis=1, keepdims=True)
    return numpy.ascontiguousarray(numpy.hstack([xyz, quat]))
