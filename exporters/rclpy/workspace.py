"""A ROS 2 workspace from an AADL instance: planning, rendering, and safe regeneration.

:func:`plan_workspace` decides every package and file from the instance (nothing is written);
:func:`generate_workspace` merges the plan with what is already in the output folder and
writes it:

* every block between user-code markers is kept: in place when its marker is still generated,
  moved to its new marker when its model element was renamed (a trace of the edit says so, see
  :func:`generate_workspace`) or when the element is the same but its file or name changed,
  otherwise kept, commented out, in the file's orphan section;
* a file with no marker that is not what the generator would write is never overwritten unless
  ``force``; a file that would not change is not rewritten;
* every path is joined under the output folder with :func:`rosaadl.fileio.safe_join`,
  everything is computed before the first write, and the files are written all-or-nothing
  (:func:`rosaadl.fileio.write_files`: all to temporaries, then renamed; an interrupt or an
  error leaves the workspace as it was); stale temporaries of an earlier, killed run are swept
  from every folder of the plan;
* the output folder keeps a trace of the generation (``.rosaadl-rclpy.trace``: which model
  element each block and file came from), read back at the next generation.
"""

from __future__ import annotations

import json
import logging
import os
import re
import time
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.arguments import checked
from rosaadl.errors import Diagnostic, ExportError, GenerationError, Location, RosaadlError, UsageError
from rosaadl.exporters.rclpy import naming, preservation
from rosaadl.exporters.rclpy.deployment import Deployment, HostPlan, NodeInstance, find_feature
from rosaadl.exporters.rclpy.instances import caching, enum_name, prop
from rosaadl.exporters.rclpy.instances import key as instance_key
from rosaadl.exporters.rclpy.messages import InterfaceDefinition, MessageCatalog
from rosaadl.exporters.rclpy.nodes import NodeBuilder, NodeClass
from rosaadl.exporters.rclpy.preservation import fit_marker
from rosaadl.exporters.rclpy.render import render_template
from rosaadl.exporters.rclpy.topics import Topology
from rosaadl.exporters.rclpy.twin import skeleton_before_twin
from rosaadl.fileio import existing, loads_bounded, safe_join, sweep_temporaries, write_files
from rosaadl.properties import own_property

__all__ = [
    "LICENSES",
    "MANIFEST_NAME",
    "GenerationOptions",
    "PlannedFile",
    "PackagePlan",
    "LaunchPlan",
    "WorkspacePlan",
    "FileChange",
    "BlockMove",
    "GenerationResult",
    "plan_workspace",
    "generate_workspace",
    "rename_map",
]

log = logging.getLogger(__name__)

#: Licences the generated files can carry (their headers pass ament_copyright).
LICENSES = ("Apache-2.0", "MIT")
#: The generation trace kept in the output folder.
MANIFEST_NAME = ".rosaadl-rclpy.trace.json"
_WRITERS = 8
_COPYRIGHT_RE = re.compile(r"^(#\s*Copyright\s+)(\d{4}(?:-\d{4})?)(\s)", re.MULTILINE)


@dataclass(frozen=True)
class GenerationOptions:
    """Choices that do not come from the model."""

    app_name: str | None = None  # default: the root classifier's type name
    license: str = "Apache-2.0"
    maintainer: str = "Maintainer"
    maintainer_email: str = "maintainer@example.com"
    copyright_holder: str | None = None  # default: "The <app> authors"
    year: int | None = None  # default: SOURCE_DATE_EPOCH's year, else this year
    version: str = "0.0.0"


@dataclass
class PlannedFile:
    """One file of the workspace: its path below the output folder and its generated text."""

    path: str
    text: str
    style: str | None  # comment style of its markers, None when it has none
    keys: dict[str, str] = field(default_factory=dict)  # marker -> model element key


@dataclass
class PackagePlan:
    name: str
    build_type: str  # "ament_python" | "ament_cmake"
    description: str
    depends: list[str] = field(default_factory=list)
    exec_depends: list[str] = field(default_factory=list)
    classes: list[NodeClass] = field(default_factory=list)
    scripts: list[str] = field(default_factory=list)
    launch_files: list[str] = field(default_factory=list)
    definitions: list[InterfaceDefinition] = field(default_factory=list)


@dataclass
class LaunchPlan:
    file: str
    marker: str
    title: str
    short: str
    description: str
    key: str
    nodes: list[NodeInstance] = field(default_factory=list)
    markers: dict[str, str] = field(default_factory=dict)  # node ident / imports / actions -> block

    def __post_init__(self) -> None:
        self.markers["imports"] = fit_marker(f"{self.marker}.imports", 0)
        self.markers["actions"] = fit_marker(f"{self.marker}.actions", 8)
        for node in self.nodes:
            self.markers[node.ident] = fit_marker(f"{self.marker}.{node.ident}", 12)


@dataclass
class WorkspacePlan:
    """Everything the generator decided, before anything is written."""

    app: str
    root: EObject
    packages: list[PackagePlan] = field(default_factory=list)
    classes: list[NodeClass] = field(default_factory=list)
    nodes: list[NodeInstance] = field(default_factory=list)
    hosts: list[HostPlan] = field(default_factory=list)
    launches: list[LaunchPlan] = field(default_factory=list)
    interfaces: PackagePlan | None = None
    bringup: PackagePlan | None = None
    files: list[PlannedFile] = field(default_factory=list)
    diagnostics: list[Diagnostic] = field(default_factory=list)

    def file(self, path: str) -> PlannedFile | None:
        return next((f for f in self.files if f.path == path), None)


@dataclass(frozen=True)
class FileChange:
    path: str
    action: str  # "create" | "update" | "unchanged" | "skip"
    reason: str = ""


@dataclass(frozen=True)
class BlockMove:
    name: str
    source: str  # file it came from
    target: str  # file it went to
    target_name: str  # marker it went to ("" when orphaned)


@dataclass
class GenerationResult:
    """What a generation did (or, with ``dry_run``, would do)."""

    output: Path
    plan: WorkspacePlan
    dry_run: bool = False
    changes: list[FileChange] = field(default_factory=list)
    moved: list[BlockMove] = field(default_factory=list)
    orphaned: list[BlockMove] = field(default_factory=list)
    restored: list[BlockMove] = field(default_factory=list)
    stale: list[str] = field(default_factory=list)
    diagnostics: list[Diagnostic] = field(default_factory=list)

    def paths(self, *actions: str) -> list[str]:
        return [c.path for c in self.changes if not actions or c.action in actions]

    @property
    def written(self) -> list[str]:
        return self.paths("create", "update")

    @property
    def skipped(self) -> list[str]:
        return self.paths("skip")


# --------------------------------------------------------------------------- source


def _system_instance(source: EObject, root: str | None) -> tuple[EObject | None, EObject]:
    """(AadlModel or None, SystemInstance) from an instance, a model with instances, or a
    declarative model and a root implementation name (instantiated here)."""
    if _model.is_a(source, "SystemInstance"):
        container = source.eContainer()
        return (container if container is not None and _model.is_a(container, "AadlModel") else None), source
    if not _model.is_a(source, "AadlModel"):
        raise UsageError(f"expected an AadlModel or a SystemInstance, got a {source.eClass.name}")
    instances = list(source.instances)
    if root:
        wanted = root.strip().lower()
        for instance in instances:
            if (instance.classifier or "").lower() == wanted or (instance.name or "").lower() == wanted:
                return source, instance
        from rosaadl.transforms.instantiate import instantiate

        return source, instantiate(source, root)
    if len(instances) == 1:
        return source, instances[0]
    if not instances:
        raise UsageError("the model has no instance: name the root implementation (Pkg::Sys.impl)")
    names = ", ".join(i.classifier or i.name for i in instances)
    raise UsageError(f"the model has {len(instances)} instances ({names}): name the root to generate")


def _app_name(instance: EObject, options: GenerationOptions) -> str:
    if options.app_name:
        return naming.package_name(options.app_name, fallback="app")
    classifier = instance.classifier or ""
    local = classifier.rpartition("::")[2].partition(".")[0]
    if not local:
        local = re.sub(r"_Instance$", "", instance.name or "") or "app"
    return naming.package_name(local, fallback="app")


def _default_year() -> int:
    epoch = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    if epoch.isdigit():
        return time.gmtime(int(epoch)).tm_year
    return time.gmtime().tm_year


# --------------------------------------------------------------------------- planning


def _processes(root: EObject) -> list[EObject]:
    found = []
    for obj in _model.component_instances(root):
        if enum_name(obj.category) == "process":
            found.append(obj)
    return found


def _package_of(process: EObject, app: str, model: EObject | None) -> str:
    """``Package_Name``, else the AADL package of the process classifier; for a process of a
    deployment package (``ROSMOD_Properties::Unit_Kind => Deployment``, as ROSMOD nodes are),
    the package of the software it runs (its first thread group or thread classifier)."""
    value = prop(process, "Package_Name")
    if isinstance(value, str) and value.strip():
        return naming.package_name(value, fallback="nodes")
    classifier = process.classifier or ""
    if "::" in classifier:
        package = classifier.rpartition("::")[0]
        unit = _model.find_unit(model, package) if model is not None else None
        kind = own_property(unit, "Unit_Kind") if unit is not None else None
        if kind is not None and str(kind).lower() == "deployment":
            for child in _model.component_instances(process):
                software = child.classifier or ""
                if child is not process and "::" in software:
                    package = software.rpartition("::")[0]
                    break
        return naming.package_name(package, fallback="nodes")
    return naming.package_name(f"{app}_nodes", fallback="nodes")


def _module_base(process: EObject) -> str:
    value = prop(process, "Node_Name")
    if isinstance(value, str) and value.strip():
        return value
    classifier = process.classifier or ""
    if classifier:
        return classifier.rpartition("::")[2].partition(".")[0]
    return process.name or "node"


@checked
def plan_workspace(
    source: EObject,
    *,
    root: str | None = None,
    options: GenerationOptions | None = None,
    rosmod_trace: EObject | None = None,
) -> WorkspacePlan:
    """Decide the packages and files of the workspace for ``source`` (see the package docs).

    ``source`` is a ``SystemInstance``, an ``AadlModel`` holding one (or several: ``root`` picks
    it), or a declarative ``AadlModel`` with ``root`` naming the implementation to instantiate.
    ``rosmod_trace`` is the trace of a ROSMOD → AADL conversion, for the ``.msg``/``.srv``
    definitions.
    """
    with caching():
        return _plan(source, root, options or GenerationOptions(), rosmod_trace)


def _plan(
    source: EObject, root: str | None, options: GenerationOptions, rosmod_trace: EObject | None
) -> WorkspacePlan:
    if options.license not in LICENSES:
        raise UsageError(f"license {options.license!r} is not supported; use one of {', '.join(LICENSES)}")
    model, instance = _system_instance(source, root)
    app = _app_name(instance, options)
    interfaces_name = f"{app}_interfaces"
    bringup_name = f"{app}_bringup"
    plan = WorkspacePlan(app=app, root=instance)
    catalog = MessageCatalog(model, interfaces_name, rosmod_trace)
    topology = Topology(instance)
    builder = NodeBuilder(instance, catalog, topology)
    deployment = Deployment(instance)

    processes = _processes(instance)
    model_name = instance.classifier or instance.name
    names = deployment.node_names(processes)

    # Node classes: one per (package, classifier, structure).
    packages: dict[str, PackagePlan] = {}
    module_tables: dict[str, naming.NameTable] = {}
    script_tables: dict[str, naming.NameTable] = {}
    classes: dict[tuple, NodeClass] = {}
    class_of: dict[int, NodeClass] = {}
    reserved = {interfaces_name, bringup_name}
    for process in processes:
        package = _package_of(process, app, model)
        if package in reserved:
            package = naming.package_name(f"{package}_nodes")
        signature = builder.signature(process)
        key = (package, (process.classifier or "").lower() or _model.instance_path(process), signature)
        cls = classes.get(key)
        if cls is None:
            pkg = packages.get(package)
            if pkg is None:
                pkg = PackagePlan(
                    name=package,
                    build_type="ament_python",
                    description=f"ROS 2 nodes generated from the AADL model {model_name}.",
                )
                packages[package] = pkg
                module_tables[package] = naming.NameTable({"__init__"})
                script_tables[package] = naming.NameTable()
            module = module_tables[package].unique(naming.module_name(_module_base(process), fallback="node"))
            class_name = naming.camel(module, fallback="Node")
            if not class_name.endswith("Node"):
                class_name += "Node"
            exe_value = prop(process, "Executable")
            exe_base = exe_value if isinstance(exe_value, str) and exe_value.strip() else module
            executable = script_tables[package].unique(naming.module_name(exe_base, fallback="node"))
            cls = builder.build(
                process,
                package=package,
                module=module,
                class_name=class_name,
                node_name=naming.node_name(_module_base(process)),
                executable=executable,
                signature=signature,
            )
            classes[key] = cls
            pkg.classes.append(cls)
            pkg.scripts.append(f"{executable} = {package}.{module}:main")
            plan.classes.append(cls)
        else:
            cls.instances.append(process)
        class_of[id(process)] = cls

    # Topics and services, then the node instances.
    port_features, access_features = [], []
    for process in processes:
        cls = class_of[id(process)]
        for port in cls.ports:
            feature = find_feature(process, port.rel_path)
            if feature is not None:
                port_features.append(feature)
        for service in cls.services:
            feature = find_feature(process, service.rel_path)
            if feature is not None:
                access_features.append(feature)
    node_names = {pid: name for pid, (_, name) in names.items()}
    topics = topology.groups("topic", _unique(port_features), node_names)
    services = topology.groups("service", _unique(access_features), node_names)
    idents = naming.NameTable({"imports", "actions"})
    for process in processes:
        cls = class_of[id(process)]
        namespace, node_name = names[id(process)]
        ident = idents.unique(naming.identifier(f"{namespace}_{node_name}" if namespace else node_name))
        plan.nodes.append(deployment.instance(process, cls, names[id(process)], ident, topics, services))
    plan.hosts = deployment.hosts

    # Packages: node packages, interfaces, bringup.
    definitions = catalog.definitions()
    for pkg in packages.values():
        used = sorted({i.package for cls in pkg.classes for i in cls.interfaces})
        pkg.depends = ["rclpy", *used]
        plan.packages.append(pkg)
    if definitions:
        deps = sorted({d for definition in definitions for d in definition.dependencies} - {interfaces_name})
        plan.interfaces = PackagePlan(
            name=interfaces_name,
            build_type="ament_cmake",
            description=f"Messages and services of {app} that are not standard ROS 2 interfaces.",
            depends=deps,
            exec_depends=["rosidl_default_runtime"],
            definitions=definitions,
        )
    if plan.nodes:
        _plan_launches(plan, instance, app)
        plan.bringup = PackagePlan(
            name=bringup_name,
            build_type="ament_python",
            description=f"Launch files of the deployments of {app}.",
            exec_depends=["launch", "launch_ros", *sorted(packages)],
            launch_files=[launch.file for launch in plan.launches],
        )
    plan.diagnostics = [
        *catalog.diagnostics,
        *topology.diagnostics,
        *builder.diagnostics,
        *deployment.diagnostics,
    ]
    _render_files(plan, options)
    return plan


def _unique(items: list[EObject]) -> list[EObject]:
    seen: set[int] = set()
    out = []
    for item in items:
        if id(item) not in seen:
            seen.add(id(item))
            out.append(item)
    return out


def _plan_launches(plan: WorkspacePlan, instance: EObject, app: str) -> None:

    what = instance.classifier or instance.name or app
    deployment = LaunchPlan(
        file=f"{app}.launch.py",
        marker=app,
        title=f"the deployment {app}",
        short=f"the deployment {app}",
        description=f"Every node of the AADL system {what}, with its processor binding (CPU affinity), "
        "its scheduling (SCHED_FIFO priority), its parameters and the remappings of its topics.",
        key=instance_key(instance),
        nodes=list(plan.nodes),
    )
    plan.launches.append(deployment)
    stems = naming.NameTable({app, "imports", "actions"})
    for host in plan.hosts:
        stem = stems.unique(host.ident)
        plan.launches.append(
            LaunchPlan(
                file=f"{stem}.launch.py",
                marker=stem,
                title=f"the nodes bound to host {stem}",
                short=f"the host {host.name}",
                description=f"The nodes of the AADL system {what} bound to {host.path}, with their CPU "
                "affinity, scheduling, parameters and remappings.",
                key=host.key,
                nodes=list(host.nodes),
            )
        )


# --------------------------------------------------------------------------- rendering


def _render_files(plan: WorkspacePlan, options: GenerationOptions) -> None:
    holder = options.copyright_holder or f"The {plan.app} authors"
    common = {
        "license": options.license,
        "holder": " ".join(holder.split()),
        "year": options.year or _default_year(),
        "maintainer": options.maintainer,
        "maintainer_email": options.maintainer_email,
        "version": options.version,
    }
    files = plan.files
    for pkg in plan.packages:
        _python_package(files, pkg, common)
        for cls in pkg.classes:
            path = f"{pkg.name}/{pkg.name}/{cls.module}.py"
            text = render_template(
                "node.py.j2",
                cls=cls,
                instance_paths=[_model.instance_path(p) for p in cls.instances],
                **common,
            )
            keys = {cls.marker(part): f"{cls.key}#{part}" for part in ("imports", "init", "members")}
            for thread in cls.threads:
                keys[thread.marker] = thread.key
                for port in thread.ports:
                    if port.marker:
                        keys[port.marker] = port.key
                for service in thread.services:
                    keys[service.marker] = service.key
            files.append(PlannedFile(path, text, "hash", keys))
    if plan.interfaces is not None:
        pkg = plan.interfaces
        files.append(
            PlannedFile(
                f"{pkg.name}/package.xml", render_template("package.xml.j2", pkg=pkg, **common), "xml"
            )
        )
        files.append(
            PlannedFile(f"{pkg.name}/CMakeLists.txt", render_template("CMakeLists.txt.j2", pkg=pkg), "hash")
        )
        for definition in pkg.definitions:
            files.append(
                PlannedFile(
                    f"{pkg.name}/{definition.type.kind}/{definition.file_name}",
                    render_template("interface.j2", pkg=pkg, definition=definition),
                    "hash",
                )
            )
    if plan.bringup is not None:
        pkg = plan.bringup
        _python_package(files, pkg, common)
        for launch in plan.launches:
            text = render_template("launch.py.j2", launch=launch, **common)
            keys = {launch.markers[node.ident]: node.key for node in launch.nodes}
            files.append(PlannedFile(f"{pkg.name}/launch/{launch.file}", text, "hash", keys))
    files.sort(key=lambda f: f.path)
    seen: set[str] = set()
    for planned in files:
        if planned.path in seen:
            raise GenerationError(f"two generated files would be {planned.path!r}")
        seen.add(planned.path)


def _python_package(files: list[PlannedFile], pkg: PackagePlan, common: dict) -> None:
    name = pkg.name
    files.append(
        PlannedFile(f"{name}/package.xml", render_template("package.xml.j2", pkg=pkg, **common), "xml")
    )
    files.append(PlannedFile(f"{name}/setup.py", render_template("setup.py.j2", pkg=pkg, **common), "hash"))
    files.append(PlannedFile(f"{name}/setup.cfg", render_template("setup.cfg.j2", pkg=pkg), "hash"))
    files.append(PlannedFile(f"{name}/resource/{name}", "", None))
    files.append(
        PlannedFile(
            f"{name}/{name}/__init__.py", render_template("package_init.py.j2", pkg=pkg, **common), "hash"
        )
    )
    for test in ("copyright", "flake8", "pep257"):
        files.append(
            PlannedFile(
                f"{name}/test/test_{test}.py",
                render_template(f"test_{test}.py.j2", pkg=pkg, **common),
                "hash",
            )
        )


# --------------------------------------------------------------------------- renames


def rename_map(trace: EObject | str | os.PathLike[str] | None) -> dict[str, str]:
    """Old element key → new element key, from a trace whose links go from the elements of the
    previous model (sources) to the elements they became (targets)."""
    if trace is None:
        return {}
    if isinstance(trace, (str, os.PathLike)):
        from rosaadl.transforms.trace import load_trace

        trace = load_trace(trace)
    trace = getattr(trace, "trace", trace)  # a TraceIndex
    mapping: dict[str, str] = {}
    for link in trace.links:
        sources = [end.path for end in link.sources if end.path]
        targets = [end.path for end in link.targets if end.path]
        if len(sources) == 1 and targets and sources[0] != targets[0]:
            mapping.setdefault(sources[0], targets[0])
    return mapping


def _renamed(key: str, mapping: dict[str, str]) -> str:
    """``key`` after the renames of ``mapping`` (a renamed container renames what it contains)."""
    seen = {key}
    current = key
    for _ in range(64):
        best = None
        for prefix, target in _prefixes(current, mapping):
            best = (prefix, target)
            break
        if best is None:
            return current
        current = best[1] + current[len(best[0]) :]
        if current in seen:
            return current
        seen.add(current)
    return current


def _prefixes(key: str, mapping: dict[str, str]):
    # longest prefix first, cut at step boundaries ("/" between elements, "#" before a role)
    position = len(key)
    while position > 0:
        prefix = key[:position]
        if prefix in mapping:
            yield prefix, mapping[prefix]
            return
        position = max(key.rfind("/", 0, position), key.rfind("#", 0, position))


# --------------------------------------------------------------------------- writing


@dataclass
class _OldBlock:
    path: str
    block: preservation.Block
    key: str | None
    used: bool = False


def _style_of(path: str) -> str | None:
    name = PurePosixPath(path).name
    if name.endswith(".xml"):
        return "xml"
    if name.endswith((".py", ".cfg", ".txt", ".msg", ".srv")) or name == "CMakeLists.txt":
        return "hash"
    return None


def _load_manifest(output: Path, result: GenerationResult) -> tuple[dict[tuple[str, str], str], list[str]]:
    """(file, marker) → element key, and the files, of the previous generation's trace."""
    path = output / MANIFEST_NAME
    if not path.is_file():
        return {}, []
    try:
        document = loads_bounded(path.read_bytes().decode("utf-8"))
        links = document["links"]
        if not isinstance(links, list):
            raise TypeError("links is not a list")
        keys: dict[tuple[str, str], str] = {}
        files: list[str] = []
        for link in links:
            rule = link["rule"]
            targets = [(str(t.get("uri") or ""), str(t.get("path") or "")) for t in link.get("targets", [])]
            sources = [str(t.get("path") or "") for t in link.get("sources", [])]
            if rule == "file":
                files.extend(uri for uri, _ in targets if uri)
            elif rule in ("user-code", "orphan"):
                for source in sources:
                    for uri, marker in targets:
                        if uri and marker and source:
                            keys[(uri, marker)] = source
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        # JsonLimitError (long integers, deep nesting) and UnicodeDecodeError are ValueErrors.
        # Regenerating without the trace would orphan the blocks of renamed elements: stop
        # before writing anything, and say how to go on.
        reason = f"{exc.__class__.__name__}: {exc}"
        raise GenerationError(
            f"the previous generation trace is unreadable ({reason[:200]}); nothing was written:"
            " restore the file from version control to use it, or delete it to regenerate without"
            " it (hand-written blocks are then kept by marker name, unmatched ones as orphans, and"
            " renames are not followed)",
            file=str(path),
        ) from None
    return keys, files


def _end(uri: str, path: str, class_name: str) -> dict[str, str]:
    return {"uri": uri, "path": path, "className": class_name}


def _manifest(plan: WorkspacePlan, orphan_keys: dict[tuple[str, str], str]) -> bytes:
    """The generation trace, a ``trace.ecore`` model in the JSON layout :func:`rosaadl.model.load`
    reads (written directly: it holds one link per block of the workspace)."""
    links: list[dict] = []
    for planned in plan.files:
        links.append({"rule": "file", "targets": [{"uri": planned.path, "className": "File"}]})
        for marker, key in sorted(planned.keys.items()):
            links.append(
                {
                    "rule": "user-code",
                    "sources": [_end("model", key, "InstanceObject")],
                    "targets": [_end(planned.path, marker, "UserCode")],
                }
            )
    for (path, name), key in sorted(orphan_keys.items()):
        links.append(
            {
                "rule": "orphan",
                "sources": [_end("model", key, "InstanceObject")],
                "targets": [_end(path, name, "UserCode")],
            }
        )
    document = {
        "eClass": "urn:rosaadl:trace:1.0#//Trace",
        "transformation": "rosaadl.exporters.rclpy",
        "links": links,
    }
    return (json.dumps(document, ensure_ascii=False, separators=(",", ":")) + "\n").encode("utf-8")


def _read(output: Path, path: str) -> str | None:
    target = safe_join(output, *PurePosixPath(path).parts)
    if not target.is_file():
        return None
    try:
        return target.read_bytes().decode("utf-8")
    except UnicodeDecodeError as exc:
        raise GenerationError(
            f"not UTF-8 text (byte {exc.start}); cannot merge user code", file=str(target)
        ) from None
    except OSError as exc:
        raise GenerationError(f"cannot read the file: {exc.strerror}", file=str(target)) from None


def _check_writable(root: Path, target: Path) -> None:
    """A file can be written at ``target``: it is not a folder, and no folder on its way is a file."""
    if target.is_dir():
        raise GenerationError("a folder is where a generated file goes", file=str(target))
    current = target.parent
    while current != root and root in current.parents:
        if current.exists() and not current.is_dir():
            raise GenerationError("a file is where a generated folder goes", file=str(current))
        current = current.parent


def _keep_year(old: str | None, new: str) -> str:
    """Keep the copyright year an existing file already carries."""
    if not old:
        return new
    found = _COPYRIGHT_RE.search(old[:2000])
    if found is None:
        return new
    return _COPYRIGHT_RE.sub(lambda m: m.group(1) + found.group(2) + m.group(3), new, count=1)


@checked
def generate_workspace(
    source: EObject,
    output: str | os.PathLike[str],
    *,
    root: str | None = None,
    options: GenerationOptions | None = None,
    force: bool = False,
    dry_run: bool = False,
    trace: EObject | str | os.PathLike[str] | None = None,
    rosmod_trace: EObject | None = None,
) -> GenerationResult:
    """Generate (or regenerate) the ROS 2 workspace of ``source`` into ``output`` (``WS/src``).

    ``trace`` tells renames of model elements since the previous generation: a trace model (or
    a saved one) whose links go from the old element (source, by its element key, see
    :func:`rosaadl.element_keys.element_key`) to the element it became (target); the blocks
    of a renamed element, and of everything it contains, move to their new markers.  ``force``
    overwrites files that carry no marker; ``dry_run`` computes everything and writes nothing.
    Errors are located :class:`~rosaadl.errors.RosaadlError` s raised before any file is written.
    """
    plan = plan_workspace(source, root=root, options=options, rosmod_trace=rosmod_trace)
    out = Path(output)
    if existing(out, GenerationError) and not out.is_dir():
        raise GenerationError("the output is not a directory", file=str(out))
    result = GenerationResult(output=out, plan=plan, dry_run=dry_run, diagnostics=list(plan.diagnostics))
    previous_keys, previous_files = _load_manifest(out, result) if out.is_dir() else ({}, [])
    renames = rename_map(trace)

    planned_paths = {f.path for f in plan.files}
    old_texts: dict[str, str] = {}
    old_parsed: dict[str, preservation.ParsedFile] = {}
    candidates = sorted(planned_paths | set(previous_files))
    for path in candidates:
        try:
            text = _read(out, path)
        except RosaadlError:
            if path in planned_paths:
                raise
            result.diagnostics.append(
                Diagnostic("warning", f"previous file {path!r} ignored", Location(file=path))
            )
            continue
        if text is None:
            continue
        old_texts[path] = text
        style = _style_of(path)
        if style is not None:
            old_parsed[path] = preservation.parse(text, style, filename=str(out / path))
        if path not in planned_paths:
            result.stale.append(path)

    # Every old block, and where the new markers are.
    old_blocks: list[_OldBlock] = []
    for path in sorted(old_parsed):
        parsed = old_parsed[path]
        for block in [*parsed.blocks.values(), *parsed.orphans.values()]:
            old_blocks.append(_OldBlock(path, block, previous_keys.get((path, block.name))))
    new_markers: dict[str, tuple[str, str]] = {}
    generated: dict[str, preservation.ParsedFile] = {}
    for planned in plan.files:
        if planned.style is None:
            continue
        parsed = preservation.parse(planned.text, planned.style, filename=planned.path)
        generated[planned.path] = parsed
        for name in parsed.blocks:
            key = planned.keys.get(name)
            if key is not None:
                new_markers.setdefault(key, (planned.path, name))

    # Place the old blocks: same file and name, then renamed or moved elements, then orphans.
    placed: dict[tuple[str, str], preservation.Content] = {}
    for old in old_blocks:
        if old.block.orphan:
            continue
        gen = generated.get(old.path)
        if gen is not None and old.block.name in gen.blocks:
            if not skeleton_before_twin(old.block.content, gen.blocks[old.block.name].content):
                placed[(old.path, old.block.name)] = old.block.content
            old.used = True
    for old in old_blocks:
        if old.used or old.key is None:
            continue
        new_key = _renamed(old.key, renames)
        target = new_markers.get(new_key)
        if target is None or target in placed:
            continue
        placed[target] = old.block.content
        old.used = True
        move = BlockMove(old.block.name, old.path, target[0], target[1])
        if old.block.orphan:
            result.restored.append(move)
        elif target != (old.path, old.block.name):
            result.moved.append(move)
    for old in old_blocks:
        if old.used or not old.block.orphan:
            continue
        gen = generated.get(old.path)
        name = old.block.name
        if gen is not None and name in gen.blocks and (old.path, name) not in placed:
            placed[(old.path, name)] = old.block.content
            old.used = True
            result.restored.append(BlockMove(name, old.path, old.path, name))

    orphans: dict[str, list[tuple[str, preservation.Content]]] = {}
    orphan_keys: dict[tuple[str, str], str] = {}
    for old in old_blocks:
        if old.used:
            continue
        if old.path not in generated:
            continue  # a stale or unmerged file keeps its blocks where they are
        orphans.setdefault(old.path, []).append((old.block.name, old.block.content))
        if old.key is not None:
            orphan_keys[(old.path, old.block.name)] = old.key
        if not old.block.orphan:
            result.orphaned.append(BlockMove(old.block.name, old.path, old.path, ""))

    # Final texts, conflicts, and the writes.
    outputs: list[tuple[str, str]] = []
    for planned in plan.files:
        old_text = old_texts.get(planned.path)
        old = old_parsed.get(planned.path)
        if planned.style is None:
            text = planned.text
        else:
            gen = generated[planned.path]
            path = planned.path
            text = preservation.render(
                gen,
                lambda block, path=path: placed.get((path, block.name)),
                orphans.get(path, []),
                planned.style,
            )
            text = _keep_year(old_text, text)
        if old_text is None:
            result.changes.append(FileChange(planned.path, "create"))
            outputs.append((planned.path, text))
        elif old_text == text:
            result.changes.append(FileChange(planned.path, "unchanged"))
        elif (old is None or not old.has_markers) and not force:
            reason = (
                "it has no user-code markers (not generated, or taken over by hand); use force to overwrite"
            )
            result.changes.append(FileChange(planned.path, "skip", reason))
            result.diagnostics.append(
                Diagnostic("warning", f"not overwritten: {reason}", Location(file=planned.path))
            )
        else:
            result.changes.append(FileChange(planned.path, "update"))
            outputs.append((planned.path, text))
    targets = [(safe_join(out, *PurePosixPath(path).parts), text) for path, text in outputs]
    manifest_target = safe_join(out, MANIFEST_NAME)
    for target, _ in [*targets, (manifest_target, "")]:
        _check_writable(out, target)
    if dry_run:
        return result
    try:
        out.mkdir(parents=True, exist_ok=True)
        planned_folders = {safe_join(out, *PurePosixPath(p.path).parts).parent for p in plan.files}
        sweep_temporaries(sorted(planned_folders | {out}))
        writes: list[tuple[Path, str | bytes]] = list(targets)
        manifest = _manifest(plan, orphan_keys)
        if not manifest_target.is_file() or manifest_target.read_bytes() != manifest:
            writes.append((manifest_target, manifest))
        # Each file is synced to disk; syncing many files concurrently is much faster.
        try:
            write_files(writes, workers=_WRITERS)
        except GenerationError:
            raise
        except ExportError as exc:
            raise GenerationError(f"cannot write the file: {exc.message}", exc.location) from None
    except OSError as exc:
        raise GenerationError(f"cannot write: {exc.strerror or exc}", file=str(exc.filename or out)) from None
    log.info(
        "generated %d files in %s (%d unchanged, %d skipped)",
        len(targets),
        out,
        len(result.paths("unchanged")),
        len(result.skipped),
    )
    return result
