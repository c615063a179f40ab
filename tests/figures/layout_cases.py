"""The figures the layout check covers (tests/figures/test_layout.py): a name,
the arguments of `jumpcyl` that draw it as SVG (the output is added), and the
rules it is allowed to break, each with its reason (layout_check.py --allow).

To check another figure, add a line here; `test_layout.py JUMPCYL --only NAME`
checks one, `--keep DIR` keeps the SVGs. Every figure of `make run` is
here (overview-15/30/45, trajectory-15/30/45/hoop), every kind of `plot
--what` for every preset, and two maps.
"""

# paper-uncertainty's axis is the jump site along the incline: the band, the
# printed site and the measurement with its error bar are close together on
# some inclines and far apart on others; the axis spans all three with room.
_PU = ["span:*:x"]

CASES = [
    ("overview-15", ["plot", "--incline", "15", "--what", "overview"], []),
    ("overview-30", ["plot", "--incline", "30", "--what", "overview"], []),
    ("overview-45", ["plot", "--incline", "45", "--what", "overview"], []),
    # No lift-off, one event (the ramp's end): nothing zoomed, no inset.
    ("overview-5", ["plot", "--incline", "5", "--what", "overview"], []),
]
for _kind in ("paper-criterion", "forces", "gap", "energy"):
    for _a in ("15", "30", "45"):
        CASES.append(("%s-%s" % (_kind, _a), ["plot", "--incline", _a, "--what", _kind], []))
    CASES.append(("%s-hoop" % _kind, ["plot", "--preset", "hoop", "--what", _kind], []))
CASES.append(("paper-uncertainty", ["plot", "--what", "paper-uncertainty"], _PU))
# The other presets: a hoop rocking on a floor for the whole time limit
# without lifting off (shown until its losses settle), and a plain disc
# (d = 0: two flat force curves, no paper's threshold).
for _preset in ("rocking-hoop", "disc"):
    for _kind in ("overview", "paper-criterion", "forces", "gap", "energy"):
        CASES.append(("%s-%s" % (_kind, _preset), ["plot", "--preset", _preset, "--what", _kind], []))

# Regime maps (plot_map.c), on small grids: the paper's cylinder over incline
# and rod offset, and over incline and friction (cells that slide at once).
CASES += [
    ("map-incline-rod-offset", ["map", "--x", "incline=5:60:5", "--y", "rod-offset=1cm:9cm:1cm", "--quiet"], []),
    ("map-incline-mu", ["map", "--x", "incline=5:60:5", "--y", "mu=0.1:0.8:0.1", "--quiet"], []),
]

# The trajectory figures (plot_trajectory.c).
TRAJECTORY = [
    ("trajectory-15", ["plot", "--incline", "15", "--what", "trajectory"], []),
    ("trajectory-30", ["plot", "--incline", "30", "--what", "trajectory"], []),
    ("trajectory-45", ["plot", "--incline", "45", "--what", "trajectory"], []),
    ("trajectory-hoop", ["plot", "--preset", "hoop", "--what", "trajectory"], []),
]
# The other presets: a rocking hoop that never lifts off, a plain disc.
for _preset in ("rocking-hoop", "disc"):
    TRAJECTORY.append(("trajectory-%s" % _preset, ["plot", "--preset", _preset, "--what", "trajectory"], []))
CASES += TRAJECTORY
