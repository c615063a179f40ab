"""Shared helpers: the tool to compare with, and an exact comparison with its JSON."""
import json
import os
import struct
import subprocess

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, os.pardir, os.pardir))
TOOL = os.environ.get("JUMPCYL_TOOL", os.path.join(REPO, "build", "jumpcyl"))


def tool(*args, check=True):
    """The tool's standard output for args."""
    if not os.access(TOOL, os.X_OK):
        pytest.skip("the tool is not built at %s (set JUMPCYL_TOOL)" % TOOL)
    r = subprocess.run([TOOL, *args], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError("jumpcyl %s failed (%d): %s" % (" ".join(args), r.returncode, r.stderr))
    return r


def tool_json(*args):
    """The tool's JSON output parsed, every number as a float (so that "-0"
    keeps its sign): the tool writes each double so that it reads back to
    the same double."""
    return json.loads(tool(*args).stdout, parse_int=float)


def _bits(x):
    return struct.pack("<d", float(x))


def assert_same(ours, tools, where="$"):
    """ours (the package's) is tools (the tool's JSON, from tool_json)
    exactly: the same members and items, the same strings and booleans,
    None where the tool wrote null, and every number the same double bit for
    bit (struct-packed: -0 is not 0)."""
    if isinstance(tools, dict):
        assert isinstance(ours, dict), "%s: %r, the tool has an object" % (where, ours)
        assert sorted(ours) == sorted(tools), "%s: members %s, the tool's %s" % (where, sorted(ours), sorted(tools))
        for k in tools:
            assert_same(ours[k], tools[k], "%s.%s" % (where, k))
    elif isinstance(tools, list):
        assert isinstance(ours, (list, tuple)), "%s: %r, the tool has an array" % (where, ours)
        assert len(ours) == len(tools), "%s: %d items, the tool's %d" % (where, len(ours), len(tools))
        for i, (a, b) in enumerate(zip(ours, tools)):
            assert_same(a, b, "%s[%d]" % (where, i))
    elif isinstance(tools, float):
        assert isinstance(ours, (int, float)) and not isinstance(ours, bool), \
            "%s: %r, the tool has the number %r" % (where, ours, tools)
        assert _bits(ours) == _bits(tools), "%s: %r (%s), the tool's %r (%s)" % (
            where, ours, float(ours).hex(), tools, tools.hex())
    else:  # str, bool, None
        assert type(ours) is type(tools) and ours == tools, "%s: %r, the tool's %r" % (where, ours, tools)
