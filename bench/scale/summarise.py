"""Charts and a summary of bench/scale/run's CSVs (results/scale/, docs/smpi.md).

    /usr/bin/python3 bench/scale/summarise.py OUT_DIR

Reads OUT_DIR/{bench-scale,validation,big}.csv (those present) and writes:
  time_<platform>.png   simulated seconds against P per strategy (float, RLE on), one panel per
                        image size, with the cost model fitted on this machine at 2-8 ranks
                        (results/compositing/fit.md: t = a*messages + b*bytes + g*pixels, totals
                        over all ranks; radix-k's k = 4 fit stands for every k) applied to the
                        simulated run's own counts, dashed;
  bytes_per_rank.png    the most bytes one rank sent, and all ranks' bytes, against P (fat tree);
  validation.png        simulated against measured seconds at 2-8 ranks;
  summary.md            the tables behind them.
"""
import csv
import math
import os
import re
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def load(name):
    path = os.path.join(out, name)
    if not os.path.exists(path):
        return []
    rows = list(csv.DictReader(open(path)))
    for r in rows:
        for k in ("ranks", "width", "active_ranks"):
            r[k] = int(float(r[k]))
        for k in ("seconds", "bytes_sent", "max_rank_bytes", "messages", "pixels_composited", "layer_pixels"):
            r[k] = float(r[k])
        r["name"] = r["strategy"] if r["strategy"] in ("direct", "binary-swap", "auto") else f"radix-k k={r['radix']}"
    return rows


# The strategies' own runs at coverage 0.4 (auto's runs and other coverages: auto.py).
sweep = [r for r in load("bench-scale.csv") + load("sweep-k32.csv") + load("big.csv")
         if r["strategy"] != "auto" and abs(float(r["coverage"]) - 0.4) < 1e-9]
valid = load("validation.csv")

# The fitted model (non-negative fit, the first table of fit.md).
fits = {}
fit_md = os.path.join(root, "results", "compositing", "fit.md")
if os.path.exists(fit_md):
    for line in open(fit_md):
        m = re.match(r"\| (direct|binary-swap k=2|radix-k k=4) (float|rgba8) rle-(on|off) \| \d+ \| "
                     r"([\d.]+) \| ([\d.]+) \| ([\d.]+) \|", line)
        if m and (m.group(1), m.group(2), m.group(3)) not in fits:
            fits[(m.group(1), m.group(2), m.group(3))] = (float(m.group(4)) * 1e-6, float(m.group(5)) * 1e-9,
                                                           float(m.group(6)) * 1e-9)


def predict(r):
    key = {"direct": "direct", "binary-swap": "binary-swap k=2"}.get(r["strategy"], "radix-k k=4")
    f = fits.get((key, r["precision"], r["rle"]))
    if not f:
        return None
    return f[0] * r["messages"] + f[1] * r["bytes_sent"] + f[2] * r["pixels_composited"]


colours = {"direct": "tab:red", "binary-swap": "tab:blue", "radix-k k=4": "tab:green",
           "radix-k k=8": "tab:purple", "radix-k k=16": "tab:brown", "radix-k k=32": "tab:olive"}
md = ["# Compositing at scale: summary", "",
      "Written by `bench/scale/summarise.py` from the CSVs here. Simulated seconds: SimGrid SMPI, "
      "the real strategies, compute charged at `rates.csv` (one simulated host = one core of the "
      "measuring machine). Synthetic sphere layers, coverage 0.4.", ""]

base = [r for r in sweep if r["precision"] == "float" and r["rle"] == "on"]
for plat in sorted({r["platform"] for r in base}):
    rows = [r for r in base if r["platform"] == plat]
    sizes = sorted({r["width"] for r in rows})
    fig, axes = plt.subplots(1, len(sizes), figsize=(4.2 * len(sizes), 4.2), squeeze=False)
    for ax, size in zip(axes[0], sizes):
        for name in sorted({r["name"] for r in rows}, key=lambda n: list(colours).index(n) if n in colours else 9):
            pts = sorted((r["ranks"], r["seconds"], predict(r)) for r in rows if r["width"] == size and r["name"] == name)
            if not pts:
                continue
            c = colours.get(name, "black")
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=c, label=name)
            model = [(p[0], p[2]) for p in pts if p[2]]
            if model:
                ax.plot([m[0] for m in model], [m[1] for m in model], "--" if len(model) > 1 else "x",
                        color=c, alpha=0.5)
        if size == 8192:
            ax.axhline(0.08, color="gray", lw=0.8, ls=":")
            ax.text(0.03, 0.085, "0.08 s (BG/P anchor)", color="gray", fontsize=8,
                    transform=ax.get_yaxis_transform())
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_title(f"{plat}, {size}²")
        ax.set_xlabel("simulated hosts P")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("seconds per frame (simulated)")
    axes[0][0].legend(fontsize=8, title="solid: simulated\ndashed: fitted model", title_fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"time_{plat}.png"), dpi=90)
    plt.close(fig)

    md += [f"## {plat}: seconds per frame (float, RLE on)", "",
           "| image | P | " + " | ".join(n for n in colours if any(r['name'] == n for r in rows)) + " | best | model (best's) |",
           "|---|---|" + "---|" * (sum(any(r['name'] == n for r in rows) for n in colours) + 2)]
    for size in sizes:
        for p in sorted({r["ranks"] for r in rows if r["width"] == size}):
            cell = {r["name"]: r for r in rows if r["width"] == size and r["ranks"] == p}
            best = min(cell.values(), key=lambda r: r["seconds"])
            pm = predict(best)
            md.append(f"| {size}² | {p} | " + " | ".join(
                f"{cell[n]['seconds']:.4f}" if n in cell else "–" for n in colours if any(r['name'] == n for r in rows))
                + f" | {best['name']} | " + (f"{pm:.3f} |" if pm else "– |"))
    md.append("")

ft = [r for r in base if r["platform"] == "fattree"]
if ft:
    # Direct send's load is what rank 0 receives (all of it), which "most sent by one rank" hides,
    # so the total is beside it.
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    for ax, field, label in ((axes[0], "max_rank_bytes", "most MB sent by one rank"),
                             (axes[1], "bytes_sent", "MB sent by all ranks (direct: all to rank 0)")):
        for (name, size) in sorted({(r["name"], r["width"]) for r in ft if r["width"] in (2048, 8192)}):
            pts = sorted((r["ranks"], r[field]) for r in ft if r["name"] == name and r["width"] == size)
            ax.plot([p[0] for p in pts], [p[1] / 1e6 for p in pts], "o-" if size == 2048 else "s",
                    color=colours.get(name, "black"), label=f"{name} {size}²")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel("simulated hosts P (fat tree)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "bytes_per_rank.png"), dpi=90)
    plt.close(fig)

var = [r for r in sweep if r["platform"] == "fattree" and r["width"] == 2048 and r["ranks"] in (64, 256, 1024)]
if any(r["precision"] != "float" or r["rle"] != "on" for r in var):
    md += ["## Fat tree, 2048²: precision and RLE", "",
           "| strategy | P | float RLE on | float RLE off | rgba8 RLE on | rgba8 RLE off |", "|---|---|---|---|---|---|"]
    for name in colours:
        for p in (64, 256, 1024):
            cell = {(r["precision"], r["rle"]): r["seconds"] for r in var if r["name"] == name and r["ranks"] == p}
            if cell:
                md.append(f"| {name} | {p} | " + " | ".join(
                    f"{cell[k]:.4f}" if k in cell else "–" for k in
                    (("float", "on"), ("float", "off"), ("rgba8", "on"), ("rgba8", "off"))) + " |")
    md.append("")

if valid:
    meas = {(r["strategy"], r["radix"], r["ranks"], r["width"]): r for r in valid if r["platform"] == "measured"}
    pairs = [(meas[k], r) for r in valid if r["platform"] == "local"
             for k in [(r["strategy"], r["radix"], r["ranks"], r["width"])] if k in meas]
    fig, ax = plt.subplots(figsize=(5.2, 4.6))
    for m, s in pairs:
        ax.plot(m["seconds"], s["seconds"], "o", color=colours.get(s["name"], "black"), label=s["name"])
    lo = min(min(m["seconds"], s["seconds"]) for m, s in pairs) * 0.7
    hi = max(max(m["seconds"], s["seconds"]) for m, s in pairs) * 1.4
    for f, st in ((1, "-"), (2, ":"), (0.5, ":")):
        ax.plot([lo, hi], [lo * f, hi * f], st, color="gray", lw=0.8)
    h, l = ax.get_legend_handles_labels()
    uniq = dict(zip(l, h))
    ax.legend(uniq.values(), uniq.keys(), fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("measured seconds (Open MPI, this machine)")
    ax.set_ylabel("simulated seconds (local platform)")
    ax.set_title("2-8 ranks, 1024² and 2048²; lines: 1x, 2x, 0.5x")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "validation.png"), dpi=90)
    plt.close(fig)
    ratios = sorted(s["seconds"] / m["seconds"] for m, s in pairs)
    md += ["## Validation: simulated / measured at 2-8 ranks", "",
           f"{len(pairs)} pairs; simulated / measured: median {ratios[len(ratios) // 2]:.2f}, "
           f"range {ratios[0]:.2f}–{ratios[-1]:.2f}.", "",
           "| strategy | P | image | measured s | simulated s | ratio |", "|---|---|---|---|---|---|"]
    for m, s in sorted(pairs, key=lambda p: (p[1]["name"], p[1]["width"], p[1]["ranks"])):
        md.append(f"| {s['name']} | {s['ranks']} | {s['width']}² | {m['seconds']:.4f} | {s['seconds']:.4f} | "
                  f"{s['seconds'] / m['seconds']:.2f} |")
    md.append("")

open(os.path.join(out, "summary.md"), "w").write("\n".join(md) + "\n")
print("\n".join(md))
