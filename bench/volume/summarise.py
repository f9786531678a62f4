"""Summarises the --stats JSON files of bench/volume/run into a CSV table and a gnuplot chart.

The first frame of each run is left out (it pays for texture residency and shader compilation).
Per frame: render and encode are the slowest rank's; composite is rank 0's blend time; transfer is
the rest of the frame's wall time (sending, waiting for the slowest rank, gathering stats).

Usage: summarise.py OUT_DIR [RAW_DIR]: reads RAW_DIR/stats/*.json (default build/bench-runs/volume),
writes OUT_DIR/bench-volume.csv and .png (the chart's data file in RAW_DIR).
"""
import csv
import glob
import json
import os
import statistics
import subprocess
import sys

out = sys.argv[1]
raw = sys.argv[2] if len(sys.argv) > 2 else "build/bench-runs/volume"
os.makedirs(raw, exist_ok=True)
rows = []
for path in sorted(glob.glob(os.path.join(raw, "stats", "*.json"))):
    name = os.path.basename(path)[:-5]
    dataset, size, np_ = name.rsplit("_", 2)
    s = json.load(open(path))
    frames = s["frames"][1:] or s["frames"]
    mean = lambda f: statistics.mean(f(fr) for fr in frames)
    total = mean(lambda f: f["total_s"])
    render = mean(lambda f: max(f["render_s"]))
    encode = mean(lambda f: max(f["encode_s"]))
    composite = mean(lambda f: f["composite_s"])
    rss = [max(fr["peak_rss_mb"][r] for fr in s["frames"]) for r in range(s["ranks"])]
    rows.append({
        "dataset": dataset, "image": int(size), "ranks": s["ranks"], "frames": len(s["frames"]),
        "s_per_frame": round(total, 4), "fps": round(1 / total, 2), "render_s": round(render, 4),
        "encode_s": round(encode, 4), "transfer_s": round(max(0.0, total - render - encode - composite), 4),
        "composite_s": round(composite, 4), "rle_ratio": round(mean(lambda f: f["rle_ratio"]), 3),
        "peak_rss_mb_max": round(max(rss), 1), "peak_rss_mb_per_rank": " ".join(f"{r:.0f}" for r in rss),
        "renderer": s["renderer"].split(",")[0],
    })
rows.sort(key=lambda r: (r["dataset"], r["image"], r["ranks"]))
csv_path = os.path.join(out, "bench-volume.csv")
with open(csv_path, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    w.writerows(rows)

# Markdown table for notes and the results README.
cols = ["dataset", "image", "ranks", "s_per_frame", "fps", "render_s", "encode_s", "transfer_s",
        "composite_s", "rle_ratio", "peak_rss_mb_per_rank"]
print("| " + " | ".join(cols) + " |")
print("|" + "---|" * len(cols))
for r in rows:
    print("| " + " | ".join(str(r[c]) for c in cols) + " |")

# Stacked bars: one bar per (dataset, image, ranks).
dat = os.path.join(raw, "bench-volume.dat")
with open(dat, "w") as f:
    for r in rows:
        label = f"{r['dataset'][:4]} {r['image']} np{r['ranks']}"
        f.write(f"\"{label}\" {r['render_s']} {r['encode_s']} {r['transfer_s']} {r['composite_s']}\n")
png = os.path.join(out, "bench-volume.png")
script = f"""
set terminal pngcairo size 1100,520 font ",10"
set output "{png}"
set title "sortlast, paper protocol (orbit, d = 2, opacity = value): seconds per frame, llvmpipe"
set style data histograms
set style histogram rowstacked
set style fill solid 0.85 border -1
set boxwidth 0.7
set ylabel "seconds per frame"
set xtics rotate by -40
set key top left
set yrange [0:*]
set offsets 0, 0, 0.25, 0
set grid ytics
plot "{dat}" using 2:xtic(1) title "render", "" using 3 title "encode (RLE)", \\
     "" using 4 title "transfer / wait", "" using 5 title "composite", \\
     0.29 with lines dashtype 2 lw 2 lc rgb "black" title "ParaView 5.11, 256^3 at 512^2, 1 rank (issue)"
"""
subprocess.run(["gnuplot"], input=script, text=True, check=True)
print(f"\nwrote {csv_path} and {png}", file=sys.stderr)
