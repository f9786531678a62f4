#!/usr/bin/env python3
"""The layers of CONTRIBUTING.md, checked: every #include "folder/..." in a folder's sources names
a folder at or below its own layer (lower layers first in LAYERS). A folder that is not listed, or
an include that runs back up, fails with the file and line. Exit 0: no include runs up."""
import os
import re
import sys

# Lowest first. A folder may include its own files and those of any folder before it. Folders on
# one line are one layer: neither may include the other.
LAYERS = [
    ["common"],
    ["subdiv", "transfer", "glow", "adaptive", "io"],
    ["scene"],
    ["compositing"],
    ["render"],
    ["reference"],
    ["session"],
    ["service"],
    ["app", "insitu", "python"],
]
# Trees of their own that sit on top of everything: tests, benchmarks, examples.
TOP = {"tests", "bench", "examples", "include"}

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
rank = {f: i for i, layer in enumerate(LAYERS) for f in layer}
include = re.compile(r'^\s*#\s*include\s+"([A-Za-z0-9_]+)/')
problems = []
for folder in sorted(rank):
    for dirpath, _, files in os.walk(os.path.join(root, folder)):
        for name in sorted(files):
            if not name.endswith((".h", ".cpp", ".c")):
                continue
            path = os.path.join(dirpath, name)
            for n, line in enumerate(open(path, encoding="utf-8", errors="replace"), 1):
                m = include.match(line)
                if not m:
                    continue
                target = m.group(1)
                if target in ("sortlast", "generated"):  # the public API headers; build outputs
                    continue
                if target in TOP or target not in rank:
                    problems.append(f"{os.path.relpath(path, root)}:{n}: includes {target}/, "
                                    "which is not a layer (CONTRIBUTING.md)")
                elif target != folder and rank[target] >= rank[folder]:
                    problems.append(f"{os.path.relpath(path, root)}:{n}: {folder}/ includes {target}/, "
                                    "a layer at or above its own (CONTRIBUTING.md)")
# Every top-level folder with sources is a layer or a top tree: a new folder gets its place.
for entry in sorted(os.listdir(root)):
    p = os.path.join(root, entry)
    if (os.path.isdir(p) and not entry.startswith((".", "build")) and entry not in rank and entry not in TOP
            and any(f.endswith((".h", ".cpp")) for _, _, fs in os.walk(p) for f in fs)):
        problems.append(f"{entry}/: a folder of sources with no layer in tests/layout/check_layers.py")
for p in problems:
    print(p)
print(f"{len(problems)} include(s) out of order" if problems else "layers: no include runs back up")
sys.exit(1 if problems else 0)
