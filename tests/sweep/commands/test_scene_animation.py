"""``--animate`` of ``python -m sweep.scene`` (issue 20, point 10): ``--fps``, the window
``--from``/``--to``, a default window that shows the motion rather than a body at rest, the
frame count and an estimated size said before writing, and headings that do not overlap.
Frames are counted in the written GIF with Pillow."""
import json

import matplotlib
import numpy as np
import pytest
from PIL import Image

from sweep import scene
from sweep.plots import scene as scene_plots

matplotlib.use("Agg")

# a 0.1 s pulse at t = 1 s sets the block rocking; it is at rest again at t = 2.3 s of 6
KNOCKED = {"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 10, "e_x": 0.0, "e_y": 0.5},
           "excitation": {"horizontal": {"kind": "pulse", "shape": "rectangular",
                                         "amplitude": "1.5 west", "duration": 0.1,
                                         "start": 1.0}},
           "solver": {"t_end": 6.0}}


@pytest.fixture
def knocked(tmp_path):
    path = tmp_path / "knocked.yaml"
    path.write_text(json.dumps(KNOCKED))
    return path


def test_fps_and_window_give_the_frames_asked_for(knocked, tmp_path, capsys):
    gif = tmp_path / "a.gif"
    assert scene.main([str(knocked), "--summary", "--animate", str(gif), "--fps", "10",
                       "--from", "1", "--to", "3"]) == 0
    with Image.open(gif) as image:
        assert image.n_frames in (20, 21) and image.info["duration"] == 100
    assert f"{image.n_frames} frames at 10 fps" in capsys.readouterr().err


def test_default_window_is_mostly_motion_and_said_before_writing(knocked, tmp_path, capsys,
                                                                 monkeypatch):
    """The body moves 1.3 s of the 6 s history (the kernel's mode_time): at 50 frames a
    second the whole history would be 301 frames, four fifths at rest."""
    said_before = []
    save_gif = scene_plots.save_gif

    def saving(path, frames, fps):
        said_before.append(capsys.readouterr().err)
        return save_gif(path, frames, fps)

    monkeypatch.setattr(scene_plots, "save_gif", saving)
    gif = tmp_path / "a.gif"
    assert scene.main([str(knocked), "--json", "--animate", str(gif)]) == 0
    result = json.loads(capsys.readouterr().out)
    moving = sum(time for mode, time in result["mode_time"].items() if mode != "rest")
    with Image.open(gif) as image:
        frames, delay = image.n_frames, image.info["duration"]
    shown = frames * delay / 1000
    assert delay == 20 and moving / shown > 0.5
    assert shown < moving + 2 * scene_plots.WINDOW_MARGIN + 0.05
    (line,) = [line for line in said_before[0].splitlines() if "about" in line]
    assert f"{frames} frames at 50 fps" in line and "before the first motion" in line
    size = float(line.rsplit("about ", 1)[1].split()[0]) * 1e3  # kB
    assert 0.67 < size / gif.stat().st_size < 1.5


def test_options_of_animate_checked(knocked, tmp_path, capsys):
    for options in (["--fps", "10"], ["--animate", "a.gif", "--fps", "60"],
                    ["--animate", "a.gif", "--from", "3", "--to", "2"],
                    ["--animate", str(tmp_path / "a.gif"), "--from", "9"]):
        with pytest.raises(SystemExit) as end:
            scene.main([str(knocked), *options])
        assert end.value.code == 2
    assert "the history ends at 6 s" in capsys.readouterr().err
    assert not (tmp_path / "a.gif").exists()


def test_headings_do_not_overlap(knocked, tmp_path, monkeypatch):
    """The verdict (wrapped), the scene's name and each frame's time: no two of them, nor
    the view, share a pixel."""
    kept = []
    monkeypatch.setattr(scene_plots.plt, "close", kept.append)
    history = scene.simulate(str(knocked), history=True).history
    history.attrs["mode_time"] = np.full(6, 0.12)  # every mode: a verdict of three lines
    assert scene_plots._wrap(scene_plots.scene_verdict(history),
                             scene_plots.ANIMATION_TITLE_WIDTH).count("\n") == 2
    name = "/a/long/folder/" * 8 + "knocked.yaml"
    scene_plots.animate_scene(history, tmp_path / "a.gif", name, quiet=True, start=1.2, end=1.3)
    (fig,) = kept
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    boxes = [text.get_window_extent(renderer) for text in fig.texts if text.get_text()]
    boxes += [ax.title.get_window_extent(renderer), ax.get_window_extent(renderer)]
    assert len(boxes) == 4
    for k, box in enumerate(boxes):
        assert 0 <= box.x0 and box.x1 <= fig.bbox.width and box.y1 <= fig.bbox.height
        for other in boxes[k + 1:]:
            assert not box.overlaps(other), (box, other)
    matplotlib.pyplot.close(fig)
