"""Cheddar export → import of the library's deployments keeps every task's timing and binding."""

from __future__ import annotations

from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.analysis.tasks import taskset_from_instance
from rosaadl.exporters.cheddar import dumps_cheddar
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.cheddar import loads_cheddar
from rosaadl.properties import property_value
from rosaadl.transforms.instantiate import instantiate

SYSTEMS = Path(__file__).resolve().parents[2] / "library" / "systems"


@pytest.fixture(scope="module")
def workspace():
    return read_files([SYSTEMS])


def _tasks(taskset, *, imported: bool = False):
    """Tasks by their path under the root; imported ones carry the path with '_' (a Cheddar name
    such as ``rem_trk_sw.poscmd.cmd_publisher`` is not an AADL identifier)."""
    out = {}
    for task in taskset.tasks:
        key = task.name.rsplit(".", 1)[1] if imported else task.name.split(".", 1)[1].replace(".", "_")
        out[key] = task
    return out


@pytest.mark.parametrize("root", ["sys_tracking::tracking.impl", "sys_rover::rover.impl"])
def test_export_then_import_preserves_timing_and_bindings(workspace, root: str) -> None:
    instance = instantiate(workspace, root)
    before = taskset_from_instance(instance)
    assert before.tasks, "the deployment has threads with execution times"
    document = dumps_cheddar(instance, cheddar_format=3, time_unit="us")
    back = loads_cheddar(document, f"{root}.xmlv3", time_unit="us")
    after = taskset_from_instance(back.instances[0])
    old, new = _tasks(before), _tasks(after, imported=True)
    assert sorted(old) == sorted(new)
    for name, task in old.items():
        twin = new[name]
        timing = (task.period, task.capacity, task.deadline)
        assert (twin.period, twin.capacity, twin.deadline) == timing, name
        thread = model.find_instance(instance, task.name)
        if property_value(thread, "Priority") is not None:
            assert twin.priority == task.priority, name
        else:  # no priority in the model: the exporter writes Cheddar's default, 1
            assert twin.priority == 1, name
        # bound to the same core: the SoC comes back as one Cheddar multi-core processor whose core
        # units are named by the cores' instance paths
        core = task.processor.split(".", 1)[1].replace(".", "_")
        assert (twin.core or twin.processor.rsplit(".", 1)[-1]) == core, name
    workspace.instances.remove(instance)


def test_cheddar_2_refuses_the_multicore_boards_clearly(workspace) -> None:
    from rosaadl.errors import ExportError

    instance = instantiate(workspace, "sys_tracking::tracking.impl")
    with pytest.raises(ExportError, match="Cheddar 2 has no multi-core processors"):
        dumps_cheddar(instance, cheddar_format=2)
    workspace.instances.remove(instance)


def test_exported_tracking_deployment_saves_and_reloads(workspace, tmp_path: Path) -> None:
    instance = instantiate(workspace, "sys_tracking::tracking.impl")
    back = loads_cheddar(dumps_cheddar(instance), "tracking.xmlv3")
    path = model.save(back, tmp_path / "tracking.json")
    assert model.model_differences(model.load(path), back) == []
    workspace.instances.remove(instance)
