"""Summarises the runs of scripts/bench-metaballs into two CSV tables, two gnuplot charts and
summary.md.

Usage: bench_metaballs_summary.py OUT_DIR DEPTH_TOLERANCE

Speed (stats/speed/SCENE-COUNT-SIZE-npN.json): the first frame of each orbit is left out (it pays
for shader compilation and first use); s_per_frame is the mean total_s of the others, render_s the
slowest rank's render time and rounds the largest particle_rounds of any rank, both averaged over
those frames.
Accuracy (stats/accuracy/SETTING-tI.json, SETTING.compare.json; SETTING = step<k>_ms<n>, step h/k,
max_samples n): s_per_frame is the smallest total_s of the timed single-frame runs; holes, depth
RMS, outliers and pixels come from compare-surface --ignore-edges against the CPU reference.
"""
import csv
import datetime
import glob
import json
import os
import re
import statistics
import subprocess
import sys

out, tol = sys.argv[1], float(sys.argv[2])
stats_dir = os.path.join(out, "stats")
renderers = set()


def short(renderer):
    """'osmesa: llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 ...' -> the part before ', OpenGL'."""
    return re.sub(r",\s*OpenGL.*", "", renderer)


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def md_table(rows, cols, header=None):
    lines = ["| " + " | ".join(header or cols) + " |", "|" + "---|" * len(cols)]
    lines += ["| " + " | ".join(str(r[c]) for c in cols) + " |" for r in rows]
    return "\n".join(lines)


# ---- Speed ----
speed = []
for path in sorted(glob.glob(os.path.join(stats_dir, "speed", "*.json"))):
    scene = os.path.basename(path)[:-5].split("-")[0]
    s = json.load(open(path))
    renderers.add(short(s["renderer"]))
    frames = s["frames"][1:] or s["frames"]
    mean = lambda f: statistics.mean(f(fr) for fr in frames)
    total = mean(lambda f: f["total_s"])
    speed.append({
        "scene": scene, "particles": s["particles"], "width": s["width"], "ranks": s["ranks"],
        "bricks_per_axis": s["bricks_per_axis"], "s_per_frame": round(total, 4),
        "fps": round(1 / total, 2), "render_s": round(mean(lambda f: max(f["render_s"])), 4),
        "rounds": round(mean(lambda f: max(f["particle_rounds"])), 1),
    })
if not speed:
    sys.exit(f"no speed runs in {stats_dir}/speed")
speed.sort(key=lambda r: (r["scene"] != "layers", r["scene"], r["particles"], r["width"], r["ranks"]))
frames_measured = len(json.load(open(glob.glob(os.path.join(stats_dir, "speed", "*.json"))[0]))["frames"])
speed_csv = os.path.join(out, "bench-metaballs-speed.csv")
write_csv(speed_csv, speed)


def best_of(rows):
    """For each (scene, particles, width): the run with the highest fps over rank counts."""
    best = {}
    for r in rows:
        key = (r["scene"], r["particles"], r["width"])
        if key not in best or r["fps"] > best[key]["fps"]:
            best[key] = r
    return best


best = best_of(speed)
one = {(r["scene"], r["particles"], r["width"]): r for r in speed if r["ranks"] == 1}
max_ranks = max(r["ranks"] for r in speed)

# ---- Accuracy ----
acc_dir = os.path.join(stats_dir, "accuracy")
accuracy = []
acc_width = None
for path in glob.glob(os.path.join(acc_dir, "*.compare.json")):
    setting = os.path.basename(path)[: -len(".compare.json")]
    m = re.fullmatch(r"step(\d+)_ms(\d+)", setting)
    if not m:
        continue
    k, ms = int(m.group(1)), int(m.group(2))
    c = json.loads(open(path).read().strip().splitlines()[-1])
    runs = [json.load(open(p)) for p in glob.glob(os.path.join(acc_dir, f"{setting}-t*.json"))]
    if not runs:
        continue
    acc_width = runs[0]["width"]
    renderers.add(short(runs[0]["renderer"]))
    accuracy.append({
        "setting": setting, "step_h": round(1 / k, 6), "max_samples": ms,
        "s_per_frame": round(min(fr["total_s"] for s in runs for fr in s["frames"]), 4),
        "holes": c["holes"], "depth_rms": c["depth_error_rms"], "depth_outliers": c["depth_outliers"],
        "pixels": c["pixels_hit_both"],
        # Not in the CSV: for the chart labels and summary.md.
        "_label": f"h/{k}, {ms}", "_step": f"1/{k}", "_repeats": len(runs), "_depth_max": c["depth_error_max"],
        "_extra": c["extra_hits"],
    })
accuracy.sort(key=lambda r: (-r["step_h"], r["max_samples"]))
acc_csv = os.path.join(out, "bench-metaballs-accuracy.csv")
if accuracy:
    write_csv(acc_csv, [{k: v for k, v in r.items() if not k.startswith("_")} for r in accuracy])
ref_path = os.path.join(acc_dir, "reference_s.txt")
ref_s = open(ref_path).read().strip() if os.path.exists(ref_path) else "?"
renderer = "; ".join(sorted(renderers))

# ---- Chart (a): fps against particles ----
widths = sorted({r["width"] for r in speed if r["scene"] == "layers"})
dat = os.path.join(out, "bench-metaballs-speed.dat")
plots, index = [], 0
with open(dat, "w") as f:
    def block(rows):
        global index
        for r in rows:
            f.write(f"{r['particles']} {r['fps']} \"np{r['ranks']}\"\n")
        f.write("\n\n")
        index += 1
        return index - 1
    for i, w in enumerate(widths):
        pts = sorted((k for k in one if k[0] == "layers" and k[2] == w), key=lambda k: k[1])
        if pts:
            j = block([one[k] for k in pts])
            plots.append(f'"{dat}" index {j} using 1:2 with linespoints lc {i + 1} pt 7 lw 2 '
                         f'title "{w}^2, 1 rank"')
        pts = sorted((k for k in best if k[0] == "layers" and k[2] == w), key=lambda k: k[1])
        if max_ranks > 1 and pts:
            j = block([best[k] for k in pts])
            plots.append(f'"{dat}" index {j} using 1:2 with linespoints lc {i + 1} pt 6 dt 2 lw 2 '
                         f'title "{w}^2, best of 1-{max_ranks} ranks"')
            plots.append(f'"{dat}" index {j} using 1:2:3 with labels offset 0,0.9 font ",8" '
                         f'tc lt {i + 1} notitle')
    for w in sorted({r["width"] for r in speed if r["scene"] == "dam_break"}):
        lc = widths.index(w) + 1 if w in widths else len(widths) + 1
        pts = [k for k in one if k[0] == "dam_break" and k[2] == w]
        if pts:
            j = block([one[k] for k in pts])
            plots.append(f'"{dat}" index {j} using 1:2 with points lc {lc} pt 5 ps 1.6 '
                         f'title "dam break {w}^2, 1 rank"')
        pts = [k for k in best if k[0] == "dam_break" and k[2] == w]
        if max_ranks > 1 and pts:
            j = block([best[k] for k in pts])
            plots.append(f'"{dat}" index {j} using 1:2 with points lc {lc} pt 4 ps 1.6 '
                         f'title "dam break {w}^2, best"')
            plots.append(f'"{dat}" index {j} using 1:2:3 with labels offset 0,-1 font ",8" '
                         f'tc lt {lc} notitle')
xt = sorted({r["particles"] for r in speed})
speed_png = os.path.join(out, "bench-metaballs-speed.png")
script = f"""
set terminal pngcairo size 1000,560 font ",10"
set output "{speed_png}"
set title "sortlast metaballs: frames per second ({frames_measured}-frame orbit, frame 0 left out), {renderer}"
set logscale xy
set xrange [{min(xt) / 1.5}:{max(xt) * 1.5}]
set xtics ({", ".join(f'"{n:,}" {n}' for n in xt)})
set xlabel "particles (layers; dam break: 24,389 from file)"
set ylabel "frames per second"
set grid
set key outside right top
plot {", ".join(plots)}
"""
subprocess.run(["gnuplot"], input=script, text=True, check=True)

# ---- Chart (b): frame time against holes and depth RMS ----
acc_png = os.path.join(out, "bench-metaballs-accuracy.png")
if accuracy:
    adat = os.path.join(out, "bench-metaballs-accuracy.dat")
    with open(adat, "w") as f:
        for r in accuracy:
            f.write(f"\"{r['_label']}\" {r['s_per_frame']} {r['holes']} {r['depth_rms']}\n")
    top = max(max(r["holes"] for r in accuracy) * 1.25, 4)
    rms_log = 'set logscale y; set format y "10^{%L}"' if all(r["depth_rms"] > 0 for r in accuracy) else "unset logscale y"
    script = f"""
set terminal pngcairo size 1100,480 font ",10"
set output "{acc_png}"
set multiplot layout 1,2 title "dam break {acc_width}^2, 1 rank, one view: GL settings (step, max samples) against the CPU reference, {renderer}"
set grid
set offsets graph 0.12, graph 0.12, 0, 0
set xlabel "seconds per frame (min of {accuracy[0]['_repeats']} runs)"
set ylabel "holes (pixels, silhouette edges ignored)"
set yrange [{-0.05 * top}:{top}]
plot "{adat}" using 2:3 with points pt 7 ps 1.3 lc 1 notitle, \\
     "" using 2:3:1 with labels offset 0,0.9 font ",9" notitle
set ylabel "depth error RMS (world units)"
set autoscale y
set offsets graph 0.12, graph 0.12, graph 0.1, graph 0.1
{rms_log}
plot "{adat}" using 2:4 with points pt 7 ps 1.3 lc 2 notitle, \\
     "" using 2:4:1 with labels offset 0,0.9 font ",9" notitle
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)

# ---- summary.md ----
md = [f"# Metaballs — `scripts/bench-metaballs`", "",
      f"Generated {datetime.date.today()} on {os.cpu_count()} cores, {renderer}.", ""]
md += ["## Speed, the paper's Table 1 layout", "",
       f"Frames per second, `layers` scene: 1 rank / the best of 1–{max_ranks} ranks (that rank count). "
       f"Orbit of {frames_measured} frames, frame 0 left out; d = 1 on 1 rank, d = 2 on more.", ""]
pivot_cols = [f"{w}²" for w in widths]
pivot = []
for n in sorted({r["particles"] for r in speed if r["scene"] == "layers"}):
    row = {"particles": f"{n:,}"}
    for w, col in zip(widths, pivot_cols):
        a, b = one.get(("layers", n, w)), best.get(("layers", n, w))
        row[col] = (f"{a['fps'] if a else '–'} / {b['fps']} (np{b['ranks']})" if b else "–")
    pivot.append(row)
md += [md_table(pivot, ["particles"] + pivot_cols), ""]
md += ["## Speed, every run", "", f"[CSV](bench-metaballs-speed.csv) · [chart](bench-metaballs-speed.png)", "",
       "s_per_frame: mean total_s; render_s: slowest rank's render time; rounds: largest "
       "particle_rounds over ranks; all means over the frames after the first.", "",
       md_table(speed, list(speed[0].keys())), ""]
if accuracy:
    md += ["## Accuracy against speed", "",
           f"[CSV](bench-metaballs-accuracy.csv) · [chart](bench-metaballs-accuracy.png)", "",
           f"Dam break (tests/data/dam_break.yaml) at {acc_width}², 1 rank, d = 1, one view. "
           f"s_per_frame: the smallest total_s of {accuracy[0]['_repeats']} single-frame runs (each a "
           f"fresh process, so warm-up included). Against the CPU reference surface ({ref_s} s): "
           f"holes and depth errors with silhouette edges ignored; depth_outliers: depth error above "
           f"1e-3 h = {tol:.4g}; pixels: pixels hit by both. depth_max and extra_hits are not in the CSV.", ""]
    cols = ["setting", "_step", "max_samples", "s_per_frame", "holes", "depth_rms", "depth_outliers",
            "pixels", "_depth_max", "_extra"]
    md += [md_table(accuracy, cols, ["setting", "step (h)", "max_samples", "s_per_frame", "holes",
                                     "depth_rms", "depth_outliers", "pixels", "depth_max", "extra_hits"]), ""]
summary = os.path.join(out, "summary.md")
with open(summary, "w") as f:
    f.write("\n".join(md))
print("\n".join(md))
print(f"wrote {speed_csv}, {acc_csv if accuracy else '(no accuracy runs)'}, {speed_png}, "
      f"{acc_png if accuracy else ''} and {summary}", file=sys.stderr)
