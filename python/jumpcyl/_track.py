"""Tracked videos (include/jumpcyl/track.h): read_track, the derivation of
`jumpcyl track`, and fit, the library's fit of the model to a track (as
`jumpcyl fit` reports it)."""
import math
import os

import numpy as np

from ._lib import ffi, lib, text, err_buf, check, raise_status
from ._setup import as_setup, Setup
from ._simulate import sim_options
from ._params import param, to_si
from ._study import _Ctx, run_with_ctx

_CENTRE = ("none", "tracked", "recovered from the mark")
_INCLINE = ("unknown", "measured", "given")
_NOTES = ("centre", "surface", "hops", "theta")


def _arr(p, n, dtype=np.float64):
    if p == ffi.NULL or n == 0:
        return np.full(n, np.nan) if dtype == np.float64 else np.zeros(n, dtype)
    return np.frombuffer(ffi.buffer(p, n * ffi.sizeof(ffi.typeof(p).item)), dtype=dtype).copy()


class Track:
    """A tracked experiment in the incline frame, frame by frame (jc_Track):
    arrays t, x, y (the centre), theta, omega, mark_x, mark_y, contact,
    airborne (numpy); incline (rad) and its source; sigma (the noise, m);
    hops (list of dicts); notes {quantity: (ok, text)}. The library's track
    is kept for fit()."""

    def __init__(self, name, t):
        self.name = name
        self._t = t  # ffi.gc: jc_track_free
        n = t.n
        self.t, self.x, self.y = _arr(t.t_s, n), _arr(t.x_m, n), _arr(t.y_m, n)
        self.theta, self.omega = _arr(t.theta_rad, n), _arr(t.omega_radps, n)
        self.mark_x, self.mark_y = _arr(t.mark_x_m, n), _arr(t.mark_y_m, n)
        self.centre_sigma = _arr(t.centre_sigma_m, n)
        self.contact = _arr(t.contact, n, np.uint8).astype(bool)
        self.airborne = _arr(t.airborne, n, np.uint8).astype(bool)
        self.incline = t.incline_rad
        self.incline_sigma = t.incline_sigma_rad
        self.incline_source = _INCLINE[t.incline_source]
        self.centre_source = _CENTRE[t.centre_source]
        self.has_mark = bool(t.has_mark)
        self.sigma = t.sigma_m
        self.frame_rate = t.frame_rate_hz
        self.radius = t.radius_m
        self.x0 = t.x0_m
        self.hops = [{"first": h.first, "last": h.last, "peak": h.peak, "height_m": h.height_m,
                      "height_sigma_m": h.height_sigma_m, "bound_m": h.bound_m,
                      "fitted_flight": bool(h.fitted_flight)} for h in t.hop[0:t.hops]]
        self.notes = {q: (bool(t.note[i].ok), ffi.string(t.note[i].text).decode()) for i, q in enumerate(_NOTES)}
        self.tracks = [ffi.string(t.track_names[i]).decode() for i in range(t.track_count)]

    def __len__(self):
        return int(self._t.n)

    def __repr__(self):
        return "<jumpcyl.Track %s: %d frames, incline %.3f deg (%s), noise %.3g mm, %d hop(s)>" % (
            os.path.basename(self.name), len(self), math.degrees(self.incline), self.incline_source,
            self.sigma * 1e3, len(self.hops))


def read_track(path, setup=None, incline=None, centre=None, mark=None, axes="level", fit_tilt=False):
    """Reads a Tracker .trk file or an exported data table and derives the
    track in the incline frame, as `jumpcyl track` does: the centre, the
    surface and the incline (measured from the frames in contact, or checked
    against incline when given), hops, theta and omega. setup gives the rim
    radius and g (the paper's by default)."""
    setup = as_setup(setup)
    opt = ffi.new("jc_TrackOptions *")
    lib.jc_track_options_default(opt)
    keep = []
    if centre is not None:
        keep.append(ffi.new("char[]", centre.encode()))
        opt.centre = keep[-1]
    if mark is not None:
        keep.append(ffi.new("char[]", mark.encode()))
        opt.mark = keep[-1]
    opt.incline_rad = math.nan if incline is None else to_si(param("incline"), incline)
    opt.radius_m = setup.get("radius")
    opt.gravity_mps2 = setup.get("g")
    if axes not in ("level", "incline"):
        raise ValueError("axes: %r (allowed: level, incline)" % (axes,))
    opt.axes = lib.JC_TRACK_AXES_INCLINE if axes == "incline" else lib.JC_TRACK_AXES_LEVEL
    opt.fit_tilt = bool(fit_tilt)
    t = ffi.gc(ffi.new("jc_Track *"), lib.jc_track_free)
    err = err_buf()
    st = lib.jc_track_read_file(os.fsencode(path), opt, t, err, len(err))
    if st != lib.JC_OK:
        raise_status(st, err)
    return Track(os.fspath(path), t)


def _fit_names(s):
    out = ffi.new("jc_TrackFitParam[]", lib.JC_FIT_MAX_PARAMS)
    n = lib.jc_fit_param_list(s, out, lib.JC_FIT_MAX_PARAMS)
    names = []
    buf = ffi.new("char[]", 64)
    for k in range(n):
        lib.jc_fit_param_name(s, out[k], buf, len(buf))
        names.append(ffi.string(buf).decode())
    return names


def fit(track, setup=None, free=("mu_k", "restitution"), loss="linear", hold_start=False, sigma=None,
        max_iter=None, starts=None, seed=None, window=(None, None), progress=False, **options):
    """Fits the model to a track (jc_track_fit), as `jumpcyl fit`: the values
    named in free (mu_s, mu_k, restitution, theta0, omega0, x0, rod_offset,
    rod_mass, ...) with the start's and the frame's, from many start points;
    a dict with values, sigmas, correlations, flags, the predicted first
    lift-off and the verdict. setup: the filmed body (the paper's by
    default); its incline becomes the track's."""
    if not isinstance(track, Track):
        raise TypeError("fit: a jumpcyl.Track (jc.read_track), not %s" % type(track).__name__)
    setup = as_setup(setup)
    t = track._t
    err = err_buf()
    check(lib.jc_track_require(track.name.encode(), t, lib.JC_TRACK_NEED_CENTRE | lib.JC_TRACK_NEED_INCLINE, err,
                               len(err)), err)
    s = setup._ptr()
    s.incline_rad = t.incline_rad
    fo = ffi.new("jc_TrackFitOptions *")
    lib.jc_fit_options_default(fo)
    if isinstance(free, str):
        free = free.split(",")
    allowed = _fit_names(s)
    if not free:
        raise ValueError("free: name the values to fit (allowed: %s)" % ", ".join(allowed))
    if len(free) > lib.JC_FIT_MAX_PARAMS - 5:
        raise ValueError("free: more than %d values" % (lib.JC_FIT_MAX_PARAMS - 5))
    for k, name in enumerate(free):
        v = ffi.new("jc_TrackFitParam *")
        if lib.jc_fit_param_find(s, name.replace("-", "_").encode(), v) != lib.JC_OK:
            raise ValueError("free: '%s' is not a value the fit can free for this body (allowed: %s)" % (
                name, ", ".join(allowed)))
        if any(fo.free[j].kind == v.kind and fo.free[j].part == v.part for j in range(k)):
            raise ValueError("free: '%s' is named twice" % name)
        fo.free[k] = v[0]
    fo.free_count = len(free)
    if lib.jc_fit_loss_parse(loss.encode(), ffi.addressof(fo, "loss")) != lib.JC_OK:
        raise ValueError("loss: %r (allowed: linear, huber, cauchy)" % (loss,))
    fo.hold_start = bool(hold_start)
    if sigma is not None:
        fo.sigma_m = to_si(param("radius"), sigma)
    if max_iter is not None:
        fo.max_iter = int(max_iter)
    if starts is not None:
        fo.starts = int(starts)
    if seed is not None:
        fo.seed = int(seed)
    fo.from_s = math.nan if window[0] is None else float(window[0])
    fo.to_s = math.nan if window[1] is None else float(window[1])
    sim = sim_options(**options)
    r = ffi.new("jc_TrackFitResult *")
    ctx = _Ctx("fit", progress)
    st = run_with_ctx(ctx, lambda h: lib.jcpy_track_fit(s, t, fo, sim, r, h, 1, err, len(err)))
    if st != lib.JC_OK:
        raise_status(st, err)
    return _fit_dict(r)


def _fit_dict(r):
    n = r.count
    buf = ffi.new("char[]", 64)
    names = []
    for k in range(n):
        lib.jc_fit_param_name(ffi.addressof(r, "setup"), r.param[k], buf, len(buf))
        names.append(ffi.string(buf).decode())
    flags = [text(lib.jc_fit_flag_text(r.flag[k])) if r.flag[k] else None for k in range(n)]
    params = []
    for k in range(n):
        params.append({"name": names[k], "unit": text(lib.jc_fit_param_unit(r.param[k])),
                       "added": bool(r.start_value[k]), "initial": r.initial[k], "value": r.value[k],
                       "sigma": r.sigma[k], "lo": r.lo[k], "hi": r.hi[k], "determined": not r.flag[k],
                       "flag": flags[k],
                       "correlated_with": names[r.other[k]] if r.flag[k] == lib.JC_FIT_CORRELATED else None,
                       "rho": r.rho[k] if r.flag[k] == lib.JC_FIT_CORRELATED else None})
    corr = np.array([[r.corr[i][j] for j in range(n)] for i in range(n)])
    return {"params": params, "values": {p["name"]: p["value"] for p in params},
            "sigmas": {p["name"]: p["sigma"] for p in params}, "names": names, "correlation": corr,
            "chi2": r.chi2, "chi2_dof": r.chi2_dof, "dof": r.dof, "residuals": r.residuals,
            "noise_measured": bool(r.noise_measured), "sigma_m": r.sigma_m, "iterations": r.iterations,
            "screened": r.screened, "descents": r.descents, "minima": r.minima,
            "frames": (r.first, r.frames), "rms_path_m": r.rms_path_m, "rms_theta_rad": r.rms_theta_rad,
            "liftoff": {"x_m": r.liftoff_x_m, "sigma_m": r.liftoff_sigma_m, "t_s": r.liftoff_t_s}
            if r.has_liftoff else None,
            "misfit": bool(r.misfit), "runs_z": r.runs_z, "verdict": ffi.string(r.verdict).decode(),
            "incline_rad": r.setup.incline_rad, "incline_sigma_rad": r.incline_sigma_rad}
