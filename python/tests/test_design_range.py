"""design without a range: the library's default range
(jc_design_default_range), the one the tool searches, and so the tool's
solutions; the rows design refuses (jc_design_free_check)."""
import json

import pytest

import jumpcyl as jc
from conftest import tool, assert_same


def tool_design(tmp_path, setup, jump_at, free):
    """design --json FILE parsed as tool_json parses (every number a float,
    the same double the tool computed)."""
    out = tmp_path / "design.json"
    tool("design", "--jump-at", jump_at, "--free", free, "--json", str(out), *setup.cli_args())
    return json.loads(out.read_text(), parse_int=float)


@pytest.mark.parametrize("free, jump_at", [("rod_offset", "1.2m"), ("mu_k", "1.3m")])
def test_default_range_and_solutions_are_the_tools(tmp_path, free, jump_at):
    s = jc.Setup(preset="paper")
    d = jc.design(s, jump_at=jump_at, free=free)
    ref = tool_design(tmp_path, s, jump_at, free.replace("_", "-"))
    # Bit for bit: the tool's JSON numbers read back to its doubles.
    assert d["free"]["name"] == ref["free"]["name"]
    assert_same(d["free"]["lo"], ref["free"]["lo"], "free.lo")
    assert_same(d["free"]["hi"], ref["free"]["hi"], "free.hi")
    assert d["solutions"] and len(d["solutions"]) == len(ref["solutions"]), (d["solutions"], ref["solutions"])
    for k, (mine, theirs) in enumerate(zip(d["solutions"], ref["solutions"])):
        assert_same(mine["value"], theirs["value"], "solutions[%d].value" % k)
        assert_same(mine["x_m"], theirs["x_m"], "solutions[%d].x_m" % k)
        assert mine["branch"] == theirs["branch"]


def test_default_ranges_from_the_body():
    s = jc.Setup(preset="paper")
    r, rod_r = s.get("radius"), s.get("rod_radius")
    d = jc.design(s, jump_at="1.2m", free="rod_offset", points=10)
    # 1 % of r to the rim less the rod's radius: 0.1 cm to 9.525 cm.
    assert d["free"]["lo"] == 0.01 * r and d["free"]["hi"] == r - rod_r
    # mu-k's typical span cut to valid setups: up to mu-s, to 1e-9 of the span.
    d = jc.design(s, jump_at="1.3m", free="mu_k", points=10)
    info = next(p for p in jc.params() if p.name == "mu-k")
    span = info.typical_max - info.typical_min
    assert d["free"]["lo"] == info.typical_min and s.mu_s - 1e-9 * span <= d["free"]["hi"] <= s.mu_s


@pytest.mark.parametrize("free, setup", [("restitution", {}), ("impact_law", {}), ("paper_d", {}),
                                         ("rod_offset", {"preset": "hoop"})])
def test_refused_rows(free, setup):
    with pytest.raises(ValueError, match="free: "):
        jc.design(jc.Setup(**setup), jump_at="1m", free=free, range=("0.1", "0.2"))


@pytest.mark.parametrize("given, free", [({"rod_offset": "3cm"}, "rod_offset"), ({"mu": 0.5}, "mu_s"),
                                         ({"mu_k": 0.4}, "mu")])
def test_a_given_value_of_the_free_row_is_refused(given, free):
    # The tool refuses the same (design: --rod-offset and --free rod-offset both given).
    with pytest.raises(ValueError, match="give one"):
        jc.design(jc.Setup(preset="paper", **given), jump_at="1.2m", free=free, points=10)
