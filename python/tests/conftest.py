"""Shared helpers: the tool to compare with, and the tool's JSON number form."""
import json
import math
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, os.pardir, os.pardir))
TOOL = os.environ.get("JUMPCYL_TOOL", os.path.join(REPO, "build", "jumpcyl"))
DBL_EPSILON = sys.float_info.epsilon


def tool(*args, check=True):
    """The tool's standard output for args."""
    if not os.access(TOOL, os.X_OK):
        pytest.skip("the tool is not built at %s (set JUMPCYL_TOOL)" % TOOL)
    r = subprocess.run([TOOL, *args], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError("jumpcyl %s failed (%d): %s" % (" ".join(args), r.returncode, r.stderr))
    return r


def tool_json(*args):
    return json.loads(tool(*args).stdout)


def cjson_number_text(d):
    """A double as cJSON 1.7 prints it (print_number): null for NaN and
    infinities, %d when it equals its int conversion, else %1.15g when that
    reads back within DBL_EPSILON relative, else %1.17g."""
    if not math.isfinite(d):
        return "null"
    vi = 2147483647 if d >= 2147483647 else -2147483648 if d <= -2147483648 else int(d)
    if d == float(vi):
        return "%d" % vi
    s = "%1.15g" % d
    t = float(s)
    if not abs(t - d) <= max(abs(t), abs(d)) * DBL_EPSILON:
        s = "%1.17g" % d
    return s


def as_tool_prints(x):
    """A Python document with every number replaced by the value the tool's
    JSON text of it reads back to: comparing with == then compares the texts."""
    if isinstance(x, dict):
        return {k: as_tool_prints(v) for k, v in x.items()}
    if isinstance(x, list):
        return [as_tool_prints(v) for v in x]
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return x
    if isinstance(x, (int, float)):
        return json.loads(cjson_number_text(float(x)))
    raise TypeError(type(x))
