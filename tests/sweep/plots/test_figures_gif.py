"""GIF frames with one palette (``sweep.plots.gif``) and the scene animation's progress."""
import numpy as np
from PIL import Image, ImageSequence

from sweep.plots.gif import N_COLOURS, Palette, save_gif


def _frame(colours, shape=(4, 8)):
    rgba = np.full((*shape, 4), 255, dtype=np.uint8)
    rgba.reshape(-1, 4)[:len(colours), :3] = colours
    return rgba


def test_colours_are_kept_exactly_while_the_palette_has_room(tmp_path):
    rng = np.random.default_rng(0)
    frames = [_frame(rng.integers(0, 256, size=(20, 3))) for _ in range(3)]
    save_gif(tmp_path / "a.gif", iter(frames), fps=50)
    with Image.open(tmp_path / "a.gif") as gif:
        got = [np.asarray(f.convert("RGBA")) for f in ImageSequence.Iterator(gif)]
        assert gif.info["duration"] == 20
    assert len(got) == 3
    for a, b in zip(frames, got):
        np.testing.assert_array_equal(a, b)


def test_a_full_palette_maps_new_colours_to_the_nearest():
    palette = Palette()
    grey = np.repeat(np.arange(N_COLOURS, dtype=np.uint8)[:, None], 3, axis=1)
    palette.image(_frame(grey, shape=(16, 16)))
    assert len(palette.colours) == N_COLOURS
    image = palette.image(_frame(np.array([[10, 12, 11]], dtype=np.uint8)))
    assert tuple(np.asarray(image.convert("RGB"))[0, 0]) == (11, 11, 11)
