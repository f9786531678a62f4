"""Bad input raises the right exception on every rank with the C++ message, and the next call
works: scenes, requests, actions, published arrays, NaN with on_error: abort."""
import os

import numpy as np
import pytest

import sortlast

SMALL = {"image.width": 48, "image.height": 32, "volume.dims": [16, 16, 16]}


def test_bad_scene_then_render(comm, rank):
    with pytest.raises(sortlast.InputError, match="nope.key"):
        sortlast.render(set={"nope.key": 1}, comm=comm)
    with pytest.raises(sortlast.InputError, match="cannot open"):
        sortlast.Session("/no/such/scene.yaml", comm=comm)
    img = sortlast.render(set=SMALL, comm=comm)
    assert (img is not None) == (rank == 0)


def test_bad_frame_keeps_session(comm, rank):
    with sortlast.Session(None, set=SMALL, comm=comm) as s:
        with pytest.raises(sortlast.InputError, match="volume.dims"):
            s.frame({"volume.dims": [8, 8, 8]})  # not a frame key
        with pytest.raises(sortlast.InputError, match="image.width"):
            s.frame({"image.width": -5})
        img = s.frame({"image.width": 40})
        if rank == 0:
            assert img.shape == (32, 40, 4)
    with pytest.raises(TypeError):
        sortlast.Session(None, comm="world")
    with pytest.raises(sortlast.InputError, match="closed"):
        s.frame()


def actions(work, on_error="report"):
    return f"""
on_error: {on_error}
renders:
  - name: f
    output: "{work}/err_{{step}}.png"
    trigger: {{every: 1}}
    scene: {{image: {{width: 32, height: 32}}}}
"""


def block(comm, dtype=np.float32):
    """This rank's slab (along z) of a 12^3 field, grid[x, y, z]."""
    r, n = comm.Get_rank(), comm.Get_size()
    z = np.arange(r * 12 // n, (r + 1) * 12 // n)
    x, y, zz = np.meshgrid(np.arange(12), np.arange(12), z, indexing="ij")
    return np.asfortranarray(np.sin(0.5 * x) * np.cos(0.4 * y) + 0.1 * zz).astype(dtype), float(z[0])


def test_bad_actions(comm, work):
    with pytest.raises(sortlast.InSituError):
        sortlast.InSitu.from_text(comm, "renders: 3")
    with pytest.raises(sortlast.InSituError):
        sortlast.InSitu(comm, str(work / "missing.yaml"))


@pytest.mark.parametrize("bad, message", [
    (lambda g: g.astype(np.int32), "int32"),
    (lambda g: g[:, :, 0], "3 dimensions"),
    (lambda g: g.astype(">f4"), "element type"),
    (lambda g: np.zeros(g.shape, dtype=[("a", "f8"), ("b", "u1")])["a"], "whole number"),
    (lambda g: np.broadcast_to(np.float32(1), g.shape), "broadcast"),
    (lambda g: g.tolist(), "numpy array"),
])
def test_bad_arrays_raise_everywhere(comm, rank, shared_vis, bad, message):
    vis, step = shared_vis
    grid, z0 = block(comm)
    last = comm.Get_size() - 1
    # Only the last rank's array is bad: every rank raises, naming it.
    with pytest.raises(sortlast.InSituError, match=message) as e:
        vis.publish(step, 0.0, grid=bad(grid) if rank == last else grid, origin=(0, 0, z0))
    if comm.Get_size() > 1:
        assert f"rank {last}" in str(e.value)
    with pytest.raises(sortlast.InSituError, match="ghosts"):
        vis.publish(step, 0.0, grid=grid, ghosts="x", origin=(0, 0, z0))
    vis.publish(step, 1.0, grid=grid, origin=(0, 0, z0))
    report = vis.execute()
    assert report["rendered"] and not report["error"]


@pytest.fixture(scope="module")
def _vis():
    """One InSitu for the bad-array cases (each case then renders a good step on it)."""
    from mpi4py import MPI
    vis = sortlast.InSitu.from_text(MPI.COMM_WORLD, actions(os.environ["SORTLAST_TEST_WORK"]))
    yield vis, iter(range(1000))
    vis.close()


@pytest.fixture
def shared_vis(_vis):
    vis, steps = _vis
    return vis, next(steps)


def test_nan_abort_then_next_step(comm, rank, work):
    grid, z0 = block(comm, np.float64)
    with sortlast.InSitu.from_text(comm, actions(work, "abort")) as vis:
        bad = grid.copy()
        if rank == 0:
            bad[1, 1, 0] = np.nan
        vis.publish(0, 0.0, grid=bad, origin=(0, 0, z0))
        with pytest.raises(sortlast.InSituError, match="NaN"):
            vis.execute()
        vis.publish(1, 1.0, grid=grid, origin=(0, 0, z0))
        report = vis.execute()
        assert report["rendered"] and not report["error"]
        if rank == 0:
            assert report["images"] == [f"{work}/err_000001.png"]


def test_published_array_outlives_its_names(comm, rank, work):
    """The module holds the published array: dropping the simulation's last name of it before
    execute() does not free it, and numpy refuses to resize it meanwhile."""
    import gc
    with sortlast.InSitu.from_text(comm, actions(work)) as vis:
        grid, z0 = block(comm, np.float64)
        expected = grid.copy()
        vis.publish(0, 0.0, grid=grid, origin=(0, 0, z0))
        with pytest.raises(ValueError):
            grid.resize((4, 4, 4))  # referenced elsewhere: refused
        del grid
        gc.collect()
        np.zeros_like(expected)  # reuse freed memory, if any had been freed
        report = vis.execute()
        assert report["rendered"] and not report["error"]
        vis.publish(1, 1.0, grid=expected, origin=(0, 0, z0))
        again = vis.execute()
    if rank == 0:
        assert open(report["images"][0], "rb").read() == open(again["images"][0], "rb").read()
