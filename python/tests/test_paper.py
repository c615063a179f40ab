"""paper_table against `jumpcyl paper --json`."""
import pytest

import jumpcyl as jc
from conftest import tool_json, assert_same


def test_paper_table_is_the_tool():
    t = jc.paper_table()
    assert_same(t, tool_json("paper", "--json"))
    # Independent of the tool: the paper's measured positions (Table 1).
    assert [r["incline_deg"] for r in t["rows"]] == [15, 30, 45]
    assert all(0.5 < r["measured"]["x"] < 2.0 for r in t["rows"])


def test_paper_table_refuses_another_body():
    # The tool refuses it too (jumpcyl paper --preset hoop exits 2).
    with pytest.raises(ValueError, match="not the paper's cylinder"):
        jc.paper_table(jc.Setup(preset="hoop"))
    with pytest.raises(ValueError, match="not the paper's cylinder"):
        jc.paper_table(jc.Setup(preset="paper", rod_offset="6cm"))
