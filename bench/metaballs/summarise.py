"""Summarises the runs of bench/metaballs/run into two CSV tables, two gnuplot charts and
summary.md.

Usage: summarise.py OUT_DIR DEPTH_TOLERANCE [RAW_DIR]
The stats/ paths below are under RAW_DIR (bench/metaballs/run --raw, default build/bench-runs/metaballs).

Every GL row carries its metaball method (particles.method), the last part of its file name.
Speed (stats/speed/SCENE-COUNT-SIZE-npN-METHOD.json): the first frame of each orbit is left out (it pays
for shader compilation and first use); s_per_frame is the mean total_s of the others, render_s the
slowest rank's render time and rounds the largest particle_rounds of any rank, both averaged over
those frames.
Reference (stats/reference/SCENE-COUNT-SIZE.txt): the CPU reference's seconds per frame on the
same orbit. Grid build (stats/grid_build.jsonl): bench_metaball_grid's JSON lines.
Accuracy (stats/accuracy/SETTING-METHOD-tI.json, SETTING-METHOD.compare.json; SETTING =
step<k>_ms<n>, step h/k, max_samples n): s_per_frame is the smallest total_s of the timed single-frame runs; holes, depth
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
# The charts' data files go to RAW_DIR too.
raw = sys.argv[3] if len(sys.argv) > 3 else "build/bench-runs/metaballs"
stats_dir = os.path.join(raw, "stats")
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
    parts = os.path.basename(path)[:-5].split("-")
    scene, method = parts[0], (parts[4] if len(parts) > 4 else "billboards")
    s = json.load(open(path))
    renderers.add(short(s["renderer"]))
    frames = s["frames"][1:] or s["frames"]
    mean = lambda f: statistics.mean(f(fr) for fr in frames)
    total = mean(lambda f: f["total_s"])
    speed.append({
        "method": method, "scene": scene, "particles": s["particles"], "width": s["width"], "ranks": s["ranks"],
        "bricks_per_axis": s["bricks_per_axis"], "s_per_frame": round(total, 4),
        "fps": round(1 / total, 2), "render_s": round(mean(lambda f: max(f["render_s"])), 4),
        "rounds": round(mean(lambda f: max(f["particle_rounds"])), 1),
        "_ref_key": (scene, parts[1], parts[2]),
    })
if not speed:
    sys.exit(f"no speed runs in {stats_dir}/speed")
speed.sort(key=lambda r: (r["scene"] != "layers", r["scene"], r["particles"], r["width"], r["method"], r["ranks"]))
frames_measured = len(json.load(open(glob.glob(os.path.join(stats_dir, "speed", "*.json"))[0]))["frames"])
speed_csv = os.path.join(out, "bench-metaballs-speed.csv")
write_csv(speed_csv, [{k: v for k, v in r.items() if not k.startswith("_")} for r in speed])
methods = sorted({r["method"] for r in speed}, key=lambda m: m != "grid")

reference = {}
for path in glob.glob(os.path.join(stats_dir, "reference", "*.txt")):
    parts = os.path.basename(path)[:-4].split("-")
    reference[tuple(parts)] = float(open(path).read().strip())
grid_build = []
gb_path = os.path.join(stats_dir, "grid_build.jsonl")
if os.path.exists(gb_path):
    grid_build = [json.loads(line) for line in open(gb_path) if line.strip()]


def best_of(rows):
    """For each (method, scene, particles, width): the run with the highest fps over rank counts."""
    best = {}
    for r in rows:
        key = (r["method"], r["scene"], r["particles"], r["width"])
        if key not in best or r["fps"] > best[key]["fps"]:
            best[key] = r
    return best


best = best_of(speed)
one = {(r["method"], r["scene"], r["particles"], r["width"]): r for r in speed if r["ranks"] == 1}
max_ranks = max(r["ranks"] for r in speed)

# ---- Accuracy ----
acc_dir = os.path.join(stats_dir, "accuracy")
accuracy = []
acc_width = None
for path in glob.glob(os.path.join(acc_dir, "*.compare.json")):
    name = os.path.basename(path)[: -len(".compare.json")]
    m = re.fullmatch(r"(step(\d+)_ms(\d+))(?:-(\w+))?", name)
    if not m:
        continue
    setting, k, ms, method = m.group(1), int(m.group(2)), int(m.group(3)), m.group(4) or "billboards"
    c = json.loads(open(path).read().strip().splitlines()[-1])
    runs = [json.load(open(p)) for p in glob.glob(os.path.join(acc_dir, f"{name}-t*.json"))]
    if not runs:
        continue
    acc_width = runs[0]["width"]
    renderers.add(short(runs[0]["renderer"]))
    accuracy.append({
        "method": method, "setting": setting, "step_h": round(1 / k, 6), "max_samples": ms,
        "s_per_frame": round(min(fr["total_s"] for s in runs for fr in s["frames"]), 4),
        "holes": c["holes"], "depth_rms": c["depth_error_rms"], "depth_outliers": c["depth_outliers"],
        "pixels": c["pixels_hit_both"],
        # Not in the CSV: for the chart labels and summary.md.
        "_label": f"h/{k}, {ms}", "_step": f"1/{k}", "_repeats": len(runs), "_depth_max": c["depth_error_max"],
        "_extra": c["extra_hits"],
    })
accuracy.sort(key=lambda r: (r["method"] != "grid", -r["step_h"], r["max_samples"]))
acc_csv = os.path.join(out, "bench-metaballs-accuracy.csv")
if accuracy:
    write_csv(acc_csv, [{k: v for k, v in r.items() if not k.startswith("_")} for r in accuracy])
ref_path = os.path.join(acc_dir, "reference_s.txt")
ref_s = open(ref_path).read().strip() if os.path.exists(ref_path) else "?"
renderer = "; ".join(sorted(renderers))

# ---- Chart (a): fps against particles, 1 rank, both methods and the CPU reference ----
widths = sorted({r["width"] for r in speed if r["scene"] == "layers"})
dat = os.path.join(raw, "bench-metaballs-speed.dat")
plots, index = [], 0
dash = {"grid": 1, "billboards": 2}
with open(dat, "w") as f:
    def block(points):
        global index
        for x, y in points:
            f.write(f"{x} {y}\n")
        f.write("\n\n")
        index += 1
        return index - 1
    for i, w in enumerate(widths):
        for method in methods:
            pts = sorted((k for k in one if k[0] == method and k[1] == "layers" and k[3] == w), key=lambda k: k[2])
            if pts:
                j = block([(one[k]["particles"], one[k]["fps"]) for k in pts])
                plots.append(f'"{dat}" index {j} using 1:2 with linespoints lc {i + 1} pt {7 if method == "grid" else 6} '
                             f'dt {dash.get(method, 3)} lw 2 title "{method} {w}^2"')
        refs = sorted((int(k[1]), 1 / v) for k, v in reference.items() if k[0] == "layers" and int(k[2]) == w and v > 0)
        if refs:
            j = block(refs)
            plots.append(f'"{dat}" index {j} using 1:2 with linespoints lc {i + 1} pt 2 dt 3 lw 1 '
                         f'title "CPU reference {w}^2"')
    for scene, pt in (("dam_break", 5), ("splash", 9)):
        for method in methods:
            pts = [k for k in one if k[0] == method and k[1] == scene]
            if pts:
                j = block([(one[k]["particles"], one[k]["fps"]) for k in pts])
                plots.append(f'"{dat}" index {j} using 1:2 with points lc {len(widths) + 1} pt {pt if method == "grid" else pt - 1} '
                             f'ps 1.6 title "{method} {scene.replace("_", " ")} {one[pts[0]]["width"]}^2"')
        refs = [(r["particles"], 1 / reference[r["_ref_key"]]) for r in speed
                if r["scene"] == scene and r["ranks"] == 1 and r["method"] == methods[0] and reference.get(r["_ref_key"], 0) > 0]
        if refs:
            j = block(refs)
            plots.append(f'"{dat}" index {j} using 1:2 with points lc {len(widths) + 1} pt 2 ps 1.6 '
                         f'title "CPU reference {scene.replace("_", " ")}"')
xt = sorted({r["particles"] for r in speed})
speed_png = os.path.join(out, "bench-metaballs-speed.png")
script = f"""
set terminal pngcairo size 1100,600 font ",10"
set output "{speed_png}"
set title "sortlast metaballs, 1 rank: frames per second ({frames_measured}-frame orbit, frame 0 left out), {renderer}"
set logscale xy
set xrange [{min(xt) / 1.5}:{max(xt) * 1.5}]
set xtics ({", ".join(f'"{n:,}" {n}' for n in xt)})
set xlabel "particles (layers; dam break: 24,389 from file; splash: procedural)"
set ylabel "frames per second"
set grid
set key outside right top
plot {", ".join(plots)}
"""
subprocess.run(["gnuplot"], input=script, text=True, check=True)

# ---- Chart (b): frame time against holes and depth RMS ----
acc_png = os.path.join(out, "bench-metaballs-accuracy.png")
if accuracy:
    adat = os.path.join(raw, "bench-metaballs-accuracy.dat")
    with open(adat, "w") as f:
        for method in methods:
            for r in accuracy:
                if r["method"] == method:
                    f.write(f"\"{r['_label']}\" {r['s_per_frame']} {r['holes']} {r['depth_rms']}\n")
            f.write("\n\n")
    top = max(max(r["holes"] for r in accuracy) * 1.25, 4)
    rms_log = 'set logscale y; set format y "10^{%L}"' if all(r["depth_rms"] > 0 for r in accuracy) else "unset logscale y"
    series = lambda col: ", ".join(
        f'"{adat}" index {i} using 2:{col} with points pt 7 ps 1.3 lc {i + 1} title "{m}", '
        f'"" index {i} using 2:{col}:1 with labels offset 0,0.9 font ",8" tc lt {i + 1} notitle'
        for i, m in enumerate(methods))
    script = f"""
set terminal pngcairo size 1200,500 font ",10"
set output "{acc_png}"
set multiplot layout 1,2 title "dam break {acc_width}^2, 1 rank, one view: GL settings (step, max samples) against the CPU reference, {renderer}"
set grid
set logscale x
set offsets graph 0.12, graph 0.12, 0, 0
set xlabel "seconds per frame (min of {accuracy[0]['_repeats']} runs, log)"
set ylabel "holes (pixels, silhouette edges ignored)"
set yrange [{-0.05 * top}:{top}]
plot {series(3)}
set ylabel "depth error RMS (world units)"
set autoscale y
set offsets graph 0.12, graph 0.12, graph 0.1, graph 0.1
{rms_log}
plot {series(4)}
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)

# ---- Slices: accuracy against the lattice spacing (stats/slices), and the per-brick work ----
slices = []
for sp in sorted({re.match(r"spacing([0-9.]+)-", os.path.basename(p)).group(1)
                  for p in glob.glob(os.path.join(stats_dir, "slices", "spacing*-tol*.compare.json"))},
                 key=float, reverse=True):
    tol_runs = {k: json.load(open(os.path.join(stats_dir, "slices", f"spacing{sp}-tol{k}.compare.json")))
                for k in ("0.1", "0.2", "1")}
    c = tol_runs["0.1"]
    times = [min(f["total_s"] for f in json.load(open(p))["frames"])
             for p in glob.glob(os.path.join(stats_dir, "slices", f"spacing{sp}-t[0-9]*.json"))]
    slices.append({"slice_spacing_h": float(sp), "s_per_frame": round(min(times), 4) if times else "",
                   "pixels": c["pixels_hit_both"], "holes": c["holes"], "extra_hits": c["extra_hits"],
                   "depth_rms": round(c["depth_error_rms"], 6), "depth_max": round(c["depth_error_max"], 4),
                   "over_0.1h": c["depth_outliers"], "over_0.2h": tol_runs["0.2"]["depth_outliers"],
                   "over_h": tol_runs["1"]["depth_outliers"]})
if slices:
    write_csv(os.path.join(out, "bench-metaballs-slices.csv"), slices)
slices_build = []
sb_path = os.path.join(stats_dir, "slices_build.jsonl")
if os.path.exists(sb_path):
    slices_build = [json.loads(line) for line in open(sb_path) if line.strip()]

# ---- summary.md ----
md = [f"# Metaballs — `bench/metaballs/run`", "",
      f"Generated {datetime.date.today()} on {os.cpu_count()} cores, {renderer}.", ""]
md += ["## Speed, the paper's Table 1 layout", "",
       f"Frames per second, `layers` scene: 1 rank / the best of 1–{max_ranks} ranks (that rank count). "
       f"Orbit of {frames_measured} frames, frame 0 left out; d = 1 on 1 rank, d = 2 on more.", ""]
pivot_cols = [f"{w}²" for w in widths]
for method in methods:
    pivot = []
    for n in sorted({r["particles"] for r in speed if r["scene"] == "layers"}):
        row = {"particles": f"{n:,}"}
        for w, col in zip(widths, pivot_cols):
            a, b = one.get((method, "layers", n, w)), best.get((method, "layers", n, w))
            row[col] = (f"{a['fps'] if a else '–'} / {b['fps']} (np{b['ranks']})" if b else "–")
        pivot.append(row)
    md += [f"`{method}`:", "", md_table(pivot, ["particles"] + pivot_cols), ""]
vs = []
for r in speed:
    if r["ranks"] != 1 or r["method"] != methods[0]:
        continue
    row = {"scene": r["scene"], "particles": f"{r['particles']:,}", "width": f"{r['width']}²"}
    ref = reference.get(r["_ref_key"])
    for method in methods:
        g = one.get((method, r["scene"], r["particles"], r["width"]))
        row[method] = g["s_per_frame"] if g else "–"
    row["reference"] = ref if ref is not None else "–"
    for method in methods:
        g = one.get((method, r["scene"], r["particles"], r["width"]))
        row[f"reference / {method}"] = f"{ref / g['s_per_frame']:.1f}×" if g and ref else "–"
    if len(methods) > 1:
        a, b = one.get((methods[0], r["scene"], r["particles"], r["width"])), one.get((methods[1], r["scene"], r["particles"], r["width"]))
        row[f"{methods[1]} / {methods[0]}"] = f"{b['s_per_frame'] / a['s_per_frame']:.1f}×" if a and b else "–"
    vs.append(row)
if vs:
    md += ["## Seconds per frame, 1 rank, against the CPU reference", "",
           "GL: mean total_s over the frames after the first; reference: `sortlast reference` (double "
           "precision, all cores) on the same orbit, (wall time of all frames − the first alone) / (frames − 1). "
           "A ratio above 1: the GL method is that many times faster.", "",
           md_table(vs, list(vs[0].keys())), ""]
if grid_build:
    md += ["## Grid build (`bench_metaball_grid`)", "",
           "buildParticleGrid alone, the fastest of 3, one thread: cells of h/2 (coarser when over 2^24 cells).", "",
           md_table(grid_build, list(grid_build[0].keys())), ""]
md += ["## Speed, every run", "", f"[CSV](bench-metaballs-speed.csv) · [chart](bench-metaballs-speed.png)", "",
       "s_per_frame: mean total_s; render_s: slowest rank's render time; rounds: largest "
       "particle_rounds over ranks (grid: always 1); all means over the frames after the first.", "",
       md_table(speed, [k for k in speed[0].keys() if not k.startswith("_")]), ""]
if accuracy:
    md += ["## Accuracy against speed", "",
           f"[CSV](bench-metaballs-accuracy.csv) · [chart](bench-metaballs-accuracy.png)", "",
           f"Dam break (tests/data/dam_break.yaml) at {acc_width}², 1 rank, d = 1, one view. "
           f"s_per_frame: the smallest total_s of {accuracy[0]['_repeats']} single-frame runs (each a "
           f"fresh process, so warm-up included). Against the CPU reference surface ({ref_s} s): "
           f"holes and depth errors with silhouette edges ignored; depth_outliers: depth error above "
           f"1e-3 h = {tol:.4g}; pixels: pixels hit by both. depth_max and extra_hits are not in the CSV.", ""]
    cols = ["method", "setting", "_step", "max_samples", "s_per_frame", "holes", "depth_rms", "depth_outliers",
            "pixels", "_depth_max", "_extra"]
    md += [md_table(accuracy, cols, ["method", "setting", "step (h)", "max_samples", "s_per_frame", "holes",
                                     "depth_rms", "depth_outliers", "pixels", "depth_max", "extra_hits"]), ""]
if slices:
    md += ["## Slices: accuracy against the lattice spacing", "",
           f"[CSV](bench-metaballs-slices.csv). The dam break at {acc_width}², 1 rank, d = 2 (the same image "
           f"as d = 1), default ray settings, against the same CPU reference surface, silhouette edges "
           f"ignored. over_kh: pixels whose depth error passes k h (h = 0.107). s_per_frame: the smallest "
           f"total_s of single-frame runs; like every frame time here it leaves out the splat, paid once "
           f"per time step when the bricks are uploaded (see the per-brick work below).", "",
           md_table(slices, list(slices[0].keys())), ""]
if slices_build:
    md += ["## Slices: per-brick work (`bench_metaball_slices`)", "",
           "One brick over the whole splash set, spacing h/4, the fastest of 3. cpu_bits_s: the coarse bit "
           "voxelization on the CPU; gl_bits_s: the same bits by a compute shader (upload, dispatch, read "
           "back; bits_differ: voxels where they disagree); cpu_lattice_s: bits, slots and lists; "
           "add_brick_s: all of a brick's work (lattice, upload, splat).", "",
           md_table(slices_build, list(slices_build[0].keys())), ""]
summary = os.path.join(out, "summary.md")
with open(summary, "w") as f:
    f.write("\n".join(md))
print("\n".join(md))
print(f"wrote {speed_csv}, {acc_csv if accuracy else '(no accuracy runs)'}, {speed_png}, "
      f"{acc_png if accuracy else ''} and {summary}", file=sys.stderr)
