"""Bulk construction of model objects, for the readers and the instantiator.

pyecore spends most of an object's creation on change notifications, type checks and a
process-wide registry of every object; a reader that makes tens of thousands of new,
unobserved objects needs none of that. :class:`FastFactory` fills pyecore's own state directly
(value holders, containers) and leaves the rest (``_isset``, inverse references, listener
lists) to be made on first read from what the object holds, so the objects behave exactly like
ones made with :func:`rosaadl.model.new` (saving, setters, ``delete()``; tested).
:class:`FastBuilder` is the same by feature *name*, for code that is not a hot loop's inner
body. :func:`gc_paused` keeps the cyclic garbage collector out of the way while building.
"""

from __future__ import annotations

import gc
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from functools import cache
from typing import Any

import pyecore
from pyecore.ecore import EClass, EEnum, EObject
from pyecore.innerutils import InternalSet
from pyecore.ordered_set_patch import ordered_set
from pyecore.valuecontainer import EBag, EList, EOrderedSet, ESet, EValue

from rosaadl import metamodels
from rosaadl.errors import ModelError

__all__ = ["FeatureSlot", "FastFactory", "FastBuilder", "gc_paused", "check_pyecore_version"]

#: The pyecore releases whose internals this module was tested against (``pyproject.toml`` pins the same).
TESTED_PYECORE = "0.15"


def check_pyecore_version(version: str) -> None:
    """Refuse a pyecore other than the tested minor version: this module fills pyecore's own
    object state (value holders, containers), which another release may lay out differently."""
    if version.split(".")[:2] != TESTED_PYECORE.split("."):
        raise ImportError(
            f"rosaadl needs pyecore {TESTED_PYECORE}.x (it builds pyecore objects directly), "
            f"but pyecore {version} is installed: pip install 'pyecore=={TESTED_PYECORE}.*'",
            name=__name__,
        )


check_pyecore_version(pyecore.__version__)  # the module's own, no scan of the installed metadata

OrderedSet = ordered_set.OrderedSet


_object_new = object.__new__
# pyecore's ordered sets are ``ordered_set.OrderedSet`` subclasses holding ``items`` and ``map``
# (pyecore's own patches of that class rely on both); fill them directly when that holds.
_probe = OrderedSet()
_ORDERED_SET_FIELDS = isinstance(getattr(_probe, "items", None), list) and isinstance(
    getattr(_probe, "map", None), dict
)
del _probe


# what ``EObject.__new__`` sets to None on every object, until pyecore sets it
_NONE_ATTRIBUTES = ("_internal_id", "_container", "_containment_feature", "_eresource")


class _MadeOnRead:
    """A class-level default for a per-object list pyecore makes in ``EObject.__new__``
    (``listeners``, ``_eternal_listener``): an empty list made on the first read and kept on
    the object from then on (a non-data descriptor, so the object's own value wins)."""

    __slots__ = ("name",)

    def __init__(self, name: str) -> None:
        self.name = name

    def __get__(self, obj, owner=None):
        if obj is None:
            return self
        value = obj.__dict__[self.name] = []
        return value


class _IndexOnRead:
    """The default of an ordered set's ``map`` (each item's position, which ``OrderedSet`` keeps
    beside ``items``): made on the first read from ``items`` and kept on the set from then on (a
    non-data descriptor, so the set's own value wins). :meth:`FastFactory.set_many` leaves it
    out of a set of one item, the most common (the single value of most property
    associations): a dictionary per such set costs a quarter of what its item does."""

    __slots__ = ()

    def __get__(self, obj, owner=None):
        if obj is None:
            return self
        index = obj.__dict__["map"] = {item: position for position, item in enumerate(obj.items)}
        return index


class _IssetOnRead:
    """The default of ``_isset`` (the features pyecore saves, in the order they were set): made
    on the first read from the object's value holders and collections that :class:`FastFactory`
    made (instances of :class:`_Built`, in the order they were stored), then kept on the object.

    pyecore only ever adds to ``_isset``, and always through a read of it, so this is the set
    pyecore would hold: every feature FastFactory filled, then pyecore's own additions. A holder
    pyecore's getter makes for a feature never set is not a ``_Built`` one and does not count.
    """

    __slots__ = ()

    def __get__(self, obj, owner=None):
        if obj is None:
            return self
        d = obj.__dict__
        isset = InternalSet()
        for value in d.values():
            if isinstance(value, _Built):
                isset[value.feature] = None
        d["_isset"] = isset
        return isset


class _InverseOnRead:
    """The default of ``_inverse_rels`` (the ``(owner, feature)`` pairs that refer to the
    object, which pyecore's ``delete()`` follows): made on the first read, then kept on the
    object. Most objects are only contained, and nothing else refers to them, so most never
    need one.

    It starts with the containment pair :class:`FastFactory` recorded (``_built_containment``),
    not with ``_container``: pyecore clears ``_container`` before it takes the pair out of this
    set, so the pair must be known without it. pyecore changes a container only together with
    this set (it takes the old pair out, puts the new one in), so when first read, the set
    pyecore would hold is still the recorded pair. A non-containment reference is added
    through a read, so the set exists before anything else refers to the object.
    """

    __slots__ = ()

    def __get__(self, obj, owner=None):
        if obj is None:
            return self
        d = obj.__dict__
        built = d.get("_built_containment")
        rels = d["_inverse_rels"] = set() if built is None else {built}
        return rels


class _Itself:
    """The default of ``dyn_inst``: pyecore sets it to the object itself on every object, and
    to the ``EClass`` on the class (which this keeps for reads on the class)."""

    __slots__ = ("eclass",)

    def __init__(self, eclass) -> None:
        self.eclass = eclass

    def __get__(self, obj, owner=None):
        return self.eclass if obj is None else obj


def _class_defaults(cls: type) -> None:
    """Give a metamodel class (not its subclasses: each class has its own ``dyn_inst``) the
    defaults :meth:`FastFactory.new` leaves out of its objects.

    Reading an attribute an object does not have falls back to its class, so ``None`` there
    reads as pyecore's ``None`` on the object, and the descriptors make what pyecore would
    have made; writing one (``obj._container = parent``) stores it on the object.
    ``_staticEClass`` is ``False`` on every class made from an ``EClass`` (pyecore sets it
    so), which is what a dynamic object reads; a static class is refused.
    """
    if cls.__dict__.get("_staticEClass", True) is not False:
        raise ModelError(f"{cls.__name__} is not a class made from an EClass; use its constructor")
    for name in _NONE_ATTRIBUTES:
        setattr(cls, name, None)
    cls._isset = _IssetOnRead()
    cls._inverse_rels = _InverseOnRead()
    cls.listeners = _MadeOnRead("listeners")
    cls._eternal_listener = _MadeOnRead("_eternal_listener")
    eclass = cls.__dict__.get("dyn_inst")
    cls.dyn_inst = eclass if isinstance(eclass, _Itself) else _Itself(eclass)
    cls._fast_defaults = cls  # read by FastFactory.new: set on this class, not inherited


class _Built:
    """Marks the value holders and collections :class:`FastFactory` makes (see :class:`_IssetOnRead`)."""

    __slots__ = ()


class _Shared:
    """A class attribute whose value is itself a descriptor (a pyecore feature is one): read
    from an object, it gives that value; an object may still set its own (non-data descriptor)."""

    __slots__ = ("value",)

    def __init__(self, value) -> None:
        self.value = value

    def __get__(self, obj, owner=None):
        return self.value


def _holder_class(base: type, feature, **attributes: Any) -> type:
    """A subclass of pyecore's value holder or collection ``base`` for one feature, holding on
    the class what is the same for all of that feature's values (the feature, whether it is a
    reference or a containment, no generic type yet): pyecore reads these as attributes, and
    writes them (``generic_type``) on the holder itself."""
    is_ref = bool(feature.is_reference)
    namespace = {
        "__module__": base.__module__,
        "__qualname__": base.__qualname__,
        "feature": _Shared(feature),
        "is_ref": is_ref,
        "is_cont": bool(is_ref and feature.containment),
        "generic_type": None,
        **attributes,
    }
    return type(base.__name__, (base, _Built), namespace)


@cache
def _value_holder(feature) -> type:
    """pyecore's value holder (``EValue``) for the values of one single-valued feature: each
    stores only its owner and its value, in slots (read and written as attributes, not in
    ``__dict__``), about a third less memory than an ``EValue`` and four writes fewer."""
    return _holder_class(EValue, feature, __slots__=("owner", "_value"))


@cache
def _ordered_set_holder(feature) -> type:
    """pyecore's ordered set (``EOrderedSet``) for the values of one many-valued feature: each
    stores only its owner and its items (``items`` and ``map``, as ``OrderedSet`` keeps them)."""
    return _holder_class(
        EOrderedSet, feature, _orderedset_update=False, _items_field=True, map=_IndexOnRead()
    )


@cache
def _collection_holder(base: type, feature) -> type:
    """pyecore's collection ``base`` for the values of one many-valued feature, made through its
    constructor (the ordered sets that can be are filled directly: :func:`_ordered_set_holder`)."""
    return _holder_class(base, feature)


class FeatureSlot:
    """A structural feature with what :class:`FastFactory` needs to know about it, looked up once."""

    __slots__ = ("feature", "name", "is_ref", "containment", "many", "collection", "target", "holder")

    def __init__(self, feature) -> None:
        self.feature = feature
        self.name = feature.name
        self.is_ref = bool(feature.is_reference)
        self.containment = bool(self.is_ref and feature.containment)
        self.many = bool(feature.many)
        self.collection = None
        self.holder = None if self.many else _value_holder(feature)
        if self.many:
            if feature.derived:
                raise ModelError(f"{feature.name} is derived; it cannot be filled")
            if feature.ordered and feature.unique:
                base = EOrderedSet
            elif feature.ordered:
                base = EList
            elif feature.unique:
                base = ESet
            else:
                base = EBag
            if base is EOrderedSet and _ORDERED_SET_FIELDS:
                self.holder = _ordered_set_holder(feature)
            else:
                self.collection = _collection_holder(base, feature)
        etype = feature.eType
        self.target = etype.python_class if self.is_ref else None


class FastFactory:
    """Creates and fills pyecore objects of our metamodels without per-call overhead.

    The objects behave exactly like ones made through the normal constructor and setters
    (reading, setting, containment, saving, ``delete()``): every set feature has pyecore's
    value holder (an ``EValue`` or ordered set whose feature is held by its class, see
    :func:`_value_holder`, or another collection), from which ``_isset`` (what pyecore saves)
    is made when first read; contained objects know their container and containment feature,
    and referenced objects record the inverse reference pyecore keeps for ``delete()`` (made
    on first read as well for the containment pair alone, see :class:`_InverseOnRead`). What
    is skipped is what a new, unobserved object does not need: notifications (no listener can
    be attached yet), feature lookups by name (done once, in :class:`FeatureSlot`), the type
    check of each value (the caller passes values of the right type), and the entry in
    pyecore's debugging registry of all objects (see :meth:`new`). The garbage collector is
    best paused while many objects are made (every pyecore object is part of a reference
    cycle): see :func:`gc_paused`.
    """

    __slots__ = ("_slots",)

    def __init__(self) -> None:
        self._slots: dict[tuple[int, str], FeatureSlot] = {}

    def slot(self, eclass: EClass, name: str) -> FeatureSlot:
        key = (id(eclass), name)
        found = self._slots.get(key)
        if found is None:
            feature = eclass.findEStructuralFeature(name)
            if feature is None:
                allowed = ", ".join(sorted(f.name for f in eclass.eAllStructuralFeatures()))
                raise ModelError(f"{eclass.name} has no feature {name!r} (expected one of: {allowed})")
            found = self._slots[key] = FeatureSlot(feature)
        return found

    @staticmethod
    def new(cls: type) -> EObject:
        """A new object of pyecore class ``cls`` (``eclass.python_class``), with no feature set.

        The state reads exactly as what ``EObject.__new__`` and pyecore's setters make, but
        nothing is written on the object until a feature is set: what pyecore keeps per object
        is a default on the class (see :func:`_class_defaults`), and pyecore writes its own
        value on the object when it sets one. The attributes that hold ``None`` (container,
        containment feature, resource, internal id), ``_staticEClass`` (``False`` on a
        metamodel's classes) and ``dyn_inst`` (the object itself) read from the class; the
        listener lists, ``_isset`` and ``_inverse_rels`` are made on the first read, from what
        the object holds (:class:`_IssetOnRead`, :class:`_InverseOnRead`). And the object is not
        added to pyecore's process-wide weak registry of every object ever made (what the
        debugging helper ``allInstances()`` iterates): that registry costs as much as the
        object itself and nothing in rosaadl reads it. :meth:`register` adds objects to it
        when wanted.
        """
        try:
            ready = cls._fast_defaults is cls  # one cached lookup
        except AttributeError:
            ready = False
        if not ready:
            _class_defaults(cls)
        return _object_new(cls)

    @staticmethod
    def prepare(cls: type) -> None:
        """Make ``cls`` ready, so that ``object.__new__(cls)`` gives what :meth:`new` gives (for
        readers that make many objects of a few classes known in advance)."""
        if cls.__dict__.get("_fast_defaults") is not cls:
            _class_defaults(cls)

    @staticmethod
    def register(objects: Iterable[EObject]) -> None:
        """Add objects made by :meth:`new` to pyecore's ``allInstances()`` registry."""
        for obj in objects:
            type(obj)._instances.add(obj)

    @staticmethod
    def set_value(obj: EObject, slot: FeatureSlot, value: Any) -> None:
        """Set a single-valued attribute, or a non-containment reference to ``value``."""
        ev = _object_new(slot.holder)
        ev.owner = obj
        ev._value = value
        d = obj.__dict__
        d[slot.name] = ev
        if "_isset" in d:  # already read: keep it whole
            d["_isset"][slot.feature] = None
        if slot.is_ref and value is not None:
            value._inverse_rels.add((obj, slot.feature))

    @staticmethod
    def set_child(obj: EObject, slot: FeatureSlot, child: EObject) -> None:
        """Set a single-valued containment reference."""
        ev = _object_new(slot.holder)
        ev.owner = obj
        ev._value = child
        d = obj.__dict__
        d[slot.name] = ev
        if "_isset" in d:
            d["_isset"][slot.feature] = None
        FastFactory._refer(obj, slot, (child,))

    @staticmethod
    def set_many(obj: EObject, slot: FeatureSlot, values: list) -> None:
        """Set a many-valued feature (attribute, reference or containment) to the list ``values``.

        An ordered set keeps ``values`` itself as its items: the caller hands the list over.
        """
        feature = slot.feature
        holder = slot.holder
        if holder is not None:  # an ordered set
            collection = _object_new(holder)
            collection.owner = obj
            items = values if type(values) is list else list(values)
            if len(items) == 1:  # its index is made when first read (_IndexOnRead)
                collection.items = items
            else:
                index = {value: position for position, value in enumerate(items)}
                if len(index) < len(items):  # repeated values: the first one counts
                    index = {}
                    items = []
                    for value in values:
                        if value not in index:
                            index[value] = len(items)
                            items.append(value)
                collection.items = items
                collection.map = index
        else:
            collection = slot.collection(obj, feature)
            if isinstance(collection, OrderedSet):
                add = OrderedSet.add
                for value in values:
                    add(collection, value)
            else:
                list.extend(collection, values)
        d = obj.__dict__
        d[slot.name] = collection
        if "_isset" in d:
            d["_isset"][feature] = None
        if slot.is_ref:
            FastFactory._refer(obj, slot, values)

    @staticmethod
    def _refer(obj: EObject, slot: FeatureSlot, values: Iterable[EObject]) -> None:
        """Record that ``obj`` refers to (or, for a containment, contains) each of ``values``."""
        feature = slot.feature
        couple = (obj, feature)
        if slot.containment:
            for child in values:
                cd = child.__dict__
                cd["_container"] = obj
                cd["_containment_feature"] = feature
                cd["_built_containment"] = couple  # see _InverseOnRead
                if "_inverse_rels" in cd:  # already read (the child was referred to): keep it whole
                    cd["_inverse_rels"].add(couple)
        else:
            for target in values:
                target._inverse_rels.add(couple)

    @staticmethod
    def items(collection) -> Any:
        """The stored items of a pyecore collection, indexable without pyecore's overhead."""
        if getattr(collection, "_items_field", False):  # ours: no abstract-class check needed
            return collection.items
        if isinstance(collection, EOrderedSet) and _ORDERED_SET_FIELDS:
            return collection.items
        return collection

    @staticmethod
    def extend(obj: EObject, slot: FeatureSlot, collection, values: Iterable[Any]) -> None:
        """Append ``values`` to an existing collection of ``obj`` (made by :meth:`set_many` or
        by pyecore)."""
        values = list(values)
        if isinstance(collection, OrderedSet):
            add = OrderedSet.add
            for value in values:
                add(collection, value)
        else:
            list.extend(collection, values)
        if not isinstance(collection, _Built):  # pyecore's, made by reading the feature
            obj._isset[slot.feature] = None
        if slot.is_ref:
            FastFactory._refer(obj, slot, values)


@contextmanager
def gc_paused(*, promote: bool = True) -> Iterator[None]:
    """Pause the cyclic garbage collector while a model is built, and restore it afterwards.

    Every pyecore object is part of a reference cycle, so building tens of thousands of them
    with the collector running triggers collections over an ever larger heap, and re-enabling
    it after the build makes the next allocation traverse all of them at once (as long as the
    build itself). The model is long-lived data: with ``promote`` (the default), a successful
    build hands everything the collector tracks to its oldest generation (``gc.freeze()`` then
    ``gc.unfreeze()``), where the next full collection will see it like any long-lived data,
    instead of first traversing it as young objects. The only other objects so promoted are
    the few the young generations held (at most the collector's young thresholds), whose
    collection, if they are garbage, waits for that full collection. Nothing is promoted when
    the build fails, when the collector was already disabled, or when the process has frozen
    objects of its own (``gc.get_freeze_count()``), which an unfreeze would release.
    """
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    except BaseException:
        if was_enabled:
            gc.enable()
        raise
    if was_enabled:
        if promote and gc.get_freeze_count() == 0:
            gc.freeze()
            gc.unfreeze()
        gc.enable()


class FastBuilder:
    """:class:`FastFactory` by class and feature *name*: ``make("Feature", name=..., category=...)``,
    ``add(owner, "features", child, ...)``.

    Values must already be typed: enum features take literal objects (:meth:`literal`),
    data-typed features Python values of the right type. Unknown features and abstract classes
    are refused with a :class:`ModelError`.
    """

    def __init__(self) -> None:
        self.factory = FastFactory()
        self._classes: dict[str, EClass] = {}
        self._literals: dict[tuple[str, str], Any] = {}

    def eclass(self, name: str) -> EClass:
        cls = self._classes.get(name)
        if cls is None:
            cls = metamodels.load().eclass(name)
            if cls.abstract:
                raise ModelError(f"{cls.name} is abstract; use one of its subclasses")
            self._classes[name] = cls
        return cls

    def slot(self, eclass: EClass, name: str) -> FeatureSlot:
        return self.factory.slot(eclass, name)

    def literal(self, enum_name: str, text: str):
        """The literal object of enumeration ``enum_name`` for a name or AADL spelling."""
        key = (enum_name, text)
        literal = self._literals.get(key)
        if literal is None:
            mm = metamodels.load()
            enum = mm.aadl.getEClassifier(enum_name) or mm.rosmod.getEClassifier(enum_name)
            if not isinstance(enum, EEnum):
                raise ModelError(f"no enumeration {enum_name!r}")
            literal = enum.from_string(text)
            self._literals[key] = literal
        return literal

    def make(self, class_name: str, /, **values: Any) -> EObject:
        """Create an object with single-valued features set (use :meth:`add` for lists)."""
        eclass = self.eclass(class_name)
        obj = FastFactory.new(eclass.python_class)
        for name, value in values.items():
            if value is None:
                continue
            slot = self.slot(eclass, name)
            if slot.many:
                raise ModelError(f"{eclass.name}.{name} is many-valued; use FastBuilder.add")
            if slot.containment:
                FastFactory.set_child(obj, slot, value)
            else:
                FastFactory.set_value(obj, slot, value)
        return obj

    def add(self, owner: EObject, name: str, *children: Any) -> None:
        """Append to a many-valued feature (containment, reference or attribute)."""
        slot = self.slot(owner.eClass, name)
        if not slot.many:
            raise ModelError(f"{owner.eClass.name}.{name} is single-valued; use FastBuilder.make")
        existing = owner.__dict__.get(slot.name)
        if existing is None:
            FastFactory.set_many(owner, slot, list(children))
        else:
            FastFactory.extend(owner, slot, existing, children)
