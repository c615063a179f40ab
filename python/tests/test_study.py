"""sweep, mc, map and design against the tool, and Ctrl-C in a long sweep."""
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pandas as pd
import pytest

import jumpcyl as jc
from conftest import tool, tool_json, assert_same

INCLINES = ["%ddeg" % a for a in range(10, 61, 10)]
MUS = ["0.3", "0.5", "1.0"]


def tool_rows(path):
    return pd.read_csv(path, float_precision="round_trip", keep_default_na=False, na_values=[""])


@pytest.mark.parametrize("threads", [1, 2])
def test_sweep_rows_are_the_tool_csv(tmp_path, threads):
    s = jc.Setup(preset="paper", restitution=0.4)
    df = jc.sweep(s, vary={"incline": INCLINES, "mu": MUS}, threads=threads)
    out = tmp_path / "sweep.csv"
    tool("sweep", "--vary", "incline=" + ",".join(INCLINES), "--vary", "mu=" + ",".join(MUS), "--output", str(out),
         "--threads", str(threads), "--quiet", *s.cli_args())
    ref = tool_rows(out)
    assert list(df.columns) == list(ref.columns)
    pd.testing.assert_frame_equal(df, ref, check_exact=True)
    assert len(df) == len(INCLINES) * len(MUS)
    # The last parameter varies fastest, as the tool's grid.
    assert list(df["mu"][:3]) == [0.3, 0.5, 1.0] and list(df["incline_deg"][:3]) == [10, 10, 10]


def test_sweep_range_text_is_the_tool_range(tmp_path):
    s = jc.Setup(preset="hoop")
    df = jc.sweep(s, vary={"theta0": "0:90:7.5"}, threads=2)
    out = tmp_path / "sweep.csv"
    tool("sweep", "--vary", "theta0=0:90:7.5", "--output", str(out), "--quiet", "--preset", "hoop")
    pd.testing.assert_frame_equal(df, tool_rows(out), check_exact=True)


def test_sweep_row_is_the_single_run():
    # Independent of the CSV: a case's first lift-off is simulate's, to its 12 digits.
    df = jc.sweep(jc.Setup(), vary={"incline": ["45deg"], "mu": [0.4]})
    run = jc.simulate(jc.Setup(incline="45deg", mu=0.4))
    assert float("%.12g" % run.summary["first_liftoff_x"]) == df["first_liftoff_x_m"][0]
    assert df["liftoffs"][0] == run.summary["liftoffs"]


def test_sweep_bad_inputs():
    with pytest.raises(ValueError, match="not allowed"):
        jc.sweep(jc.Setup(), vary={"incline": ["30deg", "95deg"]})
    with pytest.raises(ValueError, match="nosuch"):
        jc.sweep(jc.Setup(), vary={"nosuch": [1]})
    with pytest.raises(ValueError, match="vary"):
        jc.sweep(jc.Setup(), vary={})
    with pytest.raises(ValueError, match="sample_dt"):
        jc.sweep(jc.Setup(), vary={"mu": [0.5]}, sample_dt=0.01)


@pytest.mark.parametrize("threads", [1, 2])
def test_mc_rows_and_summary_are_the_tool(tmp_path, threads):
    s = jc.Setup(preset="paper", incline="45deg")
    r = jc.mc(s, samples=300, seed=7, sigma={"rod_offset": "0.5mm"}, range={"restitution": (0.2, 0.5)},
              threads=threads)
    out = tmp_path / "mc.csv"
    ref = tool_json("mc", "--samples", "300", "--seed", "7", "--sigma", "rod-offset=0.5mm", "--range",
                    "restitution=0.2:0.5", "--json", "--output", str(out), "--threads", str(threads), "--quiet",
                    *s.cli_args())
    pd.testing.assert_frame_equal(r.rows, tool_rows(out), check_exact=True)
    assert_same(r.summary, ref)
    assert r.summary["valid"] == 300
    # The median of the first lift-offs, recomputed here from the rows.
    x = r.rows["first_liftoff_x_m"].dropna().to_numpy()
    assert abs(np.median(x) - r.summary["first_liftoff_x_m"]["p50"]) < 1e-9


def test_mc_bad_inputs():
    with pytest.raises(ValueError, match="samples"):
        jc.mc(jc.Setup(), samples=0)
    with pytest.raises(ValueError, match="standard deviation"):
        jc.mc(jc.Setup(), samples=10, sigma={"rod_offset": -0.001})
    with pytest.raises(ValueError, match="impact_law"):
        jc.mc(jc.Setup(), samples=10, sigma={"impact_law": 1})
    with pytest.raises(ValueError, match="no such part"):
        jc.mc(jc.Setup(preset="hoop"), samples=10, sigma={"rod_offset": "1mm"})


def test_map_is_the_sweep_reshaped():
    m = jc.map(jc.Setup(), x=("incline", "20deg", "40deg", "10deg"), y=("mu", 0.3, 0.5, 0.1))
    z = m["first_liftoff_x_m"]
    assert z.shape == (3, 3)
    one = jc.simulate(jc.Setup(incline="40deg", mu=0.4))
    assert z[1, 2] == float("%.12g" % one.summary["first_liftoff_x"])


def test_design_hits_its_target():
    s = jc.Setup(incline="30deg")
    d = jc.design(s, jump_at="1.18m", free="rod_offset", range=("4cm", "7cm"), points=40)
    assert d["solutions"], d
    for sol in d["solutions"]:
        run = jc.simulate(s.replace(rod_offset=sol["value"]))
        assert abs(run.summary["first_liftoff_x"] - 1.18) < 1e-6  # JC_DESIGN_VERIFY_M


SLOW_SWEEP = r"""
import sys, time
import jumpcyl as jc
print("started", flush=True)
t0 = time.monotonic()
try:
    rows = jc.sweep(jc.Setup(), vary={"theta0": "0:1:0.00001"}, threads=1)
    print("finished", len(rows), flush=True)
except KeyboardInterrupt:
    print("interrupted after %.2f s" % (time.monotonic() - t0), flush=True)
    sys.exit(3)
"""


def test_ctrl_c_stops_a_long_sweep():
    p = subprocess.Popen([sys.executable, "-c", SLOW_SWEEP], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    assert p.stdout.readline().strip() == "started"
    time.sleep(1.0)
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 3, (out, err)
    assert out.startswith("interrupted"), (out, err)
    # 100001 cases take many seconds on one thread; the stop came within a block.
    assert time.monotonic() - t0 < 5.0
