"""The AADL component library: every file parses, and its names and values are consistent.

Besides parsing each ``library/**/*.aadl`` file with the grammar, these tests check from the
syntax trees alone what OSATE would reject when loading the library:

* one model unit per file, named like the file, and no two units with the same name (packages
  and property sets share one case-insensitive namespace);
* every classifier named ``Pkg::Name`` lives in a package that the file names in a ``with``
  clause, and exists there; every unqualified classifier exists in the same package;
* every property is declared: ``Set::Name`` in a ``with``-ed property set, a bare name in one of
  the predeclared sets; every ``with`` clause is used;
* every value fits its property's type: integer vs real literals, unit literals of the
  property's units type, enumeration literals, strings, booleans, ranges, lists, references.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import pytest
from lark import Token, Tree

from rosaadl.importers.aadl_syntax import parse

ROOT = Path(__file__).resolve().parents[2]
LIBRARY = ROOT / "library"
FILES = sorted(LIBRARY.rglob("*.aadl"))
IDS = [str(path.relative_to(LIBRARY)) for path in FILES]
PACKAGES = [path for path in FILES if re.search(r"^\s*package\b", path.read_text("utf-8"), re.M | re.I)]
PACKAGE_IDS = [str(path.relative_to(LIBRARY)) for path in PACKAGES]

# Predeclared property sets (SAE AS5506C Appendix A): visible without a ``with`` clause.
PREDECLARED = (
    "deployment_properties",
    "thread_properties",
    "timing_properties",
    "communication_properties",
    "memory_properties",
    "programming_properties",
    "modeling_properties",
    "aadl_project",
)

# The library content of the paper ("Multi-Paradigm Modeling ... Library of AADL Models").
PAPER_UNITS = (
    "ros",
    "ros_data",
    "nd_usb_cam",
    "nd_pos_to_cmd",
    "nd_ocv_color_tracking",
    "USB",
    "ETHERNET",
    "Raspberry_PI4B",
    "leo_rover",
    "sw_rover",
    "sys_rover",
    "sw_tracking",
    "sys_tracking",
    "pioneer_3dx",
    "Odroid_XU4",
    "Exynos_5422",
)


@dataclass
class Unit:
    """What the checks need to know of one package or property set."""

    name: str
    kind: str  # "package" | "property_set"
    path: Path
    tree: Tree
    withs: dict[str, str] = field(default_factory=dict)  # lower-case name -> as written
    classifiers: set[str] = field(default_factory=set)  # "type" and "type.impl", lower case
    properties: dict[str, Tree] = field(default_factory=dict)  # property name -> its type tree
    types: dict[str, Tree] = field(default_factory=dict)  # property type name -> type tree


def _ids(tree: Tree) -> list[str]:
    return [child.value for child in tree.children if isinstance(child, Token) and child.type == "ID"]


def _qname(tree: Tree) -> str:
    return "::".join(_ids(tree))


def _first_id(tree: Tree) -> str:
    return next(child.value for child in tree.children if isinstance(child, Token) and child.type == "ID")


def _build(path: Path) -> Unit:
    spec = parse(path.read_bytes(), str(path))
    assert len(spec.children) == 1, f"{path.name}: one package or property set per file"
    tree = spec.children[0]
    if tree.data == "package":
        unit = Unit(_qname(tree.children[0]), "package", path, tree)
        for section in tree.children:
            if not isinstance(section, Tree) or section.data not in ("public_section", "private_section"):
                continue
            for item in section.children:
                if item.data == "with_clause":
                    for qname in item.children:
                        unit.withs[_qname(qname).lower()] = _qname(qname)
                elif item.data == "component_type":
                    unit.classifiers.add(_first_id(item).lower())
                elif item.data == "component_implementation":
                    impl = next(c for c in item.children if isinstance(c, Tree) and c.data == "impl_name")
                    unit.classifiers.add(".".join(_ids(impl)).lower())
    else:
        unit = Unit(_first_id(tree), "property_set", path, tree)
        for item in tree.children:
            if not isinstance(item, Tree):
                continue
            if item.data == "with_clause":
                for qname in item.children:
                    unit.withs[_qname(qname).lower()] = _qname(qname)
            elif item.data == "property_definition":
                unit.properties[_first_id(item).lower()] = item.children[2]
            elif item.data == "property_type_declaration":
                unit.types[_first_id(item).lower()] = item.children[1]
            elif item.data == "property_constant":
                unit.types.setdefault(_first_id(item).lower(), item.children[1])
    return unit


@lru_cache(maxsize=1)
def _units() -> dict[str, Unit]:
    units: dict[str, Unit] = {}
    for path in FILES:
        unit = _build(path)
        key = unit.name.lower()
        assert key not in units, f"{unit.name} declared in {units[key].path} and {path}"
        units[key] = unit
    return units


def _unit_of(path: Path) -> Unit:
    return next(unit for unit in _units().values() if unit.path == path)


# ---------------------------------------------------------------------------- parsing


@pytest.mark.parametrize("path", FILES, ids=IDS)
def test_file_parses(path: Path) -> None:
    tree = parse(path.read_bytes(), str(path))
    assert tree.data == "specification"
    assert path.read_bytes().isascii(), f"{path.name}: AADL text of the library is plain ASCII"


def test_library_has_the_papers_packages() -> None:
    names = {unit.name for unit in _units().values()}
    missing = [name for name in PAPER_UNITS if name not in names]
    assert not missing, f"missing packages: {missing}"
    assert len(FILES) >= 35


@pytest.mark.parametrize("path", FILES, ids=IDS)
def test_unit_is_named_like_its_file(path: Path) -> None:
    assert _unit_of(path).name == path.stem


def test_global_names_are_unique_case_insensitively() -> None:
    seen: dict[str, str] = {}
    for unit in _units().values():
        key = unit.name.lower()
        assert key not in seen, f"{unit.name} clashes with {seen[key]}"
        seen[key] = unit.name
    assert "ros" in seen and "ros_properties" in seen  # the ROS set is not named "ROS"


# ---------------------------------------------------------------------------- references


def _classifier_problems(unit: Unit) -> list[str]:
    units = _units()
    problems = []
    for ref in unit.tree.find_data("classifier_ref"):
        *names, impl = ref.children
        names = [token.value for token in names]
        local = names[-1] + (f".{impl.value}" if impl is not None else "")
        line = ref.meta.line
        if len(names) == 1:
            if local.lower() not in unit.classifiers:
                problems.append(f"line {line}: {local} is not declared in {unit.name}")
            continue
        package = "::".join(names[:-1])
        target = units.get(package.lower())
        if target is None or target.kind != "package":
            problems.append(f"line {line}: no package {package} in the library")
        elif package.lower() not in unit.withs and package.lower() != unit.name.lower():
            problems.append(f"line {line}: {package} is not in a with clause")
        elif local.lower() not in target.classifiers:
            problems.append(f"line {line}: {package}::{local} does not exist")
    return problems


def _property_set_of(unit: Unit, qualified: str) -> tuple[Unit | None, str, str | None]:
    """``(property set, property name, problem)`` for a property name as written in ``unit``."""
    units = _units()
    set_name, _, name = qualified.rpartition("::")
    if set_name:
        owner = units.get(set_name.lower())
        if owner is None or owner.kind != "property_set":
            return None, name, f"no property set {set_name}"
        if (
            set_name.lower() not in unit.withs
            and set_name.lower() != unit.name.lower()
            and set_name.lower() not in PREDECLARED
        ):
            return None, name, f"{set_name} is not in a with clause"
        if name.lower() not in owner.properties:
            return None, name, f"{qualified} is not declared in {owner.name}"
        return owner, name, None
    for predeclared in PREDECLARED:
        owner = units.get(predeclared)
        if owner is not None and name.lower() in owner.properties:
            return owner, name, None
    return None, name, f"{name} is not a predeclared property (qualify it with its property set)"


def _used_names(unit: Unit) -> set[str]:
    """Lower-case package and property set names that the unit's text refers to."""
    used: set[str] = set()
    for ref in unit.tree.find_data("classifier_ref"):
        names = [token.value for token in ref.children[:-1]]
        if len(names) > 1:
            used.add("::".join(names[:-1]).lower())
    for data in ("qname", "named_value"):
        for node in unit.tree.find_data(data):
            names = _ids(node)
            if len(names) > 1:
                used.add("::".join(names[:-1]).lower())
    return used


@pytest.mark.parametrize("path", PACKAGES, ids=PACKAGE_IDS)
def test_classifier_references_resolve(path: Path) -> None:
    unit = _unit_of(path)
    assert unit.kind == "package"
    assert _classifier_problems(unit) == []


@pytest.mark.parametrize("path", FILES, ids=IDS)
def test_with_clauses_name_existing_and_used_units(path: Path) -> None:
    unit = _unit_of(path)
    units = _units()
    used = _used_names(unit)
    for key, written in unit.withs.items():
        assert key in units, f"{unit.name}: with {written}: no such package or property set"
        assert key in used, f"{unit.name}: with {written} is not used"


# ---------------------------------------------------------------------------- values


def _resolve_type(owner: Unit, tree: Tree) -> tuple[Unit, Tree]:
    """Follow named property types (``AADL_Project::Time``) to their definition."""
    while tree.data == "qname":
        set_name, _, name = _qname(tree).rpartition("::")
        owner = _units()[set_name.lower()] if set_name else owner
        tree = owner.types[name.lower()]
    return owner, tree


def _unit_literals(owner: Unit, type_tree: Tree) -> list[str] | None:
    """The unit literals of a number type, or None when it has no units."""
    spec = type_tree.children[1]
    if spec is None:
        return None
    if spec.data == "units_ref":
        owner, spec = _resolve_type(owner, spec.children[0])
    literals = [spec.children[0].value]
    literals += [conversion.children[0].value for conversion in spec.children[1:]]
    return [literal.lower() for literal in literals]


def _value_problems(owner: Unit, type_tree: Tree, value: Tree) -> list[str]:
    owner, type_tree = _resolve_type(owner, type_tree)
    kind = type_tree.data
    if value.data == "named_value" and len(_ids(value)) > 1 and kind != "enumeration_type":
        return []  # a property constant (Set::Name): its own type is checked where declared
    if kind in ("integer_type", "real_type"):
        wanted = "integer_value" if kind == "integer_type" else "real_value"
        if value.data != wanted:
            return [f"expected {wanted.replace('_', ' ')}, found {value.data.replace('_', ' ')}"]
        unit = value.children[2]
        literals = _unit_literals(owner, type_tree)
        if literals is None:
            return [f"unexpected unit {unit.value}"] if unit is not None else []
        if unit is None:
            return [f"missing unit, one of {literals}"]
        if unit.value.lower() not in literals:
            return [f"unit {unit.value} is not one of {literals}"]
        return []
    if kind == "enumeration_type":
        literals = [token.value.lower() for token in type_tree.children]
        names = _ids(value) if value.data == "named_value" else []
        if len(names) != 1 or names[0].lower() not in literals:
            return [f"expected one of {literals}"]
        return []
    if kind == "range_type":
        if value.data != "range_value":
            return ["expected a range"]
        lower, upper, _delta = value.children
        inner = type_tree.children[0]
        return _value_problems(owner, inner, lower) + _value_problems(owner, inner, upper)
    if kind == "list_type":
        if value.data != "list_value":
            return ["expected a list (in parentheses)"]
        inner = type_tree.children[0]
        return [problem for item in value.children for problem in _value_problems(owner, inner, item)]
    expected = {
        "string_type": "string_value",
        "boolean_type": "boolean_value",
        "reference_type": "reference_value",
        "classifier_type": "classifier_value",
        "record_type": "record_value",
    }.get(kind)
    if expected is not None and value.data != expected:
        return [f"expected {expected.replace('_', ' ')}, found {value.data.replace('_', ' ')}"]
    return []


def _association_problems(unit: Unit) -> list[str]:
    problems = []
    for association in unit.tree.find_data("property_association"):
        name = _qname(association.children[0])
        line = association.children[0].meta.line
        owner, short, problem = _property_set_of(unit, name)
        if problem is not None:
            problems.append(f"line {line}: {problem}")
            continue
        assert owner is not None
        value = association.children[3]
        for found in _value_problems(owner, owner.properties[short.lower()], value):
            problems.append(f"line {line}: {name}: {found}")
    return problems


@pytest.mark.parametrize("path", FILES, ids=IDS)
def test_property_associations_are_declared_and_well_typed(path: Path) -> None:
    unit = _unit_of(path)
    assert _association_problems(unit) == []


# ---------------------------------------------------------------------------- the checks catch errors


def _check_text(tmp_path: Path, name: str, text: str) -> Unit:
    path = tmp_path / f"{name}.aadl"
    path.write_text(text, encoding="utf-8")
    return _build(path)


def test_checks_reject_a_bad_unit_an_unknown_classifier_and_a_missing_with(tmp_path: Path) -> None:
    unit = _check_text(
        tmp_path,
        "bad_node",
        """package bad_node
        public
          with ros;
          process p extends ros::nodee end p;
          process implementation p.impl
            subcomponents
              t: thread q.impl;
              d: data ros_data::Image.rgb;
          end p.impl;
        end bad_node;
        """,
    )
    problems = _classifier_problems(unit)
    assert any("ros::nodee does not exist" in p for p in problems)
    assert any("q.impl is not declared" in p for p in problems)
    assert any("ros_data is not in a with clause" in p for p in problems)


def test_checks_reject_wrong_units_literals_and_undeclared_properties(tmp_path: Path) -> None:
    unit = _check_text(
        tmp_path,
        "bad_values",
        """package bad_values
        public
          with SEI;
          bus b
            properties
              SEI::BandWidthCapacity => 480 Mbps;
          end b;
          bus implementation b.i
            properties
              SEI::BandWidthCapacity => 480.0 Mbitsps;
              Dispatch_Protocol => Cyclic;
              Period => 10.0 ms;
              Compute_Execution_Time => 1 us;
              ROS_Profiling::IPC => 1.0;
              Frobnication => 3;
          end b.i;
        end bad_values;
        """,
    )
    problems = "\n".join(_association_problems(unit))
    assert "expected real value, found integer value" in problems
    assert "unit Mbitsps is not one of" in problems
    assert "Dispatch_Protocol: expected one of" in problems
    assert "Period: expected integer value" in problems
    assert "Compute_Execution_Time: expected a range" in problems
    assert "ROS_Profiling is not in a with clause" in problems
    assert "Frobnication is not a predeclared property" in problems
