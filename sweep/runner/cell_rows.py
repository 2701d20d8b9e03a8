"""The kernel rows of a study's cells on the plain axes, built as one structured array.

Cell 0's scene is checked, resolved and packed once (``io.study_cells.CellScenes``,
``io.scene_schema.resolve_and_pack``); its row is repeated over a chunk's cells and the
fields that the axes change are set with numpy from each axis value, checked once, in SI.  The
fields derived from them are computed as the per-cell resolution computes them, operation for
operation, so that the rows are the same byte for byte: H from ``b_over_h`` and ``size``
(``io.study_grid.cell_overrides``), a uniform body's squared radius of gyration and G, an
amplitude relative to the body (``west``, ``v_H``: ``io.units.Quantity.to_si``) or given as a
velocity or displacement (``io.units.acceleration_amplitude``), a sweep's rate
(``kernels.api.scene_row``), ``solver.t_end`` and ``dt_out`` left to their defaults, and the
peaks of the horizontal motion (``groundmotion.applied.peaks``).

A study with an axis elsewhere, a motion other than a sine or sweep, a body with G given, or
a value relative to the body outside the amplitudes has every cell built by the per-cell path;
so has any cell whose values do not check or leave the range the kernel takes, so that its
problems read as before, with its dotted path and the value given.
"""
import math

import numpy as np

from kernels import codes
from kernels.api import DEFAULTS

from ..groundmotion import applied
from ..io.scene_schema import MAX_HISTORY, SAMPLES_PER_PERIOD, T_TAIL, resolve_and_pack
from ..io.study_cells import REFUSED, CellScenes
from ..io.study_grid import _length_si, shape
from ..io.units import Quantity
from ..io.vocabulary import COMPUTED, MU_PATHS, _get, targets

_COMPONENTS = (("horizontal", "x"), ("vertical", "y"))
_KINDS = ("none", "sine", "sweep")
_BODY = ("body.B", "body.H")


def _relative_paths(model, prefix=""):
    """Dotted paths of the values relative to the body (``west``, ``v_H``, ``alpha``) in a
    checked scene."""
    for name in type(model).model_fields:
        value = getattr(model, name)
        items = value if isinstance(value, list) else [value]
        if any(isinstance(x, Quantity) and x.body_relative for x in items):
            yield prefix + name
        elif hasattr(type(value), "model_fields"):
            yield from _relative_paths(value, f"{prefix}{name}.")


def _setters(study):
    """{scene path: (dimension index, raw value per position)} of the plain axes, and
    {``b_over_h`` or ``size``: (dimension index, float per position)}, as
    ``io.study_grid.cell_overrides`` sets them."""
    plain, computed, mu = {}, {}, None
    for d, dim in enumerate(study.dims):
        for axis in dim.axes:
            if axis.name in COMPUTED:
                computed[axis.name] = (d, np.array([float(v) for v in axis.values]))
            elif axis.name == "mu":
                mu = (d, axis.values)
            else:
                plain.update({path: (d, axis.values) for path in targets(axis.name)})
    if mu is not None:
        for path in MU_PATHS:
            plain.setdefault(path, mu)
    return plain, computed


class CellRows:
    """Rows of the cells of ``study`` (:meth:`build`) and their checked scenes (``scenes``,
    its :class:`~sweep.io.study_cells.CellScenes`, for the cells built one by one)."""

    def __init__(self, study):
        self.study = study
        self.scenes = CellScenes(study)
        self.base = self._base()

    def _base(self):
        """Cell 0's checked scene, resolved scene and row, or None: every cell one by one."""
        base = self.scenes.base
        if base is None or not self.scenes.alone or "contact.mu" in self.scenes.keys:
            return None
        grounds = [getattr(base.excitation, key) for key, _ in _COMPONENTS]
        if any(g.kind not in _KINDS for g in grounds):
            return None
        if self.scenes.keys & set(_BODY):
            amplitudes = {f"excitation.{key}.amplitude" for key, _ in _COMPONENTS}
            if base.body.G is not None or set(_relative_paths(base)) - amplitudes:
                return None
        try:
            resolved, row = resolve_and_pack(base, [])
        except ValueError:
            return None
        self.plain, self.computed = _setters(self.study)
        self.checked = {path: [self.scenes.value(path, v) for v in values]
                        for path, (_, values) in self.plain.items()}
        return base, resolved, row

    def build(self, cells):
        """(rows, bodies, motions, built) of some cells, as ``runner.cells.build_rows``
        returns them; ``built`` is False for a cell left to the per-cell path (its row,
        body and motion then undefined)."""
        n = len(cells)
        if self.base is None or n == 0:
            return None, None, None, np.zeros(n, dtype=bool)
        with np.errstate(all="ignore"):  # a value out of range: the cell is not built here
            return self._build(cells, n)

    def _build(self, cells, n):
        base, resolved, row = self.base
        pos = np.unravel_index(np.asarray(cells, dtype=np.int64), shape(self.study))
        cols, bad = {}, np.zeros(n, dtype=bool)
        for path, checked in self.checked.items():
            d = self.plain[path][0]
            col = np.empty(len(checked), dtype=object)
            col[:] = checked
            cols[path] = col[pos[d]]
            bad |= np.array([v is REFUSED for v in col])[pos[d]]
        rows = np.repeat(np.array([row], dtype=codes.SCENE_DTYPE), n)
        B, H, body_bad = self._body(base, cols, pos, n)
        bad |= body_bad
        factors = _Factors(B, H, resolved["body"])
        grounds = {}
        for key, axis in _COMPONENTS:
            g = getattr(base.excitation, key)
            if g.kind != "none":
                grounds[key] = _Ground(g, key, cols, factors, n)
                bad |= grounds[key].set(rows["floor"][axis])
        bad |= _solver(base, grounds, rows["solver"])
        bad |= _contact(cols, rows["contact"])
        bodies = _bodies(rows["body"], B, H, resolved["body"])
        motions = _peaks(grounds.get("horizontal"), resolved["excitation"]["horizontal"], n)
        return rows, bodies, motions, ~bad

    def _body(self, base, cols, pos, n):
        """B, H [m] of each cell and whether a cell's are not built here."""
        bad = np.zeros(n, dtype=bool)
        if self.computed:
            B, H = (self._metres(path, pos, n) for path in _BODY)
            if "b_over_h" in self.computed:
                d, values = self.computed["b_over_h"]
                H = B / values[pos[d]]
            if "size" in self.computed:
                d, values = self.computed["size"]
                B, H = B * values[pos[d]], H * values[pos[d]]
            for path, x in zip(_BODY, (B, H)):
                unique, inverse = np.unique(x, return_inverse=True)
                refused = np.array([math.isnan(v) or self.scenes.value(path, v) is REFUSED
                                    for v in unique.tolist()])
                bad |= refused[inverse.reshape(-1)]
            return B, H, bad
        B, H = (_si_column(cols[path], n) if path in cols else
                np.full(n, getattr(base.body, path[5:]).to_si()) for path in _BODY)
        return B, H, bad

    def _metres(self, path, pos, n):
        """The raw B or H of each cell in m, as ``io.study_grid.cell_overrides`` reads it
        before setting b/h or size (NaN: not a length in m)."""
        if path in self.plain:
            d, values = self.plain[path]
            return np.array([_metres(v) for v in values])[pos[d]]
        return np.full(n, _metres(_get(self.study.scene, path)))


def _metres(raw):
    length = _length_si(raw)
    return math.nan if length is None else length


def _bodies(body, B, H, resolved):
    """Set B and H in the rows' ``body`` fields, with the squared radius of gyration and G of
    a uniform body and G in the middle (``kernels.api.scene_row``; a body given with G has
    every cell's B and H those of cell 0's); B, H, i_g and G of each cell as
    ``runner.cells.build_rows`` gives them."""
    body["B"], body["H"] = B, H
    if resolved["i_g"] is None:
        b, h = B / 2, H / 2
        body["i2"] = (b * b + h * h) / 3
    if resolved["G"] is None:
        body["x_g"], body["y_g"] = 0.0, H / 2
    n, i_g = len(B), resolved["i_g"]
    G = (np.nan, np.nan) if resolved["G"] is None else resolved["G"]
    return np.column_stack([B, H, np.full(n, np.nan if i_g is None else i_g),
                            np.full(n, G[0]), np.full(n, G[1])])


def _si_column(values, n):
    """SI floats of a column of checked values (NaN for one refused)."""
    out = np.empty(n)
    out[:] = [math.nan if v is REFUSED else v.to_si() if isinstance(v, Quantity) else float(v)
              for v in values]
    return out


class _Factors:
    """Factors of the units relative to the body (``Quantity.to_si``), per cell, each
    computed once per distinct body."""

    def __init__(self, B, H, body):
        self.unique, self.inverse = np.unique(np.column_stack([B, H]), axis=0,
                                              return_inverse=True)
        self.inverse, self.body, self.cache = self.inverse.reshape(-1), body, {}

    def __call__(self, unit, dimension):
        if unit not in self.cache:
            one = Quantity(1.0, unit, dimension)
            self.cache[unit] = np.array([one.to_si({**self.body, "B": b, "H": h})
                                         for b, h in self.unique.tolist()])
        return self.cache[unit][self.inverse]


class _Ground:
    """The resolved fields of one sine or sweep component of each cell."""

    def __init__(self, g, key, cols, factors, n):
        self.g, self.n = g, n
        prefix = f"excitation.{key}."

        def column(name):
            return cols.get(prefix + name, [getattr(g, name)] * n)

        self.start = np.array([0.0 if v is None else _si(v) for v in column("start")])
        durations = column("duration")
        self.bad = np.array([v is None for v in durations]) if g.kind == "sweep" else \
            np.zeros(n, dtype=bool)
        self.duration = np.array([math.inf if v is None else _si(v) for v in durations])
        self.amplitude = self._amplitude(column("amplitude"), factors)
        if g.kind == "sine":
            self.frequency = _si_array(column("frequency"))
            omega = 2.0 * math.pi * self.frequency
            dims = [getattr(v, "dimension", None) for v in column("amplitude")]
            velocity = np.array([d == "velocity" for d in dims])
            length = np.array([d == "length" for d in dims])
            self.amplitude = np.where(velocity, self.amplitude * omega, self.amplitude)
            self.amplitude[length] = [a * _square(w) for a, w in
                                      zip(self.amplitude[length].tolist(), omega[length].tolist())]
        else:
            self.f_start = _si_array(column("f_start"))
            self.f_stop = _si_array(column("f_stop"))

    def _amplitude(self, values, factors):
        """``Quantity.to_si(body)`` of each cell's amplitude."""
        out = np.empty(self.n)
        plain = np.array([isinstance(v, Quantity) and not v.body_relative for v in values])
        out[plain] = [v.to_si() for v, p in zip(values, plain) if p]
        for k in np.flatnonzero(~plain):
            if not isinstance(values[k], Quantity):
                out[k], self.bad[k] = math.nan, True
        relative = {(v.unit, v.dimension) for v in values if isinstance(v, Quantity)
                    and v.body_relative}
        for unit, dimension in relative:
            mask = np.array([isinstance(v, Quantity) and v.unit == unit for v in values])
            out[mask] = np.array([v.value for v, m in zip(values, mask) if m]) * \
                factors(unit, dimension)[mask]
        return out

    def set(self, floor):
        """Set the fields of ``floor`` (a ``codes.GROUND_DTYPE`` column); True for a cell whose
        values the kernel refuses (``kernels.api.scene_row``)."""
        floor["start"], floor["dur"], floor["amp"] = self.start, self.duration, self.amplitude
        finite = np.isfinite(self.start) & np.isfinite(self.amplitude) & (
            np.isinf(self.duration) & (self.g.kind == "sine") |
            np.isfinite(self.duration) & (self.duration > 0))
        if self.g.kind == "sine":
            floor["freq"] = self.frequency
            return self.bad | ~(finite & _positive(self.frequency))
        floor["f0"], floor["f1"] = self.f_start, self.f_stop
        ratio = self.f_stop / self.f_start if floor["law"][0] == codes.LAW_LOG else None
        span = (np.array([_log(r) for r in ratio.tolist()]) if ratio is not None
                else self.f_stop - self.f_start)
        floor["freq"] = span / self.duration
        return self.bad | ~(finite & _positive(self.f_start) & _positive(self.f_stop))

    def end(self):
        """When the component stops moving the floor [s] (inf: never)."""
        return self.start + self.duration

    def finest(self):
        """The highest frequency of the component [Hz]."""
        return self.frequency if self.g.kind == "sine" else np.maximum(self.f_start, self.f_stop)


def _si(v):
    return math.nan if v is REFUSED else v.to_si()


def _si_array(values):
    return np.array([_si(v) for v in values], dtype=float)


def _square(x):
    """``x ** 2`` as Python computes it (not always ``x * x`` to the last bit); NaN where it
    leaves the float range (the per-cell path then reports the cell)."""
    try:
        return x ** 2
    except OverflowError:
        return math.nan


def _over_square(x, w):
    """``x / w ** 2`` as Python computes it; NaN where ``w ** 2`` leaves the float range."""
    try:
        return x / w ** 2
    except (OverflowError, ZeroDivisionError):
        return math.nan


def _log(x):
    return math.log(x) if x > 0 and math.isfinite(x) else math.nan


def _positive(x):
    return np.isfinite(x) & (x > 0)


def _solver(base, grounds, solver):
    """Set ``t_end`` and ``dt_out`` where the scene leaves them to their defaults (as
    ``io.scene_schema.resolve_and_pack`` does); True for a cell whose values the kernel
    refuses."""
    n = len(solver)
    if base.solver.t_end is None and grounds:
        end = np.max([g.end() for g in grounds.values()], axis=0)
        solver["t_end"] = np.where(np.isfinite(end), end + T_TAIL, DEFAULTS["solver"]["t_end"])
    if base.solver.dt_out is None:
        dt = np.full(n, DEFAULTS["solver"]["dt_out"])
        for g in grounds.values():
            dt = np.minimum(dt, 1.0 / (SAMPLES_PER_PERIOD * g.finest()))
        solver["dt_out"] = np.maximum(dt, solver["t_end"] / (MAX_HISTORY - 1))
    return ~(_positive(solver["t_end"]) & _positive(solver["dt_out"])) if n else np.zeros(0, bool)


def _contact(cols, contact):
    """Set the contact coefficients the axes give; True for a cell the kernel refuses."""
    for path, values in cols.items():
        if path.startswith("contact."):
            contact[path[8:]] = _si_column(values, len(values))
    mu = np.column_stack([contact[key] for key in ("mu_s", "mu_k", "mu_edge_s", "mu_edge_k")])
    ok = (np.isfinite(mu) & (mu >= 0)).all(axis=1) & (np.abs(contact["e_x"]) <= 1) & \
        (contact["e_y"] >= 0) & (contact["e_y"] <= 1)
    return ~ok


def _peaks(ground, resolved, n):
    """``groundmotion.applied.peaks`` of each cell's horizontal motion, shape (n, 4)."""
    if ground is None:
        return np.tile(applied.peaks(resolved), (n, 1))
    a = np.abs(ground.amplitude)
    if ground.g.kind == "sine":
        omega = 2.0 * math.pi * ground.frequency
        pgd = [_over_square(x, w) for x, w in zip(a.tolist(), omega.tolist())]
        return np.column_stack([a, a / omega, pgd, np.full(n, np.nan)])
    return np.array([applied.peaks({**resolved, "amplitude": x, "f_start": f0, "f_stop": f1})
                     for x, f0, f1 in zip(ground.amplitude.tolist(), ground.f_start.tolist(),
                                          ground.f_stop.tolist())])
