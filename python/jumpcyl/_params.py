"""The library's parameter table (jc_param_*): names, units, ranges,
defaults, and values read as the tool reads them."""
import dataclasses
import math
import numbers

from ._lib import ffi, lib, text, err_buf, check

#: One degree in radians: ``30 * jc.deg``. Numbers given to jumpcyl are SI
#: (radians for angles); strings may carry units ("30deg", "5.5cm").
deg = math.pi / 180.0


@dataclasses.dataclass(frozen=True)
class Param:
    """One row of the library's parameter table (jc_ParamInfo)."""
    id: int
    name: str
    label: str
    help: str
    quantity: str
    si_unit: str
    unit: str
    min: float
    max: float
    min_open: bool
    max_open: bool
    bound: str
    choices: tuple
    sets: tuple
    body: bool
    shortcut: bool
    section: str
    key: str
    json_key: str
    typical_min: float
    typical_max: float
    default: object  # the paper preset's value (SI, or a name), None where the body has no such part
    defaults: dict   # every preset's value

    @property
    def python_name(self):
        return self.name.replace("-", "_")


_TABLE = None
_PRESETS = None


def presets():
    """The built-in setups' names and descriptions: {name: description}."""
    global _PRESETS
    if _PRESETS is None:
        out, i = {}, 0
        while True:
            n = lib.jc_preset_name(i)
            if n == ffi.NULL:
                break
            out[text(n)] = text(lib.jc_preset_description(i))
            i += 1
        _PRESETS = out
    return dict(_PRESETS)


def _value_of(setup_ptr, pid, choices):
    v = ffi.new("double *")
    if lib.jc_param_get(setup_ptr, pid, v, ffi.NULL, 0) != lib.JC_OK:
        return None
    return choices[int(v[0])] if choices else v[0]


def _build_table():
    rows = []
    preset_setups = {}
    for name in presets():
        s = ffi.new("jc_Setup *")
        check(lib.jc_preset_setup(name.encode(), s, ffi.NULL, 0), None, "preset")
        preset_setups[name] = s
    for pid in range(lib.jc_param_count()):
        p = lib.jc_param_info(pid)
        choices = ()
        if p.choices != ffi.NULL:
            k = 0
            while p.choices[k] != ffi.NULL:
                choices += (text(p.choices[k]),)
                k += 1
        defaults = {n: _value_of(s, pid, choices) for n, s in preset_setups.items()}
        rows.append(Param(
            id=pid, name=text(p.name), label=text(p.label), help=text(p.help),
            quantity=text(lib.jc_quantity_name(p.quantity)), si_unit=text(p.si_unit), unit=text(p.unit),
            min=p.min, max=p.max, min_open=bool(p.min_open), max_open=bool(p.max_open), bound=text(p.bound),
            choices=choices, sets=tuple(text(p.sets).split()) if p.sets != ffi.NULL else (),
            body=bool(p.flags & lib.JC_PARAM_BODY), shortcut=bool(p.flags & lib.JC_PARAM_SHORTCUT),
            section=text(p.section), key=text(p.key), json_key=text(p.json_key),
            typical_min=p.typical_min, typical_max=p.typical_max,
            default=defaults.get("paper"), defaults=defaults))
    return tuple(rows)


def params():
    """The parameter table: a list of Param (name, unit, range, default, help, ...),
    in the library's order. Names are the tool's (rod-offset); Python accepts
    rod_offset too."""
    global _TABLE
    if _TABLE is None:
        _TABLE = _build_table()
    return list(_TABLE)


def _names():
    return ", ".join(p.name for p in params())


def param(name):
    """The table's row for a name ("rod_offset" or "rod-offset"); ValueError if none."""
    if not isinstance(name, str):
        raise TypeError("a parameter name is a str, not %s" % type(name).__name__)
    pid = lib.jc_param_find(name.encode())
    if pid < 0:
        raise ValueError("'%s' is not a setup parameter (allowed: %s)" % (name, _names()))
    return params()[pid]


def to_si(p, value):
    """A value for parameter p as the library holds it: a number is SI (radians
    for angles), a string is read as the tool reads it (jc_param_parse: "30deg",
    "5.5cm"; a plain number in a string is degrees for an angle, as on the
    command line), a choice by its name. Ranges are checked when the setup is
    built."""
    if isinstance(value, str):
        out = ffi.new("double *")
        err = err_buf()
        check(lib.jc_param_parse(p.id, value.encode(), out, err, len(err)), err, p.name.replace("-", "_"))
        return out[0]
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError("%s: expected a number (SI) or a string with units, not %r" % (p.python_name, value))
    if p.choices:
        if float(value) != int(value) or not 0 <= int(value) < len(p.choices):
            raise ValueError("%s: %r is not one of %s" % (p.python_name, value, ", ".join(p.choices)))
    return float(value)


def format_value(pid, v):
    """v (SI) as text that the library reads back to exactly v (jc_param_format)."""
    buf = ffi.new("char[]", 96)
    check(lib.jc_param_format(pid, v, buf, len(buf)), None, "format")
    return ffi.string(buf).decode()


def quantity_parse(value, quantity, what):
    """A number (SI) or a string with units of a quantity (JC_Q_*), as SI."""
    if isinstance(value, str):
        out = ffi.new("double *")
        err = err_buf()
        check(lib.jc_quantity_parse(value.encode(), quantity, out, err, len(err)), err, what)
        return out[0]
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError("%s: expected a number (SI) or a string with units, not %r" % (what, value))
    return float(value)


def quantity_format(v, quantity, unit):
    buf = ffi.new("char[]", 96)
    check(lib.jc_quantity_format(v, quantity, unit.encode(), buf, len(buf)), None, "format")
    return ffi.string(buf).decode()
