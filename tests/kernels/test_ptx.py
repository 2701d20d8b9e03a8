"""The kernel's records as the GPU reads them: aligned, laid out as before, and compiled for
sm_90 without byte-wise loads (``python -m benchmarks.gpu --ptx``; docs/gpu.md).

A record numba types as packed (``aligned=False``) has its float64 fields loaded with
alignment 1: NVVM then reads each field a byte at a time (``ld.u8``) and puts the eight bytes
together (``bfi``).  Every record the kernel reads is built with ``align=True``; its fields
are all eight bytes wide, so the layout is the packed one.  The device code is cached beside
the CPU's."""
import importlib.util
import math
import re
from pathlib import Path

import numba
import pytest

from benchmarks.gpu import ptx_figures, ptxas_figures, ptxas_path
from kernels import codes, state

RECORDS = {"SCENE_DTYPE": codes.SCENE_DTYPE, "GROUND_DTYPE": codes.GROUND_DTYPE,
           "RESULT_DTYPE": codes.RESULT_DTYPE, "WORK_DTYPE": state.WORK_DTYPE,
           "VALUES_DTYPE": state.VALUES_DTYPE, "SCRATCH_DTYPE": state.SCRATCH_DTYPE}
# eight-byte words of each record, counted from the field lists in codes.py and state.py
WORDS = {"GROUND_DTYPE": 13,
         "SCENE_DTYPE": 5 + 7 + 5 + 11 + 2 * 13 + 2,        # body .. floor x, y, restraint
         "RESULT_DTYPE": 17 + codes.N_MODES,                 # scalars, mode_time
         "VALUES_DTYPE": 3 * state.MAX_EVENTS,
         "SCRATCH_DTYPE": 2 * codes.N_STATE + state.MAX_EVENTS,
         "WORK_DTYPE": 146}                                   # 1,168 bytes


def _leaves(dtype, offset=0):
    """(offset, numpy scalar dtype, count) of every scalar field of a record, depth first."""
    for name in dtype.names:
        field, at = dtype.fields[name][:2]
        if field.base.names:
            for _ in range(math.prod(field.shape)):
                yield from _leaves(field.base, offset + at)
        else:
            yield offset + at, field.base, math.prod(field.shape)


@pytest.mark.parametrize("name", RECORDS)
def test_records_are_aligned_with_the_packed_layout(name):
    dtype = RECORDS[name]
    assert dtype.isalignedstruct and numba.from_dtype(dtype).aligned
    assert dtype.itemsize == 8 * WORDS[name]
    expected = 0
    for offset, scalar, count in _leaves(dtype):    # one field after the other, no padding
        assert scalar.itemsize == 8 and offset == expected, (name, offset, expected)
        expected += 8 * count
    assert expected == dtype.itemsize


def test_nested_records_are_aligned_too():
    for sub in ("body", "contact", "initial", "solver", "floor", "restraint"):
        assert numba.from_dtype(codes.SCENE_DTYPE[sub]).aligned, sub
    assert numba.from_dtype(state.WORK_DTYPE["values"]).aligned


def test_ptx_figures_count_byte_loads_but_not_byte_arguments():
    ptx = "\n".join(["ld.u8 %rs1, [%rd1];", "ld.global.u8 %rs2, [%rd2+3];",
                     "ld.global.nc.u8 %rs3, [%rd3];", "ld.local.s8 %rs4, [%rd4];",
                     "ld.param.u8 %rs5, [f_param_0];", "ld.f64 %fd1, [%rd5];",
                     "bfi.b64 %rd6, %rd7, %rd8, 8, 8;", "st.u8 [%rd9], %rs1;", ""])
    assert ptx_figures(ptx) == {"lines": 8, "byte loads": 4, "bfi": 1}


def test_the_device_code_is_cached_in_the_cpu_s_cache_folder():
    """The kernel's cache (numba-cuda's, keyed on its own bytecode and the compute
    capability) lives in the folder named after the digest of every kernel source.  That a
    second process loads it needs a GPU: numba-cuda asks the driver for the key."""
    pytest.importorskip("numba_cuda")
    from kernels import _jit, cuda_batch
    assert Path(cuda_batch._run_rows._cache._cache_path).parent == Path(_jit.CACHE_DIR)


@pytest.fixture(scope="module")
def ptx():
    """The kernel's PTX for sm_90 (about 40 s of NVVM), or skip where it cannot compile."""
    if importlib.util.find_spec("numba_cuda") is None:
        pytest.skip("numba-cuda is not installed")
    from kernels import gpu
    try:
        return gpu.ptx((9, 0))
    except Exception as err:            # no NVVM/NVRTC: nothing to compile with
        pytest.skip(f"the CUDA compilers are not usable: {err}")


@pytest.mark.slow
def test_the_kernel_loads_no_field_a_byte_at_a_time(ptx):
    """Zero byte loads at all: the kernel has no one-byte data (booleans travel as
    arguments, ``ld.param``), so any byte load would be a record field read byte-wise."""
    figures = ptx_figures(ptx)
    assert ".entry" in ptx and "run_scene" in ptx
    assert figures["byte loads"] == 0 and figures["bfi"] == 0, figures


@pytest.mark.slow
def test_each_thread_s_work_record_is_in_local_memory(ptx):
    """The kernel takes no work array: its arguments are rows, rec, results, ctl, the row
    counter (1-d) and log, hist (2-d), and a local depot holds the thread's 1,168-byte
    ``WORK_DTYPE`` record."""
    entry = ptx[ptx.index(".entry"):]
    params = entry[:entry.index(")")].count(".param")
    depots = [int(n) for n in re.findall(r"__local_depot\d+\[(\d+)\]", entry)]
    # an array argument is meminfo, parent, size, itemsize, data and ndim shapes and strides
    assert params == 5 * (5 + 2 * 1) + 2 * (5 + 2 * 2)
    assert max(depots) >= state.WORK_DTYPE.itemsize


@pytest.mark.slow
def test_ptxas_fits_the_kernel_in_the_register_file(ptx, tmp_path):
    """Registers per thread within sm_90's limit of 255; the thread's work record is in its
    stack frame."""
    ptxas = ptxas_path()
    if ptxas is None:
        pytest.skip("ptxas is not installed")
    path = tmp_path / "kernel.ptx"
    path.write_text(ptx)
    figures = ptxas_figures(path, ptxas)
    assert 0 < figures["registers"] <= 255
    assert figures["stack frame [B]"] >= state.WORK_DTYPE.itemsize
