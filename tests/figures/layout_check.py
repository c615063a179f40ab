#!/usr/bin/env python3
"""The layout check of a figure: gnuplot's SVG read back, every text's box
estimated, and the figure refused when

  - a text box overlaps another text box;
  - a text box overlaps a data curve or a point of a plot (a heat map's
    cells, opaque rectangles of a plot, are data for the span only: labels
    on a map are meant to sit on its cells);
  - a text box, a curve or a point leaves the canvas (is clipped);
  - a panel's data span less than a fraction (60 %) of an axis' range (a
    vertical axis that starts at zero, a tic "0" at its bottom: from there
    to the highest data).

What gnuplot's SVG terminal (5.4) writes, and how it is read here:

  - each plot of a `plot` command is a group <g id="gnuplot_plot_N">, with a
    letter after N for the panels of a multiplot (1a, 2a, 1b, ...) and its key
    title as <title>; a plot without a key entry is titled "gnuplot_plot_N".
    The key entry (its text and its sample line or point) is inside the group:
    its text is the group's first text, its sample what lies beside that text;
  - everything else (grid lines: class "gridline"; tics, borders, labels,
    arrows, objects) is outside those groups. A panel's border is a path of
    axis-parallel segments through the plot area's corners;
  - a text is <g transform="translate(x,y) [rotate(a)]" font-size text-anchor>
    around <text><tspan>...; boxed labels (`with labels boxed`) come twice,
    once with a filter, at the same place.

Text widths come from DejaVu Sans' advance widths (the font 'Sans' is on
Debian), per character and per tspan font size; heights from its metrics:
capitals and digits reach 0.73 em above the baseline, descenders 0.24 em
below. A box is shrunk by TOLERANCE_PX on every side before it is compared,
so touching is not overlapping.

Usage: layout_check.py [--name NAME] [--allow RULE]... FILE.svg
       RULE: "span:PANEL:x" or "span:PANEL:y" (PANEL: the panel's title, or
       its start; * for every panel) lets that axis be wider than its data;
       "overlap:TEXT" lets a text (its start) overlap curves (reason in the
       case list). Exit status 1 and one line per failure when the figure
       fails.
"""
import math
import re
import sys
import xml.etree.ElementTree as ET

SVG = "{http://www.w3.org/2000/svg}"
XLINK = "{http://www.w3.org/1999/xlink}"
TOLERANCE_PX = 1.0
SPAN_MIN = 0.6

# DejaVu Sans advance widths (em), from its hmtx table; others: DEFAULT_EM.
_WIDTHS = {
    " ": 0.318, "!": 0.401, '"': 0.46, "#": 0.838, "$": 0.636, "%": 0.95, "&": 0.78, "'": 0.275,
    "(": 0.39, ")": 0.39, "*": 0.5, "+": 0.838, ",": 0.318, "-": 0.361, ".": 0.318, "/": 0.337,
    ":": 0.337, ";": 0.337, "<": 0.838, "=": 0.838, ">": 0.838, "?": 0.531, "@": 1.0,
    "A": 0.684, "B": 0.686, "C": 0.698, "D": 0.77, "E": 0.632, "F": 0.575, "G": 0.775, "H": 0.752,
    "I": 0.295, "J": 0.295, "K": 0.656, "L": 0.557, "M": 0.863, "N": 0.748, "O": 0.787, "P": 0.603,
    "Q": 0.787, "R": 0.695, "S": 0.635, "T": 0.611, "U": 0.732, "V": 0.684, "W": 0.989, "X": 0.685,
    "Y": 0.611, "Z": 0.685, "[": 0.39, "\\": 0.337, "]": 0.39, "^": 0.838, "_": 0.5, "`": 0.5,
    "a": 0.613, "b": 0.635, "c": 0.55, "d": 0.635, "e": 0.615, "f": 0.352, "g": 0.635, "h": 0.634,
    "i": 0.278, "j": 0.278, "k": 0.579, "l": 0.278, "m": 0.974, "n": 0.634, "o": 0.612, "p": 0.635,
    "q": 0.635, "r": 0.411, "s": 0.521, "t": 0.392, "u": 0.634, "v": 0.592, "w": 0.818, "x": 0.592,
    "y": 0.592, "z": 0.525, "{": 0.636, "|": 0.337, "}": 0.636, "~": 0.838,
    "°": 0.5, "²": 0.401, "³": 0.401, "·": 0.318, "×": 0.838, "–": 0.5, "—": 1.0, "−": 0.838,
    "…": 1.0, "≤": 0.838, "≥": 0.838, "±": 0.838, "µ": 0.636, "μ": 0.636, "θ": 0.612, "α": 0.659,
    "β": 0.638, "γ": 0.592, "δ": 0.612, "ε": 0.541, "ω": 0.837, "π": 0.602, "σ": 0.634, "Δ": 0.684,
    "Θ": 0.787, "Ω": 0.764, "′": 0.227, "″": 0.374, "’": 0.318, "‘": 0.318, "“": 0.518, "”": 0.518,
    "→": 0.838, "←": 0.838, "√": 0.637, "∞": 0.833, "≈": 0.838, "≠": 0.838, "½": 0.969,
}
for _d in "0123456789":
    _WIDTHS[_d] = 0.636
DEFAULT_EM = 0.65
TALL = set("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789bdfhklt()[]{}|/\\!?'\"%&#$@°²³θδβΘΩΔ")
LOW = set("gjpqy(),;[]{}|μµβγ")


def text_width(s, size):
    return sum(_WIDTHS.get(c, DEFAULT_EM) for c in s) * size


class Box:
    __slots__ = ("x0", "y0", "x1", "y1")

    def __init__(self, x0, y0, x1, y1):
        self.x0, self.y0, self.x1, self.y1 = min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1)

    def union(self, o):
        return Box(min(self.x0, o.x0), min(self.y0, o.y0), max(self.x1, o.x1), max(self.y1, o.y1))

    def shrunk(self, d):
        return Box(self.x0 + d, self.y0 + d, max(self.x0 + d, self.x1 - d), max(self.y0 + d, self.y1 - d))

    def overlaps(self, o):
        return self.x0 < o.x1 and o.x0 < self.x1 and self.y0 < o.y1 and o.y0 < self.y1

    def contains(self, x, y, slack=0.0):
        return self.x0 - slack <= x <= self.x1 + slack and self.y0 - slack <= y <= self.y1 + slack

    def __str__(self):
        return "[x %.0f–%.0f, y %.0f–%.0f]" % (self.x0, self.x1, self.y0, self.y1)


class Text:
    def __init__(self, string, box, group, order, key=False):
        self.string, self.box, self.group, self.order, self.key = string, box, group, order, key

    def __str__(self):
        return '"%s" %s' % (self.string, self.box)


class Curve:
    """One subpath (a polyline) or one point marker of a plot."""

    def __init__(self, points, group, title, order, marker_r=0.0):
        self.points, self.group, self.title, self.order, self.marker_r = points, group, title, order, marker_r
        xs = [p[0] for p in points]
        ys = [p[1] for p in points]
        self.box = Box(min(xs) - marker_r, min(ys) - marker_r, max(xs) + marker_r, max(ys) + marker_r)


class Figure:
    def __init__(self):
        self.width = self.height = 0.0
        self.texts, self.curves, self.borders, self.occluders = [], [], [], []
        self.cells = []  # a heat map's cells (opaque rectangles of a plot): data for the span only


_NUM = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _transform(s):
    """translate(x,y), rotate(a), scale(k) of a gnuplot transform."""
    tx = ty = rot = 0.0
    scale = 1.0
    for name, args in re.findall(r"(\w+)\s*\(([^)]*)\)", s or ""):
        v = [float(a) for a in _NUM.findall(args)]
        if name == "translate":
            tx, ty = v[0], v[1] if len(v) > 1 else 0.0
        elif name == "rotate":
            rot = v[0]
        elif name == "scale":
            scale = v[0]
    return tx, ty, rot, scale


def _subpaths(d):
    """The polylines of a path's d (gnuplot writes M, L, h, v, z)."""
    out, cur = [], []
    tokens = re.findall(r"[MLHVZmlhvz]|" + _NUM.pattern, d)
    cmd, i, x, y = None, 0, 0.0, 0.0
    while i < len(tokens):
        t = tokens[i]
        if t.isalpha():
            cmd = t
            i += 1
            if cmd in "Zz":
                if cur:
                    cur.append(cur[0])
                continue
            continue
        if cmd in ("M", "m"):
            if len(cur) > 0:
                out.append(cur)
            nx, ny = float(tokens[i]), float(tokens[i + 1])
            x, y = (x + nx, y + ny) if cmd == "m" else (nx, ny)
            cur = [(x, y)]
            cmd = "L" if cmd == "M" else "l"
            i += 2
        elif cmd in ("L", "l"):
            nx, ny = float(tokens[i]), float(tokens[i + 1])
            x, y = (x + nx, y + ny) if cmd == "l" else (nx, ny)
            cur.append((x, y))
            i += 2
        elif cmd in ("H", "h"):
            x = x + float(tokens[i]) if cmd == "h" else float(tokens[i])
            cur.append((x, y))
            i += 1
        elif cmd in ("V", "v"):
            y = y + float(tokens[i]) if cmd == "v" else float(tokens[i])
            cur.append((x, y))
            i += 1
        else:
            i += 1
    if cur:
        out.append(cur)
    return out


def _text_box(g, tx, ty, rot):
    """The box of the text in g (anchor, size, tspans with their sizes and
    baseline shifts), rotated about (tx, ty); None if the text is empty."""
    size = float(g.get("font-size", "12"))
    anchor = g.get("text-anchor", "start")
    parts = []  # (string, size, baseline offset)
    shift = 0.0
    text = g.find(SVG + "text")
    if text is None:
        return None, ""
    if text.text and text.text.strip():
        parts.append((text.text, size, 0.0))
    for ts in text.iter(SVG + "tspan"):
        fs = float(ts.get("font-size", size))
        dy = ts.get("dy")
        if dy:
            shift += float(_NUM.findall(dy)[0])
        if ts.text:
            parts.append((ts.text, fs, shift))
    string = "".join(p[0] for p in parts)
    if not string.strip():
        return None, string
    width = sum(text_width(s, fs) for s, fs, _ in parts)
    x = {"start": 0.0, "middle": -width / 2, "end": -width}.get(anchor, 0.0)
    top, bottom = 0.0, 0.0
    for s, fs, dy in parts:
        up = 0.73 if any(c in TALL for c in s) else 0.53
        down = 0.24 if any(c in LOW for c in s) else 0.0
        top = min(top, dy - up * fs)
        bottom = max(bottom, dy + down * fs)
    corners = [(x, top), (x + width, top), (x + width, bottom), (x, bottom)]
    a = math.radians(rot)
    c, s_ = math.cos(a), math.sin(a)
    pts = [(tx + px * c - py * s_, ty + px * s_ + py * c) for px, py in corners]
    return Box(min(p[0] for p in pts), min(p[1] for p in pts), max(p[0] for p in pts), max(p[1] for p in pts)), string


def _opaque(fill, opacity):
    return fill not in (None, "none", "currentColor") and (opacity is None or float(opacity) >= 0.99)


def parse(path):
    """The figure's texts, curves, borders and opaque areas, in drawing order."""
    fig = Figure()
    root = ET.parse(path).getroot()
    vb = [float(v) for v in _NUM.findall(root.get("viewBox", "0 0 0 0"))]
    fig.width, fig.height = vb[2], vb[3]
    seen = set()
    order = [0]

    def walk(el, group, title):
        tag = el.tag.replace(SVG, "")
        order[0] += 1
        if tag == "g" and (el.get("id") or "").startswith("gnuplot_plot_"):
            group = el.get("id")[len("gnuplot_plot_"):]
            t = el.find(SVG + "title")
            title = t.text if t is not None and t.text and not t.text.startswith("gnuplot_plot_") else None
        if tag == "g" and el.find(SVG + "text") is not None:
            tx, ty, rot, _ = _transform(el.get("transform"))
            box, string = _text_box(el, tx, ty, rot)
            key = (string, el.get("transform"))
            if box is not None and key not in seen:
                seen.add(key)
                fig.texts.append(Text(string, box, group, order[0], key=bool(title) and string == title))
            return
        if tag == "path" and el.get("d") and el.get("id") is None:
            subs = _subpaths(el.get("d"))
            if group is not None:
                for sp in subs:
                    fig.curves.append(Curve(sp, group, title, order[0]))
            elif el.get("class") != "gridline":
                for sp in subs:
                    _maybe_border(fig, sp)
        elif tag == "polygon" and group is not None and _opaque(el.get("fill"), el.get("fill-opacity")):
            pts = [float(v) for v in _NUM.findall(el.get("points", ""))]
            corners = list(zip(pts[0::2], pts[1::2]))
            if corners and len(set(round(x, 1) for x, _ in corners)) == 2 and len(set(round(y, 1) for _, y in corners)) == 2:
                fig.cells.append(Curve(corners, group, title, order[0]))
        elif tag == "polygon" and group is None and _opaque(el.get("fill"), el.get("fill-opacity")):
            pts = [float(v) for v in _NUM.findall(el.get("points", ""))]
            xs, ys = pts[0::2], pts[1::2]
            if xs:
                fig.occluders.append((order[0], Box(min(xs), min(ys), max(xs), max(ys))))
        elif tag == "rect" and group is None and el.get("id") is None and _opaque(el.get("fill"), el.get("fill-opacity")):
            x, y = float(el.get("x", 0)), float(el.get("y", 0))
            w, h = float(el.get("width", 0)), float(el.get("height", 0))
            if not (x == 0 and y == 0 and w >= fig.width and h >= fig.height):  # the background
                fig.occluders.append((order[0], Box(x, y, x + w, y + h)))
        elif tag == "use" and group is not None:
            tx, ty, _, scale = _transform(el.get("transform"))
            fig.curves.append(Curve([(tx, ty)], group, title, order[0], marker_r=scale))
        for child in el:
            walk(child, group, title)

    walk(root, None, None)
    return fig


def _maybe_border(fig, sp):
    """A panel's border: axis-parallel segments through a rectangle's corners."""
    if len(sp) < 3:
        return
    xs = sorted(set(round(p[0], 1) for p in sp))
    ys = sorted(set(round(p[1], 1) for p in sp))
    if len(xs) == 2 and len(ys) == 2 and xs[1] - xs[0] > 40 and ys[1] - ys[0] > 40:
        b = Box(xs[0], ys[0], xs[1], ys[1])
        if not any(abs(o.x0 - b.x0) < 0.5 and abs(o.y0 - b.y0) < 0.5 and abs(o.x1 - b.x1) < 0.5 and abs(o.y1 - b.y1) < 0.5
                   for o in fig.borders):
            fig.borders.append(b)


def _hidden(fig, order, box):
    """Whether an opaque area drawn later covers the box (an inset's background)."""
    return any(o > order and ob.x0 <= box.x0 and ob.y0 <= box.y0 and ob.x1 >= box.x1 and ob.y1 >= box.y1
               for o, ob in fig.occluders)


def _key_samples(fig, curves):
    """The key entries' samples: what a titled plot draws beside its key
    text (indices into curves)."""
    keys = {t.group: t for t in fig.texts if t.key}
    samples = set()
    for i, c in enumerate(curves):
        t = keys.get(c.group)
        if t is None:
            continue
        h = t.box.y1 - t.box.y0
        zone = Box(t.box.x0 - 5 * h, t.box.y0 - 0.5 * h, t.box.x1 + 5 * h, t.box.y1 + 0.5 * h)
        if zone.contains(c.box.x0, c.box.y0) and zone.contains(c.box.x1, c.box.y1) and not t.box.overlaps(c.box):
            samples.add(i)
    return samples


def _segment_hits_box(p, q, b):
    """Liang-Barsky: where the segment pq enters the box b, or None."""
    t0, t1 = 0.0, 1.0
    dx, dy = q[0] - p[0], q[1] - p[1]
    for pp, qq in ((-dx, p[0] - b.x0), (dx, b.x1 - p[0]), (-dy, p[1] - b.y0), (dy, b.y1 - p[1])):
        if pp == 0:
            if qq < 0:
                return None
        else:
            r = qq / pp
            if pp < 0:
                t0 = max(t0, r)
            else:
                t1 = min(t1, r)
            if t0 > t1:
                return None
    return (p[0] + t0 * dx, p[1] + t0 * dy)


def _curve_hit(c, b):
    """A point of the curve c inside box b (or where it crosses b), else None."""
    if not c.box.overlaps(b):
        return None
    if c.marker_r > 0:
        return c.points[0]
    pts = c.points
    if len(pts) == 1:
        return pts[0] if b.contains(*pts[0]) else None
    for p, q in zip(pts, pts[1:]):
        if min(p[0], q[0]) > b.x1 or max(p[0], q[0]) < b.x0 or min(p[1], q[1]) > b.y1 or max(p[1], q[1]) < b.y0:
            continue
        hit = _segment_hits_box(p, q, b)
        if hit:
            return hit
    return None


def _panel_title(fig, b):
    """The text centred above the border b: the panel's title (the nearest)."""
    best = None
    for t in fig.texts:
        cx = (t.box.x0 + t.box.x1) / 2
        if b.x0 <= cx <= b.x1 and t.box.y1 <= b.y0 + 1 and b.y0 - t.box.y1 < 120 and not t.key:
            if abs(cx - (b.x0 + b.x1) / 2) < 0.1 * (b.x1 - b.x0) and t.box.x1 - t.box.x0 > 0.2 * (b.x1 - b.x0) * 0.3:
                if best is None or t.box.y1 > best.box.y1:
                    best = t
    return best.string if best else "panel at %s" % b


def _allowed(allow, kind, what, axis=None):
    for rule in allow:
        parts = rule.split(":")
        if parts[0] != kind:
            continue
        if kind == "span" and len(parts) == 3 and parts[2] == axis and (parts[1] == "*" or what.startswith(parts[1])):
            return True
        if kind == "overlap" and len(parts) >= 2 and what.startswith(":".join(parts[1:])):
            return True
    return False


def check(path, name=None, allow=()):
    """The failures of the figure at path, one line each."""
    name = name or path
    fig = parse(path)
    out = []
    canvas = Box(0, 0, fig.width, fig.height)
    samples = _key_samples(fig, fig.curves)
    cell_samples = _key_samples(fig, fig.cells)
    cells = [c for i, c in enumerate(fig.cells) if i not in cell_samples]
    texts = [t for t in fig.texts if not _hidden(fig, t.order, t.box)]
    curves = [c for i, c in enumerate(fig.curves) if i not in samples]
    # Text against text.
    for i, a in enumerate(texts):
        ba = a.box.shrunk(TOLERANCE_PX)
        for b in texts[i + 1:]:
            if ba.overlaps(b.box.shrunk(TOLERANCE_PX)):
                out.append("%s: text %s overlaps text %s" % (name, a, b))
    # Text against curves and points (not a curve's own key sample).
    for t in texts:
        if _allowed(allow, "overlap", t.string):
            continue
        bt = t.box.shrunk(TOLERANCE_PX)
        reported = set()
        for c in curves:
            if (c.group, c.marker_r > 0) in reported:
                continue
            hit = _curve_hit(c, bt)
            if hit and not _hidden(fig, c.order, Box(hit[0], hit[1], hit[0], hit[1])):
                reported.add((c.group, c.marker_r > 0))
                what = "point" if c.marker_r > 0 else "curve"
                out.append('%s: text %s overlaps the %s "%s" at (%.0f, %.0f)'
                           % (name, t, what, c.title or "plot " + c.group, hit[0], hit[1]))
    # The canvas' edges.
    for t in texts:
        if not (canvas.contains(t.box.x0, t.box.y0, TOLERANCE_PX) and canvas.contains(t.box.x1, t.box.y1, TOLERANCE_PX)):
            out.append("%s: text %s is clipped by the canvas (%.0fx%.0f)" % (name, t, fig.width, fig.height))
    for c in curves:
        if not (canvas.contains(c.box.x0, c.box.y0, TOLERANCE_PX) and canvas.contains(c.box.x1, c.box.y1, TOLERANCE_PX)):
            out.append('%s: the %s "%s" %s is clipped by the canvas (%.0fx%.0f)'
                       % (name, "point" if c.marker_r else "curve", c.title or "plot " + c.group, c.box,
                          fig.width, fig.height))
    out.extend(_spans(fig, curves + cells, name, allow))
    return out


def _spans(fig, curves, name, allow):
    """Each panel's data (curves of 3 points or more, and points) against its
    plot area: a span under SPAN_MIN of an axis fails."""
    out = []
    panels = {}
    for c in curves:
        panels.setdefault(re.sub(r"^\d+", "", c.group), []).append(c)
    for _, cs in sorted(panels.items()):
        border = _border_of(fig, [p for c in cs for p in c.points])
        if border is None:
            continue
        data = [c for c in cs if not _reference_line(c, border)]
        pts = [p for c in data for p in c.points]
        inside = [p for p in pts if border.contains(p[0], p[1], 1.0)]
        if not inside:
            continue
        title = _panel_title(fig, border)
        y_hi = border.y1 if _zero_at_bottom(fig, border) else max(p[1] for p in inside)
        for axis, lo, hi, a0, a1 in (("x", min(p[0] for p in inside), max(p[0] for p in inside), border.x0, border.x1),
                                     ("y", min(p[1] for p in inside), y_hi, border.y0, border.y1)):
            span = (hi - lo) / (a1 - a0)
            if span < SPAN_MIN and not _allowed(allow, "span", title, axis):
                out.append('%s: panel "%s": the data span %.0f %% of the %s axis (data %.0f–%.0f px, axis %.0f–%.0f px)'
                           % (name, title, 100 * span, axis, lo, hi, a0, a1))
    return out


def _zero_at_bottom(fig, b):
    """Whether a vertical axis of the panel starts at zero: a tic label "0"
    beside the border's bottom, left or right. Such an axis (a force, a
    gap, a speed) is read against zero, so its data span from there."""
    for t in fig.texts:
        if t.string.strip() not in ("0", "0.0", "0.00"):
            continue
        cy = (t.box.y0 + t.box.y1) / 2
        beside = (b.x0 - 80 < t.box.x1 <= b.x0 + 2) or (b.x1 - 2 <= t.box.x0 < b.x1 + 80)
        if beside and abs(cy - b.y1) < 0.5 * (t.box.y1 - t.box.y0) + 2:
            return True
    return False


def _reference_line(c, b):
    """A straight line across the whole plot area (an event's line): not data."""
    if c.marker_r > 0 or len(c.points) != 2:
        return False
    (x0, y0), (x1, y1) = c.points
    return (abs(x0 - x1) < 0.5 and abs(y1 - y0) >= 0.9 * (b.y1 - b.y0)) or \
        (abs(y0 - y1) < 0.5 and abs(x1 - x0) >= 0.9 * (b.x1 - b.x0))


def _border_of(fig, pts):
    """The smallest border holding most of the points."""
    best = None
    for b in fig.borders:
        n = sum(1 for p in pts if b.contains(p[0], p[1], 1.0))
        if n >= 0.9 * len(pts) and (best is None or (b.x1 - b.x0) * (b.y1 - b.y0) < (best.x1 - best.x0) * (best.y1 - best.y0)):
            best = b
    return best


def main(argv):
    name, allow, files = None, [], []
    i = 0
    while i < len(argv):
        if argv[i] == "--name":
            name, i = argv[i + 1], i + 2
        elif argv[i] == "--allow":
            allow.append(argv[i + 1])
            i += 2
        else:
            files.append(argv[i])
            i += 1
    if not files:
        print(__doc__.strip().splitlines()[-8], file=sys.stderr)
        return 2
    failures = []
    for f in files:
        failures.extend(check(f, name or f, allow))
    for line in failures:
        print(line)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
