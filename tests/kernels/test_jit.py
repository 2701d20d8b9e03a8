"""The numba policy of ``kernels._jit``: inlining left to LLVM, one compiled version per
argument types, no reference counts outside ``runtime=True``, the cache folder keyed by the
kernel's sources, one line before a compile."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numba
import numpy as np
import pytest

from kernels import _jit, state

pytestmark = pytest.mark.skipif(_jit.DISABLED, reason="numba's compiler is off")

KERNELS = Path(_jit.__file__).resolve().parent
SAID = "compiling the kernel once"
# A kernel function quick to compile: its cache hits and misses in this process.
CALL = ("from kernels.motion import n_dof; n_dof(2); s = n_dof.stats; "
        "print(sum(s.cache_hits.values()), sum(s.cache_misses.values()))")


def _env(cache_home, **extra):
    """This environment without a cache folder or MPI rank of its own, caches under
    ``cache_home``."""
    env = {key: value for key, value in os.environ.items()
           if key != "NUMBA_CACHE_DIR" and key not in _jit._RANK_VARIABLES}
    return {**env, "XDG_CACHE_HOME": str(cache_home), **extra}


def _python(code, env, cwd=None):
    return subprocess.run([sys.executable, "-c", code], env=env, cwd=cwd, capture_output=True,
                          text=True, check=True)


def test_inline_always_is_left_to_llvm():
    twice = _jit.jit(inline="always", cache=False)(lambda x: 2.0 * x)
    plain = _jit.jit(cache=False)(lambda x: x + 1.0)
    assert twice.targetoptions["forceinline"] and "inline" not in twice.targetoptions
    assert plain.targetoptions["forceinline"] is False
    assert state.scene_of.targetoptions["inline"] == "always"  # IR_INLINED: returns records
    assert (twice(1.5), plain(1.5)) == (3.0, 2.5)


def test_one_version_per_argument_types():
    @_jit.jit(cache=False)
    def add(x, k):
        return x + k

    @_jit.jit(cache=False)
    def caller(x, k):
        return add(x, 0) + add(x, 1) + add(x, k)

    assert caller(1.0, 2) == 6.0
    assert len(add.signatures) == 1


def test_reference_counts_only_with_the_runtime():
    """Arrays pass between kernel functions without numba's reference counts (no call of
    NRT_incref in the code); ``runtime=True`` counts them, and only it allocates."""
    @_jit.jit(cache=False)
    def total(a):
        s = 0.0
        for v in a:
            s += v
        return s

    def outer(a, b):
        return total(a) + total(b)

    bare = _jit.jit(cache=False)(outer)
    counted = _jit.jit(cache=False, runtime=True)(outer)
    x = np.arange(4.0)
    assert bare(x, x) == counted(x, x) == 12.0
    assert "NRT_incref" not in "".join(bare.inspect_llvm().values())
    assert "NRT_incref" in "".join(counted.inspect_llvm().values())
    zeros = _jit.jit(cache=False, runtime=True)(lambda n: np.zeros(n))
    assert zeros(3).tolist() == [0.0, 0.0, 0.0]
    with pytest.raises(numba.core.errors.TypingError):
        _jit.jit(cache=False)(lambda n: np.zeros(n))(3)


def test_cache_folder_keyed_by_the_kernel_sources(tmp_path):
    code = "import numba, kernels._jit as j; print(j.CACHE_DIR); print(numba.config.CACHE_DIR)"
    folders = []
    for name, extra in (("a", ""), ("b", "\n# an edit\n")):
        copy = tmp_path / name / "kernels"
        shutil.copytree(KERNELS, copy, ignore=shutil.ignore_patterns("__pycache__"))
        (copy / "codes.py").write_text((copy / "codes.py").read_text() + extra)
        out = _python(code, _env(tmp_path / "home"), cwd=copy.parent).stdout.split()
        assert out[0] == out[1]  # numba imported first still takes it
        folders.append(Path(out[0]))
    assert folders[0] == tmp_path / "home" / "rigid-block-sweeps" / f"numba-{_jit.SOURCE_DIGEST[:16]}"
    assert folders[1].parent == folders[0].parent and folders[1] != folders[0]


def test_numba_cache_dir_is_used_as_it_is(tmp_path):
    env = _env(tmp_path, NUMBA_CACHE_DIR=str(tmp_path / "shared"))
    assert _python("import kernels._jit as j; print(j.CACHE_DIR)", env).stdout.split() == \
        [str(tmp_path / "shared")]


def test_first_compile_is_said_once_and_later_runs_load_it(tmp_path):
    env = _env(tmp_path)
    cold = _python(CALL, env)
    assert cold.stdout.split() == ["0", "1"] and cold.stderr.count(SAID) == 1
    folder = tmp_path / "rigid-block-sweeps" / f"numba-{_jit.SOURCE_DIGEST[:16]}"
    assert folder.as_posix() in cold.stderr and list(folder.rglob("motion.n_dof-*.nbi"))
    warm = _python(CALL, env)
    assert warm.stdout.split() == ["1", "0"] and SAID not in warm.stderr


def test_only_rank_0_says_it(tmp_path):
    cold = _python(CALL, _env(tmp_path, PMI_RANK="1"))
    assert cold.stdout.split() == ["0", "1"] and SAID not in cold.stderr


def test_contraction_compiles_into_a_folder_of_its_own(tmp_path):
    code = ("import kernels._jit as j; print(j.CACHE_DIR, j._OPTIONS['fastmath'] == {'contract'})")
    out = _python(code, _env(tmp_path, KERNEL_CONTRACT="1"), cwd=KERNELS.parent).stdout.split()
    folder = tmp_path / "rigid-block-sweeps" / f"numba-{_jit.SOURCE_DIGEST[:16]}-contract"
    assert out == [str(folder), "True"]
