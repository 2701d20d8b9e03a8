"""Start-up: the cold compile of everything a scene and a study need, and a warm start.

The cold compile runs in a child process with an empty numba cache folder of its own
(``NUMBA_CACHE_DIR``): one scene (``sweep.simulate``) and one study chunk
(``sweep.runner.cells.warm_up``), its CPU time taken from the operating system's account of
the finished child (user + system), so imports count too.  The warm start is the wall time
from launch to exit of ``python -m sweep.scene studies/steady_rocking.yaml --json`` on that
now warm cache, against ``python -c "import numba"`` launched the same way, alternating, median
of the runs, and so is that of ``python -m sweep.run studies/smoke.yaml`` (384 cells, one
rank, into a temporary folder); the scene's own ``cpu_s`` is read from its JSON.  In this
process, the CPU time of one ``sweep.simulate(scene)`` call (file read aside: the scene as a
dict) against the kernel's own ``cpu_s`` of that call, medians over many calls: what a
notebook loop over scenes pays.
"""
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .markdown import Section, ms, table, verdict

ROOT = Path(__file__).resolve().parents[1]
SCENE = "studies/steady_rocking.yaml"
STUDY = "studies/smoke.yaml"
COLD = ("import sweep; from sweep.runner.cells import warm_up; "
        f"sweep.simulate({SCENE!r}); warm_up()")
TARGET_COLD_CPU = 20.0      # s of CPU for the first compile (docs/design.md 10)
TARGET_WARM_EXTRA = 0.15    # s of wall time a warm scene may take beyond `import numba`
TARGET_SIMULATE = 1.3       # CPU of a sweep.simulate() call / the kernel's own CPU in it


def _child_cpu(command, env):
    """(wall, CPU of the child) of one command run to its end."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed: {done.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, done.stdout


def simulate_cost(calls):
    """Medians of the CPU time of ``sweep.simulate(scene)`` [s] and of its ``cpu_s``."""
    import yaml

    from sweep.runner.simulate import simulate
    scene = yaml.safe_load((ROOT / SCENE).read_text())
    simulate(scene)                                  # the kernel, loaded from the cache
    whole, kernel = [], []
    for _ in range(calls):
        t0 = time.process_time()
        result = simulate(scene)
        whole.append(time.process_time() - t0)
        kernel.append(result.cpu_s)
    return statistics.median(whole), statistics.median(kernel)


def measure(quick):
    """Dict of the measurements (see ``section``)."""
    repeats = 3 if quick else 10
    with tempfile.TemporaryDirectory(prefix="bench_cache_") as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        cold_wall, cold_cpu, _ = _child_cpu([sys.executable, "-c", COLD], env)
        scene, numba, cpu_s, study = [], [], [], []
        run = [sys.executable, "-m", "sweep.run", STUDY, "--force", "--quiet", "-o",
               str(Path(cache) / "smoke.nc")]
        for _ in range(repeats):
            wall, _, out = _child_cpu([sys.executable, "-m", "sweep.scene", SCENE, "--json"],
                                      env)
            scene.append(wall)
            cpu_s.append(json.loads(out)["cpu_s"])
            numba.append(_child_cpu([sys.executable, "-c", "import numba"], env)[0])
            study.append(_child_cpu(run, env)[0])
    call, kernel = simulate_cost(50 if quick else 400)
    return {"cold_wall": cold_wall, "cold_cpu": cold_cpu, "scene": statistics.median(scene),
            "numba": statistics.median(numba), "cpu_s": statistics.median(cpu_s),
            "study": statistics.median(study),
            "repeats": repeats, "call": call, "kernel": kernel}


def targets(m):
    """Rows (target, measured, met) of docs/design.md 10."""
    extra = m["scene"] - m["numba"]
    return [
        [f"cold compile of a scene and a study <= {TARGET_COLD_CPU:g} s CPU",
         f"{m['cold_cpu']:.1f} s CPU ({m['cold_wall']:.1f} s wall)",
         verdict(m["cold_cpu"] <= TARGET_COLD_CPU)],
        [f"warm `sweep.scene --json` within {TARGET_WARM_EXTRA:g} s of `import numba`",
         f"{m['scene']:.2f} s against {m['numba']:.2f} s: +{extra:.2f} s",
         verdict(extra <= TARGET_WARM_EXTRA)],
        [f"`sweep.simulate()` <= {TARGET_SIMULATE:g}x the kernel's own CPU (steady rocking)",
         f"{ms(m['call'])} ms a call against {ms(m['kernel'])} ms: "
         f"{m['call'] / m['kernel']:.2f}x", verdict(m["call"] <= TARGET_SIMULATE * m["kernel"])]]


def section(quick):
    """Markdown of the start-up benchmark."""
    m = measure(quick)
    rows = targets(m)
    return Section("\n".join([
        "## Start-up: first compile and warm start", "",
        "A child process with an empty numba cache folder of its own compiles what one scene "
        f"(`{SCENE}`) and one study chunk need; its CPU time is the operating system's account "
        "of the child (imports included). Then, on that warm cache, "
        f"`python -m sweep.scene {SCENE} --json` and `python -c \"import numba\"` are launched "
        f"alternately, {m['repeats']} times each, wall time from launch to exit (medians). The "
        f"scene's own `cpu_s` (the simulation alone) is {ms(m['cpu_s'])} ms; a warm "
        f"`python -m sweep.run {STUDY}` (384 cells, one rank) takes {m['study']:.2f} s.", "",
        table(["target (docs/design.md 10)", "measured", "met"], rows), ""]), rows)
