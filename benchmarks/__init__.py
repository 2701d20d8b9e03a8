"""Speed against error, throughput and stability of the kernel (docs/design.md section 10).

``python -m benchmarks [--quick]`` (``make bench``) writes ``results/bench.md`` and
``figures/bench_work_precision.png``.  Each section is a module with ``section(quick) -> str``
returning Markdown.
"""
