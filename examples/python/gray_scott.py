#!/usr/bin/env python3
"""gray_scott.py: the Gray-Scott example (examples/gray_scott/) as a numpy + mpi4py simulation,
rendered in situ by sortlast every --every steps from its own arrays (no copy).

    mpirun -np 4 python3 examples/python/gray_scott.py --size 64 --steps 2000 --every 20 --out gs

The same model, initial state, decomposition (MPI.Compute_dims, periodic Cartesian communicator),
halo exchange and built-in actions as the C++ example, computed in the same order of operations:
for the same options and step the two write the same images, byte for byte.
    dU/dt = Du lap(U) - U V^2 + F (1 - U),   dV/dt = Dv lap(V) + U V^2 - (F + k) V
Each rank holds its block with one ghost layer on every face as a C-ordered array indexed
[z, y, x]; sortlast takes grid[x, y, z], so it is handed the transpose `v.T`, a view.
"""
import argparse
import os
import sys
import time

import numpy as np
from mpi4py import MPI

import sortlast


def noise(gi, field):
    """Deterministic noise in [0, 1) from global sample indices (the C++ example's splitmix)."""
    with np.errstate(over="ignore"):
        z = gi.astype(np.uint64) * np.uint64(2) + np.uint64(field) + np.uint64(0x9E3779B97F4A7C15)
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        z ^= z >> np.uint64(31)
    return (z >> np.uint64(11)).astype(np.float64) * 2.0**-53


class GrayScott:
    def __init__(self, n=64, F=0.022, k=0.051, Du=0.16, Dv=0.08, dt=1.0, comm=MPI.COMM_WORLD):
        self.n, self.F, self.k, self.Du, self.Dv, self.dt = n, F, k, Du, Dv, dt
        dims = MPI.Compute_dims(comm.Get_size(), 3)
        if max(dims) > n:
            raise ValueError(f"--size {n} is too small for {comm.Get_size()} ranks")
        self.cart = comm.Create_cart(dims, periods=[True] * 3, reorder=False)
        coords = self.cart.Get_coords(self.cart.Get_rank())
        self.procs = dims
        self.owned, self.offset, self.neighbours = [], [], []
        for a in range(3):  # a = 0 is x
            base, extra = divmod(n, dims[a])
            self.owned.append(base + (1 if coords[a] < extra else 0))
            self.offset.append(coords[a] * base + min(coords[a], extra))
            self.neighbours.append(self.cart.Shift(a, 1))  # (lower, upper)
        ox, oy, oz = self.owned
        shape = (oz + 2, oy + 2, ox + 2)
        self.u = np.ones(shape)
        self.v = np.zeros(shape)
        # Global indices of the owned samples, [z, y, x].
        z, y, x = np.meshgrid(*(np.arange(self.offset[a], self.offset[a] + self.owned[a]) for a in (2, 1, 0)),
                              indexing="ij")
        gi = x + n * (y + n * z)
        lo, hi = n // 2 - max(2, n // 10), n // 2 + max(2, n // 10)
        seeded = (x >= lo) & (x < hi) & (y >= lo) & (y < hi) & (z >= lo) & (z < hi)
        n0, n1 = noise(gi, 0), noise(gi, 1)
        inner = (slice(1, -1),) * 3
        self.u[inner] = np.where(seeded, 0.25 + 0.1 * (n0 - 0.5), 1.0 - 0.1 * n0)
        self.v[inner] = np.where(seeded, 0.33 + 0.3 * (n1 - 0.5), 0.0)
        self.exchange(self.u)
        self.exchange(self.v)

    def exchange(self, a):
        """Halo exchange along x, then y, then z; whole faces (ghosts included along the other
        axes), so edges and corners fill too. Periodic: the communicator wraps around."""
        for axis in range(3):
            lower, upper = self.neighbours[axis]
            npaxis = 2 - axis

            def face(i):
                index = [slice(None)] * 3
                index[npaxis] = i
                return tuple(index)

            recv = np.empty_like(a[face(0)])
            # First owned layer down, the upper neighbour's into the high ghost; then the other way.
            self.cart.Sendrecv(np.ascontiguousarray(a[face(1)]), dest=lower, sendtag=2 * axis,
                               recvbuf=recv, source=upper, recvtag=2 * axis)
            a[face(-1)] = recv
            self.cart.Sendrecv(np.ascontiguousarray(a[face(-2)]), dest=upper, sendtag=2 * axis + 1,
                               recvbuf=recv, source=lower, recvtag=2 * axis + 1)
            a[face(0)] = recv

    def step(self):
        u, v = self.u, self.v
        c = (slice(1, -1),) * 3
        uc, vc = u[c], v[c]

        def lap(f, fc):  # x-, x+, y-, y+, z-, z+: the C++ example's order of additions
            return (f[1:-1, 1:-1, :-2] + f[1:-1, 1:-1, 2:] + f[1:-1, :-2, 1:-1] + f[1:-1, 2:, 1:-1]
                    + f[:-2, 1:-1, 1:-1] + f[2:, 1:-1, 1:-1]) / 6.0 - fc

        uvv = uc * vc * vc
        u2 = uc + self.dt * (self.Du * lap(u, uc) - uvv + self.F * (1.0 - uc))
        v2 = vc + self.dt * (self.Dv * lap(v, vc) + uvv - (self.F + self.k) * vc)
        u[c] = u2
        v[c] = v2
        self.exchange(u)
        self.exchange(v)

    def publish(self, vis, step):
        """V where it lies: the whole array with its ghost layers, as grid[x, y, z]."""
        vis.publish(step, step * self.dt, grid=self.v.T, ghosts=1, origin=self.offset,
                    spacing=1.0, name="V")


def builtin_actions(n, every, width, out):
    """The C++ example's built-in actions (examples/gray_scott/main.cpp), the same text."""
    c, d = 0.5 * (n - 1), 3.5 * n
    quoted = '"' + (out + "/v_{step}.png").replace("\\", "\\\\").replace('"', '\\"') + '"'
    return f"""renders:
  - name: v
    output: {quoted}
    trigger: {{every: {every}}}
    scene:
      image: {{width: {width}, height: {width}}}
      camera: {{look_at: [{c:g}, {c:g}, {c:g}], position: [{c + 0.5 * d:g}, {c + 0.45 * d:g}, {c + 0.74 * d:g}], fov: 30}}
      render: {{sample_spacing: 0.5}}
      transfer:
        range: [0, 0.5]
        points:
          - [0, 0, 0, 0, 0]
          - [0.25, 0.05, 0.1, 0.4, 0]
          - [0.42, 0.15, 0.35, 0.85, 0.02]
          - [0.55, 0.95, 0.55, 0.2, 0.12]
          - [0.68, 1, 0.8, 0.45, 0.4]
          - [0.85, 1, 1, 0.9, 0.7]
          - [1, 1, 1, 1, 0.85]
"""


def run(size=64, steps=2000, every=20, width=512, out="gray_scott_out", actions=None, F=0.022, k=0.051,
        comm=MPI.COMM_WORLD, log=True):
    """Runs the simulation; returns the image files rank 0 wrote."""
    sim = GrayScott(size, F=F, k=k, comm=comm)
    if actions is None:
        if comm.Get_rank() == 0:
            os.makedirs(out, exist_ok=True)
        vis = sortlast.InSitu.from_text(comm, builtin_actions(size, every, width, out))
    else:
        vis = sortlast.InSitu(comm, actions)
    images = []
    with vis:
        for step in range(steps + 1):
            sim_s = 0.0
            if step > 0:
                t0 = time.perf_counter()
                sim.step()
                sim_s = time.perf_counter() - t0
            sim.publish(vis, step)
            report = vis.execute()
            images += report["images"]
            if log and comm.Get_rank() == 0:
                r = report  # the C++ examples' line (examples/common/example_cli.h)
                print(f"step {step} sim_s {sim_s:.6f} vis_s {r['seconds']:.6f} "
                      f"mem_mib {r['memory_added_mib'] + r['texture_mib']:.3f} added_mib {r['memory_added_mib']:.3f} "
                      f"texture_mib {r['texture_mib']:.3f}" + (f" error {r['error']}" if r["error"] else ""), flush=True)
    sim.cart.Free()
    return images


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size", type=int, default=64, help="global grid N^3 (periodic)")
    p.add_argument("--steps", type=int, default=2000, help="steps after the initial state (step 0)")
    p.add_argument("--every", type=int, default=20, help="built-in actions: an image every K steps")
    p.add_argument("--width", type=int, default=512, help="built-in actions: image W x W")
    p.add_argument("--out", default="gray_scott_out", help="built-in actions: DIR/v_{step}.png")
    p.add_argument("--actions", help="an actions file instead of the built-in actions")
    p.add_argument("--F", type=float, default=0.022)
    p.add_argument("--k", type=float, default=0.051)
    p.add_argument("--quiet", action="store_true", help="no line per step")
    a = p.parse_args()
    try:
        run(a.size, a.steps, a.every, a.width, a.out, a.actions, a.F, a.k, log=not a.quiet)
    except sortlast.InSituError as e:  # raised on every rank alike
        if MPI.COMM_WORLD.Get_rank() == 0:
            print(f"gray_scott.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
