#!/usr/bin/env python3
"""explore.py: a notebook-style tour of sortlast from Python (runnable as a script, or cell by
cell in Jupyter, where frames show inline).

Opens a resident session on a volume, orbits it at several sample spacings, and plots each
spacing's frame time (the session's --stats `total_s`, median over the orbit) against its
accuracy: the PSNR of its frames against the same frames drawn at a much finer spacing (1/8
voxel). Writes a figure with the orbit's frames and the chart.

    python3 examples/python/explore.py tests/data/neghip.yaml --out explore.png
    mpirun -np 2 python3 examples/python/explore.py tests/data/neghip.yaml --out explore.png
"""
import argparse
import statistics

import numpy as np

import sortlast


def over_background(img):
    """A premultiplied float frame over its background, RGB (what a PNG of it shows)."""
    a = np.asarray(img, dtype=np.float64)
    return a[..., :3] + (1.0 - a[..., 3:]) * np.asarray(img.background)


def psnr(a, b):
    mse = np.mean((over_background(a) - over_background(b)) ** 2)
    return float("inf") if mse == 0 else 10 * np.log10(1.0 / mse)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene", nargs="?", default="tests/data/neghip.yaml")
    p.add_argument("--frames", type=int, default=6, help="cameras on the orbit")
    p.add_argument("--size", type=int, default=256, help="image side")
    p.add_argument("--spacings", default="2,1,0.5,0.25", help="sample spacings to try (voxels)")
    p.add_argument("--out", default="explore.png")
    a = p.parse_args()
    spacings = [float(s) for s in a.spacings.split(",")]

    # Loads the scene once; every frame below is a request on top of it (frame keys only).
    s = sortlast.Session(a.scene, set={"camera.orbit.frames": a.frames, "image.width": a.size,
                                       "image.height": a.size})
    info = s.scene  # describe(): bounds, data range, keys a frame may set ... (rank 0)
    reference = [s.frame({"render.sample_spacing": 0.125}, float=True, orbit_frame=f) for f in range(a.frames)]
    rows = []  # (spacing, median frame seconds, mean PSNR dB)
    frames = {}
    for spacing in spacings:
        seconds, quality = [], []
        for f in range(a.frames):
            img = s.frame({"render.sample_spacing": spacing}, float=True, orbit_frame=f)
            if img is None:
                continue  # not rank 0
            seconds.append(s.stats["total_s"])
            quality.append(psnr(img, reference[f]))
            frames.setdefault(spacing, []).append(img)
        if seconds:
            rows.append((spacing, statistics.median(seconds), statistics.mean(quality)))
    s.close()
    if info is None:
        return  # other ranks: they only helped render

    print(f"{a.scene}: bounds {info.get('bounds')}, {a.frames} orbit frames at {a.size}^2")
    print("spacing  median_frame_s  mean_psnr_db")
    for spacing, sec, q in rows:
        print(f"{spacing:7g}  {sec:14.4f}  {q:12.2f}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(12, 6.5))
    grid = fig.add_gridspec(2, a.frames)
    finest = frames[spacings[-1]]
    for f in range(a.frames):
        ax = fig.add_subplot(grid[0, f])
        ax.imshow(np.clip(over_background(finest[f]), 0, 1))
        ax.set_title(f"orbit {f}", fontsize=8)
        ax.axis("off")
    ax = fig.add_subplot(grid[1, :])
    ax.plot([r[1] * 1e3 for r in rows], [r[2] for r in rows], "o-")
    for spacing, sec, q in rows:
        ax.annotate(f"spacing {spacing:g}", (sec * 1e3, q), textcoords="offset points", xytext=(6, -10), fontsize=8)
    ax.margins(x=0.1, y=0.1)
    ax.set_xlabel("frame time, median over the orbit (ms, --stats total_s)")
    ax.set_ylabel("PSNR vs spacing 0.125 (dB)")
    ax.grid(True, alpha=0.3)
    fig.suptitle(f"{a.scene}: sample spacing, frame time and accuracy ({a.size}x{a.size})")
    fig.tight_layout()
    fig.savefig(a.out, dpi=100)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
