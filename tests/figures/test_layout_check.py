#!/usr/bin/env python3
"""The layout check's own test: small SVGs written here in gnuplot's form,
each with one known fault, must fail with that fault named; the clean one
must pass. Prints "N passed, N failed"; exits 1 on a failure."""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import layout_check  # noqa: E402

HEAD = """<?xml version="1.0" encoding="utf-8"  standalone="no"?>
<svg viewBox="0 0 600 400" xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink">
<g id="gnuplot_canvas">
<rect x="0" y="0" width="600" height="400" fill="#ffffff"/>
"""
BORDER = """<g fill="none" color="black" stroke="currentColor" stroke-width="1.80">
	<path stroke='rgb( 34,  34,  34)'  d='M100.00,50.00 L100.00,300.00 L550.00,300.00 L550.00,50.00 M100.00,50.00  '/></g>
"""
TAIL = "</g>\n</svg>\n"


def text(x, y, s, size=18, anchor="start", rotate=None):
    rot = " rotate(%g)" % rotate if rotate is not None else ""
    return ('<g transform="translate(%g,%g)%s" stroke="none" fill="black" font-family="Sans" font-size="%g"'
            ' text-anchor="%s">\n\t<text><tspan font-family="Sans" >%s</tspan></text>\n</g>\n' % (x, y, rot, size, anchor, s))


def curve(n, title, points, key_at=None):
    """A plot group: its key text and sample (when key_at), then the curve."""
    out = '<g id="gnuplot_plot_%d" ><title>%s</title>\n' % (n, title if key_at else "gnuplot_plot_%d" % n)
    d = ""
    if key_at:
        out += text(key_at[0], key_at[1], title)
        d = "M%g,%g L%g,%g " % (key_at[0] - 60, key_at[1] - 6, key_at[0] - 12, key_at[1] - 6)
    d += "M" + " L".join("%g,%g" % p for p in points)
    out += "<g fill=\"none\" stroke=\"currentColor\">\n\t<path stroke='rgb(0,114,178)' d='%s'/></g>\n</g>\n" % d
    return out


# A curve across the whole plot area, a title above, tick labels, a key entry below.
CLEAN_CURVE = [(100 + 9 * i, 290 - 4.8 * i) for i in range(51)]
CLEAN = (BORDER + text(325, 30, "A clean panel", anchor="middle") + text(90, 306, "0", anchor="end")
         + text(90, 56, "50", anchor="end") + text(150, 120, "a label") + curve(1, "the curve", CLEAN_CURVE, (180, 360)))

# A heat map: opaque cells over the plot area, a label on them.
CELLS = "".join("\t<polygon fill = 'rgb(68, 1, 84)' points = '%g,%g %g,%g %g,%g %g,%g '/>\n"
                % (x, y, x + 90, y, x + 90, y + 50, x, y + 50)
                for x in range(100, 550, 90) for y in range(50, 300, 50))
MAP = (BORDER + text(325, 30, "A map", anchor="middle") + '<g id="gnuplot_plot_1" ><title>gnuplot_plot_1</title>\n'
       + "<g stroke='none' shape-rendering='crispEdges'>\n" + CELLS + "</g>\n</g>\n" + text(300, 150, "on a cell"))
# A flat curve high on an axis from zero (a tic "0" at the bottom), or not.
FLAT = [(100 + 9 * i, 100) for i in range(51)]
ZERO = BORDER + text(325, 30, "A flat panel", anchor="middle") + text(90, 56, "1.2", anchor="end")


CASES = [
    # name, body, the words every failure line must hold (empty: passes)
    ("clean", CLEAN, []),
    ("two texts overlap", CLEAN + text(170, 125, "another label"), ['"a label"', '"another label"', "overlaps text"]),
    ("a curve through a text", CLEAN + text(300, 150, "on the curve"), ['"on the curve"', 'curve "the curve"']),
    ("a rotated text on a curve", CLEAN + text(330, 200, "up the curve", rotate=-90), ['"up the curve"', 'curve "the curve"']),
    ("a text past the edge", CLEAN + text(560, 200, "too far right"), ['"too far right"', "clipped by the canvas"]),
    ("a curve past the edge", CLEAN + curve(2, "gnuplot_plot_2", [(200, 200), (640, 210)]), ["clipped by the canvas"]),
    ("data in a corner", BORDER + text(325, 30, "A narrow panel", anchor="middle")
     + curve(1, "the curve", [(100 + i, 290 - i) for i in range(100)], (180, 360)),
     ['panel "A narrow panel"', "22 % of the x axis", "40 % of the y axis"]),
    ("a map's cells are its data", MAP, []),
    ("flat data on an axis from zero", ZERO + text(90, 306, "0", anchor="end") + curve(1, "the curve", FLAT, (180, 360)), []),
    ("flat data on an axis not from zero", ZERO + text(90, 306, "0.8", anchor="end") + curve(1, "the curve", FLAT, (180, 360)),
     ['panel "A flat panel"', "0 % of the y axis"]),
]


def main():
    passed = failed = 0
    with tempfile.TemporaryDirectory(prefix="jc-layout-check-") as tmp:
        for name, body, words in CASES:
            path = os.path.join(tmp, "case.svg")
            with open(path, "w", encoding="utf-8") as f:
                f.write(HEAD + body + TAIL)
            lines = layout_check.check(path, name)
            ok = (not lines) if not words else (lines and all(any(w in line for line in lines) for w in words))
            if ok and words == [] and lines:
                ok = False
            print("%s %s%s" % ("ok  " if ok else "FAIL", name, "" if ok else ": got %s" % lines))
            passed += bool(ok)
            failed += not ok
    # The allowance lets a panel's axis be wider than its data.
    with tempfile.TemporaryDirectory(prefix="jc-layout-check-") as tmp:
        path = os.path.join(tmp, "case.svg")
        with open(path, "w", encoding="utf-8") as f:
            f.write(HEAD + dict((c[0], c[1]) for c in CASES)["data in a corner"] + TAIL)
        lines = layout_check.check(path, "allowed", ["span:A narrow:x", "span:A narrow:y"])
        ok = not lines
        print("%s allowance%s" % ("ok  " if ok else "FAIL", "" if ok else ": got %s" % lines))
        passed += ok
        failed += not ok
    print("%d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
