"""The board and core a measured process's profile is named after (``<board>_<core>``, the
implementation name of the PDM ``rosaadl library add-profile`` writes from ``measurements.json``).

What a run measures belongs to the core whose execution times the dispatches burned:

* with ``--emulate``, the workload twin burns the model's ``Compute_Execution_Time``: the
  execution times are those of the PDM the deployment picked for the core the process is bound to
  (``Actual_Processor_Binding``). When the process's classifier is such a PDM (an implementation
  ``<type>.<board>_<core>`` with a ``Reference_Processor``, as the library names them), and its
  ``Reference_Processor`` is the type of the processor it is bound to (or it is bound to none),
  the profile is named after it: ``nd_usb_cam::usb_cam_nd.xu4_a15`` bound to an ``ARM_A15``
  core → board ``xu4``, core ``a15`` (split at the first underscore);
* otherwise (user code ran, or the model names no PDM), the execution times are this machine's:
  board ``host``, core the machine's architecture (``platform.machine()``: ``x86_64``).

The middleware's share a profile adds to each thread is always this machine's.
"""

from __future__ import annotations

import platform
import re
from collections.abc import Sequence

from pyecore.ecore import EObject

from rosaadl.errors import RosaadlError
from rosaadl.model import find_instance
from rosaadl.properties import property_value

__all__ = ["HOST_BOARD", "host_profile", "model_profile", "run_profile"]

#: The board name of a profile measured on the machine the run happened on.
HOST_BOARD = "host"
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9]*(?:_[A-Za-z0-9]+)+\Z")


def host_profile() -> tuple[str, str]:
    """(``host``, this machine's architecture as an identifier part)."""
    machine = re.sub(r"[^A-Za-z0-9]+", "_", platform.machine()).strip("_") or "cpu"
    return HOST_BOARD, machine


def _type_name(classifier: object) -> str:
    """``Exynos_5422::ARM_A15.impl`` → ``exynos_5422::arm_a15``."""
    text = str(getattr(classifier, "classifier", None) or classifier or "")
    package, _, name = text.rpartition("::")
    return f"{package}::{name.partition('.')[0]}".lower() if package else name.partition(".")[0].lower()


def model_profile(root: EObject, path: str) -> tuple[str, str] | None:
    """The (board, core) of the PDM the process ``path`` (below ``root``) is, for the core it is
    bound to; None when it is none (see the module docstring)."""
    try:
        process = find_instance(root, path)
    except RosaadlError:
        return None
    classifier = str(process.classifier or "")
    implementation = classifier.rpartition("::")[2].partition(".")[2]
    reference = property_value(process, "Reference_Processor")
    if not implementation or reference is None or not _NAME.match(implementation):
        return None
    bound = property_value(process, "Actual_Processor_Binding") or []
    cores = {_type_name(getattr(core, "classifier", "")) for core in bound if core is not None}
    if cores and cores != {_type_name(reference)}:
        return None  # a PDM of another core type than the one it runs on: not its profile
    board, _, core = implementation.partition("_")
    return board, core


def run_profile(model: Sequence[str] | None, *, emulate: bool) -> tuple[str, str]:
    """The (board, core) of a measured process: its PDM's (``model``) when it was emulated,
    else this machine's."""
    return (model[0], model[1]) if emulate and model else host_profile()
