"""read_track and fit on the sample experiment (examples/tracker/incline.trk:
a video of the model made with mu_k 0.4, restitution 0.3)."""
import os
import subprocess

import numpy as np
import pytest

import jumpcyl as jc
from conftest import REPO

TRK = os.path.join(REPO, "examples", "tracker", "incline.trk")
FIT_EXAMPLE = os.path.join(os.path.dirname(os.environ.get("JUMPCYL_TOOL", os.path.join(REPO, "build", "jumpcyl"))),
                           "fit_example")


def test_read_track():
    t = jc.read_track(TRK)
    assert len(t) == 39 and t.incline_source == "measured"
    assert abs(np.degrees(t.incline) - 30) < 0.2 and len(t.hops) == 3
    assert np.all(np.diff(t.t) > 0) and t.contact.sum() > 10
    with pytest.raises(ValueError):
        jc.read_track(TRK, incline="45deg")  # refused: the frames in contact say 30 deg
    with pytest.raises(ValueError, match="nosuch"):
        jc.read_track("/nosuch.trk")


def test_fit_finds_the_filmed_values():
    t = jc.read_track(TRK)
    f = jc.fit(t, jc.Setup(), free=["mu_k", "restitution"])
    v, s = f["values"], f["sigmas"]
    assert abs(v["mu_k"] - 0.4) < 3 * s["mu_k"] + 0.002
    assert abs(v["restitution"] - 0.3) < 3 * s["restitution"] + 0.005
    assert not f["misfit"] and f["verdict"].startswith("the model describes")
    assert f["correlation"].shape == (len(f["names"]),) * 2
    if os.access(FIT_EXAMPLE, os.X_OK):  # the C example's fit, the same calls: the same digits
        out = subprocess.run([FIT_EXAMPLE, TRK], capture_output=True, text=True).stdout
        assert "mu_k         = %.5f +- %.5f" % (v["mu_k"], s["mu_k"]) in out
        assert "restitution  = %.5f +- %.5f" % (v["restitution"], s["restitution"]) in out
    with pytest.raises(ValueError, match="not a value the fit can free"):
        jc.fit(t, jc.Setup(), free=["colour"])
