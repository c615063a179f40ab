"""Setup: a value object for a jc_Setup, built as the tool builds one from
its options: a preset (the paper's by default), optional parts, then the
given parameters set together in the table's order (jc_param_values_apply)."""
import configparser
import numbers

from ._lib import ffi, lib, text, err_buf, check
from ._params import param, params, to_si, format_value, quantity_parse, quantity_format, presets

_PART_KINDS = {"disc": lib.JC_PART_DISC, "hoop": lib.JC_PART_HOOP, "rod": lib.JC_PART_ROD,
               "point": lib.JC_PART_POINT}
_PART_KEYS = (("mass", lib.JC_Q_MASS), ("offset", lib.JC_Q_LENGTH), ("radius", lib.JC_Q_LENGTH),
              ("angle", lib.JC_Q_ANGLE))


def _part_from(spec, rim_m):
    """A part as (kind, mass, offset, angle, radius) SI, from a dict
    {"kind": "rod", "mass": "32.1g", "offset": 0.055, ...} or the tool's text
    "rod:mass=32.1g,offset=5.5cm". A disc or hoop without a radius fills the rim."""
    if isinstance(spec, str):
        kind, _, rest = spec.partition(":")
        d = {"kind": kind}
        for item in filter(None, rest.split(",")):
            k, eq, v = item.partition("=")
            if not eq:
                raise ValueError("part '%s': '%s' is not KEY=VALUE" % (spec, item))
            if k in d:
                raise ValueError("part '%s': key '%s' given twice" % (spec, k))
            d[k] = v
        spec = d
    if not isinstance(spec, dict):
        raise TypeError("a part is a dict or a string like 'rod:mass=32.1g,offset=5.5cm', not %r" % (spec,))
    kind = spec.get("kind")
    if kind not in _PART_KINDS:
        raise ValueError("part %r: unknown kind %r (allowed: disc, hoop, rod, point)" % (spec, kind))
    unknown = set(spec) - {"kind", "mass", "offset", "radius", "angle"}
    if unknown:
        raise ValueError("part %r: unknown key %s (allowed: mass, offset, radius, angle)" % (spec, sorted(unknown)[0]))
    if "mass" not in spec:
        raise ValueError("part %r: mass is required" % (spec,))
    vals = {k: quantity_parse(spec[k], q, "part %s" % k) if k in spec else None for k, q in _PART_KEYS}
    radius = vals["radius"]
    if radius is None:
        radius = rim_m if kind in ("disc", "hoop") else 0.0
    return (kind, vals["mass"], vals["offset"] or 0.0, vals["angle"] or 0.0, radius)


class Setup:
    """An experiment's setup, a value: ``Setup(preset="paper", incline="30deg", mu=0.5)``.

    Any parameter of the table (jc.params()) by name, with ``_`` or ``-``;
    numbers are SI (radians for angles: ``30 * jc.deg``), strings may carry
    units ("30deg", "5.5cm", "32.1g") and are read as the tool reads them.
    ``parts``: the body part by part, as dicts or the tool's --part texts.
    The setup is built and checked at once (ValueError with the library's
    message). ``s.replace(rod_offset="6cm")`` (or ``s.with_``) makes another;
    ``s.incline`` reads a value (SI)."""

    __slots__ = ("_preset", "_parts", "_values", "_numbers", "_bytes", "_model_cache")

    def __init__(self, preset=None, parts=None, **values):
        if preset is not None and not isinstance(preset, str):
            raise TypeError("preset is a name (%s)" % ", ".join(presets()))
        self._preset = preset
        self._values = {}
        self._numbers = set()  # ids given as plain numbers (SI), for the hint on angles
        for name, v in values.items():
            p = param(name)
            if p.id in self._values:
                raise ValueError("%s given twice" % p.python_name)
            self._values[p.id] = to_si(p, v)
            if not isinstance(v, str):
                self._numbers.add(p.id)
        self._check_shortcuts()
        base = self._base()
        rim = self._values.get(param("radius").id, base.body.radius_m)
        self._parts = None if parts is None else tuple(_part_from(q, rim) for q in parts)
        if self._parts is not None and not 1 <= len(self._parts) <= lib.JC_MAX_PARTS:
            raise ValueError("parts: %d given (allowed: 1 to %d)" % (len(self._parts), lib.JC_MAX_PARTS))
        self._bytes = self._build(base)

    # ---- building ----

    def _base(self):
        s = ffi.new("jc_Setup *")
        if self._preset is None:
            s[0] = lib.jc_paper_setup()
        else:
            err = err_buf()
            check(lib.jc_preset_setup(self._preset.encode(), s, err, len(err)), err, "preset")
        return s

    def _check_shortcuts(self):
        for pid in self._values:
            p = params()[pid]
            clash = [q for q in p.sets if param(q).id in self._values]
            if clash:
                names = [param(q).python_name for q in p.sets]
                raise ValueError("%s sets %s; give either %s or %s" % (
                    p.python_name, " and ".join(names), p.python_name, "/".join(names)))

    def _param_values(self):
        v = ffi.new("jc_ParamValues *")
        for pid, x in self._values.items():
            v.given[pid] = 1
            v.value[pid] = x
        v.parts_given = self._parts is not None
        return v

    def _build(self, s):
        if self._parts is not None:
            s.body.part_count = len(self._parts)
            for i, (kind, mass, offset, angle, radius) in enumerate(self._parts):
                s.body.parts[i] = (_PART_KINDS[kind], mass, offset, angle, radius)
        failed = ffi.new("int *")
        err = err_buf()
        st = lib.jc_param_values_apply(self._param_values(), s, failed, err, len(err))
        if st != lib.JC_OK and failed[0] >= 0:
            p = params()[failed[0]]
            msg = "%s: %s" % (p.python_name, ffi.string(err).decode())
            if p.quantity == "angle" and p.id in self._numbers:
                msg += " (numbers are SI, radians; for degrees write '%gdeg' or %g * jc.deg)" % (
                    self._values[p.id], self._values[p.id])
            raise ValueError(msg)
        check(st, err, "invalid setup")
        return bytes(ffi.buffer(s))

    def _ptr(self):
        """A fresh jc_Setup * holding this setup."""
        s = ffi.new("jc_Setup *")
        ffi.buffer(s)[:] = self._bytes
        return s

    def _model(self):
        """The setup's jc_Model * (jc_model_init), made once: a model is only
        ever read, so one serves every run and thread."""
        m = getattr(self, "_model_cache", None)
        if m is None:
            m = ffi.new("jc_Model *")
            err = err_buf()
            check(lib.jc_model_init(m, self._ptr(), err, len(err)), err)
            self._model_cache = m
        return m

    def study_base(self):
        """(base jc_Setup *, jc_ParamValues *): the setup before its values, and
        the values, as a study of the library takes them (jc_StudyDef base, fixed)."""
        base = self._base()
        if self._parts is not None:
            base.body.part_count = len(self._parts)
            for i, (kind, mass, offset, angle, radius) in enumerate(self._parts):
                base.body.parts[i] = (_PART_KINDS[kind], mass, offset, angle, radius)
        return base, self._param_values()

    # ---- values ----

    @property
    def preset(self):
        return self._preset

    @property
    def given(self):
        """The parameters given (SI), by Python name."""
        return {params()[pid].python_name: v for pid, v in self._values.items()}

    def get(self, name):
        """A parameter's value in this setup (SI; a choice's name). ValueError
        when the body has no such part (rod_mass of a hoop)."""
        p = param(name)
        v = ffi.new("double *")
        err = err_buf()
        check(lib.jc_param_get(self._ptr(), p.id, v, err, len(err)), err, p.python_name)
        return p.choices[int(v[0])] if p.choices else v[0]

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        if lib.jc_param_find(name.encode()) < 0:
            raise AttributeError("Setup has no parameter '%s' (jc.params() lists them)" % name)
        return self.get(name)

    def to_dict(self):
        """Every parameter the setup has (SI; choices by name), by Python name."""
        out = {}
        for p in params():
            if p.shortcut:
                continue
            try:
                out[p.python_name] = self.get(p.name)
            except ValueError:
                pass
        return out

    @property
    def parts(self):
        """The body's parts as dicts (SI)."""
        s = self._ptr()
        return [{"kind": text(lib.jc_part_kind_name(q.kind)), "mass": q.mass_kg, "offset": q.offset_m,
                 "radius": q.radius_m, "angle": q.angle_rad} for q in s.body.parts[0:s.body.part_count]]

    @property
    def body(self):
        """The body's mass properties (jc_body_compute), SI."""
        b = ffi.new("jc_Body *")
        check(lib.jc_body_compute(ffi.addressof(self._ptr()[0], "body"), b, ffi.NULL, 0), None, "body")
        return {"radius": b.radius_m, "mass": b.mass_kg, "cm_offset": b.cm_offset_m, "cm_angle": b.cm_angle_rad,
                "inertia_c": b.inertia_c_kgm2, "inertia_g": b.inertia_g_kgm2, "disc_mass": b.disc_mass_kg}

    def replace(self, **values):
        """A new setup with these values changed (the rest kept). A shortcut
        (mu) replaces the rows it sets, and a row it sets (mu_s) takes the
        shortcut's value apart first."""
        new = {params()[pid].name: v for pid, v in self._values.items()}
        for name, v in values.items():
            p = param(name)
            for other in list(new):
                q = param(other)
                if p.name in q.sets:  # mu given, mu_s replaced: mu becomes mu_s and mu_k
                    x = new.pop(other)
                    for r in q.sets:
                        new.setdefault(r, x)
                elif q.name in p.sets:
                    new.pop(other)
            new[p.name] = v
        out = Setup.__new__(Setup)
        out._preset = self._preset
        out._values = {}
        out._numbers = set()
        for name, v in new.items():
            p = param(name)
            out._values[p.id] = to_si(p, v)
            if not isinstance(v, str):
                out._numbers.add(p.id)
        out._check_shortcuts()
        out._parts = self._parts
        out._bytes = out._build(out._base())
        return out

    with_ = replace

    def _key(self):
        """The jc_Setup's fields (the parts the body has; no padding bytes), for == and hash."""
        s = self._ptr()[0]
        b = s.body
        parts = tuple((q.kind, q.mass_kg, q.offset_m, q.angle_rad, q.radius_m) for q in b.parts[0:b.part_count])
        return (b.radius_m, parts) + tuple(getattr(s, f) for f in _SCALAR_FIELDS)

    def __eq__(self, other):
        return isinstance(other, Setup) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def __repr__(self):
        items = ["preset=%r" % self._preset] if self._preset else []
        if self._parts is not None:
            items.append("parts=%r" % (self.part_texts(),))
        items += ["%s=%r" % (params()[pid].python_name, format_value(pid, v)) for pid, v in self._values.items()]
        return "Setup(%s)" % ", ".join(items)

    # ---- the tool's forms ----

    def part_texts(self):
        """The parts as the tool's --part texts (reading back exactly)."""
        if self._parts is None:
            return None
        return ["%s:mass=%s,offset=%s,radius=%s,angle=%s" % (
            kind, quantity_format(m, lib.JC_Q_MASS, "g").replace(" ", ""),
            quantity_format(o, lib.JC_Q_LENGTH, "cm").replace(" ", ""),
            quantity_format(r, lib.JC_Q_LENGTH, "cm").replace(" ", ""),
            quantity_format(a, lib.JC_Q_ANGLE, "deg").replace(" ", ""))
            for kind, m, o, a, r in self._parts]

    def cli_args(self):
        """The tool's options for this setup: ['--preset', 'paper', '--incline', '30 deg', ...]."""
        args = ["--preset", self._preset] if self._preset else []
        for t in self.part_texts() or ():
            args += ["--part", t]
        for pid, v in self._values.items():
            args += ["--" + params()[pid].name, format_value(pid, v)]
        return args

    def to_config(self):
        """The setup as an experiment file: the text of the tool's --dump-config."""
        s = self._ptr()
        sections = []
        for p in params():
            if p.section not in sections:
                sections.append(p.section)
        out = ["# jumpcyl experiment file (docs/config.md): units as a person types them (cm, g,\n"
               "# deg); every number reads back to the same double.\n"]

        def section(sec):
            out.append("\n[%s]\n" % sec)
            for names in (False, True):
                for p in params():
                    if p.section == sec and not p.shortcut and bool(p.choices) == names:
                        v = ffi.new("double *")
                        lib.jc_param_get(s, p.id, v, ffi.NULL, 0)
                        out.append("%s = %s\n" % (p.key, format_value(p.id, v[0])))

        section(sections[0])
        for i in range(s.body.part_count):
            q = s.body.parts[i]
            out.append("\n[part.%d]\nkind = %s\nmass = %s\noffset = %s\nradius = %s\nangle = %s\n" % (
                i + 1, text(lib.jc_part_kind_name(q.kind)), quantity_format(q.mass_kg, lib.JC_Q_MASS, "g"),
                quantity_format(q.offset_m, lib.JC_Q_LENGTH, "cm"), quantity_format(q.radius_m, lib.JC_Q_LENGTH, "cm"),
                quantity_format(q.angle_rad, lib.JC_Q_ANGLE, "deg")))
        for sec in sections[1:]:
            section(sec)
        return "".join(out)

    @classmethod
    def from_config(cls, text_or_path):
        """A setup from an experiment file's text (or its path): every key of
        the table's sections and [part.N] sections, as --dump-config writes them."""
        if "\n" not in text_or_path and "[" not in text_or_path:
            with open(text_or_path) as f:
                text_or_path = f.read()
        cp = configparser.ConfigParser(inline_comment_prefixes=None, comment_prefixes=("#", ";"),
                                       interpolation=None)
        cp.optionxform = str
        cp.read_string(text_or_path)
        keys = {(p.section, p.key): p for p in params()}
        values, parts = {}, []
        for sec in cp.sections():
            if sec.startswith("part."):
                parts.append((int(sec[5:]), dict(cp[sec])))
                continue
            for k, v in cp[sec].items():
                p = keys.get((sec, k))
                if p is None:
                    raise ValueError("[%s] %s: not a key of an experiment file" % (sec, k))
                values[p.name] = v
        parts = [d for _, d in sorted(parts, key=lambda x: x[0])] or None
        return cls(parts=parts, **values)


_SCALAR_FIELDS = tuple(f for f, _ in ffi.typeof("jc_Setup").fields if f != "body")


def as_setup(s):
    if isinstance(s, Setup):
        return s
    if s is None:
        return Setup()
    if isinstance(s, dict):
        return Setup(**s)
    raise TypeError("expected a jumpcyl.Setup, not %s" % type(s).__name__)
