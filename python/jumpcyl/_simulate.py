"""simulate and predict: one run of the full model, and the models' predictions,
with the keys of the tool's simulate --json and predict --json."""
import dataclasses
import math
import numbers

import numpy as np

from ._lib import ffi, lib, text, err_buf, check, num, raise_status
from ._params import params, quantity_parse
from ._setup import as_setup

# The simulation options as the tool names them (--t-max, ...): (field, quantity or None for a count).
SIM_OPTIONS = {
    "t_max": ("t_max_s", lib.JC_Q_TIME),
    "max_events": ("max_events", None),
    "sample_dt": ("sample_dt_s", lib.JC_Q_TIME),
    "max_samples": ("max_samples", None),
    "rtol": ("ode_rtol", lib.JC_Q_NUMBER),
    "atol": ("ode_atol", lib.JC_Q_NUMBER),
    "event_tol": ("event_tol_s", lib.JC_Q_TIME),
    "contact_height": ("contact_height_m", lib.JC_Q_LENGTH),
}


def sim_options(**kw):
    """A jc_SimOptions * from the tool's simulation options (t_max, max_events,
    sample_dt, rtol, atol, event_tol, contact_height; and max_samples): numbers
    SI, strings with units; None keeps the default. ValueError when invalid."""
    o = ffi.new("jc_SimOptions *")
    o[0] = lib.jc_default_sim_options()
    for name, v in kw.items():
        key = name.replace("-", "_")
        if key not in SIM_OPTIONS:
            raise TypeError("unknown simulation option '%s' (allowed: %s)" % (name, ", ".join(SIM_OPTIONS)))
        if v is None:
            continue
        field, q = SIM_OPTIONS[key]
        if q is None:
            if isinstance(v, bool) or not isinstance(v, numbers.Real) or v != int(v) or not 1 <= v <= 10_000_000:
                raise ValueError("%s: %r is out of range (allowed: a whole number from 1 to 10000000)" % (key, v))
            setattr(o, field, int(v))
        else:
            setattr(o, field, quantity_parse(v, q, key))
        err = err_buf()
        check(lib.jc_sim_options_validate(o, err, len(err)), err, key)
    return o


def model_of(setup):
    return setup._model()


_MODES = None


def mode_names():
    global _MODES
    if _MODES is None:
        _MODES = tuple(text(lib.jc_mode_name(i)) for i in range(3))
    return _MODES


@dataclasses.dataclass(frozen=True)
class Event:
    """One event of a run, with the fields of simulate --json (SI: s, m, rad,
    rad/s, m/s, N, N s). The flight fields are None except on a lift-off or a
    bounce into flight (landing_x None also when the run ended in flight); the
    impact fields None except on a touchdown or a bounce."""
    kind: str
    mode_before: str
    mode_after: str
    t: float
    x: float
    y: float
    theta: float
    omega: float
    vx: float
    vy: float
    slip: float
    normal: float
    friction: float
    flight_time: float = None
    hop_height: float = None
    landing_x: float = None
    impact_speed: float = None
    impulse_normal: float = None
    impulse_tangent: float = None

    def to_dict(self):
        """As simulate --json prints the event (the keys it has)."""
        d = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)[:13]}
        d = {k: (num(v) if isinstance(v, float) else v) for k, v in d.items()}
        if self.flight_time is not None:
            d.update(flight_time=num(self.flight_time), hop_height=num(self.hop_height), landing_x=self.landing_x)
        if self.impact_speed is not None:
            d.update(impact_speed=num(self.impact_speed), impulse_normal=num(self.impulse_normal),
                     impulse_tangent=num(self.impulse_tangent))
        return d


_EVENT_NAMES = tuple(text(lib.jc_event_name(k)) for k in range(lib.JC_EVENT_COUNT))


def _event(e):
    s = e.state
    modes = mode_names()
    kind = _EVENT_NAMES[e.kind]
    flight = e.kind == lib.JC_EVENT_LIFTOFF or (e.kind == lib.JC_EVENT_BOUNCE and e.mode_after == lib.JC_MODE_FLIGHT)
    impact = e.kind in (lib.JC_EVENT_TOUCHDOWN, lib.JC_EVENT_BOUNCE)
    return Event(kind, modes[e.mode_before], modes[e.mode_after], s.t_s, s.x_m, s.y_m, s.theta_rad, s.omega_radps,
                 s.vx_mps, s.vy_mps, e.slip_mps, e.normal_N, e.friction_N,
                 e.flight_time_s if flight else None, e.hop_height_m if flight else None,
                 (None if math.isnan(e.landing_x_m) else e.landing_x_m) if flight else None,
                 e.impact_speed_mps if impact else None, e.impulse_normal_Ns if impact else None,
                 e.impulse_tangent_Ns if impact else None)


def sample_dtype():
    """The samples' numpy dtype: the library's sample columns (simulate --csv's), in order."""
    fields = []
    for c in range(lib.jc_sample_column_count()):
        info = lib.jc_sample_column_info(c)
        fields.append((text(info.name), "U7" if info.is_mode else "f8"))
    return np.dtype(fields)


def _samples(run):
    n = run.sample_count
    cols = lib.jc_sample_column_count()
    dtype = sample_dtype()
    out = np.empty(n, dtype=dtype)
    if n == 0:
        return out
    mat = np.empty((n, cols), dtype=np.float64)
    lib.jcpy_sample_matrix(run.samples, n, ffi.cast("double *", mat.ctypes.data))
    modes = np.array(mode_names())
    for c, name in enumerate(dtype.names):
        if dtype[name].kind == "U":
            out[name] = modes[mat[:, c].astype(np.int64)]
        else:
            out[name] = mat[:, c]
    return out


def energy_dict(e):
    return {"kinetic": e.kinetic_J, "potential": e.potential_J, "friction_loss": e.friction_loss_J,
            "impact_loss": e.impact_loss_J, "air_loss": e.air_loss_J,
            "rolling_resistance_loss": e.rolling_resistance_loss_J, "balance_error": e.balance_error_J}


def setup_json(m):
    """The setup as the tool's JSON outputs hold it (cli_json_setup): the body, then every
    parameter that has a json_key, in the table's order (degrees for keys ending _deg)."""
    s = m.setup
    b = m.body
    parts = [{"kind": text(lib.jc_part_kind_name(q.kind)), "mass": q.mass_kg, "offset": q.offset_m,
              "angle": q.angle_rad, "radius": q.radius_m} for q in s.body.parts[0:s.body.part_count]]
    out = {"body": {"radius": b.radius_m, "mass": b.mass_kg, "cm_offset": b.cm_offset_m, "inertia_c": b.inertia_c_kgm2,
                    "inertia_g": b.inertia_g_kgm2, "parts": parts}}
    v = ffi.new("double *")
    sp = ffi.addressof(m, "setup")
    for p in params():
        if not p.json_key or lib.jc_param_get(sp, p.id, v, ffi.NULL, 0) != lib.JC_OK:
            continue
        out[p.json_key] = v[0] * 180.0 / 3.14159265358979323846 if p.json_key.endswith("_deg") else v[0]
    return out


def summary_dict(sm):
    d = {"liftoffs": sm.liftoffs, "bounces": sm.bounces, "largest_hop": sm.largest_hop_m}
    if sm.first_liftoff >= 0:
        d.update(first_liftoff_x=sm.first_liftoff_state.x_m, first_liftoff_theta=sm.first_liftoff_state.theta_rad)
    else:
        d.update(first_liftoff_x=None, first_liftoff_theta=None)
    return d


def _state(s):
    return {"t": s.t_s, "x": s.x_m, "y": s.y_m, "vx": s.vx_mps, "vy": s.vy_mps, "theta": s.theta_rad,
            "omega": s.omega_radps}


class Run:
    """A run of the full model (jc_simulate). .events: list of Event; .samples:
    numpy structured array with simulate --csv's columns (t_s, mode, x_m, ...);
    .summary: simulate --json's summary; .termination (its name) and
    .termination_detail; .energy: the energy book (J); .to_dict(): the whole
    simulate --json document. The run's arrays stay in the library's memory
    (freed with the Run); events and samples are converted on first use."""

    def __init__(self, setup, model, run):
        self._run = run  # owns the library's arrays (ffi.gc: jc_run_free)
        self._model = model
        self._events = None
        self._samples = None
        sm = ffi.new("jc_RunSummary *")
        lib.jc_run_summarize(run, sm)
        self.setup = setup
        self.summary = summary_dict(sm)
        self.termination = text(lib.jc_termination_name(run.termination))
        self.termination_detail = ffi.string(run.termination_detail).decode()
        self.t_end = run.final_state.t_s
        self.final_mode = mode_names()[run.final_mode]
        self.energy = energy_dict(run.energy)
        self.energy_gaining_impacts = run.energy_gaining_impacts
        self.largest_impact_gain_J = run.largest_impact_gain_J
        self.micro_slips = run.micro_slips
        self.rocking_period_s = run.rocking_period_s
        self.ode_steps = run.ode_steps

    @property
    def events(self):
        if self._events is None:
            r = self._run
            self._events = [_event(r.events[i]) for i in range(r.event_count)]
        return self._events

    @property
    def samples(self):
        if self._samples is None:
            self._samples = _samples(self._run)
        return self._samples

    @property
    def final_state(self):
        return _state(self._run.final_state)

    @property
    def impact_law(self):
        return text(lib.jc_impact_law_name(self._model.setup.impact_law))

    def to_dict(self):
        """The document simulate --json prints for this run (None where it prints null)."""
        return {"setup": _clean(setup_json(self._model)), "events": [e.to_dict() for e in self.events],
                "termination": self.termination, "termination_detail": self.termination_detail,
                "t_end": num(self.t_end), "energy": _clean(self.energy), "impact_law": self.impact_law,
                "energy_gaining_impacts": self.energy_gaining_impacts,
                "largest_impact_gain_J": num(self.largest_impact_gain_J), "micro_slips": self.micro_slips,
                "rocking_period_s": num(self.rocking_period_s), "summary": _clean(self.summary)}

    def __len__(self):
        return self._run.event_count

    def __repr__(self):
        lo = self.summary["first_liftoff_x"]
        return "<jumpcyl.Run: %d events, %d samples, %s at t = %.6g s%s>" % (
            self._run.event_count, self._run.sample_count, self.termination, self.t_end,
            ", first lift-off at x = %.4g m" % lo if lo is not None else ", no lift-off")


def _clean(d):
    if isinstance(d, dict):
        return {k: _clean(v) for k, v in d.items()}
    if isinstance(d, list):
        return [_clean(v) for v in d]
    if isinstance(d, float):
        return num(d)
    return d


def simulate(setup=None, **options):
    """Runs the full model from the setup's start (jc_simulate; the GIL is
    released while it runs). Options as the tool's: sample_dt (0: samples only
    at events... as the library), t_max, max_events, rtol, atol, event_tol,
    contact_height, max_samples; numbers SI, strings with units. Returns a Run."""
    setup = as_setup(setup)
    o = sim_options(**options) if options else _default_options()
    m = setup._model()
    run = ffi.gc(ffi.new("jc_Run *"), lib.jc_run_free)
    err = err_buf()
    st = lib.jc_simulate(m, o, run, err, len(err))
    if st != lib.JC_OK:
        raise_status(st, err)
    return Run(setup, m, run)


_DEFAULT_OPTIONS = None


def _default_options():
    global _DEFAULT_OPTIONS
    if _DEFAULT_OPTIONS is None:
        _DEFAULT_OPTIONS = sim_options()
    return _DEFAULT_OPTIONS


def _crossing(c):
    if not c.found:
        return None
    s = c.state
    return {"theta": s.theta_rad, "x": s.x_m, "omega": s.omega_radps, "normal": s.normal_N,
            "friction": s.friction_N, "grazing": bool(c.grazing)}


def paper_solve(m):
    p = ffi.new("jc_PaperResult *")
    err = err_buf()
    check(lib.jc_paper_solve(m, p, err, len(err)), err)
    return p


def rolling_predict(m):
    r = ffi.new("jc_RollingResult *")
    err = err_buf()
    check(lib.jc_rolling_predict(m, r, err, len(err)), err)
    return r


def predict(setup=None):
    """The paper's model (Eq. 9), the exact rolling model and the full model's
    first lift-off for a setup: a dict with the keys of predict --json."""
    setup = as_setup(setup)
    m = model_of(setup)
    p = paper_solve(m)
    r = rolling_predict(m)
    run = simulate(setup)
    pm = {"cm_offset": p.cm_offset_m, "disc_mass": p.disc_mass_kg,
          "roots": [p.theta_rad[i] for i in range(p.root_count)], "truncated": bool(p.truncated),
          "first": {"theta": p.theta_rad[p.first], "x": p.x_m[p.first]} if p.first >= 0 else None}
    ro = {"liftoff": _crossing(r.liftoff), "slip": _crossing(r.slip), "end": text(lib.jc_rolling_end_name(r.end)),
          "end_x": r.end_x_m}
    lo = None
    for e in run.events:
        if e.kind == "liftoff":
            lo = {"theta": e.theta, "x": e.x, "t": e.t}
            break
    full = {"liftoff": lo, "hops": run.summary["liftoffs"], "bounces": run.summary["bounces"],
            "largest_hop": run.summary["largest_hop"], "termination": run.termination}
    return _clean({"setup": setup_json(m), "paper_model": pm, "rolling": ro, "full": full})
