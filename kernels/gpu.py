"""The one door to the GPU: whether the chunk kernel can run there, and chunks run there.

The only module that imports ``kernels.cuda_batch`` (numba-cuda; docs/gpu.md), and only when
called: importing this one loads no numba-cuda, so a machine without it imports the package
and is told in words why the GPU cannot run.  ``cuda_batch`` builds on ``kernels.api`` (the
rows' records) and ``api`` knows nothing of the GPU: the imports point one way.
"""
import importlib.util


def unavailable():
    """None when ``cuda_batch`` can run (numba-cuda and a GPU, or its simulator), else the
    reason in words."""
    if importlib.util.find_spec("numba_cuda") is None:
        return "numba-cuda is not installed (pip install '.[cuda]')"
    from . import cuda_batch
    return cuda_batch.available()


def device_records():
    """A study's records to keep in device memory from chunk to chunk
    (``cuda_batch.DeviceRecords``; its ``update(cache)`` is the device record buffer)."""
    from . import cuda_batch
    return cuda_batch.DeviceRecords()


def run_cells(rows, rec):
    """``kernels.api.run_cells`` on the GPU (``cuda_batch.run_cells``): n scene rows to n
    result records; ``rec`` is a host record buffer or a device one (:func:`device_records`)."""
    from . import cuda_batch
    return cuda_batch.run_cells(rows, rec)


def ptx(cc=(9, 0)):
    """The chunk kernel's PTX for compute capability ``cc``, compiled without a GPU
    (``cuda_batch.ptx``; needs numba-cuda and its NVVM)."""
    from . import cuda_batch
    return cuda_batch.ptx(cc)
