"""Lossless text encoding of the job model for storage in FreeCAD properties.

Stage values (``Drawing``, ``Recognition``, ``Layout``, ``CutPlan``) are plain
dataclasses.  The document keeps each one in a hidden string property so that
it is saved in the ``.FCStd`` and recorded by undo like any other property.
The encoding is JSON with a type tag per dataclass (``"@"``: class name) and
tuples kept as tuples (``{"@t": [...]}``); it is then zlib-compressed and
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


def _enc(value: Any) -> Any:
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        out = {"@": type(value).__name__}
        for f in dataclasses.fields(value):
            out[f.name] = _enc(getattr(value, f.name))
        return out
    if isinstance(value, tuple):
        return {"@t": [_enc(v) for v in value]}
    if isinstance(value, list):
        return [_enc(v) for v in value]
    if isinstance(value, dict):
        return {"@d": [[_enc(k), _enc(v)] for k, v in value.items()]}
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    if hasattr(value, "item"):          # numpy scalar
        return value.item()
    if hasattr(value, "tolist"):        # numpy array
        return value.tolist()
    raise TypeError(f"cannot store a {type(value).__name__} in a LeatherCut document")


def _dec(value: Any) -> Any:
    if isinstance(value, list):
        return [_dec(v) for v in value]
    if isinstance(value, dict):
        if "@t" in value:
            return tuple(_dec(v) for v in value["@t"])
        if "@d" in value:
            return {_dec(k): _dec(v) for k, v in value["@d"]}
        name = value.get("@")
        cls = _REGISTRY.get(name)
        if cls is None:
            raise ValueError(f"unknown stored type {name!r}")
        known = {f.name for f in dataclasses.fields(cls)}
        kwargs = {k: _dec(v) for k, v in value.items() if k in known}
        return cls(**kwargs)
    return value


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
