#!/usr/bin/env python3
"""Checks that no source file includes a header of a higher layer.

The layers, lowest first (docs/DESIGN.md says what each holds). A file may
include headers of its own layer and of any layer below it:

    tools/check_layers.py [ROOT]

prints every include that points up and exits with 1 if there is one.
"""
import os
import re
import sys

# Lowest first. backend/cpu and backend/cuda are the execution policies, which
# build cell lists (neighbor/); engine/instances compiles the engine's
# templates for each policy.
LAYERS = [
    "core",
    "backend",
    "neighbor",
    "walls",
    "contact",
    "integrate",
    "backend/cpu",
    "backend/cuda",
    "io",
    "scene",
    "analysis",
    "engine",
    "engine/instances",
    "decomposition",
    "comm",
    "run",
    "app",
]
RANK = {name: k for k, name in enumerate(LAYERS)}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def layer_of(path):
    """The layer of a path relative to src/ (or comm/, decomposition/)."""
    parts = path.split("/")
    if len(parts) > 2 and "/".join(parts[:2]) in RANK:
        return "/".join(parts[:2])
    return parts[0] if parts[0] in RANK else None


def main(root):
    problems = []
    for top in ("src", "comm", "decomposition"):
        for directory, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if not name.endswith((".hpp", ".cpp", ".cu", ".cuh")):
                    continue
                path = os.path.join(directory, name)
                relative = os.path.relpath(path, os.path.join(root, "src") if top == "src" else root)
                mine = layer_of(relative)
                if mine is None:
                    problems.append(f"{path}: in no layer of tools/check_layers.py")
                    continue
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for target in INCLUDE.findall(text):
                    theirs = layer_of(target)
                    if theirs is not None and RANK[theirs] > RANK[mine]:
                        problems.append(f"{path}: layer {mine} includes {target} of the higher layer {theirs}")
    for p in problems:
        print(p)
    if not problems:
        print(f"layers: no include points up ({len(LAYERS)} layers)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")))
