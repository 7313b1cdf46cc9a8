#!/usr/bin/env python3
"""octomotion from Python: the Panda in a MotionBenchMaker scene.

Loads the Panda of ../shared/data/panda in one MotionBenchMaker problem, checks --states random
states in one check_many call, plans with RRTConnect and checks the path, then runs the
speed/accuracy trade study over a few resolutions and plots check time against the false-positive
rate (states FCL calls free that the octree calls colliding) to --out (PNG).

    PYTHONPATH=build/python /usr/bin/python3 demos/python_demo.py --out demo.png

Exits 77 when the data is absent (../shared/data, see its README).
"""

import argparse
import os
import sys
import tarfile
import tempfile
import time

import numpy

import octomotion

SOURCE_DIR = os.environ.get("OCTOMOTION_SOURCE_DIR",
                            os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DATA = os.path.join(SOURCE_DIR, "..", "shared", "data")


def write_scene(folder, problem_set, index):
    """A scene YAML for one problem (as tests/validation/mbm_planning_test.cpp writes it)."""
    with tarfile.open(os.path.join(DATA, "mbm_panda", "problems.tar.bz2")) as archive:
        names = [f"problems/{problem_set}/scene{index:04d}.yaml",
                 f"problems/{problem_set}/request{index:04d}.yaml"]
        archive.extractall(folder, members=[archive.getmember(n) for n in names])
    panda = os.path.abspath(os.path.join(DATA, "panda"))
    path = os.path.join(folder, f"{problem_set}_{index:04d}.yaml")
    with open(path, "w") as f:
        f.write(f"robot: {{urdf: {panda}/panda.urdf, srdf: {panda}/panda.srdf}}\n"
                f"environment:\n  - moveit_scene: {folder}/{names[0]}\n"
                f"problem: {{moveit_request: {folder}/{names[1]}, seed: 1}}\n")
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--set", default="bookshelf_small_panda", help="MotionBenchMaker set")
    parser.add_argument("--problem", type=int, default=1, help="problem number in the set")
    parser.add_argument("--states", type=int, default=100000, help="states checked in one call")
    parser.add_argument("--threads", type=int, default=1, help="check_many's threads (0: all)")
    parser.add_argument("--time", type=float, default=10.0, help="planning time limit (s)")
    parser.add_argument("--resolutions", default="0.04,0.02,0.01,0.005",
                        help="the trade study's resolutions (m)")
    parser.add_argument("--study-states", type=int, default=5000, help="states per setting")
    parser.add_argument("--out", default="python_demo.png", help="the plot (PNG)")
    args = parser.parse_args()
    if not os.path.exists(os.path.join(DATA, "panda", "panda.urdf")) or not os.path.exists(
            os.path.join(DATA, "mbm_panda", "problems.tar.bz2")):
        print("python_demo: no Panda or MotionBenchMaker problems under", DATA)
        return 77

    with tempfile.TemporaryDirectory() as folder:
        path = write_scene(folder, args.set, args.problem)
        scene = octomotion.load_scene(path)
        print(f"{args.set} #{args.problem}: {scene.dof} joints ({', '.join(scene.joint_names)}), "
              f"checker {scene.checker} at {scene.resolution} m, objects: "
              f"{len(scene.object_names)}")

        # One call checks every state; the GIL is released while it runs.
        rng = numpy.random.default_rng(1)
        low, high = scene.bounds
        Q = rng.uniform(low, high, size=(args.states, scene.dof))
        t0 = time.perf_counter()
        valid = scene.check_many(Q, threads=args.threads)
        seconds = time.perf_counter() - t0
        print(f"check_many: {args.states} states in {seconds:.3f} s "
              f"({1e6 * seconds / args.states:.2f} us per state), {valid.mean():.1%} valid")
        colliding = Q[~valid][0]
        print("a colliding state:", "; ".join(str(r) for r in scene.explain(colliding)))

        path_q = octomotion.plan(scene, time=args.time, seed=1)
        if path_q is None:
            print(f"plan: no path found in {args.time} s")
            return 1
        if not scene.check_many(path_q).all():
            print("plan: a state of the path is invalid")
            return 1
        hand = [scene.forward_kinematics(q)["panda_hand"][:3, 3] for q in path_q]
        print(f"plan: {len(path_q)} states, the hand travels "
              f"{sum(numpy.linalg.norm(b - a) for a, b in zip(hand, hand[1:])):.2f} m")

        # The speed/accuracy curve: the fused octree checker at each resolution against FCL.
        resolutions = [float(r) for r in args.resolutions.split(",")]
        study = octomotion.trade_study(path, states=args.study_states, resolutions=resolutions,
                                       roundings=["conservative"], paths=["octree-fused"],
                                       fcl_octomap=False)
    rows = [r for r in study["checks"] if r["checker"] == "octree-fused"]
    fcl = [r for r in study["checks"] if r["checker"] == "fcl"][0]
    for r in rows:
        print(f"  {r['resolution_m']} m: {r['mean_us']:.2f} us per state, false positives "
              f"{100 * r['fp_rate']:.2f} %, {r['speedup_vs_fcl']:.1f}x FCL")
    print(f"  FCL: {fcl['mean_us']:.2f} us per state")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot([r["mean_us"] for r in rows], [100 * r["fp_rate"] for r in rows], "o-",
            label="octree-fused, conservative")
    for r in rows:
        ax.annotate(f"{100 * r['resolution_m']:g} cm", (r["mean_us"], 100 * r["fp_rate"]),
                    textcoords="offset points", xytext=(5, 5))
    ax.axvline(fcl["mean_us"], color="gray", linestyle="--", label="FCL (exact)")
    ax.set_xscale("log")
    ax.set_xlabel("mean check time per state (us)")
    ax.set_ylabel("false positives (% of free states)")
    ax.set_title(f"{args.set} #{args.problem}: speed against accuracy")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print("plot written to", args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
