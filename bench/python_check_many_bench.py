#!/usr/bin/env python3
"""Scene.check_many's time per state against the C++ per-state time on the same states.

The C++ figure is `octomotion check`'s own per-state timing (the OMPL validity checker's isValid,
the call check_many makes per row), summed over the same states file; the Python figure is one
check_many call over the array, divided by N, in the calling thread's CPU time (the command's
short per-state intervals leave out most of the time its process waits for a core; a batch of
10 ms or more on a loaded machine does not), with the wall-clock time beside it. Each is the
best of --repeats runs, the two interleaved. Also shown: a Python
loop of Scene.check, one call per state. Exits 1 if check_many and the command disagree.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_check_many_bench.py --cli build/planner/octomotion
"""

import argparse
import csv
import io
import os
import subprocess
import sys
import tempfile
import time

import numpy

import octomotion


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=os.path.join(root, "robots/scenes/bookshelf.yaml"))
    parser.add_argument("--resolution", default="0.01")
    parser.add_argument("--states", default="1000,10000", help="N values, comma-separated")
    parser.add_argument("--repeats", type=int, default=9)
    parser.add_argument("--cli", default=os.path.join(root, "build/planner/octomotion"))
    args = parser.parse_args()

    scene = octomotion.load_scene(args.scene, resolution=float(args.resolution))
    print(f"scene {os.path.basename(args.scene)} at {args.resolution} m, checker {scene.checker}, "
          f"{scene.dof} joints; best of {args.repeats} interleaved runs, one thread")
    print(f"{'N':>7} {'valid':>6} {'C++ us/state':>13} {'check_many':>11} {'ratio':>6} "
          f"{'(wall)':>8} {'check loop':>11}")
    rng = numpy.random.default_rng(1)
    low, high = scene.bounds
    ok = True
    for n in (int(s) for s in args.states.split(",")):
        Q = rng.uniform(low, high, size=(n, scene.dof))
        scene.check_many(Q)  # warm the caches and the per-thread scratch
        python, wall, cpp, loop = [], [], [], []
        with tempfile.TemporaryDirectory() as tmp:
            states = os.path.join(tmp, "states.csv")
            with open(states, "w") as f:
                f.write(",".join(scene.joint_names) + "\n")
                for q in Q:
                    f.write(",".join(repr(float(v)) for v in q) + "\n")
            # Interleaved, so both see the same machine load.
            for _ in range(args.repeats):
                t0, c0 = time.perf_counter(), time.thread_time()
                valid = scene.check_many(Q)
                python.append((time.thread_time() - c0) / n * 1e6)
                wall.append((time.perf_counter() - t0) / n * 1e6)
                out = subprocess.run([args.cli, "check", args.scene, "--states", states,
                                      "--resolution", args.resolution],
                                     check=True, capture_output=True, text=True).stdout
                rows = list(csv.DictReader(io.StringIO(out)))
                cpp.append(sum(int(r["time_ns"]) for r in rows) / n / 1e3)
                if [r["valid"] == "1" for r in rows] != list(valid):
                    ok = False
        for _ in range(max(1, args.repeats // 3)):
            t0 = time.perf_counter()
            for q in Q:
                scene.check(q)
            loop.append((time.perf_counter() - t0) / n * 1e6)
        p, c = min(python), min(cpp)
        print(f"{n:>7} {valid.mean():>6.1%} {c:>13.3f} {p:>11.3f} {p / c:>6.3f} "
              f"{min(wall):>8.3f} {min(loop):>11.3f}")
    print("check_many and `octomotion check` agree on every state" if ok else
          "check_many and `octomotion check` DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
