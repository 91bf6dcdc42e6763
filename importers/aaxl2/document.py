"""The state of one read of one ``.aaxl2`` document, and its helpers: :class:`Reader`.

A :class:`Reader` holds what every part of a read shares: the parsed tree, the metamodel
facts (copied in one step), the tables the element readers fill (objects by ``xmi:id``, the
roots, references to resolve once every object exists, positional literal hrefs to decode
once the era is known, the declarative URIs seen) and the per-read caches (``xsi:type`` by
its text, hrefs, link names). Its methods are the small helpers every element reader uses:
located errors and warnings, unknown elements, ``xsi:type`` and enumeration decoding, hrefs
and links into the declarative model, and the queueing of references for later.

The readers of instance elements, property values and declarative units are functions over a
:class:`Reader` (:mod:`.instances`, :mod:`.values`, :mod:`.declarative`); resolving the queued
references and decoding literals are :mod:`.references` and :mod:`.literals`.
"""

from __future__ import annotations

import os
from typing import Any

from lxml import etree
from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, ImportFormatError, Location, RosaadlError
from rosaadl.importers import osate_eras

from .metamodel import metamodel_facts
from .xmi import (
    NS_AADL2,
    XMI_ID_KEY,
    XSI_TYPE,
    XSI_TYPE_KEY,
    fragment_index_problem,
    link_class,
    name_of,
    split_ref_attribute,
)

__all__ = ["Reader", "directory_of"]


def directory_of(filename: str) -> str | None:
    """The directory a file's relative sidecar URIs resolve against (None for ``<...>`` names)."""
    if not filename or filename.startswith("<"):
        return None
    directory = os.path.dirname(filename)
    return directory if os.path.isabs(filename) else os.path.join(os.getcwd(), directory)


class Reader:
    """One read of one file (no state survives it): the shared state and its helpers."""

    def __init__(self, filename: str, tree: etree._ElementTree, *, strict: bool) -> None:
        meta = metamodel_facts()
        # what is the same for every read (metamodel classes, feature slots), in one step
        self.__dict__.update(meta.reader_constants)
        self.filename = filename
        self.tree = tree
        self.strict = strict
        # sidecar paths are normalised when they are looked up (ImportResult.sidecars)
        self.base_dir = directory_of(filename)
        self.warnings: list[Diagnostic] = []
        self.enum_cache: dict[tuple[str, str], Any] = dict(meta.enum_literals)
        self.ids: dict[str, EObject] = {}
        self.roots: list[EObject] = []
        # reference attributes to resolve once every object exists:
        # (object, slot, text, line of its element, attribute, many, names_of)
        self.pending: list[tuple] = []
        # positional literal hrefs into property sets, decoded once the era is known:
        # (uri, fragment, role, property, field href) → [(object, feature name)]
        self.literal_uses: dict[tuple, list[tuple[EObject, str]]] = {}
        self.href_cache: dict[str, tuple[str, str]] = {}
        self.link_names: dict[tuple[str | None, str | None], str] = {}
        # a unit's (href, property, field href) → (the unit kept until decoded, its literal_uses list)
        self.unit_uses: dict[tuple, tuple[str, list]] = {}
        self.xsi_cache: dict[tuple[str, str], tuple[str, str]] = {}
        self.unknown_tags: dict[tuple[str, str], int] = {}
        self.declarative_uris: set[str] = set()
        self.seen_uris: set[str] = set()
        # the root's namespace prefixes (lxml makes a new dict at each read of nsmap)
        self.nsmap: dict[str | None, str] = tree.getroot().nsmap
        self.has_ids = True
        self.nsmap_is_global = True
        self.property_cache: dict[str, tuple[str, bool]] = {}
        self.handler_cache: dict[str, Any] = {}
        self.link_types_ok: set[tuple[str | None, frozenset[str]]] = set()
        self.path_cache: dict[str, EObject] = {}
        # a record field's (uri, fragment) → (the name kept for it, whether it is positional)
        self.field_names: dict[tuple[str, str], tuple[str, bool]] = {}
        # a named value's (uri, fragment) → (its name, whether it is positional)
        self.named_values: dict[tuple[str, str], tuple[str, bool]] = {}

    def release(self) -> None:
        """Free the reader's tables before the parsed document (which goes with the caller's
        last reference to it, at the end of the call).

        In that order, nothing large is freed or allocated after the document within the call:
        glibc keeps the document's ~10^5 small freed nodes in its fast bins, and the next large
        request merges them all at once (about 40 ms for a 10 MB file, cold in the cache). Freed
        last, they are reused chunk for chunk by the next parse instead, as by a bare parse.
        """
        tree = self.tree
        self.__dict__.clear()
        del tree

    # ------------------------------------------------------------------ helpers

    def location(self, element: etree._Element | None, attribute: str | None = None) -> Location:
        if element is None:
            return Location(file=self.filename)
        try:
            path = self.tree.getpath(element)
        except ValueError:
            path = None
        if path and attribute:
            path = f"{path}/@{attribute}"
        return Location(file=self.filename, line=element.sourceline, path=path)

    def error(self, message: str, element: etree._Element | None = None, attribute: str | None = None):
        return ImportFormatError(message, self.location(element, attribute))

    def error_at(self, message: str, line: int | None, attribute: str, text: str) -> ImportFormatError:
        """An error located at the element of ``line`` whose ``attribute`` is ``text``."""
        for element in self.tree.getroot().iter():
            if element.sourceline == line and element.get(attribute) == text:
                return self.error(message, element, attribute)
        return ImportFormatError(message, Location(file=self.filename, line=line))

    def warn(self, message: str, element: etree._Element | None = None) -> None:
        self.warnings.append(Diagnostic("warning", message, self.location(element)))

    def unknown(self, element: etree._Element, parent: str) -> None:
        tag = element.tag
        if not isinstance(tag, str):  # comments, processing instructions
            return
        if self.strict:
            raise self.error(f"unexpected element <{tag}> in {parent}", element)
        key = (parent, tag)
        if key not in self.unknown_tags:
            self.warn(f"skipped unknown element <{tag}> in {parent} (and any further ones there)", element)
        self.unknown_tags[key] = self.unknown_tags.get(key, 0) + 1

    def xsi_type(self, element: etree._Element, required: bool = True) -> tuple[str, str] | None:
        """(namespace URI, local name) of the element's ``xsi:type``."""
        text = element.get(XSI_TYPE)
        if text is None:
            if required:
                raise self.error(f"<{element.tag}> has no xsi:type; expected one naming its class", element)
            return None
        key = (text, "")
        found = self.xsi_cache.get(key)
        if found is None:
            prefix, sep, local = text.rpartition(":")
            ns = self.nsmap.get(prefix if sep else None)
            if ns is None:
                ns = element.nsmap.get(prefix if sep else None)
            if ns is None:
                raise self.error(
                    f"xsi:type {text!r} uses an undeclared namespace prefix", element, "xsi:type"
                )
            found = (ns, local)
            if self.nsmap_is_global:
                self.xsi_cache[key] = found
        return found

    def enum(self, enum_name: str, text: str, element: etree._Element, attribute: str):
        key = (enum_name, text)
        literal = self.enum_cache.get(key)
        if literal is None:
            try:
                literal = self.enums[enum_name].from_string(text)
            except RosaadlError as exc:
                raise self.error(exc.message, element, attribute) from None
            self.enum_cache[key] = literal
        return literal

    def int_text(self, text: str | None, element: etree._Element, attribute: str) -> int:
        if text is None:
            return 0
        try:
            return int(text.strip())
        except ValueError:
            raise self.error(f"{attribute} {text!r} is not an integer", element, attribute) from None

    def href(self, element: etree._Element) -> tuple[str, str]:
        """(uri, fragment) of a link element's ``href``."""
        text = element.get("href")
        if text is None:
            raise self.error(f"<{element.tag}> has no href", element)
        found = self.href_cache.get(text)
        if found is None:
            uri, _, frag = text.partition("#")
            self.check_fragment(frag, element, "href")
            found = (uri, frag)
            self.href_cache[text] = found
            self.note_uri(uri)
        return found

    def check_fragment(self, fragment: str, element: etree._Element, attribute: str) -> None:
        """A located error when the positions of the fragment path of ``element``'s
        ``attribute`` are malformed (:func:`~.xmi.fragment_index_problem`)."""
        problem = fragment_index_problem(fragment)
        if problem is not None:
            raise self.error(f"{attribute} #{fragment}: {problem}", element, attribute)

    def link_checked(self, element: etree._Element) -> None:
        """A link element whose target the instance object already names (a subcomponent's, a
        feature's): only its href's presence and file are noted (see :attr:`ImportResult.sidecars`)."""
        text = element.get("href")
        if text is None:
            raise self.error(f"<{element.tag}> has no href", element)
        uri, _, frag = text.partition("#")
        self.check_fragment(frag, element, "href")
        self.note_uri(uri)

    def note_uri(self, uri: str) -> None:
        if uri and uri not in self.seen_uris:
            self.seen_uris.add(uri)
            if osate_eras.classify_uri(uri) is None:
                self.declarative_uris.add(uri)

    def check_link_type(self, element: etree._Element, allowed: frozenset[str]) -> None:
        key = (element.get(XSI_TYPE_KEY), allowed)
        if key in self.link_types_ok:
            return
        ns, local = self.xsi_type(element)
        if ns == NS_AADL2 and local in allowed:
            if self.nsmap_is_global:
                self.link_types_ok.add(key)
            return
        raise self.error(
            f"<{element.tag}> has unknown xsi:type {element.get(XSI_TYPE)!r} "
            f"(expected aadl2: one of {', '.join(sorted(allowed))})",
            element,
            "xsi:type",
        )

    def link_name(self, element: etree._Element) -> str:
        """The name a link element's ``href`` is kept as (see :func:`name_of`; its ``xsi:type``
        tells the class of the element a fragment by name designates), one string per href."""
        xsi_type = element.get(XSI_TYPE_KEY)
        key = (element.get("href"), xsi_type)
        name = self.link_names.get(key)
        if name is None:
            name = self.link_names[key] = name_of(*self.href(element), link_class(xsi_type, element.tag))
        return name

    def typed_link(self, el: etree._Element, tag: str, owner: str) -> tuple[str | None, str, str] | None:
        """(class, uri, fragment) of the link ``tag`` of ``el``: a child element, or else the
        attribute form EMF also writes (None when there is neither); the class is the ``aadl2``
        class its ``xsi:type`` names (:func:`~.xmi.link_class`), or None."""
        target = None
        for child in el:
            if child.tag == tag:
                target = (link_class(child.get(XSI_TYPE_KEY), tag), *self.href(child))
            else:
                self.unknown(child, owner)
        if target is None and el.get(tag) is not None:
            xsi_type, uri, frag = split_ref_attribute(el.get(tag))
            self.check_fragment(frag, el, tag)
            target = (link_class(xsi_type, tag), uri, frag)
        return target

    def link(self, el: etree._Element, tag: str, owner: str) -> tuple[str, str] | None:
        """(uri, fragment) of the link ``tag`` of ``el``: a child element, or else the attribute
        form EMF also writes; None when there is neither."""
        target = self.typed_link(el, tag, owner)
        return None if target is None else target[1:]

    def ref_later(self, obj, feature, element, attribute, *, many=False, names_of: str | None = None) -> None:
        """Resolve reference ``attribute`` into ``feature`` once every object exists.

        ``names_of``: the feature holds the *names* of the referenced objects, which must be of
        that class (modes in which a component or a value exists).
        """
        text = element.get(attribute)
        if text is not None and text.strip():
            self.pending.append((obj, feature, text, element.sourceline, attribute, many, names_of))

    def literal_use(self, key: tuple, obj: EObject, feature_name: str) -> None:
        self.literal_uses.setdefault(key, []).append((obj, feature_name))

    def ends_later(
        self, obj: EObject, el: etree._Element, ends: tuple, what: str, name: str | None = None
    ) -> None:
        """Resolve later each of ``ends`` (``(attribute, slot)`` pairs of single-valued
        references), which ``el`` must have (a connection's, a connection reference's).
        ``what`` and ``name`` say what ``el`` is, in the error when one is missing."""
        line = el.sourceline
        append = self.pending.append
        for attribute, slot in ends:
            text = el.get(attribute)
            if text is None:
                named = what if name is None else f"{what} {name!r}"
                raise self.error(f"{named} has no {attribute}", el)
            if text.strip():
                append((obj, slot, text, line, attribute, False, None))

    def register_id(self, obj: EObject, element: etree._Element) -> None:
        """Index ``obj`` by its element's ``xmi:id`` (callers check :attr:`has_ids` first)."""
        xid = element.get(XMI_ID_KEY)
        if xid is not None:
            self.ids[xid] = obj
