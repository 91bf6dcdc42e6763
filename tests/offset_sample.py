"""The library's tracking example with a ``Dispatch_Offset``: package ``offset_tracking``
(root ``offset_tracking::tracking_offset.impl``), whose pos_to_cmd node's command timer
(``rem_trk_sw.poscmd.cmd_publisher``, Period 100 ms) releases 20 ms into each period."""

from __future__ import annotations

from pathlib import Path

__all__ = ["OFFSET_ROOT", "OFFSET_TRACKING", "write_offset_tracking"]

OFFSET_ROOT = "offset_tracking::tracking_offset.impl"

OFFSET_TRACKING = """package offset_tracking
public
  with sys_tracking;
  system tracking_offset extends sys_tracking::tracking
  end tracking_offset;
  system implementation tracking_offset.impl extends sys_tracking::tracking.impl
  properties
    Dispatch_Offset => 20 ms applies to rem_trk_sw.poscmd.cmd_publisher;
  end tracking_offset.impl;
end offset_tracking;
"""


def write_offset_tracking(folder: Path) -> Path:
    """``folder/offset_tracking.aadl``, the package above."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "offset_tracking.aadl"
    path.write_text(OFFSET_TRACKING)
    return path
