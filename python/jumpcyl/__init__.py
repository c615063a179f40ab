"""jumpcyl: an off-centre-mass cylinder rolling, slipping and jumping on an
incline; a thin layer over libjumpcyl's public API (docs/python.md).

    import jumpcyl as jc
    s = jc.Setup(preset="paper", incline="30deg", mu=0.5)
    run = jc.simulate(s, sample_dt=1e-3)
    run.summary["first_liftoff_x"]
"""
from ._lib import Error, lib as _clib, text as _text
from ._params import Param, params, presets, deg
from ._setup import Setup
from ._simulate import Event, Run, simulate, predict, sample_dtype
from ._study import sweep, mc, map, design, McResult, Map
from ._paper import paper_table
from ._track import Track, read_track, fit

__version__ = _text(_clib.jc_version())

__all__ = ["Error", "Param", "params", "presets", "deg", "Setup", "Event", "Run", "simulate", "predict",
           "sample_dtype", "sweep", "mc", "map", "design", "McResult", "Map", "paper_table", "Track", "read_track", "fit"]
