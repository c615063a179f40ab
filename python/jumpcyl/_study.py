"""Studies on the library (include/jumpcyl/study.h): sweep (a grid), mc
(Monte Carlo samples), map (a 2-D grid as arrays), design (the values of one
parameter that put the first lift-off at a place). Cases run on the
library's OpenMP threads without the GIL; their CSV rows are gathered in C
(jumpcyl_build.py) and read as sweep's and mc's CSV files are; progress and
Ctrl-C go through the study's progress callback."""
import io
import math
import numbers
import sys
import threading
import time

import numpy as np

from ._lib import ffi, lib, text, err_buf, check, raise_status, num
from ._params import param, params, to_si, format_value
from ._setup import as_setup
from ._simulate import sim_options

try:
    import pandas as _pd
except ImportError:  # pragma: no cover - Debian's python3-pandas is optional
    _pd = None

# ---- progress and Ctrl-C ----


class _Ctx:
    """What a running study's callbacks see: the progress line, and the
    exception (KeyboardInterrupt) that stopped it."""

    def __init__(self, label, progress):
        self.label = label
        self.progress = progress
        self.exc = None
        self.t0 = time.monotonic()
        self.shown = 0.0

    def tick(self, done, total, stage=None):
        if not self.progress:
            return
        now = time.monotonic()
        if callable(self.progress):
            self.progress(done, total)
            return
        if now - self.shown < 0.1 and done != total:
            return
        self.shown = now
        what = stage or self.label
        if total > 0:
            sys.stderr.write("\r%s: %d/%d, %.1f s" % (what, done, total, now - self.t0))
        else:
            sys.stderr.write("\r%s, %.1f s" % (what, now - self.t0))
        sys.stderr.flush()

    def end(self):
        if self.progress is True:
            sys.stderr.write("\n")
            sys.stderr.flush()


_interrupted = threading.local()


def _onerror(exception, exc_value, traceback):
    # A Ctrl-C (or any exception) raised in a callback before its own try:
    # kept for the caller, and the study asked to stop.
    _interrupted.exc = exc_value
    return 1


def _tick(pyctx, *args):
    """The context's tick(*args): 0 to go on, 1 to stop, the exception kept
    for run_with_ctx (a call: a pending Ctrl-C is raised here)."""
    ctx = ffi.from_handle(pyctx)
    try:
        ctx.tick(*args)
    except BaseException as e:
        ctx.exc = e
        return 1
    return 0


@ffi.def_extern(onerror=_onerror)
def _jcpy_study_progress(pyctx, done, count):
    return _tick(pyctx, done, count)


@ffi.def_extern(onerror=_onerror)
def _jcpy_design_progress(pyctx, p):
    return _tick(pyctx, p.done, p.total, "design: " + text(p.stage))


@ffi.def_extern(onerror=_onerror)
def _jcpy_fit_progress(pyctx, p):
    return _tick(pyctx, int(1000 * p.fraction), 1000, "fit: " + text(p.stage))


def run_with_ctx(ctx, call):
    """call(handle) with the context's handle; a stop from a callback raises
    what stopped it (KeyboardInterrupt) once the library has returned."""
    _interrupted.exc = None
    handle = ffi.new_handle(ctx)
    try:
        st = call(handle)
    finally:
        ctx.end()
    exc = ctx.exc or getattr(_interrupted, "exc", None)
    _interrupted.exc = None
    if exc is not None and st == lib.JC_ESTOPPED:
        raise exc
    return st


# ---- the study's definition ----


def _values_of(p, spec):
    """A grid axis: a list or array of values (numbers SI, strings with units,
    choices by name), or the tool's "START:STOP:STEP" text (values START + k STEP,
    as the tool computes them)."""
    if isinstance(spec, str) and spec.count(":") == 2:
        lo, hi, step = (to_si(p, t) for t in spec.split(":"))
        if not step > 0 or hi < lo:
            raise ValueError("vary %s='%s': needs STOP >= START and STEP > 0" % (p.python_name, spec))
        n = int(math.floor((hi - lo) / step + 1e-9)) + 1
        vals = [lo + float(k) * step for k in range(n)]
        if abs(vals[-1] - hi) <= 1e-9 * step:
            vals[-1] = hi
        return vals
    if isinstance(spec, (str, numbers.Real)):
        spec = [spec]
    return [to_si(p, v) for v in spec]


def _study(kind, setup, sim, threads):
    d = ffi.new("jc_StudyDef *")
    base, fixed = setup.study_base()
    d.kind = kind
    d.base = base[0]
    d.fixed = fixed[0]
    d.sim = sim[0]
    d.threads = 0 if threads is None else int(threads)
    if d.threads < 0:
        raise ValueError("threads: %d (allowed: 0 or more; None: every core)" % d.threads)
    return d


def _drop_fixed(d, p):
    """The study varies p: the setup's own value of p (and of a shortcut or
    the rows it sets) gives way, as if the setup had not given it."""


def _batch_sim(options):
    if options.get("sample_dt"):
        raise ValueError("sample_dt: a study's cases record no trajectory")
    return sim_options(**options)


class _Rows:
    def __init__(self, count, nvalues, tally=None, keep_outcomes=False):
        self.r = ffi.gc(ffi.new("jcpy_Rows *"), lib.jcpy_rows_free)
        if lib.jcpy_rows_init(self.r, count, nvalues, keep_outcomes, tally if tally is not None else ffi.NULL):
            raise MemoryError("jumpcyl: out of memory for %d rows" % count)

    def csv(self):
        return ffi.unpack(self.r.csv, self.r.csv_len).decode()


def _run_study(d, label, progress, tally=None):
    err = err_buf()
    check(lib.jc_study_check(d, err, len(err)), err)
    count = lib.jc_study_case_count(d)
    rows = _Rows(count, d.param_count, tally)
    ctx = _Ctx(label, progress)

    def call(handle):
        rows.r.pyctx = handle
        return lib.jcpy_study_run(d, 0, count, rows.r, 1, err, len(err))

    st = run_with_ctx(ctx, call)
    if rows.r.failed:
        raise MemoryError("jumpcyl: out of memory gathering the rows")
    if st != lib.JC_OK:
        raise_status(st, err)
    hdr = ffi.new("char[]", 4096)
    lib.jc_study_header(d, hdr, len(hdr))
    return ffi.string(hdr).decode() + rows.csv()


def read_rows(csv_text):
    """Rows as the tool's CSV files hold them, parsed: a pandas DataFrame
    (numbers read back exactly: float_precision="round_trip"), or a numpy
    record array without pandas."""
    if _pd is not None:
        return _pd.read_csv(io.StringIO(csv_text), float_precision="round_trip", keep_default_na=False,
                            na_values=[""])
    import csv
    r = list(csv.reader(io.StringIO(csv_text)))
    head, body = r[0], r[1:]
    cols = []
    for j, _ in enumerate(head):
        col = [row[j] for row in body]
        try:
            cols.append(np.array([float(v) if v else np.nan for v in col]))
        except ValueError:
            cols.append(np.array(col))
    return np.rec.fromarrays(cols, names=head)


def sweep(setup=None, vary=None, threads=None, progress=False, **options):
    """The full model over every combination of the varied values (the last
    varying fastest), as `jumpcyl sweep`: a pandas DataFrame with the columns
    of its CSV (case, the varied values in SI with angles in degrees, then the
    outcome). vary: {name: values}, values a list or array (numbers SI,
    strings with units) or the tool's "START:STOP:STEP". threads: None for
    every core. progress=True shows a line on stderr (or a callable(done,
    total)). Ctrl-C stops it: KeyboardInterrupt, nothing returned."""
    setup = as_setup(setup)
    if not vary:
        raise ValueError("vary: give at least one parameter and its values, e.g. vary={'incline': '15deg:45deg:5deg'}")
    if len(vary) > lib.JC_STUDY_PARAM_MAX:
        raise ValueError("vary: %d parameters (allowed: at most %d)" % (len(vary), lib.JC_STUDY_PARAM_MAX))
    d = _study(lib.JC_STUDY_GRID, setup, _batch_sim(options), threads)
    keep = []
    for j, (name, spec) in enumerate(vary.items()):
        p = param(name)
        vals = _values_of(p, spec)
        if not vals:
            raise ValueError("vary %s: no values" % p.python_name)
        _check_alone(setup, p, vals)
        arr = ffi.new("double[]", vals)
        keep.append(arr)
        _drop_fixed(d, p)
        d.params[j] = {"id": p.id, "spread": lib.JC_STUDY_VALUES, "values": arr, "count": len(vals)}
    d.param_count = len(vary)
    return read_rows(_run_study(d, "sweep", progress))


def _check_alone(setup, p, vals):
    """Each value alone on the setup, as the tool checks a --vary before any
    work: a value no setup allows is refused (ValueError)."""
    base, fixed = setup.study_base()
    err = err_buf()
    s = ffi.new("jc_Setup *")
    for v in sorted(set(vals)):
        s[0] = base[0]
        fixed.given[p.id] = 1
        fixed.value[p.id] = v
        if lib.jc_param_values_apply(fixed, s, ffi.NULL, err, len(err)) != lib.JC_OK:
            raise ValueError("vary %s: the value %s is not allowed: %s" % (
                p.python_name, format_value(p.id, v), ffi.string(err).decode()))


# ---- Monte Carlo ----


def _stats_dict(s, total):
    d = {"count": s.n, "fraction": s.n / total if total else 0.0}
    if s.n > 0:
        d.update(mean=s.mean, sd=s.sd, p2_5=s.p2_5, p50=s.p50, p97_5=s.p97_5)
    d["regions"] = [{"lo": r.lo_m, "hi": r.hi_m, "mean": r.mean_m, "fraction": r.count / total}
                    for r in s.regions[0:s.region_count]]
    return d


class McResult:
    """A Monte Carlo: .rows (a DataFrame of every sample's drawn values and
    outcome, as mc --output), .summary (mc --json's document), .spreads
    (the inputs and their spreads), .liftoff_x (the first lift-offs, m, sorted)."""

    def __init__(self, rows, summary, spreads, liftoff_x):
        self.rows, self.summary, self.spreads, self.liftoff_x = rows, summary, spreads, liftoff_x

    def __repr__(self):
        s = self.summary["first_liftoff_x_m"]
        return "<jumpcyl.McResult: %d samples, first lift-off median %s m>" % (
            self.summary["samples"], "%.4g" % s["p50"] if "p50" in s else "none")


def mc(setup=None, samples=1000, seed=1, sigma=None, range=None, defaults=True, threads=None, progress=False,
       region_gap=None, **options):
    """Monte Carlo propagation of input uncertainties, as `jumpcyl mc`:
    sigma={name: sd} normal spreads about the setup's values, range={name:
    (lo, hi)} uniform ones (numbers SI, strings with units); unless
    defaults=False, the paper's stated tolerances and the friction and
    restitution it did not measure (jc_study_default_spreads) for every
    input neither spread nor given in the setup. Sample i depends only on
    (seed, i): the same for any thread count."""
    setup = as_setup(setup)
    sigma, rng = dict(sigma or {}), dict(range or {})
    if isinstance(samples, bool) or not isinstance(samples, numbers.Integral) or not 1 <= samples <= 100_000_000:
        raise ValueError("samples: %r (allowed: a whole number from 1 to 100000000)" % (samples,))
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or not 0 <= seed < 2 ** 64:
        raise ValueError("seed: %r (allowed: a whole number from 0 to 2^64-1)" % (seed,))
    gap = lib.JC_MC_LIFTOFF_GAP_M if region_gap is None else to_si(param("radius"), region_gap)
    if not gap > 0:
        raise ValueError("region_gap: %r (allowed: a length > 0)" % (region_gap,))
    d = _study(lib.JC_STUDY_MONTE_CARLO, setup, _batch_sim(options), threads)
    d.samples = samples
    d.seed = seed
    given = {params()[pid].name for pid in setup._values}
    spreads = []  # (param, kind, a, b, why)
    for kind, table, why in ((lib.JC_STUDY_NORMAL, sigma, "sigma"), (lib.JC_STUDY_UNIFORM, rng, "range")):
        for name, v in table.items():
            p = param(name)
            if p.choices:
                raise ValueError("%s %s: a name, not a number (vary it with a sweep)" % (why, p.python_name))
            if any(q[0].id == p.id for q in spreads):
                raise ValueError("%s %s: already has a spread (one sigma or range per input)" % (why, p.python_name))
            if (p.name == "mu" and given & {"mu-s", "mu-k"}) or (p.name.startswith("mu-") and "mu" in given):
                raise ValueError("%s %s: mu sets both coefficients; spread either mu or mu_s/mu_k, as the setup "
                                 "gives them" % (why, p.python_name))
            try:
                nominal = setup.get(p.name)
            except ValueError:
                raise ValueError("%s %s: the setup's body has no such part" % (why, p.python_name)) from None
            if kind == lib.JC_STUDY_NORMAL:
                sd = to_si(p, v)
                if not sd >= 0:
                    raise ValueError("sigma %s: a standard deviation is >= 0" % p.python_name)
                spreads.append((p, kind, nominal, sd, "sigma"))
            else:
                if isinstance(v, str) and ":" in v:
                    v = v.split(":")
                lo, hi = (to_si(p, x) for x in v)
                if not hi >= lo:
                    raise ValueError("range %s: needs hi >= lo" % p.python_name)
                spreads.append((p, kind, lo, hi, "range"))
    if defaults:
        cap = lib.JC_STUDY_PARAM_MAX
        out = ffi.new("jc_StudyParam[]", cap)
        why = ffi.new("char *[]", cap)
        n = lib.jc_study_default_spreads(setup._ptr(), out, ffi.cast("const char **", why), cap)
        for k in builtins_range(min(n, cap)):
            p = params()[out[k].id]
            owned = any(q[0].id == p.id for q in spreads) or p.name in given or (
                p.name == "mu" and given & {"mu-s", "mu-k"})
            if not owned:
                spreads.append((p, out[k].spread, out[k].a, out[k].b, text(why[k])))
    if len(spreads) > lib.JC_STUDY_PARAM_MAX:
        raise ValueError("too many uncertain inputs (allowed: at most %d)" % lib.JC_STUDY_PARAM_MAX)
    for j, (p, kind, a, b, _) in enumerate(spreads):
        d.params[j] = {"id": p.id, "spread": kind, "values": ffi.NULL, "count": 0, "a": a, "b": b}
    d.param_count = len(spreads)
    tally = ffi.gc(ffi.new("jc_Tally *"), lib.jc_tally_free)
    if lib.jc_tally_init(tally, samples) != lib.JC_OK:
        raise MemoryError("jumpcyl: out of memory for %d samples" % samples)
    csv_text = _run_study(d, "mc", progress, tally)
    lift, hop = ffi.new("jc_Stats *"), ffi.new("jc_Stats *")
    t = tally
    xs = np.array(ffi.unpack(t.liftoff_x_m, t.liftoffs)) if t.liftoffs else np.empty(0)
    lib.jc_stats_compute(t.liftoff_x_m, t.liftoffs, t.none, t.invalid, gap, lift)
    lib.jc_stats_compute(t.hop_m, t.valid, 0, t.invalid, lib.JC_MC_HOP_GAP_M, hop)
    summary = {"samples": samples, "valid": t.valid, "invalid": t.invalid, "slides_at_start": t.slides,
               "no_liftoff": t.none, "first_liftoff_x_m": _stats_dict(lift, t.valid),
               "largest_hop_m": _stats_dict(hop, t.valid)}
    spread_list = [{"name": p.python_name, "spread": "normal" if k == lib.JC_STUDY_NORMAL else "uniform",
                    "a": a, "b": b, "why": w} for p, k, a, b, w in spreads]
    return McResult(read_rows(csv_text), summary, spread_list, np.sort(xs))


builtins_range = range


# ---- maps ----


class Map:
    """A 2-D grid of the full model: .x and .y (the axes' values, SI), and
    for each outcome column of a sweep (first_liftoff_x_m, liftoffs,
    largest_hop_m, termination, ...) a 2-D array z[column] of shape
    (len(y), len(x)): row i is y[i], ready for imshow / pcolormesh. .rows:
    the sweep's DataFrame."""

    def __init__(self, xname, yname, x, y, rows):
        self.xname, self.yname, self.x, self.y, self.rows = xname, yname, np.asarray(x), np.asarray(y), rows
        self.z = {}
        n, m = len(self.x), len(self.y)
        cols = rows.columns if _pd is not None else rows.dtype.names
        for c in list(cols)[3:]:
            self.z[c] = np.asarray(rows[c]).reshape(n, m).T

    def __getitem__(self, column):
        return self.z[column]


def _axis(spec):
    if not isinstance(spec, (tuple, list)) or len(spec) not in (2, 4):
        raise ValueError("an axis is (name, start, stop, step) or (name, values)")
    p = param(spec[0])
    if len(spec) == 4:
        lo, hi, step = (to_si(p, v) for v in spec[1:])
        if not step > 0 or hi < lo:
            raise ValueError("axis %s: needs stop >= start and step > 0" % p.python_name)
        n = int(math.floor((hi - lo) / step + 1e-9)) + 1
        vals = [lo + float(k) * step for k in builtins_range(n)]
        if abs(vals[-1] - hi) <= 1e-9 * step:
            vals[-1] = hi
        return p, vals
    return p, _values_of(p, spec[1])


def map(setup=None, x=None, y=None, threads=None, progress=False, **options):
    """A regime map: the full model over a 2-D grid, x=(name, start, stop,
    step) and y likewise (or (name, values)); numbers SI, strings with units.
    Returns a Map with 2-D arrays of every outcome column."""
    (px, vx), (py, vy) = _axis(x), _axis(y)
    rows = sweep(setup, vary={px.name: vx, py.name: vy}, threads=threads, progress=progress, **options)
    return Map(px.python_name, py.python_name, vx, vy, rows)


# ---- design ----


def _side(s):
    return {"value": s.p, "outcome": text(lib.jc_case_kind_name(s.kind)),
            "x_m": s.x_m if s.kind == lib.JC_CASE_LIFTOFF else None}


def design(setup=None, jump_at=None, free=None, range=None, points=1000, threads=None, progress=False, **options):
    """The values of one parameter (free) that put the first lift-off at
    jump_at, branch by branch (jc_design_run): a dict with the keys of design
    --json (target_x_m, free, branches, discontinuities, reachable_m,
    solutions with their sensitivities dX/dp). free: a row design can free
    (jc_design_free_check: not restitution, ramp_length, paper_d or a row of
    names). range=(lo, hi): its range (numbers SI, strings with units); by
    default the library's (jc_design_default_range), as the tool's."""
    setup = as_setup(setup)
    p = param(free)
    target = to_si(param("radius"), jump_at) if jump_at is not None else None
    if target is None or not target > 0:
        raise ValueError("jump_at: %r (allowed: a length > 0, e.g. '1.2m')" % (jump_at,))
    d = ffi.new("jc_DesignDef *")
    base, fixed = setup.study_base()
    d.base = base[0]
    d.fixed = fixed[0]
    d.free_id = p.id
    err = err_buf()
    check(lib.jc_design_free_check(p.id, ffi.addressof(d[0], "base"), ffi.addressof(d[0], "fixed"), err, len(err)),
          err, "free")
    if range is None:
        check(lib.jc_design_default_range(d, ffi.NULL, err, len(err)), err, "free")
        lo, hi = d.lo, d.hi
    else:
        if isinstance(range, str):
            range = range.split(":")
        lo, hi = (to_si(p, v) for v in range)
    if not lo < hi:
        raise ValueError("range %s: needs lo < hi" % p.python_name)
    d.lo, d.hi = lo, hi
    d.target_x_m = target
    d.points = int(points)
    d.threads = 0 if threads is None else int(threads)
    d.sim = _batch_sim(options)[0]
    res = ffi.gc(ffi.new("jc_DesignResult *"), lib.jc_design_free)
    ctx = _Ctx("design", progress)
    st = run_with_ctx(ctx, lambda h: lib.jcpy_design_run(d, res, h, 1, err, len(err)))
    if st != lib.JC_OK:
        raise_status(st, err)
    r = res
    reach_lo, reach_hi = ffi.new("double[]", 64), ffi.new("double[]", 64)
    n = lib.jc_design_reachable(r, reach_lo, reach_hi, 64)
    branches = []
    for b in r.branches[0:r.branch_count]:
        o = {"lo": b.p_lo, "hi": b.p_hi, "outcome": text(lib.jc_case_kind_name(b.kind))}
        if b.kind == lib.JC_CASE_LIFTOFF:
            o.update(x_min_m=b.x_min_m, x_max_m=b.x_max_m)
        branches.append(o)
    sols = [{"value": s.p, "x_m": s.x_m, "error_m": s.x_m - target, "dxdp": s.dxdp,
             "edge_margin": s.edge_margin if math.isfinite(s.edge_margin) else None, "branch": s.branch}
            for s in r.solutions[0:r.solution_count]]
    return {"target_x_m": target, "free": {"name": p.name, "si_unit": p.si_unit, "lo": lo, "hi": hi},
            "points": r.scan_count, "evaluations": r.evaluations, "seconds": r.seconds, "edge_width": r.edge_width,
            "branches": branches,
            "discontinuities": [{"below": _side(e.lo), "above": _side(e.hi)} for e in r.edges[0:r.edge_count]],
            "reachable_m": [[reach_lo[k], reach_hi[k]] for k in builtins_range(n)],
            "solutions": sols, "unverified": r.unverified, "at_edge": r.at_edge,
            "scan": {"value": np.array([q.p for q in r.scan[0:r.scan_count]]),
                     "x_m": np.array([q.x_m for q in r.scan[0:r.scan_count]])}}
