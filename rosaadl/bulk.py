"""Bulk construction of model objects, for the readers and the instantiator.

pyecore spends most of an object's creation on change notifications, type checks and a
process-wide registry of every object; a reader that makes tens of thousands of new,
unobserved objects needs none of that. :class:`FastFactory` fills pyecore's own state directly
(value holders, containers; single-valued attributes without a holder, which is most of a read
model's memory otherwise: :class:`_PlainAttribute`) and leaves the rest (``_isset``, inverse
references, listener lists) to be made on first read from what the object holds, so the
objects behave exactly like ones made with :func:`rosaadl.model.new` (saving, setters,
``delete()``; tested). :class:`FastBuilder` is the same by feature *name*, for code that is
not a hot loop's inner body. :func:`gc_paused` keeps the cyclic garbage collector out of the
way while building.
"""

from __future__ import annotations

import gc
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from functools import cache
from typing import Any

import pyecore
from pyecore.ecore import EClass, EEnum, EObject, EStructuralFeature
from pyecore.innerutils import InternalSet
from pyecore.ordered_set_patch import ordered_set
from pyecore.valuecontainer import EBag, EList, EOrderedSet, ESet, EValue, PyEcoreValue

from rosaadl import metamodels
from rosaadl.errors import ModelError

__all__ = [
    "FeatureSlot",
    "FastFactory",
    "FastBuilder",
    "gc_paused",
    "check_pyecore_version",
    "stored_value",
]

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
    out: a reader never reads it (it appends by making a new set or through :meth:`~FastFactory.
    extend`, which reads it), most sets of a read model are only iterated, and a dictionary per
    set costs about as much as the items it indexes."""

    __slots__ = ()

    def __get__(self, obj, owner=None):
        if obj is None:
            return self
        index = obj.__dict__["map"] = {item: position for position, item in enumerate(obj.items)}
        return index


class _IssetOnRead:
    """The default of ``_isset`` (the features pyecore saves, in the order they were set): made
    on the first read from the object's value holders and collections that :class:`FastFactory`
    made (instances of :class:`_Built`) and the attribute values it stored plain (see
    :class:`_PlainAttribute`), in the order they were stored, then kept on the object.

    pyecore only ever adds to ``_isset``, and always through a read of it, so this is the set
    pyecore would hold: every feature FastFactory filled, then pyecore's own additions. A holder
    pyecore's getter makes for a feature never set is not a ``_Built`` one and does not count.
    """

    __slots__ = ()

    def __get__(self, obj, owner=None):
        if obj is None:
            return self
        d = obj.__dict__
        cls = type(obj)
        isset = InternalSet()
        for name, value in d.items():
            if name == "_built_containment":  # the holder of the object itself, in its container
                continue
            if isinstance(value, _Built):
                isset[value.feature] = None
            elif not isinstance(value, PyEcoreValue) and name[0] != "_":
                # a plain value, or one of pyecore's per-object lists (``listeners``)
                feature = getattr(cls, name, None)
                if isinstance(feature, EStructuralFeature):
                    isset[feature] = None
        d["_isset"] = isset
        return isset


class _InverseOnRead:
    """The default of ``_inverse_rels`` (the ``(owner, feature)`` pairs that refer to the
    object, which pyecore's ``delete()`` follows): made on the first read, then kept on the
    object. Most objects are only contained, and nothing else refers to them, so most never
    need one.

    It starts with the containment pair of the value holder or collection :class:`FastFactory`
    recorded as the one holding the object (``_built_containment``: its ``owner`` and
    ``feature``, no pair stored per object), not with ``_container``: pyecore clears
    ``_container`` before it takes the pair out of this set, so the pair must be known without
    it. pyecore changes a container only together with
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
        rels = d["_inverse_rels"] = set() if built is None else {(built.owner, built.feature)}
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


_ABSENT = object()


class _PlainAttribute:
    """The class attribute of a single-valued attribute (an ``EAttribute``) of a metamodel
    class, in place of the feature itself (pyecore's descriptor): :class:`FastFactory` stores
    such a value in the object's dictionary as it is, without pyecore's value holder (an
    ``EValue`` per value, the largest part of a read model: a model object has about four set
    attributes, its position among them, and the holder of each costs more than the value).

    Reading gives the plain value, or the holder's value as pyecore does. Everything else is
    pyecore's: reading a feature never set (pyecore makes its holder with the default), and
    every write (``obj.x = v``, ``eSet``, the XMI and JSON readers), before which a plain value
    gets the holder pyecore would have made for it, so that the write checks, notifies and
    marks the feature set exactly as before. ``_isset`` counts the plain values
    (:class:`_IssetOnRead`), so saving writes them like any other. Read from the class, it is
    the feature, as pyecore's own descriptor is. :func:`stored_value` reads a value without
    pyecore's getter (which would make a holder for a feature never set).
    """

    __slots__ = ("feature", "name")

    def __init__(self, feature) -> None:
        self.feature = feature
        self.name = feature.name

    def __get__(self, obj, owner=None):
        if obj is None:
            return self.feature
        held = obj.__dict__.get(self.name, _ABSENT)
        if held is _ABSENT:
            return self.feature.__get__(obj, owner)
        if isinstance(held, EValue):
            return held._value
        return held

    def __set__(self, obj, value) -> None:
        d = obj.__dict__
        held = d.get(self.name, _ABSENT)
        if held is not _ABSENT and not isinstance(held, EValue):
            holder = _object_new(_value_holder(self.feature))
            holder.owner = obj
            holder._value = held
            d[self.name] = holder
        self.feature.__set__(obj, value)

    def __delete__(self, obj) -> None:
        self.feature.__delete__(obj)


def _plain_storage(feature) -> bool:
    """Whether :class:`FastFactory` may store the values of ``feature`` plain: a single-valued,
    non-derived attribute of a class made from an ``EClass`` (not a static pyecore class), whose
    class then gets a :class:`_PlainAttribute` in place of the feature (once)."""
    if feature.many or feature.is_reference or feature.derived:
        return False
    cls = feature.eContainingClass.python_class
    if cls.__dict__.get("_staticEClass", True) is not False:
        return False
    current = cls.__dict__.get(feature.name)
    if isinstance(current, _PlainAttribute):
        return current.feature is feature
    if current is not feature:
        return False
    setattr(cls, feature.name, _PlainAttribute(feature))
    return True


def stored_value(obj: EObject, name: str, default: Any = None) -> Any:
    """The value of feature ``name`` as ``obj`` holds it (plain, or in pyecore's value holder;
    a many-valued feature's collection), ``default`` when it was never set or read, without
    pyecore's getter (which makes a holder for a feature never set)."""
    held = obj.__dict__.get(name, _ABSENT)
    if held is _ABSENT:
        return default
    return held._value if isinstance(held, EValue) else held


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

    __slots__ = (
        "feature",
        "name",
        "is_ref",
        "containment",
        "many",
        "collection",
        "target",
        "holder",
        "plain",
    )

    def __init__(self, feature) -> None:
        self.feature = feature
        self.name = feature.name
        self.is_ref = bool(feature.is_reference)
        self.containment = bool(self.is_ref and feature.containment)
        self.many = bool(feature.many)
        self.collection = None
        self.holder = None if self.many else _value_holder(feature)
        self.plain = _plain_storage(feature)  # an attribute stored without its holder
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
    :func:`_value_holder`, or another collection), except single-valued attributes, whose
    values are stored plain (:class:`_PlainAttribute`); ``_isset`` (what pyecore saves) is
    made from these when first read; contained objects know their container and containment feature,
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
        """Set a single-valued attribute (stored plain, see :class:`_PlainAttribute`), or a
        non-containment reference to ``value``."""
        if slot.plain:
            d = obj.__dict__
            d[slot.name] = value
            if "_isset" in d:  # already read: keep it whole
                d["_isset"][slot.feature] = None
            return
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
        FastFactory._refer(obj, slot, (child,), ev)

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
            if len(items) > 1 and len(set(items)) < len(items):  # repeated: the first one counts
                seen = set()
                items = [value for value in items if not (value in seen or seen.add(value))]
            collection.items = items  # its index is made when first read (_IndexOnRead)
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
            FastFactory._refer(obj, slot, values, collection)

    @staticmethod
    def _refer(obj: EObject, slot: FeatureSlot, values: Iterable[EObject], holder: Any) -> None:
        """Record that ``obj`` refers to (or, for a containment, contains) each of ``values``,
        which ``holder`` (its value holder or collection of the feature) holds."""
        feature = slot.feature
        if slot.containment:
            for child in values:
                cd = child.__dict__
                cd["_container"] = obj
                cd["_containment_feature"] = feature
                cd["_built_containment"] = holder  # see _InverseOnRead
                if "_inverse_rels" in cd:  # already read (the child was referred to): keep it whole
                    cd["_inverse_rels"].add((obj, feature))
        else:
            couple = (obj, feature)
            for target in values:
                target._inverse_rels.add(couple)

    @staticmethod
    def replace_value(obj: EObject, name: str, value: Any) -> None:
        """Replace the value of the single-valued attribute ``name`` that :meth:`set_value` set,
        in place, as a reader's second pass does (no notification: the object is still new)."""
        d = obj.__dict__
        held = d[name]
        if isinstance(held, EValue):
            held._value = value
        else:
            d[name] = value

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
            FastFactory._refer(obj, slot, values, collection)


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
