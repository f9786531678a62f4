"""Summarises bench/scaling/run's --stats JSON files: OUT/scaling.csv, OUT/scaling.md (tables:
strong and weak scaling, overlap on/off) and OUT/scaling.png (seconds per frame against ranks).

The first frame of each run is left out (texture residency, shader compilation). Per frame:
render = the slowest rank's render time; composite = rank 0's blend time; the rest of the frame's
wall time is transfer and waiting. Strong-scaling speed-up is t(1 rank) / t(P); weak-scaling
efficiency is t(1) / t(P).

Usage: python3 bench/scaling/summarise.py OUT_DIR [RAW_DIR]: reads RAW_DIR/stats/*.json (default
build/bench-runs/scaling); the chart's data files go to RAW_DIR.
"""
import csv
import glob
import json
import os
import statistics
import subprocess
import sys

out = sys.argv[1]
raw = sys.argv[2] if len(sys.argv) > 2 else "build/bench-runs/scaling"
os.makedirs(raw, exist_ok=True)
rows = []
for path in sorted(glob.glob(os.path.join(raw, "stats", "*.json"))):
    kind, dataset, strategy, np_ = os.path.basename(path)[:-5].split("__")
    s = json.load(open(path))
    frames = s["frames"][1:] or s["frames"]
    mean = lambda f: statistics.mean(f(fr) for fr in frames)
    total = mean(lambda f: f["total_s"])
    rows.append({
        "kind": kind, "dataset": dataset, "strategy": strategy, "ranks": s["ranks"],
        "frames": len(s["frames"]), "s_per_frame": round(total, 4),
        "render_s_max": round(mean(lambda f: max(f["render_s"])), 4),
        "render_s_sum": round(mean(lambda f: sum(f["render_s"])), 4),
        "composite_s": round(mean(lambda f: f["composite_s"]), 4),
        "bytes_sent": int(mean(lambda f: sum(f["bytes_sent"]))),
    })
rows.sort(key=lambda r: (r["kind"], r["strategy"], r["dataset"], r["ranks"]))
base = {}
for r in rows:
    if r["ranks"] == 1 or (r["kind"] == "overlap" and r["strategy"] == "direct-nooverlap"):
        base.setdefault((r["kind"], r["strategy"]), {})[r["ranks"]] = r["s_per_frame"]
for r in rows:
    if r["kind"] == "overlap":
        ref = base.get(("overlap", "direct-nooverlap"), {}).get(r["ranks"])
        r["vs_base"] = round(ref / r["s_per_frame"], 3) if ref else ""
    else:
        ref = base.get((r["kind"], r["strategy"]), {}).get(1)
        r["vs_base"] = round(ref / r["s_per_frame"], 3) if ref else ""
fields = list(rows[0].keys())
with open(os.path.join(out, "scaling.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=fields)
    w.writeheader()
    w.writerows(rows)

with open(os.path.join(out, "scaling.md"), "w") as md:
    for kind, what in (("strong", "speed-up t(1)/t(P)"), ("weak", "efficiency t(1)/t(P)"),
                       ("overlap", "speed-up over no overlap")):
        sel = [r for r in rows if r["kind"] == kind]
        if not sel:
            continue
        md.write(f"\n### {kind} ({what} in the last column)\n\n")
        cols = ["dataset", "strategy", "ranks", "s_per_frame", "render_s_max", "render_s_sum",
                "composite_s", "bytes_sent", "vs_base"]
        md.write("| " + " | ".join(cols) + " |\n|" + "---|" * len(cols) + "\n")
        for r in sel:
            md.write("| " + " | ".join(str(r[c]) for c in cols) + " |\n")
print(open(os.path.join(out, "scaling.md")).read())

# Two panels: strong and weak, seconds per frame against ranks, one line per strategy.
plots = []
for kind in ("strong", "weak"):
    series = []
    for strategy in sorted({r["strategy"] for r in rows if r["kind"] == kind}):
        dat = os.path.join(raw, f"scaling_{kind}_{strategy}.dat")
        with open(dat, "w") as f:
            for r in rows:
                if r["kind"] == kind and r["strategy"] == strategy:
                    f.write(f"{r['ranks']} {r['s_per_frame']}\n")
        series.append(f'"{dat}" using 1:2 with linespoints lw 2 title "{strategy}"')
    plots.append((kind, series))
png = os.path.join(out, "scaling.png")
script = f"""
set terminal pngcairo size 1100,460 font ",10"
set output "{png}"
set multiplot layout 1,2 title "sortlast on a 2-core machine (llvmpipe, ranks oversubscribed), 512^2, d = 2"
set xlabel "ranks"
set ylabel "seconds per frame"
set grid
set key top left
set yrange [0:*]
set xrange [0.5:8.5]
set title "strong: procedural 256^3"
plot {", ".join(plots[0][1])}
set title "weak: procedural [128 P, 128, 128] over one box"
plot {", ".join(plots[1][1])}
unset multiplot
"""
subprocess.run(["gnuplot"], input=script, text=True, check=True)
for f in glob.glob(os.path.join(raw, "scaling_*.dat")):
    os.remove(f)
print(f"wrote {out}/scaling.csv, scaling.md and scaling.png", file=sys.stderr)
