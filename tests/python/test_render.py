"""sortlast.render and Session.frame against `sortlast render` of the same scene (run.sh made the
references on the same ranks): the files they write, byte for byte, PNG and EXR; frame keys in a
request against the same keys in the scene."""
import json

import numpy as np

import sortlast

# The step pinned (run.sh's references too): `sortlast render` of one frame takes a still image's
# step, a session's frames the probes' (session/auto_spacing.h).
SMALL = {"image.width": 96, "image.height": 64, "volume.dims": [32, 32, 32], "render.sample_spacing": 1}
KEYS = {"camera.position": [200, 120, 300], "transfer.preset": "sharp"}


def same_bytes(a, b):
    return a.read_bytes() == b.read_bytes()


def test_render_png_and_float(comm, rank, work):
    img = sortlast.render(set=SMALL, comm=comm)
    img_f = sortlast.render(set=SMALL, comm=comm, float=True)
    if rank != 0:
        assert img is None and img_f is None
        return
    assert isinstance(img, sortlast.Image) and isinstance(img, np.ndarray)
    assert img.shape == (64, 96, 4) and img.dtype == np.uint8
    assert img_f.shape == (64, 96, 4) and img_f.dtype == np.float32
    assert img[..., 3].max() > 0, "an empty frame"
    img.save(work / "py.png")
    img_f.save(work / "py.exr")
    assert same_bytes(work / "py.png", work / "ref_default.png")
    assert same_bytes(work / "py.exr", work / "ref_default.exr")
    assert img._repr_png_() == (work / "ref_default.png").read_bytes()
    # Premultiplied: colour never above alpha; the 8-bit frame is the float one rounded.
    assert (img[..., :3] <= img[..., 3:]).all()
    assert np.abs(img / 255.0 - img_f).max() <= 0.5 / 255 + 1e-6


def test_session_frames_and_stats(comm, rank, work):
    with sortlast.Session(None, set=SMALL, comm=comm) as s:
        keyed = s.frame(KEYS)
        keyed_stats = s.stats
        plain = s.frame()  # each request starts from the base scene again
        scene = s.scene
    keyed_ref = sortlast.render(set={**SMALL, **KEYS}, comm=comm)
    if rank != 0:
        assert keyed is None and plain is None and scene is None and keyed_ref is None
        return
    plain.save(work / "plain.png")
    assert same_bytes(work / "plain.png", work / "ref_default.png")
    # Frame keys in a request give what the same keys in the base scene give (`render --set`,
    # which test_render_png_and_float holds to `sortlast render`).
    assert np.array_equal(keyed, keyed_ref) and keyed.background == keyed_ref.background
    # The frame's --stats record: the fields `sortlast render --stats` writes for a frame.
    ref = json.loads((work / "ref_default.json").read_text())["frames"][0]
    assert set(keyed_stats) == set(ref)
    assert keyed_stats["camera"]["position"] == [200, 120, 300]
    assert isinstance(scene, dict) and scene, "describe() as a dict"


def test_dict_scene(comm, rank, work):
    scene = {"image": {"width": 96, "height": 64}, "volume": {"dims": [32, 32, 32]}, "render": {"sample_spacing": 1}}
    img = sortlast.render(scene, comm=comm)
    if rank == 0:
        img.save(work / "dict.png")
        assert same_bytes(work / "dict.png", work / "ref_default.png")
