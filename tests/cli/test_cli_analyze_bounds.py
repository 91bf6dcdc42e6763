"""``analyze --only sim`` on an overload whose first miss lies past the simulation's job cap: the
cut horizon is reported inconclusive with exit 1, never "0 deadline misses ... OK"."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from time_limit import within_seconds

from rosaadl.cli import main

LIMIT_S = 10

# EDF, U = 0.5 + 5000002/10000003 > 1: the first miss is near 3.3·10⁹ us, the job cap cuts the
# feasibility interval (10⁸ us, 10⁷ jobs) near 2·10⁶ us.
OVERLOAD = """\
package overload
public
  thread worker
  properties
    Dispatch_Protocol => Periodic;
  end worker;
  process node
  end node;
  process implementation node.impl
    subcomponents
      a: thread worker;
      b: thread worker;
  end node.impl;
  processor cpu
  properties
    Scheduling_Protocol => (EDF);
  end cpu;
  system top
  end top;
  system implementation top.impl
    subcomponents
      cpu: processor cpu;
      n: process node.impl;
    properties
      Period => 10 us applies to n.a;
      Compute_Execution_Time => 5 us .. 5 us applies to n.a;
      Period => 10000003 us applies to n.b;
      Compute_Execution_Time => 5000002 us .. 5000002 us applies to n.b;
      Actual_Processor_Binding => (reference (cpu)) applies to n.a, n.b;
  end top.impl;
end overload;
"""


_ten_seconds = pytest.fixture(autouse=True, name="ten_seconds")(within_seconds(LIMIT_S))


@pytest.fixture()
def overload(tmp_path: Path) -> Path:
    (tmp_path / "overload.aadl").write_text(OVERLOAD)
    return tmp_path


def test_a_cut_simulation_alone_is_inconclusive(overload: Path, capsys) -> None:
    code = main(["analyze", str(overload), "--root", "overload::top.impl", "--only", "sim"])
    out = capsys.readouterr().out
    assert code == 1, out
    assert "0 deadline misses, horizon cut by the job cap: inconclusive" in out
    assert out.rstrip().splitlines()[-1].startswith("INCONCLUSIVE") and "\nOK" not in out
    assert "simulated up to" in out


def test_a_cut_simulation_in_json_is_not_ok(overload: Path, capsys) -> None:
    args = ["--format", "json", "analyze", str(overload), "--root", "overload::top.impl", "--only", "sim"]
    code = main(args)
    doc = json.loads(capsys.readouterr().out)
    assert code == 1 and doc["ok"] is False and doc["inconclusive"] is True
    assert doc["analyses"]["simulation"]["inconclusive"] is True
