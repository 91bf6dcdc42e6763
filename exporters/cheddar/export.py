"""Writing a system instance as Cheddar XML: the public entry points.

:func:`dumps_cheddar` reads the instance into the intermediate system
(:mod:`~rosaadl.exporters.cheddar.collect`), writes it in the format asked for
(:mod:`~rosaadl.exporters.cheddar.v3` or :mod:`~rosaadl.exporters.cheddar.v2`), and refuses to
return a document while there are problems: times that are not whole numbers of the unit first,
then what the model cannot say in Cheddar, then what Cheddar's reader would reject
(:func:`~rosaadl.exporters.cheddar.structure.structure_problems`), each list in one
:class:`ExportError`. Unless told otherwise it writes the format the model was read from
(:func:`source_format`), Cheddar 3 for a model that did not come from Cheddar.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.arguments import checked
from rosaadl.bulk import gc_paused
from rosaadl.errors import Diagnostic, ExportError, Location, RosaadlError
from rosaadl.exporters.cheddar import v2, v3
from rosaadl.exporters.cheddar.collect import collect
from rosaadl.exporters.cheddar.context import ExportContext, Props
from rosaadl.exporters.cheddar.structure import structure_problems
from rosaadl.exporters.cheddar.system import Collection
from rosaadl.fileio import atomic_write_bytes, parse_xml_bytes
from rosaadl.importers.cheddar.vocabulary import CP, EXPORT_SECTIONS_V3, SECTIONS_V2, TIME_UNITS

__all__ = ["dumps_cheddar", "write_cheddar", "source_format"]


def _document(c: Collection) -> etree._Element:
    """The document: the sections in the file's order (new ones where Cheddar puts them), with
    the elements the reader kept verbatim back in their sections."""
    root = etree.Element("cheddar")
    sections: dict[str, etree._Element] = {}
    known = EXPORT_SECTIONS_V3 if c.ctx.version == 3 else SECTIONS_V2
    content = v3.sections(c) if c.ctx.version == 3 else v2.sections(c)
    order = [s for s in c.system.section_order if c.ctx.version == 3 or s != "core_units"]
    wanted = [name for name in known if content.get(name)] + [s for s, _ in c.system.kept]
    for name in wanted:
        if name in order:
            continue
        # a section the file did not have: before the first later one, in Cheddar's order
        rank = known.index(name) if name in known else len(known)
        position = next((i for i, s in enumerate(order) if s in known and known.index(s) > rank), len(order))
        order.insert(position, name)
    for name in order:
        if name in sections:
            etree.SubElement(root, name)  # a repeated section stays, empty
            continue
        sections[name] = etree.SubElement(root, name)
    for name, items in content.items():
        if items:
            sections[name].extend(items)
    for section, xml in c.system.kept:
        try:
            element = parse_xml_bytes(xml.encode("utf-8"), "<kept element>").getroot()
        except RosaadlError as exc:
            c.ctx.problems.append(f"a kept element of section {section} is not XML: {exc.message}")
            continue
        sections[section].append(element)
    return root


def _system_instance(source: EObject, root: str | None) -> EObject:
    """The system instance to export: ``source`` itself, or the one (named ``root``) in a model."""
    if not isinstance(source, EObject):
        raise ExportError(
            f"cannot export {type(source).__name__} to Cheddar; expected an AadlModel or a SystemInstance"
        )
    if model.is_a(source, "SystemInstance"):
        return source
    if model.is_a(source, "AadlModel"):
        instances = list(source.instances)
        if root is not None:
            wanted = root.lower()
            for instance in instances:
                if (instance.name or "").lower() == wanted or (instance.classifier or "").lower() == wanted:
                    return instance
            names = ", ".join(i.name for i in instances) or "none"
            raise ExportError(f"no system instance {root!r} in the model (instances: {names})")
        if len(instances) == 1:
            return instances[0]
        if not instances:
            raise ExportError("the model holds no system instance; instantiate a system implementation first")
        names = ", ".join(i.name for i in instances)
        raise ExportError(f"the model holds several system instances ({names}); choose one with root=")
    raise ExportError(
        f"cannot export a {source.eClass.name} to Cheddar; expected an AadlModel or a SystemInstance"
    )


def source_format(instance: EObject) -> int | None:
    """The Cheddar format (2 or 3) ``instance`` was read from, or None when it was not read
    from a Cheddar file (``Cheddar_Properties::Cheddar_Format`` on the system instance)."""
    value = Props(instance).get(CP + "Cheddar_Format")
    return value if value in (2, 3) and not isinstance(value, bool) else None


@checked
def dumps_cheddar(
    source: EObject,
    *,
    root: str | None = None,
    cheddar_format: int | None = None,
    time_unit: str = "us",
    diagnostics: list[Diagnostic] | None = None,
) -> bytes:
    """A system instance (or the one in an ``AadlModel``) as Cheddar XML bytes.

    ``cheddar_format`` is 3 (Cheddar 3 ADL) or 2 (Cheddar 2); by default, the format the
    instance was read from when it came from a Cheddar file (:func:`source_format`: what was
    read is written back, so a Cheddar 2 file whose tasks name an undeclared processor, which
    Cheddar 2's reader accepts, stays a file Cheddar loads), else 3. ``time_unit`` is ``us``
    or ``ms``. Problems (unbound threads, missing capacities, times that are not whole numbers
    of ``time_unit``, what the format cannot say) raise one :class:`ExportError` listing them
    all, with instance paths. Warnings go to ``diagnostics`` (and the log).
    """
    if cheddar_format not in (None, 2, 3):
        raise ExportError(f"cheddar_format must be 2 or 3, not {cheddar_format!r}")
    if time_unit not in TIME_UNITS:
        raise ExportError(f"time_unit must be one of {', '.join(TIME_UNITS)}, not {time_unit!r}")
    instance = _system_instance(source, root)
    read_as = source_format(instance)
    if cheddar_format is None:
        cheddar_format = read_as or 3
    found = diagnostics if diagnostics is not None else []
    ctx = ExportContext(instance, time_unit, cheddar_format, found)
    with gc_paused():
        collection = collect(ctx)
        try:
            document = _document(collection)
        except ValueError as exc:  # lxml refuses text XML cannot carry (ids, names)
            raise ExportError(
                f"a value cannot be written in XML: {exc}", Location(path=instance.name)
            ) from None
    if ctx.time_problems:
        raise ExportError(
            f"times that are not whole numbers of {time_unit} (not rounded; export with another time unit "
            "or fix the model):" + _listed(ctx.time_problems),
            Location(path=model.instance_path(instance)),
        )
    if ctx.problems:
        raise ExportError(
            "the model cannot be written as Cheddar XML:" + _listed(ctx.problems),
            Location(path=model.instance_path(instance)),
        )
    problems = structure_problems(document, cheddar_format)
    if problems:
        hint = (
            "\n(the model was read from a Cheddar 2 file, whose reader does not check these names: "
            "export it as Cheddar 2, or declare them in the model)"
            if read_as == 2 and cheddar_format == 3
            else ""
        )
        raise ExportError(
            "the Cheddar model would not load in Cheddar:\n  " + "\n  ".join(problems[:20]) + hint,
            Location(path=model.instance_path(instance)),
        )
    etree.indent(document, space=" ")
    body = etree.tostring(document, encoding="utf-8")
    return b'<?xml version="1.0" encoding="utf-8"?>\n' + body + b"\n"


def _listed(problems: list[str]) -> str:
    """The distinct problems, one an indented line (the first 20, then how many more)."""
    unique = list(dict.fromkeys(problems))
    shown = unique[:20]
    more = len(unique) - len(shown)
    return "\n  " + "\n  ".join(shown) + (f"\n  ... and {more} more" if more > 0 else "")


@checked
def write_cheddar(
    source: EObject,
    path: str | Path,
    *,
    root: str | None = None,
    cheddar_format: int | None = None,
    time_unit: str = "us",
    diagnostics: list[Diagnostic] | None = None,
) -> Path:
    """Write :func:`dumps_cheddar`'s document to ``path`` atomically (nothing is written on error)."""
    data = dumps_cheddar(
        source, root=root, cheddar_format=cheddar_format, time_unit=time_unit, diagnostics=diagnostics
    )
    target = Path(path)
    atomic_write_bytes(target, data)
    return target
