"""How `compositing.strategy: auto` does on the simulated sweep (docs/smpi.md).

Joins bench_scale's simulated times (the sweep CSVs) with forecast_sweep's forecasts of the same
points and reports, per point, the strategy auto chooses, its simulated time against the best
simulated strategy's, and the forecast's error per strategy. Writes a CSV, a markdown table and
a chart (forecast against simulated seconds).

    python3 bench/scale/auto.py FORECAST.csv SWEEP.csv... --out results/scale/auto
"""
import argparse
import collections
import csv
import math
import sys


def key(r):
    return (r["platform"], r["precision"], r["rle"], int(r["ranks"]), int(r["width"]), float(r["coverage"]))


def label(strategy, radix):
    return f"radix-k k={radix}" if strategy == "radix-k" else strategy


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("forecast")
    ap.add_argument("sweeps", nargs="+")
    ap.add_argument("--out", required=True, help="prefix of the .csv, .md and .png written")
    ap.add_argument("--tolerance", type=float, default=0.10)
    a = ap.parse_args()
    sim = collections.defaultdict(dict)
    ran = {}  # point -> (the strategy auto chose in the simulation, its simulated seconds)
    for path in a.sweeps:
        for r in csv.DictReader(open(path)):
            if r["strategy"] == "auto":  # radix column: auto:NAME[:k]
                parts = r["radix"].split(":")
                ran[key(r)] = (label(parts[1], parts[2] if len(parts) > 2 else ""), float(r["seconds"]))
                continue
            sim[key(r)][label(r["strategy"], r["radix"])] = float(r["seconds"])
    fc = collections.defaultdict(dict)
    chosen = {}
    for r in csv.DictReader(open(a.forecast)):
        k = key(r)
        fc[k][label(r["strategy"], r["radix"])] = float(r["forecast_s"])
        if r["chosen"] == "1":
            chosen[k] = label(r["strategy"], r["radix"])
    rows, bad, unsimulated, ratios = [], 0, 0, collections.defaultdict(list)
    for k in sorted(sim, key=lambda k: (k[0], k[1], k[2], k[4], k[3])):
        if k not in chosen and k in ran:  # real layers: no forecast here, auto's own choice
            chosen[k] = ran[k][0]
        if k not in chosen:
            print(f"no forecast for {k}", file=sys.stderr)
            continue
        s, f, c = sim[k], fc[k], chosen[k]
        best = min(s, key=s.get)
        if k in ran:  # auto itself ran there: its choice must be the forecast's, its time the choice's
            if ran[k][0] != c:
                print(f"{k}: auto chose {ran[k][0]} in the simulation, the forecast says {c}", file=sys.stderr)
                bad += 1
            elif c in s and abs(ran[k][1] / s[c] - 1) > 0.01:
                print(f"{k}: auto took {ran[k][1]:.6g} s, {c} alone {s[c]:.6g} s", file=sys.stderr)
        for name, t in s.items():
            if name in f:
                ratios[name].append(f[name] / t)
        if c not in s:
            unsimulated += 1
            rows.append(list(k) + [c, "", best, s[best], "", "not simulated"])
            continue
        over = s[c] / s[best] - 1
        ok = over <= a.tolerance
        bad += not ok
        rows.append(list(k) + [c, s[c], best, s[best], over, "ok" if ok else "over"])
    with open(a.out + ".csv", "w") as o:
        w = csv.writer(o)
        w.writerow(["platform", "precision", "rle", "ranks", "width", "coverage", "auto", "auto_s",
                    "best", "best_s", "auto_over_best", "verdict"])
        for r in rows:
            w.writerow(r[:6] + [r[6], f"{r[7]:.6g}" if r[7] != "" else "", r[8], f"{r[9]:.6g}",
                                f"{r[10]:.4f}" if r[10] != "" else "", r[11]])
    n = len(rows)
    worst = max((r for r in rows if r[10] != ""), key=lambda r: r[10], default=None)
    lines = [f"# `compositing.strategy: auto` on the simulated sweep", "",
             f"Written by `bench/scale/auto.py`. {n} points; auto within "
             f"{100 * a.tolerance:.0f} % of the best simulated strategy at {n - bad - unsimulated} "
             f"of {n - unsimulated} simulated choices; auto itself ran in the simulation at "
             f"{sum(k in ran for k in sim)} points, choosing as forecast at "
             f"{sum(k in ran and ran[k][0] == chosen.get(k) for k in sim)}" +
             (f" ({unsimulated} choices not simulated)" if unsimulated else "") +
             (f"; worst +{100 * worst[10]:.1f} % ({worst[0]}, {worst[3]} ranks, {worst[4]}², {worst[6]} "
              f"against {worst[8]})" if worst else "") + ".", "",
             "Forecast ÷ simulated, per strategy (median, range):", ""]
    for name in sorted(ratios):
        v = sorted(ratios[name])
        lines.append(f"- {name}: {v[len(v) // 2]:.2f} ({v[0]:.2f}–{v[-1]:.2f}, {len(v)} points)")
    lines += ["", "| platform | precision | RLE | P | image | coverage | auto | auto s | best | best s | over |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} | {r[4]}² | {r[5]:g} | {r[6]} | "
                     + (f"{r[7]:.4f}" if r[7] != "" else "–") + f" | {r[8]} | {r[9]:.4f} | "
                     + (f"{100 * r[10]:+.1f} %" if r[10] != "" else r[11]) + " |")
    open(a.out + ".md", "w").write("\n".join(lines) + "\n")
    print("\n".join(lines[:4 + len(ratios) + 3]))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return 1 if bad else 0
    fig, ax = plt.subplots(figsize=(6.5, 6))
    marks = {"direct": "o", "binary-swap": "s", "radix-k k=4": "^", "radix-k k=8": "v", "radix-k k=16": "D"}
    for name in sorted(ratios):
        xs = [sim[k][name] for k in sim if name in sim[k] and name in fc.get(k, {})]
        ys = [fc[k][name] for k in sim if name in sim[k] and name in fc.get(k, {})]
        ax.scatter(xs, ys, label=name, marker=marks.get(name, "x"), s=18)
    lo = min(min(v.values()) for v in sim.values()) / 2
    hi = max(max(v.values()) for v in sim.values()) * 2
    ax.plot([lo, hi], [lo, hi], "k-", lw=0.8)
    ax.plot([lo, hi], [lo * 2, hi * 2], "k:", lw=0.6)
    ax.plot([lo, hi], [lo / 2, hi / 2], "k:", lw=0.6)
    ax.set_xscale("log"), ax.set_yscale("log")
    ax.set_xlabel("simulated seconds (SMPI)"), ax.set_ylabel("forecast seconds (strategy_model)")
    ax.set_title(f"auto's cost model against the simulation ({n} points; dotted: 2x)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=110)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
