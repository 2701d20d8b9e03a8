"""``benchmarks.gpu.ptxas_figures`` reads ``ptxas -v``: the entry's registers and stack frame,
the spills of every function, and passes a register limit on as ``-maxrregcount``."""
import sys

from benchmarks.gpu import ptxas_figures

# ptxas -v's report of a kernel that calls one device function, as ptxas 12.9 words it
SAID = """\
ptxas info    : 1032 bytes gmem
ptxas info    : Compiling entry function '_Z4kern' for 'sm_90'
ptxas info    : Function properties for _Z4kern
    1488 bytes stack frame, 16 bytes spill stores, 4 bytes spill loads
ptxas info    : Used {registers} registers, used 0 barriers, 1488 bytes cumulative stack size
ptxas info    : Function properties for _Z4step
    0 bytes stack frame, 380 bytes spill stores, 448 bytes spill loads
"""


def _fake_ptxas(tmp_path):
    """An executable that answers like ptxas -v, its register count the -maxrregcount it was
    given (240 without one)."""
    script = tmp_path / "ptxas"
    script.write_text(
        f"#!{sys.executable}\n"
        "import sys\n"
        "limits = [a.split('=')[1] for a in sys.argv if a.startswith('-maxrregcount=')]\n"
        f"sys.stderr.write({SAID!r}.format(registers=(limits or ['240'])[0]))\n")
    script.chmod(0o755)
    return str(script)


def test_spills_of_every_function_are_summed(tmp_path):
    figures = ptxas_figures(tmp_path / "k.ptx", _fake_ptxas(tmp_path))
    assert figures["registers"] == 240 and figures["stack frame [B]"] == 1488
    assert figures["spill stores [B]"] == 16 + 380
    assert figures["spill loads [B]"] == 4 + 448


def test_a_register_limit_goes_to_ptxas(tmp_path):
    assert ptxas_figures(tmp_path / "k.ptx", _fake_ptxas(tmp_path), 168)["registers"] == 168
