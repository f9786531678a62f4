"""The Python module's costs (bench/python/run runs it): one measurement per call.

  frame SCENE_ARGS...: Session.frame's wall time in Python against the session's own frame time
      (--stats total_s), median of 20 frames after 2 warm-up frames; JSON on stdout.
  rss SIZE PUBLISH(0/1): peak RSS of a process holding a SIZE^3 float64 block and (PUBLISH=1)
      publishing and rendering it once, or (0) publishing a 2^3 block instead; JSON on stdout.
"""
import json
import resource
import statistics
import sys
import time

import numpy as np

import sortlast


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def bench_frame(size):
    s = sortlast.Session(None, set={"image.width": size, "image.height": size, "camera.orbit.frames": 22})
    wall, session = [], []
    for f in range(22):
        t0 = time.perf_counter()
        s.frame(orbit_frame=f)
        t = time.perf_counter() - t0
        if f >= 2:
            wall.append(t)
            session.append(s.stats["total_s"])
    s.close()
    print(json.dumps({"python_wall_s": statistics.median(wall), "session_total_s": statistics.median(session),
                      "overhead_s": statistics.median(w - t for w, t in zip(wall, session))}))


ACTIONS = """renders:
  - name: v
    output: "{out}/rss_{{step}}.png"
    trigger: {{every: 1}}
    scene:
      image: {{width: 256, height: 256}}
      transfer: {{range: [0, 1]}}
"""


def bench_rss(n, publish, out):
    block = np.empty((n, n, n), order="F")
    x = np.linspace(0.0, 1.0, n)
    for k in range(n):  # touch every page, a smooth field
        block[:, :, k] = np.outer(x, x) * x[k]
    before = peak_mib()
    vis = sortlast.InSitu.from_text(None, ACTIONS.format(out=out))
    small = np.zeros((2, 2, 2))
    vis.publish(0, 0.0, grid=block if publish else small)
    report = vis.execute()
    vis.close()
    print(json.dumps({"size": n, "published": bool(publish), "block_mib": block.nbytes / 2**20,
                      "peak_before_mib": before, "peak_after_mib": peak_mib(),
                      "memory_added_mib": report["memory_added_mib"], "texture_mib": report["texture_mib"],
                      "execute_s": report["seconds"], "error": report["error"]}))


if __name__ == "__main__":
    if sys.argv[1] == "frame":
        bench_frame(int(sys.argv[2]))
    else:
        bench_rss(int(sys.argv[2]), int(sys.argv[3]), sys.argv[4])
