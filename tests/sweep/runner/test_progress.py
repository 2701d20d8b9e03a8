"""Progress on rank 0: log lines when not on a terminal or under CI, a bar otherwise, quiet."""
import io

from sweep.runner.progress import Progress, format_seconds


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_log_lines_under_ci(monkeypatch):
    monkeypatch.setenv("CI", "1")
    out = _Terminal()
    progress = Progress(100, initial=20, stream=out)
    assert progress.mode == "log"
    for _ in range(8):
        progress.update(10, failed=1)
    progress.close()
    lines = out.getvalue().splitlines()
    assert lines[-1].startswith("sweep.run: 100/100 cells (100%), 8 failed")
    assert "ETA" in lines[0] and "ETA" not in lines[-1]
    assert len(lines) == 8  # 30 % ... 90 %, then 100 % by close()


def test_bar_on_a_terminal_and_quiet(monkeypatch):
    monkeypatch.delenv("CI", raising=False)
    out = _Terminal()
    progress = Progress(10, stream=out)
    assert progress.mode == "bar"
    progress.update(10)
    progress.close()
    assert "10/10" in out.getvalue()
    assert Progress(10, stream=io.StringIO()).mode == "log"  # not a terminal
    quiet = io.StringIO()
    silent = Progress(10, quiet=True, stream=quiet)
    silent.update(10)
    silent.close()
    assert quiet.getvalue() == ""


def test_format_seconds():
    assert [format_seconds(s) for s in (0.0004, 2.5, 600, 36000)] == \
        ["0.4 ms", "2.5 s", "10.0 min", "10.0 h"]
