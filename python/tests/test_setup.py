"""Setup: built as the tool builds it, round trips through --dump-config, and bad inputs."""
import pytest

import jumpcyl as jc
from conftest import tool


@pytest.mark.parametrize("preset", list(jc.presets()))
def test_dump_config_round_trip(preset):
    s = jc.Setup(preset=preset)
    text = tool("simulate", "--dump-config", *s.cli_args()).stdout
    assert s.to_config() == text
    assert jc.Setup.from_config(text) == s


def test_dump_config_of_given_values():
    s = jc.Setup(preset="paper", incline="30deg", mu=0.5, rod_offset="6cm", theta0=0.1, impact_law="newton",
                 drag_coefficient=0.6)
    text = tool("simulate", "--dump-config", *s.cli_args()).stdout
    assert s.to_config() == text
    assert jc.Setup.from_config(text) == s
    assert s.rod_offset == 0.06 and s.impact_law == "newton" and s.theta0 == 0.1


def test_parts_as_the_tool():
    parts = ["disc:mass=34.2g", "rod:mass=32.1g,offset=5.5cm,radius=4.75mm"]
    s = jc.Setup(parts=parts, radius="10cm")
    text = tool("simulate", "--dump-config", "--radius", "10cm", "--part", parts[0], "--part", parts[1]).stdout
    assert s.to_config() == text
    assert jc.Setup.from_config(text) == s
    same = jc.Setup(parts=[{"kind": "disc", "mass": 0.0342}, {"kind": "rod", "mass": "32.1g", "offset": 0.055,
                                                               "radius": "4.75mm"}], radius=0.1)
    assert same == s


def test_numbers_are_si_and_strings_carry_units():
    assert jc.Setup(incline=30 * jc.deg).incline == jc.Setup(incline="30deg").incline
    assert jc.Setup(rod_offset="5.5cm") == jc.Setup(rod_offset=0.055)
    assert jc.Setup(**{"rod-offset": 0.05}) == jc.Setup(rod_offset=0.05)
    assert jc.Setup(mu=0.4).mu_s == 0.4 and jc.Setup(mu=0.4).mu_k == 0.4


def test_setups_are_values():
    s = jc.Setup(preset="paper", incline="30deg", mu=0.5)
    s2 = s.replace(rod_offset="6cm")
    assert s.rod_offset == 0.055 and s2.rod_offset == 0.06
    assert s2.incline == s.incline and s2.mu_s == 0.5
    assert s.with_(mu_s=0.7).mu_s == 0.7 and s.with_(mu_s=0.7).mu_k == 0.5
    assert s.replace(mu=0.3) == jc.Setup(incline="30deg", mu=0.3)
    assert hash(s) == hash(jc.Setup(incline="30deg", mu=0.5))


def test_params_table():
    table = jc.params()
    names = [p.name for p in table]
    assert "incline" in names and "rod-offset" in names and "impact-law" in names
    inc = next(p for p in table if p.name == "incline")
    assert inc.si_unit == "rad" and inc.unit == "deg" and inc.min == 0.0
    assert abs(inc.default - 30 * jc.deg) < 1e-15
    assert next(p for p in table if p.name == "impact-law").choices[:1] == ("stronge",)


def one_line(e):
    msg = str(e.value)
    assert msg and "\n" not in msg
    return msg


@pytest.mark.parametrize("kwargs,words", [
    ({"incline": 2.0}, "incline"),             # 2 rad: beyond 90 deg
    ({"incline": "95deg"}, "incline"),
    ({"rod_offset": "5 parsecs"}, "parsecs"),
    ({"mu": -1}, "mu"),
    ({"restitution": 1.5}, "restitution"),
    ({"impact_law": "elastic"}, "elastic"),
    ({"preset": "nosuch"}, "nosuch"),
    ({"nosuch": 1}, "nosuch"),
    ({"mu": 0.5, "mu_s": 0.6}, "mu"),
    ({"rod_offset": "20cm"}, "rim"),           # outside the rim
    ({"incline": float("nan")}, "incline"),
])
def test_bad_setups_raise_value_error(kwargs, words):
    with pytest.raises(ValueError) as e:
        jc.Setup(**kwargs)
    assert words in one_line(e)


def test_bad_types_raise_type_error():
    with pytest.raises(TypeError):
        jc.Setup(incline=[30])
    with pytest.raises(TypeError):
        jc.Setup(incline=True)
    with pytest.raises(TypeError):
        jc.simulate(jc.Setup(), nosuch=1)


@pytest.mark.parametrize("kwargs,words", [
    ({"t_max": -1}, "t_max"), ({"sample_dt": "1 parsec"}, "parsec"), ({"max_events": 0}, "max_events"),
    ({"rtol": 0}, "rtol"),
])
def test_bad_options_raise_value_error(kwargs, words):
    with pytest.raises(ValueError) as e:
        jc.simulate(jc.Setup(), **kwargs)
    assert words in one_line(e)


def test_library_message_is_the_tool_message():
    with pytest.raises(ValueError) as e:
        jc.Setup(incline="95deg")
    r = tool("simulate", "--incline", "95deg", check=False)
    assert r.returncode != 0
    assert one_line(e).split(": ", 1)[-1] in r.stderr
