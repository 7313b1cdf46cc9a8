#!/usr/bin/env python3
"""Checks the library's layering from its #include lines (docs/architecture.md, "Layers").

Every source and header of octree/, planner/ and tools/ belongs to one layer; a file may include
its own layer and the layers below it, never one above (the FCL references in reference/
implement the collision-backend interface of model/; the octree model never sees them). Also:
nothing below ompl/ includes OMPL, and no library file is longer than MAX_LINES.
Exit status 1 with one line per violation. Usage: check_layers.py [ROOT] or --self-test (the
check against a made-up tree with known violations).
"""
import os
import re
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
MAX_LINES = 650

# (layer, rank): a file may include layers of lower rank, and its own layer.
RANKS = {"octree": 0, "robot": 1, "scene": 2, "model": 3, "reference": 4, "ompl": 5, "tools": 6}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]', re.M)


def layer_of_path(rel):
    """The layer of a repository file, or None for files outside the libraries."""
    parts = rel.split("/")
    if parts[0] == "octree":
        return "octree"
    if parts[0] == "tools":
        return "tools"
    if parts[0] == "planner":
        for p in parts[1:]:
            if p in RANKS and p not in ("octree", "tools"):
                return p
        if len(parts) > 1 and parts[1] == "cli":
            return "tools"
    return None


def layer_of_include(name, including_file):
    """The layer an #include names, or None for third-party and standard headers."""
    if name.startswith("octomotion/planner/"):
        sub = name.split("/")[2]
        return sub if sub in RANKS else "tools"
    if name.startswith("octomotion/tools/"):
        return "tools"
    if name.startswith("octomotion/"):
        return "octree"
    if name.startswith("ompl/"):
        return "ompl-third-party"
    if not name.endswith(".h"):
        return None
    # A relative include: resolve against the including file's folder.
    path = os.path.normpath(os.path.join(os.path.dirname(including_file), name))
    if os.path.exists(path):
        return layer_of_path(os.path.relpath(path, ROOT))
    return None


def violations_in(root):
    global ROOT
    ROOT = root
    violations = []
    for top in ("octree", "planner", "tools"):
        for dirpath, _, files in os.walk(os.path.join(ROOT, top)):
            for f in files:
                if not f.endswith((".h", ".cpp")):
                    continue
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, ROOT)
                layer = layer_of_path(rel)
                if layer is None:
                    continue
                text = open(path, encoding="utf-8").read()
                lines = text.count("\n")
                if lines > MAX_LINES:
                    violations.append(f"{rel}: {lines} lines (at most {MAX_LINES})")
                for name in INCLUDE.findall(text):
                    target = layer_of_include(name, path)
                    if target is None or target == layer:
                        continue
                    if target == "ompl-third-party":
                        if RANKS[layer] < RANKS["ompl"]:
                            violations.append(f"{rel}: layer {layer} includes OMPL <{name}>")
                        continue
                    if RANKS[target] > RANKS[layer] or RANKS[target] == RANKS[layer]:
                        violations.append(f"{rel}: layer {layer} includes {name} (layer {target})")
    return violations


def self_test():
    """The check finds what it must on a made-up tree, and nothing on a clean one."""
    import tempfile

    def write(root, rel, text):
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)

    with tempfile.TemporaryDirectory() as root:
        inc = "planner/include/octomotion/planner/"
        write(root, inc + "robot/robot.h", '#include "octomotion/octree/octree.h"\n')
        write(root, inc + "model/model.h", '#include "octomotion/planner/robot/robot.h"\n')
        write(root, inc + "ompl/glue.h", '#include <ompl/base/State.h>\n#include "octomotion/planner/model/model.h"\n')
        write(root, "planner/src/model/internal/part.h", "#pragma once\n")
        write(root, "planner/src/model/model.cpp", '#include "internal/part.h"\n')
        write(root, "tools/cli/main.cpp", '#include "octomotion/planner/ompl/glue.h"\n')
        clean = violations_in(root)
        if clean:
            print("self-test: a clean tree was reported:", *clean, sep="\n  ")
            return 1
        write(root, inc + "model/bad.h", '#include "octomotion/planner/ompl/glue.h"\n')
        write(root, "planner/src/robot/bad.cpp", '#include <ompl/base/State.h>\n#include "../model/internal/part.h"\n')
        write(root, "octree/src/long.cpp", "//\n" * (MAX_LINES + 1))
        found = violations_in(root)
        expected = ["model/bad.h: layer model includes octomotion/planner/ompl/glue.h",
                    "robot/bad.cpp: layer robot includes OMPL", "robot/bad.cpp: layer robot includes ../model",
                    "octree/src/long.cpp: "]
        missing = [e for e in expected if not any(e in v for v in found)]
        if missing or len(found) != len(expected):
            print("self-test: expected", expected, "found", found, sep="\n  ")
            return 1
    print("self-test: ok")
    return 0


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--self-test":
        return self_test()
    violations = violations_in(ROOT)
    for v in violations:
        print(v)
    if violations:
        print(f"{len(violations)} layering violation(s); see docs/architecture.md", file=sys.stderr)
        return 1
    print("layers: octree -> robot -> scene -> model -> reference -> ompl -> tools, no arrow back")
    return 0


if __name__ == "__main__":
    sys.exit(main())
