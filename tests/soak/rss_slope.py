#!/usr/bin/env python3
"""Least-squares slope of resident memory over a long run, per rank, after the warm-up.

Usage: rss_slope.py SAMPLES.json WARMUP BOUND_KIB LABEL
SAMPLES.json: {"x": [frame or request index...], "rss_mb": [[rank 0, rank 1, ...] per sample]}.
Prints one line per rank (slope in KiB per frame/request, growth after the warm-up) and exits 1 if
any rank's slope reaches BOUND_KIB. A leak of a few KiB per frame shows as a slope of that size;
the allocator's and the GL driver's settling shows in the warm-up, which is left out.
"""
import json
import sys


def slope(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def main():
    samples, warmup, bound, label = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
    s = json.load(open(samples))
    pairs = [(x, r) for x, r in zip(s["x"], s["rss_mb"]) if x >= warmup]
    if len(pairs) < 20:
        print(f"{label}: only {len(pairs)} samples after the warm-up of {warmup}")
        return 1
    xs = [p[0] for p in pairs]
    ok = True
    for rank in range(len(pairs[0][1])):
        ys = [p[1][rank] * 1024.0 for p in pairs]  # KiB
        k = slope(xs, ys)
        verdict = "ok" if k < bound else "GROWS"
        ok = ok and k < bound
        print(f"{label}: rank {rank}: slope {k:+.3f} KiB per step over {len(xs)} samples "
              f"(x {xs[0]}..{xs[-1]}), RSS {ys[0] / 1024:.1f} -> {ys[-1] / 1024:.1f} MiB, "
              f"bound {bound} KiB: {verdict}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
