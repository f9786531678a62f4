"""Summarises bench/accuracy/run: OUT/accuracy.md (per data set every setting, the Pareto front of
the settings without issue 13's features ("old") and of all settings ("new"), the fastest setting at
>= 45 and >= 50 dB of each; the adaptive-sampling table like the paper's Tables 5-6) and
OUT/accuracy.png (seconds per frame against PSNR, one panel per data set, both fronts drawn).

Usage: python3 bench/accuracy/summarise.py OUT_DIR [RAW_DIR]   (reads OUT_DIR/accuracy.csv)
"""
import csv
import glob
import json
import os
import subprocess
import sys

NEW_TAGS = ("pre", "astep", "shade")  # issue 13's features, as tags in the setting names
# The setting that was sortlast's defaults per data set before issue 30 (ray casting, 0.5 voxel,
# ERT 0.99, pre-integration `auto`: on for neghip's steep band only, scene/scene.h
# kSteepOpacitySlope); since issue 30 the defaults are `defaults_auto` (render.sample_spacing: auto).
DEFAULTS = {"neghip": "raycast_s0.5_ert0.99_pre"}
DEFAULT_PLAIN = "raycast_s0.5_ert0.99"
AUTO = "defaults_auto"
out = sys.argv[1]
# The raw --stats JSON (the step `auto` chose, the adaptive-stats tables): bench/accuracy/run's
# build/bench-runs/accuracy unless given; without them those cells read "?" and the tables are left out.
raw = sys.argv[2] if len(sys.argv) > 2 else "build/bench-runs/accuracy"
os.makedirs(raw, exist_ok=True)
rows = [r for r in csv.DictReader(open(os.path.join(out, "accuracy.csv"))) if r["setting"] != "default"]
for r in rows:
    r["s_per_frame"] = float(r["s_per_frame"])
    r["psnr_db"] = float(r["psnr_db"])
    tags = [t for t in r["setting"].split("_")[1:] if t in NEW_TAGS]
    r["family"] = "+".join([r["setting"].split("_")[0]] + tags)
    r["new"] = bool(tags)
order = ["engine", "neghip", "procedural", "headsq", "hydrogen", "hydrogen_log", "bucky", "ironprot"]
datasets = sorted({r["dataset"] for r in rows}, key=lambda d: order.index(d) if d in order else 9)


def pareto(sel):
    """Fastest first: a setting is on the front if nothing faster is as accurate."""
    front, best = [], -1.0
    for r in sorted(sel, key=lambda r: r["s_per_frame"]):
        if r["psnr_db"] > best:
            front.append(r)
            best = r["psnr_db"]
    return front


def fastest(sel, db):
    ok = sorted([r for r in sel if r["psnr_db"] >= db], key=lambda r: r["s_per_frame"])
    return (f"**{ok[0]['setting']}** ({ok[0]['s_per_frame']:.3f} s, {ok[0]['psnr_db']:.1f} dB)"
            if ok else f"none reaches {db} dB")


md = ["# Accuracy against speed\n",
      "Frame time (1 rank, 512², d = 2, llvmpipe; mean over frames after the first) against PSNR "
      "versus the CPU reference (mean over the frames). `slicing_sX`: 3D-texture slicing at X "
      "voxels between slices; `raycast_sX_ertE`: GL ray casting at X voxels, early termination at "
      "opacity E (1: off); `adaptive_bB_tT`: ray casting the adaptive blocks (B per axis, "
      "tolerance T %). Issue 13's tags: `_pre` "
      "pre-integrated transfer function, `_astep` adaptive step length, `_shade` gradient shading "
      "(compared with a shaded reference). Old front: the settings without those tags. "
      f"The defaults are `{AUTO}` (ray casting, the default ERT threshold (0.99 in rows measured "
      "before 2026-12-07, 0.999 since), pre-integration and the sample spacing "
      f"`auto`: issue 30); before issue 30 they were `{DEFAULT_PLAIN}` (pre-integration `auto` is off "
      f"on smooth transfer functions), on neghip `{DEFAULTS['neghip']}`.\n",
      "\n| data set | the defaults (step chosen) | before issue 30 (0.5 voxel) | fastest >= 45 dB, old | "
      "fastest >= 45 dB, new | fastest >= 50 dB, old | fastest >= 50 dB, new |",
      "|---|---|---|---|---|---|---|"]
for ds in datasets:
    sel = [r for r in rows if r["dataset"] == ds]
    old = [r for r in sel if not r["new"]]
    d = [r for r in sel if r["setting"] == DEFAULTS.get(ds, DEFAULT_PLAIN)]
    dflt = f"{d[0]['s_per_frame']:.3f} s, {d[0]['psnr_db']:.1f} dB" if d else "–"
    a = [r for r in sel if r["setting"] == AUTO]
    auto = "–"
    if a:
        stats = os.path.join(raw, "stats", f"{ds}__{AUTO}.json")
        step = "?"
        if os.path.exists(stats):
            step = json.load(open(stats))["frames"][0].get("sample_spacing", "?")
        speed = f", {d[0]['s_per_frame'] / a[0]['s_per_frame']:.2f}x" if d else ""
        auto = f"{a[0]['s_per_frame']:.3f} s, {a[0]['psnr_db']:.1f} dB ({step} voxel{speed})"
    md.append(f"| {ds} | {auto} | {dflt} | {fastest(old, 45)} | {fastest(sel, 45)} | {fastest(old, 50)} | "
              f"{fastest(sel, 50)} |")
for ds in datasets:
    sel = sorted([r for r in rows if r["dataset"] == ds], key=lambda r: r["s_per_frame"])
    front, old_front = pareto(sel), pareto([r for r in sel if not r["new"]])
    md += [f"\n## {ds}\n", "| setting | s/frame | PSNR dB (mean) | PSNR dB (worst frame) | max diff | front |",
           "|---|---|---|---|---|---|"]
    for r in sorted(sel, key=lambda r: (r["family"], r["setting"])):
        on = ["old"] * (r in old_front) + ["new"] * (r in front)
        md.append(f"| {r['setting']} | {r['s_per_frame']:.3f} | {r['psnr_db']:.1f} | "
                  f"{float(r['psnr_min_db']):.1f} | {r['max_diff']} | {', '.join(on)} |")
    for name, f in (("old", old_front), ("new", front)):
        md += ["", f"Pareto front, {name} (fastest first): " +
               ", ".join(f"{r['setting']} ({r['s_per_frame']:.3f} s, {r['psnr_db']:.1f} dB)" for r in f)]

# The paper's Tables 5-6: data left and preprocessing time per tolerance and block count.
stats = sorted(glob.glob(os.path.join(raw, "stats", "*__adaptive-stats_*.json")))
if stats:
    md += ["\n## Adaptive sampling: data left and preprocessing (the paper's Tables 5-6)\n",
           "| data set | blocks | tolerance % | data left % | preprocessing s | frame s (ray cast, 0.5 voxel) | PSNR dB |",
           "|---|---|---|---|---|---|---|"]
    timing = {(r["dataset"], r["setting"]): r for r in rows}
    for p in stats:
        ds, rest = os.path.basename(p)[:-5].split("__adaptive-stats_")
        b, t = rest.split("_")
        j = json.load(open(p))
        left = j.get("data_left_percent", j.get("data_left_pct", float("nan")))
        pre = j.get("preprocess_s_best", float("nan"))
        r = timing.get((ds, f"adaptive_{b}_{t}"))
        md.append(f"| {ds} | {b[1:]} | {t[1:]} | {left:.1f} | {pre:.3f} | "
                  f"{r['s_per_frame']:.3f} | {r['psnr_db']:.1f} |" if r else
                  f"| {ds} | {b[1:]} | {t[1:]} | {left:.1f} | {pre:.3f} | | |")
open(os.path.join(out, "accuracy.md"), "w").write("\n".join(md) + "\n")
print("\n".join(md))

# Chart: one panel per data set, one point series per family.
families = sorted({r["family"] for r in rows})
# The front measured before issue 13 (its build, 2026-11-23; no head CT then), if kept beside.
before_csv = os.path.join(out, "accuracy_before_issue13.csv")
before = []
if os.path.exists(before_csv):
    before = [dict(r, s_per_frame=float(r["s_per_frame"]), psnr_db=float(r["psnr_db"]))
              for r in csv.DictReader(open(before_csv))]
panels = []
for ds in datasets:
    series = []
    for fam in families:
        dat = os.path.join(raw, f"acc_{ds}_{fam}.dat")
        pts = [r for r in rows if r["dataset"] == ds and r["family"] == fam]
        if not pts:
            continue
        with open(dat, "w") as f:
            for r in sorted(pts, key=lambda r: r["s_per_frame"]):
                f.write(f"{r['s_per_frame']} {r['psnr_db']} \"{r['setting'].split('_', 1)[-1]}\"\n")
        pt = [7, 5, 9, 11, 13, 15, 4, 6, 8, 10, 12, 14][families.index(fam) % 12]
        series.append(f'"{dat}" using 1:2 with points pt {pt} ps 1.1 title "{fam}", '
                      f'"{dat}" using 1:2:3 with labels offset 0,0.8 font ",6" notitle')
    sel = [r for r in rows if r["dataset"] == ds]
    fronts = [("old settings, today's code", "gray40", pareto([r for r in sel if not r["new"]])),
              ("all settings", "black", pareto(sel))]
    if any(r["dataset"] == ds for r in before):
        fronts.insert(0, ("before issue 13", "red", pareto([r for r in before if r["dataset"] == ds])))
    for name, colour, f in fronts:
        dat = os.path.join(raw, f"acc_{ds}_front_{fronts.index((name, colour, f))}.dat")
        with open(dat, "w") as fh:
            for r in f:
                fh.write(f"{r['s_per_frame']} {r['psnr_db']}\n")
        series.append(f'"{dat}" using 1:2 with steps lw 2 lc rgb "{colour}" '
                      f'dashtype {1 if name == "all settings" else 2} title "front: {name}"')
    panels.append((ds, series))
png = os.path.join(out, "accuracy.png")
cols = min(2, max(1, len(panels)))
rows_n = (len(panels) + cols - 1) // cols
script = [f'set terminal pngcairo size {640 * cols},{520 * rows_n} font ",10"', f'set output "{png}"',
          f'set multiplot layout {rows_n},{cols} title "Frame time vs PSNR against the CPU reference (512^2, 1 rank, llvmpipe)"',
          'set termoption noenhanced', 'set xlabel "seconds per frame"', 'set ylabel "PSNR (dB)"', "set grid", "set key bottom right",
          "set logscale x"]
for ds, series in panels:
    script += [f'set title "{ds}"', "plot 45 with lines dashtype 2 lc rgb 'gray' title '45 dB', "
               "50 with lines dashtype 3 lc rgb 'gray' title '50 dB', " + ", ".join(series)]
script.append("unset multiplot")
subprocess.run(["gnuplot"], input="\n".join(script), text=True, check=True)
for f in glob.glob(os.path.join(raw, "acc_*.dat")):
    os.remove(f)
print(f"wrote {out}/accuracy.md and {png}", file=sys.stderr)
