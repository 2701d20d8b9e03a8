"""Work-precision: error against CPU time on the reference scenes (docs/design.md section 10).

In one run: the kernel's adaptive integrator over a ladder of rtol, its fixed step over a
ladder of dt, the floor (``floor``: the kernel's adaptive tableau in a compact rocking-only
loop) and the rocking-only scipy program (``scipy_rocking``, DOP853 with events, scipy's
default step limits) over the same ladder of rtol on the scenes they model.  atol = 1e-2 rtol for both
(the ratio of the kernel's defaults).  CPU is the median ``time.process_time`` of repeated runs
after compilation: for the kernel the compiled call alone (``SceneResult.cpu_s``), for scipy the
whole call.  Errors: ``scenes.error`` against an exact anchor or the kernel at rtol 1e-13.
"""
import math
import statistics
import time
from dataclasses import dataclass, field

import numpy as np

from kernels.api import run_scene

from . import floor, scenes, scipy_rocking
from .markdown import Section, ms, sci, table, verdict, write_figure

ATOL_PER_RTOL = 1e-2
REFERENCE_RTOL = 1e-13
CHECK_RTOL = 1e-12          # the reference's own error is estimated against this run
CPU_BUDGET = 2.0            # s of CPU per rung of the kernel: fewer repeats for slow runs
SCIPY_BUDGET = 5.0          # the same for scipy
TARGET_ERROR = 1e-8         # s: docs/design.md 10, steady rocking
TARGET_CPU = 0.5e-3         # s


@dataclass(frozen=True)
class Ladder:
    adaptive: tuple
    fixed: tuple
    scipy: tuple
    repeats: int
    scipy_repeats: int
    scenes: tuple


FULL = Ladder(adaptive=tuple(m * 10.0 ** -k for k in range(4, 12) for m in (1.0, 0.3)),
              fixed=(1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5),
              scipy=tuple(10.0 ** -k for k in range(4, 13)), repeats=5, scipy_repeats=3,
              scenes=tuple(s.key for s in scenes.SCENES))
QUICK = Ladder(adaptive=(1e-5, 1e-8), fixed=(1e-3, 1e-4), scipy=(1e-5, 1e-8), repeats=2,
               scipy_repeats=1, scenes=("steady_rocking", "sliding"))

METHODS = ("adaptive", "fixed", "floor", "scipy")
LABELS = {"adaptive": "kernel, adaptive", "fixed": "kernel, fixed step (RK4)",
          "floor": "floor: the same tableau, rocking only", "scipy": "scipy solve_ivp DOP853"}


@dataclass(frozen=True)
class Point:
    """One rung: method, setting (rtol or dt), steps, median CPU [s], repeats, error, note."""

    method: str
    setting: float
    steps: int
    cpu: float
    repeats: int
    error: float
    note: str = ""


@dataclass
class Curves:
    """The points of one scene and where its reference came from."""

    scene: scenes.ReferenceScene
    reference: str
    points: list = field(default_factory=list)

    def of(self, method):
        return [p for p in self.points if p.method == method]


def _solver(resolved, **solver):
    """A copy of a resolved scene with some solver settings changed."""
    return {**resolved, "solver": {**resolved["solver"], **solver}}


def _adaptive(resolved, rtol):
    return _solver(resolved, method="adaptive", rtol=rtol, atol=ATOL_PER_RTOL * rtol)


def _fixed(resolved, dt):
    steps = int(2 * resolved["solver"]["t_end"] / dt) + 100_000
    return _solver(resolved, method="fixed", dt=dt, max_steps=max(steps, 5_000_000))


def _repeat(run, repeats, budget):
    """Run up to ``repeats`` times (fewer once ``budget`` s of CPU are spent): the last
    result, the median CPU [s] and the number of runs.  ``run`` returns (result, cpu)."""
    cpus = []
    while len(cpus) < repeats and sum(cpus) < budget:
        result, cpu = run()
        cpus.append(cpu)
    return result, statistics.median(cpus), len(cpus)


def _kernel(resolved):
    result = run_scene(resolved)
    return result, result.cpu_s


def _scipy(problem, rtol):
    t0 = time.process_time()
    out = scipy_rocking.housner_rocking(**problem, rtol=rtol, atol=ATOL_PER_RTOL * rtol,
                                        max_step=math.inf)
    return out, time.process_time() - t0


def _floor(resolved, rtol):
    t0 = time.process_time()
    out = floor.run(resolved, rtol, ATOL_PER_RTOL * rtol)
    return out, time.process_time() - t0


def _reference(scene):
    """(reference Outcome, text saying what it is and how good it is)."""
    if scene.anchor is not None:
        what = "quadrature (docs/physics.md A4)" if scene.measure == "impacts" else \
            "rigid-plastic block, scipy rtol 1e-12 (docs/physics.md A6)"
        return scene.anchor(), f"exact anchor: {what}"
    ref = scenes.Outcome.of_kernel(run_scene(_adaptive(scene.resolved, REFERENCE_RTOL)))
    check = scenes.Outcome.of_kernel(run_scene(_adaptive(scene.resolved, CHECK_RTOL)))
    err, note = scenes.error(check, ref, scene)
    return ref, (f"kernel at rtol {REFERENCE_RTOL:.0e} (rtol {CHECK_RTOL:.0e} differs by "
                 f"{sci(err)} s{', ' + note if note else ''})")


def measure_scene(scene, ladder):
    """All rungs of one scene: ``Curves``."""
    reference, text = _reference(scene)
    curves = Curves(scene, text)

    def add(method, setting, outcome, cpu, n, steps):
        err, note = scenes.error(outcome, reference, scene)
        curves.points.append(Point(method, setting, steps, cpu, n, err, note))

    for rtol in ladder.adaptive:
        r, cpu, n = _repeat(lambda: _kernel(_adaptive(scene.resolved, rtol)), ladder.repeats,
                            CPU_BUDGET)
        add("adaptive", rtol, scenes.Outcome.of_kernel(r), cpu, n, r.steps)
    for dt in ladder.fixed:
        r, cpu, n = _repeat(lambda: _kernel(_fixed(scene.resolved, dt)), ladder.repeats,
                            CPU_BUDGET)
        add("fixed", dt, scenes.Outcome.of_kernel(r), cpu, n, r.steps)
    if scene.rocking_only and floor.takes(scene.resolved):
        for rtol in ladder.adaptive:
            out, cpu, n = _repeat(lambda: _floor(scene.resolved, rtol), ladder.repeats,
                                  CPU_BUDGET)
            add("floor", rtol, scenes.Outcome.of_scipy(out), cpu, n, out["steps"])
    if scene.rocking_only:
        problem = scenes.scipy_problem(scene.resolved)
        for rtol in ladder.scipy:
            out, cpu, n = _repeat(lambda: _scipy(problem, rtol), ladder.scipy_repeats,
                                  SCIPY_BUDGET)
            add("scipy", rtol, scenes.Outcome.of_scipy(out), cpu, n, out["steps"])
    return curves


def _front(points):
    """(errors, cpus) of the cheapest way to each error level: points sorted by error, each
    kept only if it is cheaper than every point with a smaller error."""
    good = sorted((max(p.error, 1e-16), p.cpu) for p in points if math.isfinite(p.error))
    front = []
    for err, cpu in good:
        if not front or cpu < front[-1][1]:
            front.append((err, cpu))
    return np.array([e for e, _ in front]), np.array([c for _, c in front])


def cpu_to_reach(points, error):
    """CPU [s] needed for ``error``, by log-log interpolation between the cheapest runs.

    Returns (cpu, bound): bound is "=" inside the measured range, "<=" when even the cheapest
    run was more accurate (its CPU is an upper bound), ">" when no run reached ``error`` (the
    most expensive CPU is a lower bound), or (None, None) without finite errors.
    """
    errs, cpus = _front(points)
    if errs.size == 0:
        return None, None
    if error >= errs[-1]:
        return float(cpus[-1]), "<=" if error > errs[-1] else "="
    if error < errs[0]:
        return float(max(p.cpu for p in points)), ">"
    log_cpu = np.interp(math.log(error), np.log(errs), np.log(cpus))
    return float(math.exp(log_cpu)), "="


def speedup(curves, error, cpu, method="scipy"):
    """Text of ``method``'s CPU at ``error`` over ``cpu`` (e.g. '320', '>= 80', '<= 5')."""
    their_cpu, bound = cpu_to_reach(curves.of(method), error)
    if their_cpu is None or not math.isfinite(error):
        return "–"
    ratio = their_cpu / cpu
    prefix = {"=": "", "<=": "<= ", ">": "> "}[bound]
    return f"{prefix}{ratio:.3g}"


def _setting(p):
    return f"dt {p.setting:.0e} s" if p.method == "fixed" else f"rtol {p.setting:.0e}"


def _error_text(p):
    return p.note if not math.isfinite(p.error) else sci(p.error)


def scene_markdown(curves):
    scene = curves.scene
    unit = "m" if scene.measure == "slip" else "s"
    rows = []
    for p in curves.points:
        ratio = speedup(curves, p.error, p.cpu) if p.method != "scipy" and \
            scene.rocking_only else "–"
        rows.append([LABELS[p.method], _setting(p), p.steps, f"{ms(p.cpu)} ({p.repeats})",
                     _error_text(p), ratio])
    header = ["method", "setting", "steps", "CPU ms (runs)", f"error [{unit}]",
              "scipy CPU / this at equal error"]
    return (f"### {scene.title}\n\n{scene.note}.  Reference: {curves.reference}.\n\n"
            + table(header, rows))


def _cheapest_within(points, error):
    ok = [p for p in points if p.error <= error]
    return min(ok, key=lambda p: p.cpu) if ok else None


def _at_target(curves, method):
    """CPU [s] of ``method`` interpolated at ``TARGET_ERROR``, or None when not reached."""
    cpu, bound = cpu_to_reach(curves.of(method), TARGET_ERROR)
    return None if cpu is None or bound == ">" else cpu


def targets(all_curves):
    """Rows (target, measured, met) of docs/design.md 10 on steady rocking, and the engine against
    the floor and scipy at ``TARGET_ERROR`` on every rocking scene (for information)."""
    rows = []
    by_key = {c.scene.key: c for c in all_curves}
    steady = by_key.get("steady_rocking")
    if steady is not None:
        best = _cheapest_within(steady.of("adaptive"), TARGET_ERROR)
        measured = (f"{ms(best.cpu)} ms at {_setting(best)} (error {sci(best.error)} s)"
                    if best else f"no rung within {TARGET_ERROR:.0e} s")
        rows.append([f"steady rocking: impact times within {TARGET_ERROR:.0e} s in <= "
                     f"{ms(TARGET_CPU)} ms CPU", measured,
                     verdict(best is not None and best.cpu <= TARGET_CPU)])
    for curves in all_curves:
        if not curves.scene.rocking_only:
            continue
        ours = _at_target(curves, "adaptive")
        others = [(LABELS[m], _at_target(curves, m)) for m in ("floor", "scipy")]
        measured = "; ".join(
            f"{label} {ms(cpu)} ms, {cpu / ours:.3g}x ours" for label, cpu in others
            if cpu is not None and ours is not None) or "a curve does not reach the error"
        rows.append([f"{curves.scene.title}: CPU at {TARGET_ERROR:.0e} s against ours "
                     f"({ms(ours)} ms)", measured, "(information)"])
    return rows


def measure(quick):
    """``Curves`` of every scene of the ladder (quick: two scenes, two rungs each)."""
    ladder = QUICK if quick else FULL
    run_scene(scenes.SCENES[0].resolved)          # compile (or load the cache) first
    floor.run(scenes.SCENES[0].resolved, 1e-6, 1e-8)
    return [measure_scene(s, ladder) for s in scenes.SCENES if s.key in ladder.scenes]


def section(quick, figure=None):
    """Markdown of the work-precision benchmark; draws the plot to ``figure`` if given."""
    all_curves = measure(quick)
    rows = targets(all_curves)
    text = ["## Work-precision (speed against error)", "",
            f"CPU: median of up to {(QUICK if quick else FULL).repeats} runs after compilation "
            "(kernel: the compiled call; floor and scipy: the whole call). atol = 1e-2 rtol. "
            "The floor runs the kernel's adaptive tableau and step-size controller in a "
            "compact rocking-only loop (`benchmarks/floor.py`): what the engine's generality "
            "costs. The last column is the CPU scipy needs for the same error (log-log "
            "interpolation on its cheapest runs) over that row's.", "",
            table(["target (docs/design.md 10)", "measured", "met"], rows)]
    if figure is not None:
        from .figure import work_precision_figure
        write_figure(figure, work_precision_figure(all_curves, TARGET_ERROR, TARGET_CPU))
    text += ["", *[scene_markdown(c) + "\n" for c in all_curves]]
    return Section("\n".join(text), rows)
