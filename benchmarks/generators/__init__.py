"""Model generators shared by the benchmarks and the tests: one place for every synthetic input.

One module per kind of input: ``aadl_text`` (AADL text at scale), ``declarative`` (declarative
AADL models built with the model API, and the few standard property definitions small models
need), ``instances`` (instance models built as the instantiator makes them), ``tasks`` (random
task sets, and SimSo set up on them), ``cheddar`` (Cheddar XML), ``rosmod`` (ROSMOD projects as
models and as files), ``corpus`` (where the real-world corpus is, which files each reader takes).

The tests import them as ``benchmarks.generators.<module>``: the project root is on pytest's
import path (``pythonpath`` in ``pyproject.toml``, as ``python -m pytest`` from the root has it).
"""

from __future__ import annotations

from benchmarks.generators.aadl_text import aadl_package_text
from benchmarks.generators.cheddar import cheddar_document
from benchmarks.generators.corpus import aadl_files, aadl_texts, corpus_dir
from benchmarks.generators.declarative import chained_system, thread_types_package, time_units
from benchmarks.generators.instances import flat_instance, robot_fleet, ros_ring
from benchmarks.generators.rosmod import rosmod_project, write_rosmod_project
from benchmarks.generators.tasks import random_rta_tasks, random_simulation_sets, simso_model

__all__ = [
    "aadl_files",
    "aadl_package_text",
    "aadl_texts",
    "chained_system",
    "cheddar_document",
    "corpus_dir",
    "flat_instance",
    "random_rta_tasks",
    "random_simulation_sets",
    "robot_fleet",
    "ros_ring",
    "rosmod_project",
    "simso_model",
    "thread_types_package",
    "time_units",
    "write_rosmod_project",
]
