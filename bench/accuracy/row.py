"""One CSV row of bench/accuracy/run: compares each rendered frame (DIR/f[_000i].png) with the
reference frame (DIR/ref[_000i].png) using `sortlast compare`, and reads the frame time from the
--stats JSON (mean total_s over frames after the first).

Usage: python3 bench/accuracy/row.py SORTLAST DIR FRAMES DATASET SETTING STATS_JSON
"""
import json
import statistics
import subprocess
import sys

sl, d, frames, dataset, setting, stats = sys.argv[1], sys.argv[2], int(sys.argv[3]), *sys.argv[4:7]
names = [""] if frames == 1 else [f"_{i:04d}" for i in range(frames)]
psnrs, worst = [], 0
for n in names:
    line = subprocess.run([sl, "compare", f"{d}/f{n}.png", f"{d}/ref{n}.png"], check=True,
                          capture_output=True, text=True).stdout
    fields = dict(kv.split("=", 1) for kv in line.split())
    psnrs.append(min(float(fields["psnr_db"]), 99.0))  # identical images: cap at 99 dB
    worst = max(worst, int(fields["max_diff"]))
s = json.load(open(stats))["frames"]
timed = s[1:] or s
t = statistics.mean(f["total_s"] for f in timed)
print(f"{dataset},{setting},{t:.4f},{statistics.mean(psnrs):.2f},{min(psnrs):.2f},{worst},{frames}")
