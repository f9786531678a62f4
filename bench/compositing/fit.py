"""Fits the classic compositing cost model to bench/compositing/run's CSV.

    t = alpha * messages + beta * bytes_sent + gamma * pixels_composited

per strategy, by least squares without intercept (numpy if installed, else the 3x3 normal
equations solved here, columns scaled to unit norm first). Writes OUT/fit.md (alpha, beta, gamma,
R^2, and every run as measured / predicted / multiple of one memcpy of the frame's RGBA8 bytes x
ranks) and OUT/model.png (gnuplot pngcairo: measured against predicted, log-log).

Usage: python3 bench/compositing/fit.py OUT_DIR [RAW_DIR]   (reads OUT_DIR/bench-compositing.csv;
the chart's gnuplot data file goes to RAW_DIR, default build/bench-runs/compositing)
"""
import csv
import os
import subprocess
import sys

out = sys.argv[1]
raw = sys.argv[2] if len(sys.argv) > 2 else "build/bench-runs/compositing"
os.makedirs(raw, exist_ok=True)
rows = list(csv.DictReader(open(os.path.join(out, "bench-compositing.csv"))))
for r in rows:
    for k in ("ranks", "width", "height"):
        r[k] = int(r[k])
    for k in ("seconds", "bytes_sent", "messages", "pixels_composited", "memcpy_s"):
        r[k] = float(r[k]) if r[k] else 0.0
    r.setdefault("precision", "float")
    r.setdefault("rle", "on")
    r.setdefault("layers", "synthetic")
    name = r["strategy"] if r["strategy"] == "direct" else f"{r['strategy']} k={r['radix']}"
    r["label"] = f"{name} {r['precision']} rle-{r['rle']}"


def lstsq(X, y):
    """Least squares without intercept; X is a list of rows of 3 features."""
    try:
        import numpy as np
        coef, *_ = np.linalg.lstsq(np.array(X), np.array(y), rcond=None)
        return [float(c) for c in coef]
    except ImportError:
        pass
    n = len(X[0])
    norms = [max(1e-300, sum(row[j] ** 2 for row in X) ** 0.5) for j in range(n)]
    Z = [[row[j] / norms[j] for j in range(n)] for row in X]
    A = [[sum(z[i] * z[j] for z in Z) for j in range(n)] for i in range(n)]
    b = [sum(z[i] * yy for z, yy in zip(Z, y)) for i in range(n)]
    for i in range(n):
        A[i][i] += 1e-12  # a tiny ridge: a column may be (nearly) constant for one strategy
    # Gaussian elimination with partial pivoting.
    M = [A[i] + [b[i]] for i in range(n)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(M[r][c]))
        M[c], M[p] = M[p], M[c]
        for r in range(c + 1, n):
            f = M[r][c] / M[c][c]
            M[r] = [a - f * bb for a, bb in zip(M[r], M[c])]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (M[i][n] - sum(M[i][j] * x[j] for j in range(i + 1, n))) / M[i][i]
    return [x[j] / norms[j] for j in range(n)]


def nnls(X, y):
    """Non-negative least squares for a few features: the best fit over every subset of
    features whose unconstrained coefficients are all >= 0 (the others held at 0)."""
    n = len(X[0])
    best, best_res = [0.0] * n, sum(v * v for v in y)
    for mask in range(1, 1 << n):
        cols = [j for j in range(n) if mask >> j & 1]
        c = lstsq([[row[j] for j in cols] for row in X], y)
        if min(c) < 0:
            continue
        coef = [0.0] * n
        for j, v in zip(cols, c):
            coef[j] = v
        res = sum((yy - sum(a * b for a, b in zip(coef, row))) ** 2 for row, yy in zip(X, y))
        if res < best_res:
            best, best_res = coef, res
    return best


labels = sorted({r["label"] for r in rows})
fits, free_fits = {}, {}
for lab in labels:
    sel = [r for r in rows if r["label"] == lab]
    X = [[r["messages"], r["bytes_sent"], r["pixels_composited"]] for r in sel]
    y = [r["seconds"] for r in sel]
    a, b, g = nnls(X, y)
    free = lstsq(X, y)
    mean = sum(y) / len(y)
    ss_tot = sum((v - mean) ** 2 for v in y)
    for r, xr in zip(sel, X):
        r["predicted"] = a * xr[0] + b * xr[1] + g * xr[2]
    ss_res = sum((r["seconds"] - r["predicted"]) ** 2 for r in sel)
    fits[lab] = (a, b, g, 1 - ss_res / ss_tot if ss_tot > 0 else float("nan"), len(sel))
    preds = [sum(c * v for c, v in zip(free, xr)) for xr in X]
    ss_free = sum((p - v) ** 2 for p, v in zip(preds, y))
    free_fits[lab] = (*free, 1 - ss_free / ss_tot if ss_tot > 0 else float("nan"), len(sel))

md = [f"# Compositing cost model fit\n",
      f"From `{os.path.join(out, 'bench-compositing.csv')}` ({len(rows)} runs); "
      "t = α·messages + β·bytes_sent + γ·pixels_composited, least squares without intercept, "
      "one fit per strategy. messages, bytes and pixels are totals over all ranks for one "
      "composite; t is the median over repetitions of the slowest rank's seconds. "
      "Coefficients constrained to be >= 0 (a zero means that term did not help); the "
      "unconstrained fit follows.\n",
      "| strategy | runs | α (µs / message) | β (ns / byte) | γ (ns / pixel) | R² |",
      "|---|---|---|---|---|---|"]
for lab, (a, b, g, r2, n) in fits.items():
    md.append(f"| {lab} | {n} | {a * 1e6:.1f} | {b * 1e9:.3f} | {g * 1e9:.2f} | {r2:.3f} |")
md += ["", "Unconstrained least squares:", "",
       "| strategy | runs | α (µs / message) | β (ns / byte) | γ (ns / pixel) | R² |",
       "|---|---|---|---|---|---|"]
for lab, (a, b, g, r2, n) in free_fits.items():
    md.append(f"| {lab} | {n} | {a * 1e6:.1f} | {b * 1e9:.3f} | {g * 1e9:.2f} | {r2:.3f} |")
md += ["", "Negative coefficients in the unconstrained fit mean the three terms are nearly collinear for that strategy "
       "(e.g. direct send's message count is ranks − 1 and its bytes and pixels grow together), "
       "so read the fits as a description of these runs, not as hardware constants.", "",
       "memcpy_s is the median of one memcpy of width × height × 4 × ranks bytes on rank 0; "
       "× memcpy = seconds / memcpy_s.", "",
       "| strategy | layers | ranks | image | seconds | predicted (≥ 0 fit) | × memcpy | MB sent | messages | Mpixels |",
       "|---|---|---|---|---|---|---|---|---|---|"]
for r in sorted(rows, key=lambda r: (r["label"], r["layers"], r["width"], r["ranks"])):
    mult = r["seconds"] / r["memcpy_s"] if r["memcpy_s"] > 0 else float("nan")
    md.append(f"| {r['label']} | {r['layers']} | {r['ranks']} | {r['width']}² | {r['seconds']:.4f} | "
              f"{r['predicted']:.4f} | {mult:.0f} | {r['bytes_sent'] / 1e6:.2f} | "
              f"{r['messages']:.0f} | {r['pixels_composited'] / 1e6:.2f} |")

# What each variant costs against float with RLE: the median ratio of seconds and of bytes over
# every (layers, strategy, ranks, size) measured both ways.
def ratio_table(field, other, base):
    out_rows = []
    for layers in sorted({r["layers"] for r in rows}):
        for strat in sorted({(r["strategy"], r["radix"]) for r in rows}):
            t, b = [], []
            for r in rows:
                if (r["layers"], r["strategy"], r["radix"]) != (layers, *strat) or r[field] != other:
                    continue
                ref = [q for q in rows if (q["layers"], q["strategy"], q["radix"], q["ranks"],
                        q["width"]) == (layers, *strat, r["ranks"], r["width"]) and q[field] == base
                       and all(q[k] == r[k] for k in ("precision", "rle") if k != field)]
                if ref and ref[0]["seconds"] > 0 and ref[0]["bytes_sent"] > 0:
                    t.append(r["seconds"] / ref[0]["seconds"])
                    b.append(r["bytes_sent"] / ref[0]["bytes_sent"])
            if t:
                t.sort(), b.sort()
                name = strat[0] if strat[0] == "direct" else f"{strat[0]} k={strat[1]}"
                out_rows.append(f"| {layers} | {name} | {len(t)} | {t[len(t) // 2]:.2f} "
                                f"({t[0]:.2f}–{t[-1]:.2f}) | {b[len(b) // 2]:.2f} |")
    return out_rows

md += ["", "## Variants against float with RLE on", "",
       "Median (range) of seconds ratio and median bytes ratio over all sizes and rank counts.", "",
       "RLE off / on:", "", "| layers | strategy | runs | seconds ratio | bytes ratio |",
       "|---|---|---|---|---|"] + ratio_table("rle", "off", "on")
md += ["", "RGBA8 / float precision:", "", "| layers | strategy | runs | seconds ratio | bytes ratio |",
       "|---|---|---|---|---|"] + ratio_table("precision", "rgba8", "float")
open(os.path.join(out, "fit.md"), "w").write("\n".join(md) + "\n")
print("\n".join(md))

dat = os.path.join(raw, "model.dat")
with open(dat, "w") as f:
    for i, lab in enumerate(labels):
        f.write(f"# {lab}\n")
        for r in rows:
            if r["label"] == lab:
                f.write(f"{r['seconds']} {max(r['predicted'], 1e-5)}\n")
        f.write("\n\n")
png = os.path.join(out, "model.png")
plots = ", ".join(f"'{dat}' index {i} using 1:2 with points pt 7 ps 1.2 title '{lab}'"
                  for i, lab in enumerate(labels))
script = f"""
set terminal pngcairo size 800,600 font ",10"
set output "{png}"
set title "Compositing: measured vs model t = a*messages + b*bytes + g*pixels"
set xlabel "measured seconds"
set ylabel "predicted seconds"
set logscale xy
set key top left
set grid
plot x with lines lc rgb "gray" title "y = x", {plots}
"""
subprocess.run(["gnuplot"], input=script, text=True, check=True)
print(f"wrote {os.path.join(out, 'fit.md')} and {png}", file=sys.stderr)
