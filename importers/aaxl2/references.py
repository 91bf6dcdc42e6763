"""References between instance objects, resolved once every object of the file exists.

The element readers queue each reference attribute on the reader (``Reader.pending``: the
object, the feature slot, the attribute's text and its element's line); :func:`resolve_pending`
then resolves each token, an EMF fragment path (``/``, ``/1``, ``//@componentInstance.4/@featureInstance.0``,
:func:`path_at`) or an ``xmi:id`` (2014 files), checks the target's class and sets the
feature. A dangling reference or one to the wrong class is a located error; an ``xmi:id``
met in a file read without its ids indexed raises :class:`IdsNeeded` (the file is read again).
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.bulk import FastFactory, stored_value
from rosaadl.errors import ImportFormatError

from .document import Reader
from .xmi import TAG_FEATURE

__all__ = ["resolve_pending", "resolve", "path_at", "name_held", "IdsNeeded"]


def resolve_pending(r: Reader) -> None:
    set_many, set_value = FastFactory.set_many, FastFactory.set_value
    cache: dict[str, EObject] = {}
    lists: dict[tuple, list] = {}
    # a pending reference keeps its element's line, not the element: holding tens of
    # thousands of lxml element proxies costs more to free than the references to resolve
    # the class checks are isinstance against the metamodel's Python classes, not model.is_a:
    # the same answer for the classes the reader makes, without is_a's call and cache lookup
    # (about 1 us each, 5-10 % of the import of the generated 50 000-object file)
    for obj, slot, text, line, attribute, many, names_of in r.pending:
        if not many:
            # most references (a connection's ends) take this path: one token, looked up in
            # `cache` alone (going through `lists` as well costs 1-3 ms on 50 000 objects)
            token = text.strip()
            target = cache.get(token)
            if target is None:
                target = cache[token] = resolve(r, token, line, attribute, text)
            expected = slot.target if names_of is None else r.cls[names_of]
            if not isinstance(target, expected):
                raise wrong_target(r, attribute, target, expected, line, text)
            set_value(obj, slot, target if names_of is None else name_held(target))
            continue
        # the same list is often written again and again (the modes a connection or a
        # value is in): each text is resolved and checked once per expected class
        expected = slot.target if names_of is None else r.cls[names_of]
        key = (text, expected, names_of is None)
        checked = lists.get(key)
        if checked is None:
            targets = []
            for token in text.split():
                target = cache.get(token)
                if target is None:
                    target = cache[token] = resolve(r, token, line, attribute, text)
                targets.append(target)
            for target in targets:
                if not isinstance(target, expected):
                    raise wrong_target(r, attribute, target, expected, line, text)
            if names_of is not None:
                targets = [name_held(target) for target in targets]
            checked = lists[key] = targets
        set_many(obj, slot, checked[:])  # set_many keeps the list it is given


def wrong_target(
    r: Reader, attribute: str, target: EObject, expected: type, line: int | None, text: str
) -> ImportFormatError:
    return r.error_at(
        f"{attribute} refers to a {target.eClass.name}, expected a {expected.eClass.name}",
        line,
        attribute,
        text,
    )


def resolve(r: Reader, token: str, line: int | None, attribute: str, text_of_attribute: str) -> EObject:
    text = token[1:] if token.startswith("#") else token
    if not text.startswith("/"):
        if not r.has_ids:
            raise IdsNeeded
        found = r.ids.get(text)
        if found is None:
            raise r.error_at(
                f"{attribute} refers to {token!r}, which no element of the file has as xmi:id",
                line,
                attribute,
                text_of_attribute,
            )
        return found
    found = path_at(r, text)
    if found is None:
        raise r.error_at(
            f"{attribute} refers to {token!r}, which is not an element of this file",
            line,
            attribute,
            text_of_attribute,
        )
    return found


def path_at(r: Reader, text: str) -> EObject | None:
    """The object at an EMF fragment path (``/``, ``/1``, ``//@a.2/@b.0``), or None; memoised."""
    found = r.path_cache.get(text)
    if found is not None:
        return found
    head, _, last = text.rpartition("/")
    if not last.startswith("@"):
        # the root: "/" or "" (first root), or "/<n>"
        if head or not (last == "" or last.isdigit()):
            return None
        position = int(last) if last else 0
        found = r.roots[position] if position < len(r.roots) else None
    else:
        parent = path_at(r, head or "/")
        tag, _, number = last[1:].partition(".")
        # only instance objects' containment features are named in TAG_FEATURE, and only the
        # features the reader filled are in an object's dict
        feature_name = TAG_FEATURE.get(tag)
        if parent is None or feature_name is None or not number.isdigit():
            return None
        items = parent.__dict__.get(feature_name)
        position = int(number)
        if items is None:
            return None
        items = FastFactory.items(items)
        if position >= len(items):
            return None
        found = items[position]
    r.path_cache[text] = found
    return found


def name_held(obj: EObject) -> str:
    """``obj.name or ""`` for an object the reader made, read as it is stored."""
    return stored_value(obj, "name") or ""


class IdsNeeded(Exception):
    """A reference names an ``xmi:id`` but the reader did not index them: read again with ids."""
