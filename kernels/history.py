"""The sampled history of a scene: one row (``codes.H_*``) every dt_out seconds."""
from ._jit import jit
from .codes import H_AX, H_AY, H_MODE, H_T, H_X, N_STATE
from .ground import ground
from .integrate import dense
from .motion import to_full


@jit
def write_row(hist, i, t, q, mode, floor, rec):
    """Row i of the history: t, the full state q, the mode and the floor acceleration."""
    a_x, a_y = ground(t, floor, rec)
    hist[i, H_T] = t
    for j in range(N_STATE):
        hist[i, H_X + j] = q[j]
    hist[i, H_MODE] = mode
    hist[i, H_AX] = a_x
    hist[i, H_AY] = a_y


@jit
def hold(hist, i, t_to, q, mode, floor, rec, dt_out):
    """Rows from i on while their time is <= t_to with the body held in q; the next i."""
    while i < hist.shape[0] and i * dt_out <= t_to:
        write_row(hist, i, i * dt_out, q, mode, floor, rec)
        i += 1
    return i


@jit(inline="always")
def sample_step(hist, i, step, ctx, scene, rec, scratch):
    """Rows from i on whose time falls inside ``step``, from its dense output; the next i."""
    t, dt, dt_out = step.t, step.dt, scene.solver.dt_out
    while i < hist.shape[0] and i * dt_out <= t + dt:
        x = (i * dt_out - t) / dt if dt > 0.0 else 0.0
        dense(step, x, scratch.z)
        to_full(step.mode, scratch.z, ctx, scene.body, scratch.q)
        write_row(hist, i, i * dt_out, scratch.q, step.mode, scene.floor, rec)
        i += 1
    return i
