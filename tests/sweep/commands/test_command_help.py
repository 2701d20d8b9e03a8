"""``--help`` of every command (issue 20, point 13): plain text without reStructuredText
markup, the console script's name when called as one (pyproject.toml [project.scripts]) and
``python -m sweep.<name>`` otherwise, and the units epilog only where quantities are read."""
import contextlib
import importlib
import io
import re
import sys
import tomllib
from pathlib import Path

import pytest

from sweep import cli

ROOT = Path(__file__).resolve().parents[3]
COMMANDS = [f"sweep.{package}{path.stem}"  # the modules with a main run by python -m
            for package in ("", "paper.")
            for path in sorted((ROOT / "sweep" / package.rstrip(".")).glob("*.py"))
            if re.search(r'^if __name__ == "__main__":', path.read_text(), re.MULTILINE)]
QUANTITIES = {"sweep.scene", "sweep.run", "sweep.estimate", "sweep.risk"}  # scene, study, bodies, risk files
MARKUP = re.compile(r"``|:(?:func|mod|class|meth|attr|data|ref):|`[^`\s][^`]*`")


def _help(module):
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit) as end:
        importlib.import_module(module).main(["--help"])
    assert end.value.code == 0
    return out.getvalue()


def test_every_command_is_listed():
    assert {"sweep.scene", "sweep.run", "sweep.plot", "sweep.fragility", "sweep.estimate",
            "sweep.figures", "sweep.paper.rates", "sweep.paper.subharmonic"} <= set(COMMANDS)


@pytest.mark.parametrize("module", COMMANDS)
def test_help_is_plain_text_named_as_run(module, monkeypatch):
    monkeypatch.setattr(sys, "argv", [f"/usr/lib/python3/{module.replace('.', '/')}.py"])
    text = _help(module)
    assert not MARKUP.search(text), MARKUP.search(text)
    assert text.startswith(f"usage: python -m {module} ")
    assert ("A quantity is a number in SI units" in text) == (module in QUANTITIES)


def test_scripts_are_those_of_pyproject():
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    assert {target.split(":")[0]: name for name, target in scripts.items()} == cli.SCRIPTS


@pytest.mark.parametrize("module, script", sorted(cli.SCRIPTS.items()))
def test_console_script_shows_its_own_name(module, script, monkeypatch):
    monkeypatch.setattr(sys, "argv", [f"/home/user/.venv/bin/{script}"])
    assert _help(module).startswith(f"usage: {script} ")
    err = io.StringIO()
    with contextlib.redirect_stderr(err), pytest.raises(SystemExit):
        importlib.import_module(module).main(["--no-such-option"])
    assert f"\n{script}: error: " in err.getvalue()


def test_plain_reduces_markup_to_what_it_quotes():
    assert cli.plain("``python -m sweep.scene``: see :func:`~sweep.io.records.describe` and "
                     ":mod:`sweep.io.units`, `text`; example::\n\n    x") == (
        "python -m sweep.scene: see describe and sweep.io.units, text; example:\n\n    x")
