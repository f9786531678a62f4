"""Summarises bench/cluster/run's CSVs (compositing.csv, render.csv in OUT_DIR).

Writes OUT/summary.md (the 8-node 1 Gbit/s 1024² goal ratio, the fastest strategy per case, what
RLE pays, the renderer's rows), OUT/compositing.png (compositing seconds against link bandwidth,
gnuplot pngcairo) and, per bandwidth, OUT/fit-GBIT/ with the cost model of
bench/compositing/fit.py fitted to that bandwidth's runs (fit.md, model.png).

Usage: python3 bench/cluster/summarise.py OUT_DIR
"""
import csv
import os
import statistics
import subprocess
import sys

out = sys.argv[1]
# The chart's and the fits' gnuplot data files (bench/cluster/run --raw, default build/bench-runs/cluster).
raw_dir = sys.argv[2] if len(sys.argv) > 2 else "build/bench-runs/cluster"
os.makedirs(raw_dir, exist_ok=True)
here = os.path.dirname(os.path.abspath(__file__))
comp_path = os.path.join(out, "compositing.csv")
comp = list(csv.DictReader(open(comp_path))) if os.path.exists(comp_path) else []
for r in comp:
    r["nodes"], r["width"] = int(r["nodes"]), int(r["width"])
    r["gbit"], r["seconds"], r["bytes_sent"] = float(r["gbit"]), float(r["seconds"]), float(r["bytes_sent"])
    r["name"] = r["strategy"] if r["strategy"] == "direct" else f"{r['strategy']} k={r['radix']}"
render_path = os.path.join(out, "render.csv")
rend = list(csv.DictReader(open(render_path))) if os.path.exists(render_path) else []

md = ["# Cluster rehearsal: the network's cost\n",
      f"From `{out}/compositing.csv` ({len(comp)} runs of bench_compositing on the engine's real brick "
      "images) and `render.csv` ({} runs of sortlast render). Seconds: bench_compositing's median over "
      "repetitions of the slowest rank's time for one composite.\n".format(len(rend))]

def sec(nodes, gbit, size, name, precision, rle):
    for r in comp:
        if (r["nodes"], r["gbit"], r["width"], r["name"], r["precision"], r["rle"]) == (nodes, gbit, size, name, precision, rle):
            return r
    return None

names = sorted({r["name"] for r in comp}, key=lambda n: ["direct", "binary-swap k=2", "radix-k k=4"].index(n)
               if n in ("direct", "binary-swap k=2", "radix-k k=4") else 9)
gbits = sorted({r["gbit"] for r in comp})
sizes = sorted({r["width"] for r in comp})
nodes_all = sorted({r["nodes"] for r in comp})

# The goal: 8 nodes, 1 Gbit/s, 1024²: the best strategy with RLE against direct send without RLE.
md += ["## Goal: 8 nodes, 1 Gbit/s, 1024² (engine layers)", ""]
base = sec(8, 1.0, 1024, "direct", "float", "off")
if base:
    md += ["| strategy | precision | RLE | seconds | MB sent | direct send without RLE (float) / this |",
           "|---|---|---|---|---|---|"]
    for prec in ("float", "rgba8"):
        for n in names:
            for rle in ("on", "off"):
                r = sec(8, 1.0, 1024, n, prec, rle)
                if r:
                    md.append(f"| {n} | {prec} | {rle} | {r['seconds']:.4f} | {r['bytes_sent'] / 1e6:.2f} | "
                              f"{base['seconds'] / r['seconds']:.2f} |")
    for prec in ("float", "rgba8"):
        cands = [sec(8, 1.0, 1024, n, prec, "on") for n in names]
        cands = [c for c in cands if c]
        if cands:
            best = min(cands, key=lambda c: c["seconds"])
            md.append(f"\nBest with RLE ({prec}): {best['name']}, {best['seconds']:.4f} s: "
                      f"{base['seconds'] / best['seconds']:.2f}x faster than direct send without RLE in float "
                      f"({base['seconds']:.4f} s).")
else:
    md.append("(no 8-node 1 Gbit/s 1024² runs)")

md += ["", "## Fastest strategy per case (float; RGBA8 in brackets)", "",
       "| nodes | Gbit/s | image | RLE on: fastest (s) | its margin over the next | RLE off: fastest (s) |",
       "|---|---|---|---|---|---|"]
for nodes in nodes_all:
    for g in gbits:
        for size in sizes:
            cells = []
            for rle in ("on", "off"):
                txt = []
                for prec in ("float", "rgba8"):
                    rs = sorted((r for n in names if (r := sec(nodes, g, size, n, prec, rle))), key=lambda r: r["seconds"])
                    if rs:
                        m = f"{rs[1]['seconds'] / rs[0]['seconds']:.2f}x" if len(rs) > 1 else ""
                        txt.append((f"{rs[0]['name']} ({rs[0]['seconds']:.4f})", m))
                cells.append(txt)
            if cells[0]:
                on = cells[0][0][0] + (f" [{cells[0][1][0]}]" if len(cells[0]) > 1 else "")
                off = cells[1][0][0] + (f" [{cells[1][1][0]}]" if len(cells[1]) > 1 else "") if cells[1] else ""
                md.append(f"| {nodes} | {g:g} | {size}² | {on} | {cells[0][0][1]} | {off} |")

md += ["", "## What RLE pays on real frames", "",
       "Seconds and bytes without RLE over with RLE (median and range over sizes), per strategy, nodes and bandwidth; float.", "",
       "| strategy | nodes | Gbit/s | seconds off/on | bytes off/on |", "|---|---|---|---|---|"]
for n in names:
    for nodes in nodes_all:
        for g in gbits:
            t, b = [], []
            for size in sizes:
                on, off = sec(nodes, g, size, n, "float", "on"), sec(nodes, g, size, n, "float", "off")
                if on and off:
                    t.append(off["seconds"] / on["seconds"])
                    b.append(off["bytes_sent"] / on["bytes_sent"])
            if t:
                md.append(f"| {n} | {nodes} | {g:g} | {statistics.median(t):.2f} ({min(t):.2f}–{max(t):.2f}) | "
                          f"{statistics.median(b):.2f} |")

# The cost model per bandwidth (bench/compositing/fit.py's columns).
cols = ["strategy", "radix", "precision", "rle", "layers", "ranks", "width", "height", "seconds",
        "bytes_sent", "messages", "pixels_composited", "memcpy_s"]
raw = list(csv.DictReader(open(comp_path))) if comp else []
md += ["", "## The cost model per bandwidth", "",
       "bench/compositing/fit.py fitted to each bandwidth's runs (all node counts and sizes): "
       "β is seconds per byte sent (all ranks' bytes). A link of R Gbit/s moves a byte in 8/R ns; "
       "direct send's bytes all cross rank 0's link, so its β should approach 8/R ns where the wire "
       "dominates; the swap strategies' bytes cross P links at once. Full tables in fit-GBIT/fit.md.", "",
       "| Gbit/s | 8/R (ns / byte) | strategy | α (µs / message) | β (ns / byte) | γ (ns / pixel) | R² |",
       "|---|---|---|---|---|---|---|"]
for g in gbits:
    d = os.path.join(out, f"fit-{g:g}gbit")
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "bench-compositing.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in raw:
            if float(r["gbit"]) == g:
                w.writerow([r[c] for c in cols])
    res = subprocess.run([sys.executable, os.path.join(here, "..", "compositing", "fit.py"), d,
                          os.path.join(raw_dir, os.path.basename(d))],
                         capture_output=True, text=True)
    if res.returncode != 0:
        md.append(f"| {g:g} | fit failed: {res.stderr.strip()[:200]} |")
        continue
    for line in open(os.path.join(d, "fit.md")):
        if line.startswith("| ") and "float rle-" in line and "runs" not in line:
            parts = [p.strip() for p in line.strip().strip("|").split("|")]
            if len(parts) == 6:
                md.append(f"| {g:g} | {8 / g:.2f} | {parts[0]} | {parts[2]} | {parts[3]} | {parts[4]} | {parts[5]} |")
        if line.startswith("Unconstrained"):
            break

if rend:
    md += ["", "## The whole renderer (engine, ramp, d = 2)", "",
           "Median over the frames after the first. rank 0's transfer_s includes waiting for the other "
           "ranks to finish rendering (the nodes share two cores), so total_s and the difference "
           "between bandwidths say more than transfer_s alone.", "",
           "| nodes | Gbit/s | image | precision | strategy | RLE | rank 0 transfer_s | composite_s | total_s | max render_s | MB sent |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(rend, key=lambda r: (int(r["nodes"]), int(r["size"]), float(r["gbit"]))):
        md.append(f"| {r['nodes']} | {float(r['gbit']):g} | {r['size']}² | {r['precision']} | {r['strategy']} | {r['rle']} | "
                  f"{float(r['rank0_transfer_s']):.3f} | {float(r['composite_s']):.3f} | {float(r['total_s']):.3f} | "
                  f"{float(r['max_render_s']):.3f} | {int(r['bytes_sent']) / 1e6:.2f} |")

open(os.path.join(out, "summary.md"), "w").write("\n".join(md) + "\n")
print("\n".join(md))

if not comp:
    sys.exit(0)
# Chart: compositing seconds against bandwidth; top row 8 nodes at each size (float), bottom row
# 1024² on 2 and 4 nodes (float) and 8 nodes in RGBA8.
panels = [(8, s, "float") for s in sizes][:3] + [(2, 1024, "float"), (4, 1024, "float"), (8, 1024, "rgba8")]
dat = os.path.join(raw_dir, "compositing.dat")
series = [(n, rle) for n in names for rle in ("on", "off")]
blocks = {}  # (panel, series) -> index in the data file, where there are points
with open(dat, "w") as f:
    idx = 0
    for p, (nodes, size, prec) in enumerate(panels):
        for i, (n, rle) in enumerate(series):
            pts = [(g, r["seconds"]) for g in gbits if (r := sec(nodes, g, size, n, prec, rle))]
            if pts:
                f.write(f"# {nodes} nodes {size} {prec} {n} rle-{rle}\n")
                f.writelines(f"{g} {t}\n" for g, t in pts)
                f.write("\n\n")
                blocks[(p, i)] = idx
                idx += 1
colors = {"direct": "#d62728", "binary-swap k=2": "#1f77b4", "radix-k k=4": "#2ca02c"}
png = os.path.join(out, "compositing.png")
script = [f'set terminal pngcairo size 1500,900 font ",10"', f'set output "{png}"',
          'set multiplot layout 2,3 title "Compositing the engine CT\'s brick images over shaped TCP links (cluster rehearsal, bench-compositing\'s layers)"',
          'set logscale xy', f'set xrange [{min(gbits) * 0.8}:125]', 'set xtics ("0.1" 0.1, "1" 1, "10" 10, "100" 100)',
          'set xlabel "link bandwidth per node (Gbit/s)"', 'set ylabel "seconds per composite"', 'set grid',
          'set key top right font ",9"']
for p, (nodes, size, prec) in enumerate(panels):
    plots = []
    for i, (n, rle) in enumerate(series):
        if (p, i) in blocks:
            dt = 1 if rle == "on" else 2
            plots.append(f"'{dat}' index {blocks[(p, i)]} using 1:2 with linespoints lw 2 dt {dt} pt 7 "
                         f"lc rgb '{colors.get(n, 'black')}' title '{n} RLE {rle}'")
    if plots:
        script.append(f'set title "{nodes} nodes, {size}x{size}, {prec}"')
        script.append("plot " + ", ".join(plots))
script.append("unset multiplot")
subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, check=True)
print(f"wrote {os.path.join(out, 'summary.md')} and {png}", file=sys.stderr)
