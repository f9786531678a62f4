#!/usr/bin/env python3
"""Whether memory grows over a long run, per rank, after the warm-up.

Usage: rss_slope.py SAMPLES.json WARMUP BOUND_KIB LABEL [RSS_RISE_MIB]
SAMPLES.json: {"x": [frame or request index...], "rss_mb": [[rank 0, rank 1, ...] per sample],
"heap_mb": [[...] per sample]} (heap_mb optional).

Two checks per rank:
- the least-squares slope of the heap in use (heap_mb, mallinfo2: bytes malloc handed out and did
  not get back) stays below BOUND_KIB per step. A leak of a buffer per frame shows here at its size.
  Without heap_mb in the samples the slope is taken of rss_mb instead.
- resident memory (rss_mb, VmRSS) rises by at most RSS_RISE_MIB (default 8) from the first sample
  after the warm-up to the largest later one: growth that bypasses malloc (mmapped driver memory).
Why not the slope of VmRSS: it rises in steps of about 1 MiB when the allocator or llvmpipe takes a
new block of pages and keeps it (service soak: steps near requests 400 and 830 on both ranks, flat
afterwards, while the heap in use grew 0.03-0.05 KiB a request); where the steps fall decides the
fitted slope, which read 1.0 KiB a request in one run here and 2.5 in one CI run.
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
    rise_bound = float(sys.argv[5]) if len(sys.argv) > 5 else 8.0
    s = json.load(open(samples))
    key = "heap_mb" if "heap_mb" in s else "rss_mb"
    idx = [i for i, x in enumerate(s["x"]) if x >= warmup]
    if len(idx) < 20:
        print(f"{label}: only {len(idx)} samples after the warm-up of {warmup}")
        return 1
    xs = [s["x"][i] for i in idx]
    ok = True
    for rank in range(len(s["rss_mb"][idx[0]])):
        ys = [s[key][i][rank] * 1024.0 for i in idx]  # KiB
        k = slope(xs, ys)
        rss = [s["rss_mb"][i][rank] for i in idx]
        rise = max(rss) - rss[0]
        good = k < bound and rise <= rise_bound
        ok = ok and good
        print(f"{label}: rank {rank}: {key} slope {k:+.3f} KiB per step over {len(xs)} samples "
              f"(x {xs[0]}..{xs[-1]}, {ys[0] / 1024:.2f} -> {ys[-1] / 1024:.2f} MiB; bound {bound} KiB), "
              f"RSS {rss[0]:.1f} -> {rss[-1]:.1f} MiB, rise {rise:.1f} (bound {rise_bound} MiB): "
              f"{'ok' if good else 'GROWS'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
