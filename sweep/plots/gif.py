"""Frames of an animation to a GIF, with one palette for all of them.

Pillow's GIF writer quantizes each RGB frame on its own (a median cut, about 15 ms for
500 x 500 pixels); the frames of one animation repeat the same few hundred colours, so here
each colour gets a palette index once, the most frequent first, and a frame is a table look-up.
When the 256 entries are taken, a new colour gets the index of the nearest one (the rare
tints of anti-aliased edges; the axes, the text and the body keep their exact colours).

A GIF's frame delay is a whole number of 1/100 s, and players show delays under 0.02 s as
0.1 s: an animation runs at ``MAX_FPS`` frames a second at most (:func:`frame_step`).  Pillow
is imported when a frame is made, so that a command's options can name ``FPS`` cheaply.
"""
import io

import numpy as np

N_COLOURS = 256  # a GIF palette
FPS = 50  # frames a second of an animation by default: one every 0.02 s
MAX_FPS = 50  # the most that GIF players show as asked (delays under 0.02 s become 0.1 s)


def frame_step(fps, dt):
    """Seconds of a history between two frames of a real-time animation at ``fps`` frames a
    second: a whole number of 1/100 s (the GIF's delay unit; 30 fps gives 0.03 s, 33.3 frames
    a second), and at least the history's sample step ``dt``."""
    return max(max(round(100.0 / fps), 1) / 100.0, dt)


def _codes(rgba):
    """24-bit colour codes (r + 256 g + 65536 b) of an (..., 4) C-contiguous array of uint8."""
    return np.ascontiguousarray(rgba).view("<u4")[..., 0] & 0xFFFFFF


class Palette:
    """The palette of an animation, filled as its frames come (:meth:`image`)."""

    def __init__(self):
        self._index = np.full(1 << 24, -1, dtype=np.int16)  # colour code -> palette index
        self.colours = np.zeros((0, 3), dtype=np.uint8)

    def image(self, rgba):
        """A frame, ndarray (height, width, 4) of uint8 (opaque), as a P-mode image."""
        from PIL import Image

        codes = _codes(rgba)
        index = self._index[codes]
        unseen = index < 0
        if unseen.any():
            self._add(*np.unique(codes[unseen], return_counts=True))
            index = self._index[codes]
        frame = Image.fromarray(index.astype(np.uint8), "P")
        frame.putpalette(self.colours.tobytes())
        return frame

    def _add(self, codes, counts):
        """New colours: the most frequent into the free entries, the others to the nearest."""
        codes = codes[np.argsort(-counts, kind="stable")]
        rgb = np.stack([codes & 255, (codes >> 8) & 255, codes >> 16], axis=1).astype(np.uint8)
        free = N_COLOURS - len(self.colours)
        self._index[codes[:free]] = np.arange(len(self.colours), len(self.colours)
                                              + min(free, codes.size))
        self.colours = np.concatenate([self.colours, rgb[:free]])
        if codes.size > free:
            rest = rgb[free:].astype(np.int32)
            distance = ((rest[:, None, :] - self.colours[None, :, :].astype(np.int32)) ** 2
                        ).sum(axis=2)
            self._index[codes[free:]] = np.argmin(distance, axis=1)


def save_gif(path, frames, fps):
    """Write the frames (an iterable of RGBA arrays, drawn as they are asked for) as a
    looping GIF at ``fps`` frames per second (to a path or a binary file)."""
    palette = Palette()
    images = (palette.image(rgba) for rgba in frames)
    first = next(images)
    first.save(path, format="GIF", save_all=True, append_images=images,
               duration=round(1000 / fps), loop=0, optimize=False)


def _encoded(frames):
    """Bytes of the GIF of ``frames``."""
    buffer = io.BytesIO()
    save_gif(buffer, iter(frames), fps=50)
    return buffer.tell()


def estimated_size(runs, count):
    """Bytes of a GIF of ``count`` frames like ``runs`` (each three successive frames, RGBA
    arrays): one whole frame, and ``count - 1`` times the mean of what the third frame of a
    run adds, which Pillow writes as the box where it differs from the second."""
    added = [_encoded(run) - _encoded(run[:2]) for run in runs]
    return round(_encoded(runs[0][:1]) + (count - 1) * np.mean(added))
