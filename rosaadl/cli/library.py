"""``rosaadl library list | show NAME | add-profile MEASUREMENTS.csv -o DIR``: the component library.

* ``list [INPUT...]``: every package and property set of the library (and of the AADL files or
  folders given) with its components; ``--format json`` gives
  ``{"ok", "errors", "warnings", "packages": [{"name", "kind", "file", "library", "components":
  [{"name", "category", "kind", "extends"}]}]}``.
* ``show NAME [INPUT...]``: what a package, property set or classifier is (``Pkg::T``,
  ``Pkg::T.impl`` or an unqualified name searched in every package): category, extends chain,
  implementations, features, subcomponents, connections, flows and properties with units. An
  unknown or ambiguous name exits 1 and lists the candidates.
* ``add-profile MEASUREMENTS.csv|measurements.json [INPUT...] -o DIR``: measurements of nodes on
  boards and cores (or a measured run) turned into PDM packages ``<node package>_profiles`` in
  ``DIR`` (see ``docs/library.md``). Every bad row is reported with its line and column; nothing is
  written then.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import click

from rosaadl.cli.common import Options, Report, output_option, pass_options
from rosaadl.errors import Diagnostic, RosaadlError, UsageError
from rosaadl.formats import expand_errors

__all__ = ["command"]


def _fail(report: Report, options: Options, exc: RosaadlError) -> None:
    for error in expand_errors(exc):
        report.error(error)
    sys.exit(report.emit(options))


@click.group("library")
def command() -> None:
    """The component library: list its packages, show a component, add measured profiles."""


# --------------------------------------------------------------------------- list


@command.command("list")
@click.argument("inputs", nargs=-1, type=click.Path(path_type=Path))
@pass_options
def list_command(options: Options, inputs: tuple[Path, ...]) -> None:
    """List every package and property set with its components (INPUTs: more AADL files or folders)."""
    from rosaadl.workflow.library_catalog import list_packages, read_library

    report = Report()
    notes: list[Diagnostic] = []
    try:
        workspace = read_library(inputs, warnings=notes)
    except UsageError:
        raise
    except RosaadlError as exc:
        _fail(report, options, exc)
        return
    for note in notes:
        report.warn(note)
    packages = list_packages(workspace)
    report.data["packages"] = [package.as_dict() for package in packages]
    for package in packages:
        where = package.file or "?"
        if package.kind == "property set":
            report.say(f"{package.name} (property set, {where}): {len(package.properties)} properties")
            continue
        report.say(f"{package.name} (package, {where})")
        for component in package.components:
            report.say(f"  {component}")
    components = sum(len(p.components) for p in packages)
    options.progress(f"{len(packages)} packages and property sets, {components} components")
    sys.exit(report.emit(options))


# --------------------------------------------------------------------------- show


@command.command("show")
@click.argument("name")
@click.argument("inputs", nargs=-1, type=click.Path(path_type=Path))
@pass_options
def show_command(options: Options, name: str, inputs: tuple[Path, ...]) -> None:
    """Show what NAME is: a package, a property set, Pkg::T, Pkg::T.impl or an unqualified name."""
    from rosaadl.workflow.library_catalog import ComponentNotFound, describe, read_library

    report = Report()
    notes: list[Diagnostic] = []
    try:
        workspace = read_library(inputs, warnings=notes)
    except UsageError:
        raise
    except RosaadlError as exc:
        _fail(report, options, exc)
        return
    for note in notes:
        report.warn(note)
    try:
        info = describe(workspace, name)
    except ComponentNotFound as exc:
        report.data["candidates"] = exc.candidates
        _fail(report, options, exc)
        return
    report.data["component" if info["what"] == "classifier" else "package"] = info
    for line in _describe_lines(info):
        report.say(line)
    sys.exit(report.emit(options))


def _where(info: dict[str, Any]) -> str:
    file = info.get("file")
    if not file:
        return ""
    text = f"library: {file}" if info.get("library") else file
    return f"{text}:{info['line']}" if info.get("line") else text


def _describe_lines(info: dict[str, Any]) -> list[str]:
    if info["what"] != "classifier":
        return _unit_lines(info)
    kind = info["kind"]
    words = info["category"] if kind == "type" else f"{info['category']} {kind}"
    if kind == "feature group type":
        words = "feature group type"
    lines = [f"{info['name']}: {words} ({_where(info)})"]
    if info["extends"]:
        lines.append(f"  extends: {' -> '.join(info['extends'])}")
    if "type" in info:
        chain = [info["type"], *info.get("type_extends", [])]
        lines.append(f"  type: {' -> '.join(chain)}")
    if info.get("implementations"):
        lines.append("  implementations: " + ", ".join(info["implementations"]))
    if info.get("extended_by"):
        lines.append("  extended by: " + ", ".join(info["extended_by"]))

    def origin(entry: dict[str, Any]) -> str:
        return "" if entry.get("from") == info["name"] else f"  (from {entry['from']})"

    if info["features"]:
        lines.append("  features:")
        for f in info["features"]:
            words = " ".join(w for w in (f.get("direction") or f.get("access"), f["category"]) if w)
            refined = "refined to " if f["refined"] else ""
            classifier = f" {f['classifier']}" if f["classifier"] else ""
            lines.append(f"    {f['name']}: {refined}{words}{classifier}{origin(f)}")
    if info.get("subcomponents"):
        lines.append("  subcomponents:")
        for s in info["subcomponents"]:
            refined = "refined to " if s["refined"] else ""
            classifier = f" {s['classifier']}" if s["classifier"] else ""
            array = "".join(f"[{d}]" for d in s["array"])
            lines.append(f"    {s['name']}{array}: {refined}{s['category']}{classifier}{origin(s)}")
    if info.get("connections"):
        lines.append("  connections:")
        for c in info["connections"]:
            arrow = "<->" if c["bidirectional"] else "->"
            lines.append(f"    {c['name']}: {c['kind']} {c['source']} {arrow} {c['destination']}{origin(c)}")
    if info.get("flows"):
        lines.append("  flows:")
        for flow in info["flows"]:
            ends = " -> ".join(e for e in (flow["in"], flow["out"]) if e)
            lines.append(f"    {flow['name']}: flow {flow['kind']} {ends}")
    if info.get("modes"):
        lines.append("  modes: " + ", ".join(info["modes"]))
    if info["properties"]:
        lines.append("  properties:")
        for p in info["properties"]:
            arrow = "+=>" if p.get("append") else "=>"
            applies = f" applies to {', '.join(p['applies_to'])}" if p["applies_to"] else ""
            lines.append(f"    {p['property']} {arrow} {p['value']}{applies}{origin(p)}")
    return lines


def _unit_lines(info: dict[str, Any]) -> list[str]:
    lines = [f"{info['name']}: {info['what']} ({_where(info)})"]
    if info["withs"]:
        lines.append("  with " + ", ".join(info["withs"]))
    if info["what"] == "property set":
        for prop in info["properties"]:
            default = f" => {prop['default']}" if prop["default"] else ""
            applies = f" applies to ({', '.join(prop['applies_to'])})" if prop["applies_to"] else ""
            inherit = "inherit " if prop["inherit"] else ""
            lines.append(f"  {prop['name']}: {inherit}{prop['type'] or '?'}{default}{applies}")
        for ptype in info["types"]:
            lines.append(f"  type {ptype['name']}: {ptype['type']}")
        for const in info["constants"]:
            lines.append(f"  constant {const['name']} => {const['value']}")
        return lines
    for ren in info["renames"]:
        words = [ren["name"], "renames", ren["kind"], ren["target"]]
        lines.append("  " + " ".join(w for w in words if w))
    from rosaadl.workflow.library_catalog import ComponentSummary

    for component in info["components"]:
        lines.append(f"  {ComponentSummary(**component)}")
    if info.get("see_also"):
        lines.append("  see also: " + ", ".join(info["see_also"]))
    return lines


# --------------------------------------------------------------------------- add-profile


@command.command("add-profile")
@click.argument("measurements", type=click.Path(path_type=Path))
@click.argument("inputs", nargs=-1, type=click.Path(path_type=Path))
@output_option("Folder to write the profile packages into (<node package>_profiles.aadl).")
@pass_options
def add_profile_command(options: Options, measurements: Path, inputs: tuple[Path, ...], out: Path) -> None:
    """Turn a CSV of measurements, or a measured run's measurements.json, into PDM implementations
    of library nodes (INPUTs: AADL files or folders with nodes that are not in the library). CSV
    columns: node, thread, board, core, period_us, cet_us, mips_raw, ipc, data_size_bytes
    [, processor]."""
    from rosaadl.workflow.library_add_profile import add_profiles

    report = Report()
    notes: list[Diagnostic] = []
    report.data.update({"input": str(measurements), "output": str(out)})
    try:
        result = add_profiles(measurements, out, inputs=inputs, warnings=notes)
    except UsageError:
        raise
    except RosaadlError as exc:
        for note in notes:
            report.warn(note)
        report.data.update({"files": [], "packages": [], "implementations": []})
        _fail(report, options, exc)
        return
    for note in notes:
        report.warn(note)
    report.data.update(result.as_dict())
    for path in result.files:
        report.say(f"wrote {path}")
    for impl in result.implementations:
        threads = ", ".join(t.rpartition("::")[2] for t in impl.threads)
        report.say(f"  {impl.process} (rows {', '.join(map(str, impl.rows))}): {threads}")
    options.progress(f"{measurements} -> {len(result.files)} package(s) in {out}")
    sys.exit(report.emit(options))
