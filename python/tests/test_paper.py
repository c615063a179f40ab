"""paper_table against `jumpcyl paper --json`."""
import jumpcyl as jc
from conftest import tool_json, assert_same


def test_paper_table_is_the_tool():
    t = jc.paper_table()
    assert_same(t, tool_json("paper", "--json"))
    # Independent of the tool: the paper's measured positions (Table 1).
    assert [r["incline_deg"] for r in t["rows"]] == [15, 30, 45]
    assert all(0.5 < r["measured"]["x"] < 2.0 for r in t["rows"])
