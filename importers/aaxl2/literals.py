"""Positional references into property sets, decoded once the file's OSATE era is known.

While reading, every positional href into a property set (a property, a unit, an enumeration
literal, a record field) is kept as ``uri#fragment`` and recorded on the reader with the
objects that hold it (``Reader.literal_uses``). :func:`decode_literals` chooses the era from
all of them at once (:func:`~rosaadl.importers.osate_eras.choose_era`), writes the decoded
names into the holders, and reports what stays as written: hrefs that no era decodes
consistently, and hrefs into property sets that are not predeclared (kept until their
``.aadl`` source is read).
"""

from __future__ import annotations

from rosaadl.bulk import FastFactory
from rosaadl.errors import Diagnostic, Location
from rosaadl.importers import osate_eras

from .document import Reader

__all__ = ["decode_literals"]


def decode_literals(r: Reader) -> osate_eras.EraChoice:
    uses = [osate_eras.HrefUse(uri, frag, role, prop, fh) for (uri, frag, role, prop, fh) in r.literal_uses]
    choice = osate_eras.choose_era(uses, uris=sorted(r.seen_uris))
    problems = {(u.uri, u.fragment, u.role, u.property, u.field_href): why for u, why in choice.problems}
    opaque: dict[str, int] = {}
    undecoded: dict[str, tuple[int, str]] = {}
    for key, targets in r.literal_uses.items():
        uri, frag, role, _prop, _fh = key
        pre = osate_eras.classify_uri(uri)
        decoded = None
        era = choice.era_of(pre.property_set) if pre is not None else None
        if pre is not None and era is not None and key not in problems:
            era_table = osate_eras.table(era)
            path = osate_eras.normalize_fragment(frag)
            if role == "property":
                decoded = era_table.property_name(pre.property_set, int(path.rpartition(".")[2]))
            else:
                literal = era_table.literal(pre.property_set, path)
                decoded = literal.name if literal is not None else None
        if decoded is None:
            if pre is not None:
                count, _why = undecoded.get(f"{uri}#{frag}", (0, ""))
                undecoded[f"{uri}#{frag}"] = (count + len(targets), problems.get(key, "unknown position"))
            else:
                opaque[uri] = opaque.get(uri, 0) + len(targets)
            continue
        for obj, feature_name in targets:
            # the value the reader stored (FastFactory): rewritten in place, as it was made
            FastFactory.replace_value(obj, feature_name, decoded)
    for href, (count, why) in sorted(undecoded.items()):
        r.warn(
            f"{count} reference(s) to {href} do not decode consistently in any known OSATE era ({why}); "
            "kept as written"
        )
    for uri, count in sorted(opaque.items()):
        r.warn(
            f"{count} positional reference(s) into {uri} (not a predeclared property set) kept as "
            "uri#fragment until its .aadl source is read"
        )
    for set_name, era in sorted(choice.set_eras.items()):
        r.warnings.append(
            Diagnostic(
                "info",
                f"references into {set_name} decode with the {era} table (the file is {choice.era})",
                Location(file=r.filename),
            )
        )
    return choice
