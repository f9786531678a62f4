#!/usr/bin/env python3
"""bench.csv, bench.png and README.md of results/insitu from the run logs of bench/insitu/run.

Usage: summarise.py OUT_DIR EVERY [RAW_DIR]
Reads RAW_DIR/logs/ (default build/bench-runs/insitu/logs/, bench/insitu/run's):
<example>-<size>-np<ranks>-run<k>.log (rank 0's `step S sim_s X vis_s Y
mem_mib Z added_mib A texture_mib T` lines, then `# load L`) and the pictures-*.txt logs.
"""
import csv
import datetime
import glob
import os
import platform
import re
import statistics
import subprocess
import sys

DEFAULT_SIZE = {"gray_scott": 64, "particles": 8000}
RUN_FIELDS = ["example", "size", "ranks", "run", "steps", "every", "sim_s_per_step", "sim_s_median",
              "vis_s_per_render", "vis_s_first", "added_mib", "texture_mib", "load_avg"]


def parse_log(path, every):
    steps, load = [], ""
    for line in open(path):
        f = line.split()
        if f and f[0] == "step":
            steps.append({"step": int(f[1]), "sim": float(f[3]), "vis": float(f[5]),
                          "added": float(f[9]), "texture": float(f[11])})
        elif line.startswith("# load"):
            load = f[2]
    sim = [s["sim"] for s in steps if s["step"] > 0]
    rendered = [s for s in steps if s["step"] % every == 0]
    later = [s["vis"] for s in rendered if s["step"] > 0]
    return {
        "steps": max(s["step"] for s in steps), "every": every,
        "sim_s_per_step": f"{statistics.mean(sim):.6f}", "sim_s_median": f"{statistics.median(sim):.6f}",
        "vis_s_per_render": f"{statistics.mean(later):.4f}", "vis_s_first": f"{rendered[0]['vis']:.4f}",
        "added_mib": f"{max(s['added'] for s in rendered):.3f}",
        "texture_mib": f"{max(s['texture'] for s in rendered):.3f}", "load_avg": load,
    }


def machine():
    model = "unknown CPU"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    with open("/proc/meminfo") as f:
        mem_gib = int(f.readline().split()[1]) / (1024 * 1024)
    try:
        system = "Debian " + open("/etc/debian_version").read().strip()
    except OSError:
        system = platform.platform()
    return (f"{os.cpu_count()} cores ({model}), {mem_gib:.0f} GiB, {system}; no GPU: Mesa llvmpipe "
            "through OSMesa")


def label(r):
    size = f"{r['size']}³" if r["example"] == "gray_scott" else f"{int(r['size']) // 1000}k"
    return f"{'GS' if r['example'] == 'gray_scott' else 'P'} {size} np{r['ranks']}"


def best_of(runs):
    """One row per configuration: the smallest of each time over its runs (other work only adds)."""
    groups = {}
    for r in runs:
        groups.setdefault((r["example"], int(r["size"]), int(r["ranks"])), []).append(r)
    rows = []
    for (example, size, ranks), rs in sorted(groups.items(), key=lambda kv: (kv[0][2], kv[0][0], kv[0][1])):
        sim = min(float(r["sim_s_per_step"]) for r in rs)
        vis = min(float(r["vis_s_per_render"]) for r in rs)
        rows.append({
            "example": example, "size": size, "ranks": ranks, "runs": len(rs),
            "sim_s_per_step": f"{sim:.6f}",
            "sim_s_median": f"{min(float(r['sim_s_median']) for r in rs):.6f}",
            "ten_steps_s": f"{10 * sim:.4f}", "vis_s_per_render": f"{vis:.4f}",
            "vis_s_first": f"{min(float(r['vis_s_first']) for r in rs):.4f}",
            "render_over_ten_steps": f"{vis / (10 * sim):.1f}",
            "added_mib": max(r["added_mib"] for r in rs), "texture_mib": max(r["texture_mib"] for r in rs),
            "load_avg": " ".join(r["load_avg"] for r in rs),
        })
    return rows


def chart(rows, out, raw):
    os.makedirs(raw, exist_ok=True)
    dat = os.path.join(raw, "bench.dat")
    with open(dat, "w") as f:
        f.write("# label ten_steps_s vis_s_per_render added_mib texture_mib\n")
        for r in rows:
            f.write(f"\"{label(r)}\" {r['ten_steps_s']} {r['vis_s_per_render']} "
                    f"{max(float(r['added_mib']), 1e-3)} {max(float(r['texture_mib']), 1e-3)}\n")
    script = f"""
set terminal pngcairo size 1100,800 font ",10" noenhanced
set output "{os.path.join(out, 'bench.png')}"
set multiplot layout 2,1
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set xtics rotate by -35 scale 0
set logscale y
set grid ytics
set key top left
set title "In situ: an image every 10 steps against those 10 steps (rank 0, best of the runs; GS = gray_scott, P = particles)"
set ylabel "seconds"
set yrange [0.001:100]
plot "{dat}" using 2:xtic(1) title "10 simulation steps", "" using 3 title "one rendered step (execute)"
set title "Memory sortlast adds on rank 0 (particles: no texture)"
set ylabel "MiB"
set yrange [0.01:100]
plot "{dat}" using 4:xtic(1) title "host buffers (memory_added_mib)", "" using 5 title "brick texture (texture_mib)"
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def pictures_lines(raw):
    """The cost of an image late in the pictures runs (the developed state)."""
    lines = []
    for name, what in (("gray_scott", "64³, 2 ranks"), ("particles", "8,000, 2 ranks")):
        path = os.path.join(raw, "logs", f"pictures-{name}.txt")
        if not os.path.exists(path):
            continue
        steps = [l.split() for l in open(path) if l.startswith("step ")]
        sim = statistics.median(float(f[3]) for f in steps if int(f[1]) > 0)
        last = [f for f in steps if float(f[5]) > 0.02][-1]
        lines.append(f"{name} ({what}), step {last[1]}: one image {float(last[5]):.3f} s vs 10 steps "
                     f"{10 * sim:.4f} s (median step; x{float(last[5]) / (10 * sim):.0f})")
    return lines


def main():
    out, every = sys.argv[1], int(sys.argv[2])
    raw = sys.argv[3] if len(sys.argv) > 3 else "build/bench-runs/insitu"
    runs = []
    for path in sorted(glob.glob(os.path.join(raw, "logs", "*-run*.log"))):
        m = re.match(r"(gray_scott|particles)-(\d+)-np(\d+)-run(\d+)\.log$", os.path.basename(path))
        if m:
            runs.append({"example": m[1], "size": m[2], "ranks": m[3], "run": m[4], **parse_log(path, every)})
    runs.sort(key=lambda r: (int(r["ranks"]), r["example"], int(r["size"]), int(r["run"])))
    with open(os.path.join(out, "bench.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=RUN_FIELDS)
        w.writeheader()
        w.writerows(runs)
    rows = best_of(runs)
    chart(rows, out, raw)

    cols = ["example", "size", "ranks", "sim_s_per_step", "sim_s_median", "ten_steps_s", "vis_s_per_render",
            "vis_s_first", "render_over_ten_steps", "added_mib", "texture_mib", "load_avg"]
    table = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    table += ["| " + " | ".join(str(r[c]) for c in cols) + " |" for r in rows]

    mem_lines, time_lines = [], []
    for r in rows:
        added, tex = float(r["added_mib"]), float(r["texture_mib"])
        if r["example"] == "gray_scott":
            mem_lines.append(f"{label(r)}: {added:.3f} MiB host vs {tex:.3f} MiB texture: "
                             f"{'holds' if added <= tex + 1e-9 else 'FAILS'}")
        if r["size"] == DEFAULT_SIZE[r["example"]]:
            ratio = float(r["vis_s_per_render"]) / float(r["ten_steps_s"])
            time_lines.append(f"{label(r)}: one image {r['vis_s_per_render']} s vs 10 steps {r['ten_steps_s']} s "
                              f"(x{ratio:.0f}): {'holds' if ratio < 1 else 'FAILS'}")
    part_mem = "; ".join(f"{label(r)} {r['added_mib']} MiB" for r in rows if r["example"] == "particles")
    late = pictures_lines(raw)
    def spread(example):
        v = [float(r["vis_s_per_render"]) for r in rows if r["example"] == example]
        return f"{min(v):.2g}–{max(v):.2g} s" if v else "?"
    sims = [float(r["sim_s_per_step"]) for r in rows]
    if any("FAILS" in l for l in time_lines):
        verdict = (f"It does not hold on this machine: the simulations' steps are cheap ({min(sims) * 1e3:.1f}–"
                   f"{max(sims) * 1e3:.1f} ms), and the images are drawn by llvmpipe on the same two cores (a 512² "
                   f"volume image {spread('gray_scott')}, a metaball image {spread('particles')}).")
    else:
        verdict = "It holds."
    verdict += (" The 30 steps render the start of each run (gray_scott: the seeded cube, most of the domain "
                "empty and skipped); late in the default runs of the pictures below:\n\n" +
                "\n".join("- " + l for l in late))
    steps = runs[0]["steps"] if runs else "?"
    runs_per = rows[0]["runs"] if rows else "?"

    text = f"""# In situ — `bench/insitu/run`

[CSV, a row per run](bench.csv) · [chart](bench.png) · per-step logs (not kept in git) in `build/bench-runs/insitu/logs/`

Measured {datetime.date.today().isoformat()} on {machine()}; `mpirun --bind-to none`, so 2 and 4
ranks share the 2 cores (with llvmpipe's threads). Other work on the machine shows in `load_avg`
(the 1-minute load average at the end of each run; 2 = both cores busy).

Both examples (`examples/`) with their built-in actions: an image (512², the volume sampled every
0.5 voxel, metaballs of radius 0.6 spacings) every {every} steps, {steps} steps after the initial
state, {runs_per} runs per configuration, the best of each time kept (other work only adds time: a
rank waiting in a halo exchange for one that lost its core waits a whole time slice). All figures
are rank 0's, from its `step S sim_s X vis_s Y mem_mib Z` lines: `sim_s_per_step` the mean over
steps 1–{steps} (`sim_s_median` the median step), `ten_steps_s` = 10 × the mean;
`vis_s_per_render` the mean `execute()` of the rendered steps after step 0, `vis_s_first` step 0's
(it also starts GL); `render_over_ten_steps` their ratio (below 1: an image every 10 steps costs
less than those 10 steps). `added_mib` is sortlast's host memory on the rank
(`ExecuteReport::memory_added_mib`: the ghost shell fetched from the neighbours, the float64 →
float conversion chunk, particle copies; the chunk is freed after the upload, so this is a peak),
`texture_mib` its brick's R32F texture; both the largest over the rendered steps.

![seconds and memory](bench.png)

{chr(10).join(table)}

## The goal

**Memory: sortlast's host buffers no larger than one brick's GL texture per rank** (volume):

{chr(10).join('- ' + l for l in mem_lines)}

Where the brick is under 4 MiB the conversion chunk holds the whole brick as float while it is
uploaded (equal to the texture: the goal holds with no margin); above, the chunk stays at 4 MiB.
Particles have no texture: sortlast keeps float copies of the particles within reach of the rank's
bricks (12 bytes each; the simulation holds 48 per particle): {part_mem}.

**Time: an image every 10 steps costs less than those 10 steps, at the default sizes**
(gray_scott 64³, particles 8,000; 512² images):

{chr(10).join('- ' + l for l in time_lines)}

{verdict}

## Pictures

The default runs on 2 ranks: `gray_scott` (64³, F = 0.022, k = 0.051; steps 500, 1000, 2000) and
`particles` (8,000; steps 0, 200, 400).

| | | |
|---|---|---|
| ![](gray_scott_000500.png) | ![](gray_scott_001000.png) | ![](gray_scott_002000.png) |
| ![](particles_000000.png) | ![](particles_000200.png) | ![](particles_000400.png) |
"""
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
