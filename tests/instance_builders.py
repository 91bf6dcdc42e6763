"""Small builders of instance models for the analysis tests (one set, kept in one place).

Test modules import it as ``instance_builders`` (the ``tests`` folder is on pytest's import path).
"""

from __future__ import annotations

from rosaadl import model

new = model.new


def pa(prop, value, modes=None):
    """A property association; ``value`` may be a list of (value, modes) pairs for modal values."""
    if isinstance(value, list):
        values = [new("ModalPropertyValue", value=v, inModes=m) for v, m in value]
    else:
        values = [new("ModalPropertyValue", value=value, inModes=modes)]
    return new("PropertyAssociation", property=prop, ownedValues=values)


def num(value, unit):
    return new("RealValue" if isinstance(value, float) else "IntegerValue", value=value, unit=unit)


def span(low, high, unit="us"):
    return new("RangeValue", minimum=num(low, unit), maximum=num(high, unit))


def ref(*targets):
    """A list of references to instance objects (as ``Actual_Processor_Binding`` holds)."""
    return new(
        "ListValue", ownedItems=[new("InstanceReferenceValue", referencedInstanceObject=t) for t in targets]
    )


def component(name, category, *children, props=(), features=()):
    ci = new("ComponentInstance", name=name, category=category)
    ci.componentInstances.extend(children)
    ci.featureInstances.extend(features)
    ci.ownedPropertyAssociations.extend(props)
    return ci
