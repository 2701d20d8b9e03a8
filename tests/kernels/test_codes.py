"""The scene row's two faces agree: every named field of ``SCENE_DTYPE`` lies at the index
``P_*``/``G_*`` of the flat row that ``kernels.api`` packs and ``sweep`` edits."""
import numpy as np

from kernels import api, codes

ROW_INDEX = {
    ("body", "B"): codes.P_B, ("body", "H"): codes.P_H, ("body", "i2"): codes.P_I2,
    ("contact", "mu_s"): codes.P_MU_S, ("contact", "mu_k"): codes.P_MU_K,
    ("contact", "mu_edge_s"): codes.P_MU_EDGE_S, ("contact", "mu_edge_k"): codes.P_MU_EDGE_K,
    ("contact", "e_x"): codes.P_E_X, ("contact", "e_y"): codes.P_E_Y,
    ("contact", "landing"): codes.P_LANDING,
    ("initial", "theta"): codes.P_THETA0, ("initial", "omega"): codes.P_OMEGA0,
    ("initial", "u"): codes.P_U0, ("initial", "v"): codes.P_V0,
    ("initial", "lift"): codes.P_LIFT0,
    ("solver", "method"): codes.P_METHOD, ("solver", "rtol"): codes.P_RTOL,
    ("solver", "atol"): codes.P_ATOL, ("solver", "dt"): codes.P_DT,
    ("solver", "max_step"): codes.P_MAX_STEP, ("solver", "t_end"): codes.P_T_END,
    ("solver", "max_steps"): codes.P_MAX_STEPS, ("solver", "max_events"): codes.P_MAX_EVENTS,
    ("solver", "theta_over"): codes.P_THETA_OVER, ("solver", "zeno_dt"): codes.P_ZENO_DT,
    ("solver", "dt_out"): codes.P_DT_OUT,
}
GROUND_INDEX = {"kind": codes.G_KIND, "amp": codes.G_AMP, "freq": codes.G_FREQ,
                "phase": codes.G_PHASE, "start": codes.G_START, "dur": codes.G_DUR,
                "f0": codes.G_F0, "f1": codes.G_F1, "law": codes.G_LAW, "hold": codes.G_HOLD,
                "rec_off": codes.G_REC_OFF, "rec_n": codes.G_REC_N, "rec_dt": codes.G_REC_DT}


def test_every_field_is_at_its_row_index():
    """Each field of the record view reads the float at its P_*/G_* index (a row holding
    its own indices reads them back), and the record covers the row exactly."""
    row = np.arange(codes.N_PAR, dtype=float)
    rec = api.as_records(row)[0]
    assert codes.SCENE_DTYPE.itemsize == 8 * codes.N_PAR
    for (group, name), index in ROW_INDEX.items():
        assert rec[group][name] == index, (group, name)
    for axis, start in (("x", codes.P_GX), ("y", codes.P_GY)):
        for name, index in GROUND_INDEX.items():
            assert rec["floor"][axis][name] == start + index, (axis, name)
    assert len(ROW_INDEX) + 2 * len(GROUND_INDEX) == codes.N_PAR


def test_records_are_views():
    """The records share the rows' memory: an edit of a row is seen through its record."""
    rows = np.zeros((3, codes.N_PAR))
    records = api.as_records(rows)
    rows[2, codes.P_GY + codes.G_AMP] = 4.5
    assert records[2].floor.y.amp == 4.5 and records.shape == (3,)
