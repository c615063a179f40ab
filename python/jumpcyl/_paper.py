"""paper_table: the seed paper's Table 1 recomputed, with the keys of
`jumpcyl paper --json`, from the library's public calls (the tool's
cli/commands/paper.c does the same work)."""
import math

from ._lib import ffi, lib, text, check, num
from ._setup import as_setup
from ._simulate import simulate, setup_json, paper_solve, rolling_predict, _crossing, _clean
from ._study import mc

SWEEP_MU = (0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)
PAPER_DRAG_CD = 0.6
MC_SAMPLES, MC_SEED = 2000, 1


def table_rows():
    """jc_paper_table: what the paper printed and measured, per incline."""
    rows = ffi.new("jc_PaperTableRow **")
    n = lib.jc_paper_table(rows)
    return [{"incline_deg": r.incline_deg, "printed_theta": r.printed_theta_rad, "printed_x": r.printed_x_m,
             "measured_x": r.measured_x_m, "measured_error": r.measured_error_m} for r in rows[0][0:n]]


def _full(setup):
    run = simulate(setup)
    s = run.summary
    out = {"found": s["first_liftoff_x"] is not None, "summary": s, "energy_gaining_impacts":
           run.energy_gaining_impacts, "theta": None, "x": None, "first_hop": 0.0, "later_hop": 0.0}
    ev = run.events
    first = next((i for i, e in enumerate(ev) if e.kind == "liftoff"), -1)
    if first >= 0:
        e = ev[first]
        out.update(theta=e.theta, x=e.x, first_hop=e.hop_height)
        for f in ev[first + 1:]:
            if f.kind == "liftoff" or (f.kind == "bounce" and f.mode_after == "flight"):
                out["later_hop"] = max(out["later_hop"], f.hop_height)
    return out


def _theta_x(theta, x):
    return {"theta": theta, "x": x}


def _row(setup, t):
    s = setup.replace(incline=t["incline_deg"] * 3.14159265358979323846 / 180.0)
    m = s._model()
    p = paper_solve(m)
    r = rolling_predict(m)
    roots = [p.theta_rad[i] for i in range(p.root_count)]
    nearest = -1
    for i, th in enumerate(roots):
        if nearest < 0 or abs(th - t["printed_theta"]) < abs(roots[nearest] - t["printed_theta"]):
            nearest = i
    inside = lambda x: abs(x - t["measured_x"]) <= t["measured_error"]  # noqa: E731
    full, drag = _full(s), _full(s.replace(drag_coefficient=PAPER_DRAG_CD))
    newton = _full(s.replace(impact_law="newton"))
    sweep = [_full(s.replace(mu=mu)) for mu in SWEEP_MU]
    unc = mc(setup.replace(incline="%.17gdeg" % t["incline_deg"]), samples=MC_SAMPLES, seed=MC_SEED)
    st = m.setup
    pm = _theta_x(p.theta_rad[p.first], p.x_m[p.first]) if p.first >= 0 else {"theta": None, "x": None}
    pm.update(roots=roots, cm_offset=p.cm_offset_m, nearest_printed_index=nearest)
    if p.first >= 0:
        pm["minus_printed_theta"] = p.theta_rad[p.first] - t["printed_theta"]
    lo = r.liftoff
    ro = {"theta": lo.state.theta_rad if lo.found else None, "x": lo.state.x_m if lo.found else None,
          "note": "rolling N = 0: a diagnostic, not the physical jump", "liftoff": _crossing(lo),
          "slip": _crossing(r.slip), "mu_s": st.mu_static}
    fu = _theta_x(full["theta"], full["x"])
    fu.update(hops=full["summary"]["liftoffs"], bounces=full["summary"]["bounces"],
              largest_hop=full["summary"]["largest_hop"], first_hop=full["first_hop"],
              inside_error_bar=full["found"] and inside(full["x"]), mu_s=st.mu_static, mu_k=st.mu_kinetic,
              restitution=st.restitution, impact_law=text(lib.jc_impact_law_name(st.impact_law)))
    fu["newton"] = {"hops": newton["summary"]["liftoffs"], "bounces": newton["summary"]["bounces"],
                    "largest_hop": newton["summary"]["largest_hop"], "largest_later_hop": newton["later_hop"]}
    fu["largest_later_hop"] = full["later_hop"]
    fu["newton"]["energy_gaining_impacts"] = newton["energy_gaining_impacts"]
    fu["friction_sweep"] = [{"mu": mu, "x": f["x"] if f["found"] else None} for mu, f in zip(SWEEP_MU, sweep)]
    dr = _theta_x(drag["theta"], drag["x"])
    dr.update(drag_coefficient=PAPER_DRAG_CD, hops=drag["summary"]["liftoffs"], first_hop=drag["first_hop"],
              inside_error_bar=drag["found"] and inside(drag["x"]))
    if drag["found"] and full["found"]:
        dr["moved_by_drag"] = drag["x"] - full["x"]
        dr["toward_measurement"] = abs(drag["x"] - t["measured_x"]) < abs(full["x"] - t["measured_x"])
    sm = unc.summary
    lf = sm["first_liftoff_x_m"]
    liftoffs = len(unc.liftoff_x)
    un = {"samples": MC_SAMPLES, "seed": MC_SEED, "liftoff_fraction": liftoffs / sm["valid"] if sm["valid"] else 0.0}
    if lf["count"] > 0:
        un.update(p2_5=lf["p2_5"], p50=lf["p50"], p97_5=lf["p97_5"])
    un["measured_inside"] = lf["count"] > 0 and lf["p2_5"] <= t["measured_x"] <= lf["p97_5"]
    row = {"incline_deg": t["incline_deg"], "printed": _theta_x(t["printed_theta"], t["printed_x"]),
           "paper_model": pm, "rolling": ro, "full": fu, "drag": dr, "full_uncertainty": un,
           "measured": {"x": t["measured_x"], "error": t["measured_error"]}}
    return row, m


def paper_table(setup=None):
    """The seed paper's Table 1 recomputed (15, 30, 45 deg): the printed
    values, Eq. 9, the exact rolling model, the full model with friction,
    drag, Newton's impacts and a Monte Carlo of the paper's tolerances, and
    the measurement: a dict with the keys of `jumpcyl paper --json`. setup:
    the paper's by default; its incline is the table's. Its body must be
    the paper's cylinder (jc_paper_body_is), the only one the table measured:
    for another body, use predict or simulate on each incline."""
    setup = as_setup(setup)
    sp = setup._ptr()
    if not lib.jc_paper_body_is(ffi.addressof(sp[0], "body")):
        raise ValueError("paper_table: the setup's body is not the paper's cylinder, the only one its Table 1 "
                         "measured (settings that keep the body, such as mu or paper_d, may change); for this body "
                         "use jc.predict(setup.replace(incline='15deg')) (30, 45)")
    rows, first_model = [], None
    for t in table_rows():
        row, m = _row(setup, t)
        rows.append(row)
        first_model = first_model or m
    head = setup_json(first_model)
    head.pop("incline_deg", None)
    return _clean({"setup": head, "rows": rows})
