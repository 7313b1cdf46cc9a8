#!/usr/bin/env python3
"""Checks the library's layering from its #include lines (docs/architecture.md, "Layers").

Every source and header of octree/, planner/ and tools/ belongs to one layer; a file may include
its own layer and the layers below it, never one above (the FCL references in reference/
implement the collision-backend interface of model/; the octree model never sees them). Also: no header that `cmake --install` ships includes OMPL
outside ompl/, and no library file is longer than MAX_LINES.
Exit status 1 with one line per violation.
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


def main():
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
    for v in violations:
        print(v)
    if violations:
        print(f"{len(violations)} layering violation(s); see docs/architecture.md", file=sys.stderr)
        return 1
    print("layers: octree -> robot -> scene -> model -> reference -> ompl -> tools, no arrow back")
    return 0


if __name__ == "__main__":
    sys.exit(main())
