"""sortlast from Python: frames as numpy arrays, in situ from numpy simulations (docs/python.md).

    import sortlast
    img = sortlast.render("configs/engine.yaml", set={"image.width": 256})   # rank 0: (H, W, 4) uint8
    s = sortlast.Session("scene.yaml")                 # loads once; s.frame({...}) per frame
    vis = sortlast.InSitu(comm, "actions.yaml")        # vis.publish(step, t, grid=u); vis.execute()

Every call taking `comm` is collective over it (an mpi4py communicator; None: MPI_COMM_WORLD,
MPI being initialised by the module if nothing did, and finalised at exit).
"""
import atexit
import json
import weakref

import numpy as np

from . import _sortlast
from ._sortlast import Error, InputError, InSituError

__all__ = ["render", "Session", "InSitu", "Image", "Error", "InputError", "InSituError"]


# ---------------------------------------------------------------------------------------------
# Scene keys as the command line's --set takes them: key=value with the value in YAML (JSON is
# YAML, so json.dumps writes it).

def _json_default(o):
    if hasattr(o, "tolist"):  # numpy scalars and arrays
        return o.tolist()
    raise TypeError(f"{type(o).__name__} is not a scene value")


def _overrides(keys):
    if keys is None:
        return []
    if not isinstance(keys, dict):
        raise TypeError("scene keys are a dict {'key.path': value}")
    return [f"{k}={json.dumps(v, default=_json_default)}" for k, v in keys.items()]


def _scene_source(scene):
    """(path, yaml text, name): a file path, a dict (written as YAML text) or None (built-in)."""
    if scene is None:
        return "", "", ""
    if isinstance(scene, dict):
        # Relative paths in it resolve from the working directory.
        return "", json.dumps(scene, default=_json_default) or "{}", "<dict scene>"
    return str(scene), "", ""


# ---------------------------------------------------------------------------------------------
# Objects that hold a session close in the order they were made, on every rank alike (closing is
# collective), before MPI is finalised at exit.

_open = []  # weak references, oldest first


def _track(obj):
    _open.append(weakref.ref(obj))
    _open[:] = [r for r in _open if r() is not None]


@atexit.register
def _shutdown():
    for r in _open:
        obj = r()
        if obj is not None:
            obj.close()
    _open.clear()
    _sortlast._finalize_mpi()  # only if the module initialised MPI


# ---------------------------------------------------------------------------------------------

class Image(np.ndarray):
    """A frame: (H, W, 4) premultiplied RGBA, uint8 or float32, row 0 at the top.

    `background` is the scene's; save() writes the file `sortlast render` would (PNG or EXR, over
    the background) and Jupyter shows it inline (_repr_png_). Slicing or arithmetic gives plain
    arrays' behaviour otherwise."""

    def __new__(cls, array, background=(0.0, 0.0, 0.0)):
        obj = np.asarray(array).view(cls)
        obj.background = tuple(float(c) for c in background)
        return obj

    def __array_finalize__(self, obj):
        self.background = getattr(obj, "background", (0.0, 0.0, 0.0))

    def _repr_png_(self):
        return _sortlast._encode_png(np.asarray(self), self.background)

    def png(self):
        """The frame over its background as PNG bytes."""
        return self._repr_png_()

    def save(self, path):
        """Writes the frame over its background: .png, .jpg (quality 95), .ppm (8-bit) or .exr (float RGB)."""
        _sortlast._write_image(str(path), np.asarray(self), self.background)


class _Closing:
    """`with` support for the collective objects: close() on leaving the block."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class Session(_Closing):
    """A resident session: loads the scene once, then renders frames on demand (like `serve`).

    Collective over `comm`: every rank makes the same calls with the same arguments. Frames and
    stats come back on rank 0 (None elsewhere)."""

    def __init__(self, scene=None, set=None, comm=None, resident=True, quiet=True):
        path, text, name = _scene_source(scene)
        self._s = _sortlast._Session(path, text, name, _overrides(set), comm, resident, quiet)
        self.stats = None
        _track(self)

    def frame(self, keys=None, float=False, orbit_frame=None):
        """Renders one frame with frame keys (camera.*, image.*, transfer.*, ...) on top of the
        scene. Rank 0: an Image, uint8 (H, W, 4), or float32 premultiplied with float=True; and
        self.stats is the frame's --stats record. Other ranks: None."""
        out = self._s.frame(_overrides(keys), -1 if orbit_frame is None else int(orbit_frame), bool(float))
        if out is None:
            return None
        image8, image_f, stats, background = out
        self.stats = json.loads(stats)
        return Image(image_f if float else image8, background)

    @property
    def scene(self):
        """describe(): bounds, camera, data range, histogram, steps, base settings, frame keys,
        limits (rank 0; None elsewhere)."""
        text = self._s.describe()
        return None if text is None else json.loads(text)

    @property
    def job_stats(self):
        """The job-level fields of --stats (renderer, particles, adaptive preprocessing), rank 0."""
        text = self._s.job_stats()
        return None if text is None else json.loads(text)

    @property
    def orbit_frames(self):
        return self._s.orbit_frames()

    def close(self):
        """Collective: frees the session (also done at exit)."""
        self._s.close()


def render(scene=None, set=None, comm=None, float=False):
    """One frame of a scene, as `sortlast render SCENE --set ...` renders it (its first orbit
    frame). Rank 0: an Image (uint8 (H, W, 4), or float32 with float=True); other ranks: None."""
    with Session(scene, set=set, comm=comm, resident=False) as s:
        return s.frame(float=float, orbit_frame=0)


def _triple(value, what, kind):
    try:
        if np.ndim(value) == 0:
            return (kind(value),) * 3
        t = tuple(kind(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a number or 3 numbers") from None
    if len(t) != 3:
        raise ValueError(f"{what} must be a number or 3 numbers (x, y, z), not {len(t)}")
    return t


class InSitu(_Closing):
    """The in-situ library on a running simulation (docs/insitu.md).

    InSitu(comm, "actions.yaml") or InSitu.from_text(comm, yaml); each step
    publish(step, t, grid=..., ...) then execute(). Collective over comm."""

    def __init__(self, comm, actions, _from_text=False):
        self._v = _sortlast._InSitu(comm, str(actions), _from_text)
        _track(self)

    @classmethod
    def from_text(cls, comm, actions_yaml):
        return cls(comm, actions_yaml, _from_text=True)

    def publish(self, step, time, grid=None, ghosts=0, origin=(0.0, 0.0, 0.0), spacing=(1.0, 1.0, 1.0),
                particles=None, quantities=None, name="field", ghost_lo=None, ghost_hi=None):
        """Describes this step's data; nothing is copied. grid: this rank's 3-D block indexed
        grid[x, y, z] (uint8, uint16, int16, float32 or float64; any strides), `ghosts` layers
        on every face (or ghost_lo / ghost_hi per axis); origin: the first owned sample's
        position; particles: (N, 3) float64 or float32 positions; quantities: {name: number} for
        triggers (the same on every rank). The arrays must not change until execute() returns."""
        problem = ""
        lo = hi = (0, 0, 0)
        o, sp, q = (0.0, 0.0, 0.0), (1.0, 1.0, 1.0), {}
        try:
            lo = _triple(ghosts if ghost_lo is None else ghost_lo, "ghosts", int)
            hi = _triple(ghosts if ghost_hi is None else ghost_hi, "ghosts", int)
            o = _triple(origin, "origin", float)
            sp = _triple(spacing, "spacing", float)
            q = {str(k): float(v) for k, v in (quantities or {}).items()}
        except (TypeError, ValueError) as e:
            problem = str(e)
        self._v.publish(int(step), float(time), grid, lo, hi, o, sp, str(name), particles, q, problem)

    def execute(self):
        """Renders what the actions ask for if a trigger fires. A dict: rendered, images (files
        written, rank 0), error (why this step's images were skipped), seconds,
        memory_added_mib, texture_mib, gl_vendor, gl_renderer, host, device."""
        return self._v.execute()

    def close(self):
        """Collective: frees the library's session (also done at exit)."""
        self._v.close()
