#!/usr/bin/env python3
"""Summarises bench/projection/run: frame times per mode (median total_s over the frames after the
first) and their ratio to emission-absorption without early termination; sampled MIP's error
against exact MIP. Writes times.csv, error.csv and projection.png (gnuplot) into OUT.
Usage: summarise.py RAW_DIR OUT_DIR SPACING"""
import json, os, re, statistics, subprocess, sys

raw, out, spacing = sys.argv[1], sys.argv[2], sys.argv[3]
modes = ["composite", "composite_noert", "mip", "minip", "average", "additive", "mip_exact"]


def frame_times(path):
    with open(path) as f:
        frames = json.load(f)["frames"]
    return [fr["total_s"] for fr in frames[1:]] or [fr["total_s"] for fr in frames]


times = {m: statistics.median(frame_times(os.path.join(raw, m + ".json"))) for m in modes}
base = times["composite_noert"]
with open(os.path.join(out, "times.csv"), "w") as f:
    f.write("mode,frame_s,vs_composite_noert\n")
    for m in modes:
        f.write(f"{m},{times[m]:.4f},{times[m] / base:.3f}\n")
print("mode             frame_s  vs composite without ERT")
for m in modes:
    print(f"{m:16s} {times[m]:7.3f}  {times[m] / base:5.2f}x")

rows = []
for s in ["0.5", "1", "2"]:
    text = open(os.path.join(raw, f"error_{s}.txt")).read()
    m = re.search(r"max_abs=([0-9.eE+-]+|inf)", text)
    mean = re.search(r"mean_abs=([0-9.eE+-]+)", text)
    t = statistics.median(frame_times(os.path.join(raw, f"sampled_{s}.json")))
    # mean_abs from the 8-bit comparison is in 1/255 units: as a fraction of the range.
    rows.append((s, float(m.group(1)) if m else float("nan"),
                 float(mean.group(1)) / 255.0 if mean else float("nan"), t))
with open(os.path.join(out, "error.csv"), "w") as f:
    f.write("mip,spacing_voxels,max_abs_error,mean_abs_error,frame_s\n")
    for s, mx, mn, t in rows:
        f.write(f"sampled,{s},{mx:.5f},{mn:.6f},{t:.4f}\n")
    f.write(f"exact,,0,0,{times['mip_exact']:.4f}\n")
print("sampled MIP vs exact: spacing, max |error| (of the range), mean |error|, frame_s")
for r in rows:
    print(f"  {r[0]:>4s}  {r[1]:.4f}  {r[2]:.5f}  {r[3]:.3f}")
print(f"  exact frame_s {times['mip_exact']:.3f}")

plot = f"""
set terminal pngcairo size 1100,420 font ',10' noenhanced
set output '{out}/projection.png'
set datafile separator ','
set multiplot layout 1,2
set title 'Frame time, engine 256³, 1 rank, {spacing} voxel steps'
set style data histograms
set style fill solid 0.8
set ylabel 'frame time (s)'
set xtics rotate by -30
set key off
plot '{out}/times.csv' every ::1 using 2:xtic(1) lc rgb '#4477aa'
set title 'Sampled MIP against exact MIP'
set style data linespoints
set xlabel 'frame time (s)'
set ylabel 'max |value error| (fraction of the range)'
set xtics norotate
set key top right
plot '{out}/error.csv' every ::1::3 using 5:3:2 with labels offset 1,1 notitle, \\
     '' every ::1::3 using 5:3 title 'sampled (0.5, 1, 2 voxels)' lw 2 pt 7, \\
     '' every ::4::4 using 5:3 title 'exact' pt 9 ps 2
unset multiplot
"""
subprocess.run(["gnuplot"], input=plot.encode(), check=True)
