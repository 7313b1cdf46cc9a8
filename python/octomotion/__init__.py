"""octomotion: voxel-octree collision checking and OMPL planning from Python.

    import numpy, octomotion
    scene = octomotion.load_scene("robots/scenes/bookshelf.yaml")
    valid = scene.check_many(Q)          # Q: (N, scene.dof) float64 -> (N,) bool
    path = octomotion.plan(scene, time=1.0, seed=1)

See docs/python.md for the reference.
"""

import csv
import io

from ._octomotion import (
    Error,
    FileError,
    InvalidArgument,
    Reason,
    Scene,
    plan,
    _bench_set,
    _load_scene,
    _trade_study,
)

__all__ = [
    "Error",
    "FileError",
    "InvalidArgument",
    "Reason",
    "Scene",
    "bench_set",
    "load_scene",
    "plan",
    "trade_study",
]

# Keyword -> the `octomotion` command's flag (tools::sceneOptions()).
_SCENE_OPTIONS = {
    "resolution": "--resolution",
    "rounding": "--rounding",
    "checker": "--checker",
    "planner": "--planner",
    "time": "--time",
    "seed": "--seed",
    "package_paths": "--package-path",
    "max_surface_voxels": "--max-surface-voxels",
    "link_resolution": "--link-resolution",
    "self_link_resolution": "--self-link-resolution",
    "self_pair_tables": "--self-pair-tables",
    "exact_primitives": "--exact-primitives",
    "refine": "--refine",
    "motion_validator": "--motion-validator",
}

# Keyword -> `octomotion bench`'s flag (tools::studyOptions()); lists are comma-separated.
_STUDY_OPTIONS = {
    "states": "--states",
    "move_tree_states": "--move-tree-states",
    "runs": "--runs",
    "resolutions": "--resolutions",
    "roundings": "--roundings",
    "paths": "--paths",
    "planners": "--planners",
    "link_ratio": "--link-ratio",
    "self_link_ratio": "--self-link-ratio",
    "time": "--time",
    "seed": "--seed",
    "package_paths": "--package-path",
    "max_surface_voxels": "--max-surface-voxels",
    "self_pair_tables": "--self-pair-tables",
    "exact_primitives": "--exact-primitives",
}


def _value(value):
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, (list, tuple)):
        return ",".join(_value(v) for v in value)
    return str(value)


def _flags(function, table, options):
    flags = []
    for key, value in options.items():
        if key not in table:
            raise TypeError(
                f"{function}() got an unexpected keyword argument '{key}' "
                f"(known: {', '.join(sorted(table))})"
            )
        if value is None:
            continue
        if key == "package_paths":
            paths = [value] if isinstance(value, str) else list(value)
            flags.extend((table[key], str(p)) for p in paths)
        else:
            flags.append((table[key], _value(value)))
    return flags


def load_scene(path, *, require_free_start_goal=False, fit_universe_to_reach=False, **overrides):
    """Loads a scene file (YAML or OMPL.app .cfg) as `octomotion check` does.

    overrides: the command line's scene options as keywords (resolution=0.02 or "auto",
    rounding, checker, planner, time, seed, package_paths, max_surface_voxels,
    link_resolution, self_link_resolution, self_pair_tables, exact_primitives, refine,
    motion_validator).
    require_free_start_goal: refuse a scene whose start or goal collides (as `octomotion plan`).
    fit_universe_to_reach: size the octree universe for a world that changes (add_object).
    """
    flags = _flags("load_scene", _SCENE_OPTIONS, overrides)
    return _load_scene(str(path), flags, bool(require_free_start_goal), bool(fit_universe_to_reach))


def _number(text):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def _rows(text):
    return [{k: _number(v) for k, v in row.items()} for row in csv.DictReader(io.StringIO(text))]


def trade_study(path, *, states=2000, runs=0, fcl_octomap=True, plan_every_setting=False, **options):
    """The speed/accuracy trade study of a scene (`octomotion bench`), without files.

    options: `octomotion bench`'s flags as keywords (states, runs, resolutions=[0.04, 0.02],
    roundings=["conservative"], paths=["octree-fused"], planners=["RRTConnect:1"], link_ratio,
    self_link_ratio, move_tree_states, time, seed, package_paths, max_surface_voxels,
    self_pair_tables, exact_primitives). Returns {"checks": [...], "planning": [...]}, one dict per
    row of the study's CSVs (docs/trade-off.md names the columns).
    """
    options = dict(options, states=states, runs=runs)
    flags = _flags("trade_study", _STUDY_OPTIONS, options)
    if not fcl_octomap:
        flags.append(("--no-fcl-octomap", ""))
    if plan_every_setting:
        flags.append(("--plan-every-setting", ""))
    checks, planning = _trade_study(str(path), flags)
    return {"checks": _rows(checks), "planning": _rows(planning)}


def bench_set(
    dir,
    *,
    checkers=("octree-fused", "fcl"),
    robot=None,
    srdf=None,
    fixed=None,
    runs=1,
    limit=0,
    recheck_density=100,
    log_dir=None,
    **overrides,
):
    """The planning benchmark over a folder of problems (`octomotion bench-set`, docs/benchmarking.md).

    dir: scene files, MoveIt scene/request pairs (the MotionBenchMaker layout), or a folder of such
    sets. Each problem is planned with each checker in turn and every solved path is re-checked
    with exact FCL at `recheck_density` times the motion step's density. robot/srdf (and `fixed`,
    {joint: value}) are the robot of MoveIt pairs. overrides: load_scene's keywords (planner,
    time, seed, resolution, ...). log_dir: where OMPL's benchmark logs are written (none if None).
    Returns {"runs": [one dict per problem, checker and run], "summary": [one dict per set and
    checker, then "all"], "logs": [files], "seconds": wall time}.
    """
    flags = _flags("bench_set", _SCENE_OPTIONS, overrides)
    names = [checkers] if isinstance(checkers, str) else list(checkers)
    csv_text, summary, logs, seconds = _bench_set(
        str(dir),
        [str(c) for c in names],
        "" if robot is None else str(robot),
        "" if srdf is None else str(srdf),
        {str(k): float(v) for k, v in (fixed or {}).items()},
        int(runs),
        int(limit),
        float(recheck_density),
        "" if log_dir is None else str(log_dir),
        flags,
    )
    return {"runs": _rows(csv_text), "summary": list(summary), "logs": list(logs), "seconds": seconds}
