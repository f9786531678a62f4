#!/usr/bin/env python3
"""emitters.py N [SCALE]: the benchmarks' seeded list of N glow emitters as a YAML flow list
(for --set glow.emitters=...): centres uniform in [-1.5, 1.5]^3 times SCALE, Gaussian directions,
a and b uniform in [0.2, 1], colours uniform in [0.2, 1]. Used by bench/glow/run and
bench/glow/run-cpu, so both measure the same emitters."""
import random
import sys

n = int(sys.argv[1])
k = float(sys.argv[2]) if len(sys.argv) > 2 else 1.0
g = random.Random(16)
out = []
for _ in range(n):
    c = [k * g.uniform(-1.5, 1.5) for _ in range(3)]
    d = [g.gauss(0, 1) for _ in range(3)]
    col = [g.uniform(0.2, 1) for _ in range(3)]
    out.append("{center: [%g, %g, %g], direction: [%g, %g, %g], a: %g, b: %g, color: [%g, %g, %g]}"
               % (*c, *d, g.uniform(0.2, 1), g.uniform(0.2, 1), *col))
print("[" + ", ".join(out) + "]")
