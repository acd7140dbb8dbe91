"""Lossless text encoding of the job model for storage in FreeCAD properties.

Stage values (``Drawing``, ``Recognition``, ``Layout``, ``CutPlan``) are plain
dataclasses.  The document keeps each one in a hidden string property so that
it is saved in the ``.FCStd`` and recorded by undo like any other property.
The encoding is JSON with a type tag per dataclass (``"@"``: class name),
tuples kept as tuples (``{"@t": [...]}``) and compact forms for the path
segments (``{"@L": [x0, y0, x1, y1]}``, ``{"@A": [cx, cy, r, start, sweep]}``,
``{"@C": [kind, [x0, y0, x1, y1, ...]]}``); fields missing in an older file take
their defaults, unknown ones are ignored.  It is then zlib-compressed and
base64-encoded to keep Document.xml small.

Only classes from the LeatherCut model and geometry modules (and the stage
packages that extend them) are decoded: the class name is looked up in a
registry, never evaluated, so a crafted file cannot run code.
"""

from __future__ import annotations

import base64
import dataclasses
import json
import zlib
from typing import Any, Dict, Type

from ..core import geometry, model

_REGISTRY: Dict[str, Type[Any]] = {}


def register(cls: Type[Any]) -> Type[Any]:
    """Allow a dataclass to be stored (the model's classes are registered below)."""
    _REGISTRY[cls.__name__] = cls
    return cls


for _mod in (model, geometry):
    for _name in dir(_mod):
        _obj = getattr(_mod, _name)
        if isinstance(_obj, type) and dataclasses.is_dataclass(_obj) and _obj.__module__ == _mod.__name__:
            register(_obj)


#: compact forms of the three segment kinds (the bulk of every stage value)
_LINE, _ARC, _CURVE = "@L", "@A", "@C"
_FIELD_NAMES: Dict[type, frozenset] = {}
_SCALARS = (str, int, float, bool, type(None))


def _enc(value: Any) -> Any:
    t = type(value)
    if t in _SCALARS:
        return value
    if t is geometry.LineSeg:
        (x0, y0), (x1, y1) = value.start, value.end
        return {_LINE: [x0, y0, x1, y1]}
    if t is geometry.ArcSeg:
        return {_ARC: [value.center[0], value.center[1], value.radius, value.start_angle, value.sweep]}
    if t is geometry.CurveSeg:
        return {_CURVE: [value.kind, [c for p in value.pts for c in p]]}
    if t is list:
        return [_enc(v) for v in value]
    if t is tuple:
        return {"@t": [_enc(v) for v in value]}
    if t is dict:
        return {"@d": [[_enc(k), _enc(v)] for k, v in value.items()]}
    if t in _FIELD_NAMES or (dataclasses.is_dataclass(value) and t.__name__ in _REGISTRY):
        names = _FIELD_NAMES.get(t)
        if names is None:
            names = _FIELD_NAMES[t] = frozenset(f.name for f in dataclasses.fields(t))
        out = {"@": t.__name__}
        for name in names:
            out[name] = _enc(getattr(value, name))
        return out
    if isinstance(value, (set, frozenset)):
        return {"@s": [_enc(v) for v in sorted(value)]}
    if hasattr(value, "item"):          # numpy scalar
        return value.item()
    if hasattr(value, "tolist"):        # numpy array
        return value.tolist()
    raise TypeError(f"cannot store a {t.__name__} in a LeatherCut document")


def _dec(value: Any) -> Any:
    if type(value) is list:
        return [_dec(v) for v in value]
    if type(value) is not dict:
        return value
    if _LINE in value:
        x0, y0, x1, y1 = value[_LINE]
        return geometry.LineSeg((x0, y0), (x1, y1))
    if _ARC in value:
        cx, cy, r, sa, sw = value[_ARC]
        return geometry.ArcSeg((cx, cy), r, sa, sw)
    if _CURVE in value:
        kind, flat = value[_CURVE]
        return geometry.CurveSeg(tuple(zip(flat[0::2], flat[1::2])), kind)
    if "@t" in value:
        return tuple(_dec(v) for v in value["@t"])
    if "@d" in value:
        return {_dec(k): _dec(v) for k, v in value["@d"]}
    if "@s" in value:
        return frozenset(_dec(v) for v in value["@s"])
    name = value.get("@")
    cls = _REGISTRY.get(name)
    if cls is None:
        raise ValueError(f"unknown stored type {name!r}")
    known = _FIELD_NAMES.get(cls)
    if known is None:
        known = _FIELD_NAMES[cls] = frozenset(f.name for f in dataclasses.fields(cls))
    return cls(**{k: _dec(v) for k, v in value.items() if k in known})


def dumps(value: Any) -> str:
    """Encode a model value (dataclass tree) as compact ASCII text."""
    if value is None:
        return ""
    raw = json.dumps(_enc(value), separators=(",", ":")).encode("utf-8")
    return base64.b64encode(zlib.compress(raw, 6)).decode("ascii")


def loads(text: str) -> Any:
    """Decode text made by :func:`dumps` (empty text gives None)."""
    if not text:
        return None
    raw = zlib.decompress(base64.b64decode(text.encode("ascii")))
    return _dec(json.loads(raw.decode("utf-8")))
