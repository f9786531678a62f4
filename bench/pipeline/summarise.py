"""Summarises bench/pipeline/run: the frame's wall time and stages, old pipeline against new.

Wall time per frame: (wall of the N-frame job - wall of the 1-frame job) / (N - 1), median over the
repeats. Stages: the N-frame jobs' --stats `stages`, frame 0 left out (it pays for shader
compilation and texture residency), mean over frames and repeats: draw = the slowest rank's GL time
(timer queries), issue = the CPU's time in the draw calls (slowest rank), readback, encode,
exchange = the slowest rank's, composite = rank 0's. outside_draw = 1 - draw / wall per frame.

Usage: summarise.py OUT_DIR RAW_DIR: writes OUT_DIR/pipeline.csv and OUT_DIR/pipeline.png (gnuplot).
"""
import csv
import glob
import json
import os
import statistics
import subprocess
import sys
from collections import defaultdict

out, raw = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
walls = defaultdict(dict)  # (mode, np) -> repeat -> {frames: wall}
for r in csv.DictReader(open(os.path.join(raw, "times.csv"))):
    walls[(r["mode"], int(r["ranks"]))].setdefault(r["repeat"], {})[int(r["frames"])] = float(r["wall_s"])

rows = []
for (mode, np_), reps in sorted(walls.items(), key=lambda kv: (kv[0][1], ["before", "old", "new"].index(kv[0][0]))):
    per_frame = []
    n = 0
    for rep, t in reps.items():
        n = max(t)
        if 1 in t and n > 1:
            per_frame.append((t[n] - t[1]) / (n - 1))
    stages = defaultdict(list)
    for path in glob.glob(os.path.join(raw, "stats", f"{mode}_np{np_}_f{n}_r*.json")):
        for f in json.load(open(path))["frames"][1:]:
            s = f.get("stages")
            if s is None:  # a program from before the stages (--before): no draw time of its own
                s = {"frame_draw_s": float("nan"), "issue_s": f["render_s"], "readback_s": [0.0],
                     "encode_s": f["encode_s"], "exchange_s": [0.0], "composite_s": [f["composite_s"]]}
            stages["draw"].append(s["frame_draw_s"])
            for k in ("issue", "readback", "encode", "exchange"):
                stages[k].append(max(s[k + "_s"]))
            stages["composite"].append(s["composite_s"][0])
            stages["total"].append(f["total_s"])
    mean = {k: statistics.mean(v) for k, v in stages.items()}
    wall = statistics.median(per_frame)
    rows.append({"mode": mode, "ranks": np_, "wall_per_frame_s": wall, "total_s": mean["total"],
                 "draw_s": mean["draw"], "issue_s": mean["issue"], "readback_s": mean["readback"],
                 "encode_s": mean["encode"], "exchange_s": mean["exchange"],
                 "composite_s": mean["composite"], "outside_draw_share": 1 - mean["draw"] / wall,
                 "repeats": len(per_frame), "walls": " ".join(f"{w:.3f}" for w in per_frame)})

fields = list(rows[0].keys())
with open(os.path.join(out, "pipeline.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=fields)
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{v:.4f}" if isinstance(v, float) else v) for k, v in r.items()})

print(f"{'mode':5} {'ranks':>5} {'wall/frame':>10} {'total_s':>8} {'draw':>7} {'issue':>7} {'readback':>8} "
      f"{'encode':>7} {'exchange':>8} {'composite':>9} {'outside draw':>12}")
for r in rows:
    print(f"{r['mode']:5} {r['ranks']:5d} {r['wall_per_frame_s']:10.3f} {r['total_s']:8.3f} {r['draw_s']:7.3f} "
          f"{r['issue_s']:7.3f} {r['readback_s']:8.4f} {r['encode_s']:7.4f} {r['exchange_s']:8.4f} "
          f"{r['composite_s']:9.4f} {100 * r['outside_draw_share']:11.1f}%")
for np_ in sorted({r["ranks"] for r in rows}):
    new = [r for r in rows if r["ranks"] == np_ and r["mode"] == "new"]
    for base in ("before", "old"):
        old = [r for r in rows if r["ranks"] == np_ and r["mode"] == base]
        if old and new:
            print(f"{np_} rank(s): new is {old[0]['wall_per_frame_s'] / new[0]['wall_per_frame_s']:.2f}x {base} per frame")

# Chart: per frame, draw and the rest of the wall time, old and new, per rank count.
dat = os.path.join(raw, "pipeline.dat")
with open(dat, "w") as f:
    for r in rows:
        draw = r["draw_s"] if r["draw_s"] == r["draw_s"] else r["issue_s"]  # before: its render_s
        f.write(f"\"{r['mode']} {r['ranks']}r\" {draw:.4f} {max(0.0, r['wall_per_frame_s'] - draw):.4f}\n")
gp = f"""set terminal pngcairo size 800,480
set output '{os.path.join(out, "pipeline.png")}'
set title 'Engine 256^3 at 1024^2 orbit, 1 voxel, PNG written: wall time per frame'
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.6
set ylabel 'seconds per frame'
set yrange [0:*]
set key top right
plot '{dat}' using 2:xtic(1) title 'draw (GL, slowest rank)', '' using 3 title 'everything else (read-back, encode, composite, write)'
"""
subprocess.run(["gnuplot"], input=gp.encode(), check=True)
print("wrote", os.path.join(out, "pipeline.csv"), "and pipeline.png")
