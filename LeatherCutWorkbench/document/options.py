"""Stage options stored as properties of the Job object.

Each stage's options dataclass (``ImportOptions``, ``RecogniseOptions``,
``NestOptions``, ``PlanOptions``) is mirrored field by field into properties
of the Job, grouped by stage in the property editor, so a saved ``.FCStd``
reopens with the same options and the property editor, the task panels and a
macro all edit the same values.  Property names are the stage prefix plus the
field name in CamelCase (``recognise.join_tol`` -> ``RecogniseJoinTol``).

Fields map by their default value's type: float -> ``App::PropertyFloat``,
bool -> ``App::PropertyBool``, int -> ``App::PropertyInteger``, str ->
``App::PropertyString``; anything else (None, lists, tuples, nested values)
-> ``App::PropertyString`` holding JSON, empty meaning None.
"""

from __future__ import annotations

import dataclasses
import importlib
import json
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import FreeCAD


@dataclass(frozen=True)
class StageOptions:
    """Where a stage's options dataclass lives and how its properties are named."""

    key: str            # stage key used in property names and groups: "Import", "Recognise", ...
    module: str         # package holding the dataclass
    cls: str            # dataclass name


STAGE_OPTIONS: Tuple[StageOptions, ...] = (
    StageOptions("Import", "LeatherCutWorkbench.core.dxfimport", "ImportOptions"),
    StageOptions("Recognise", "LeatherCutWorkbench.core.recognition", "RecogniseOptions"),
    StageOptions("Nest", "LeatherCutWorkbench.core.nesting", "NestOptions"),
    StageOptions("Plan", "LeatherCutWorkbench.core.pathplan", "PlanOptions"),
)


def camel(name: str) -> str:
    return "".join(p[:1].upper() + p[1:] for p in name.split("_") if p)


def options_class(stage: StageOptions):
    """The options dataclass of a stage, or None when its package is absent."""
    try:
        mod = importlib.import_module(stage.module)
    except ImportError:
        return None
    return getattr(mod, stage.cls, None)


def _default(f: dataclasses.Field) -> Any:
    if f.default is not dataclasses.MISSING:
        return f.default
    if f.default_factory is not dataclasses.MISSING:  # type: ignore[misc]
        return f.default_factory()  # type: ignore[misc]
    return None


def _kind(value: Any) -> str:
    if isinstance(value, bool):
        return "App::PropertyBool"
    if isinstance(value, int):
        return "App::PropertyInteger"
    if isinstance(value, float):
        return "App::PropertyFloat"
    if isinstance(value, str):
        return "App::PropertyString"
    return "json"


#: fields the job keeps elsewhere, not as plain option properties: the nest container in
#: properties of its own (see job_properties.add_nest_container_properties), accepted / rejected
#: gap fixes as the decisions on the flag objects (see core.decisions.apply_decisions)
SPECIAL_FIELDS = {"Nest": {"container"}, "Recognise": {"accept_fixes", "reject_fixes"}}


def fields_of(stage: StageOptions) -> List[Tuple[str, str, str, Any]]:
    """(field name, property name, property type or "json" / "optstr", default) per field."""
    cls = options_class(stage)
    if cls is None:
        return []
    out = []
    for f in dataclasses.fields(cls):
        if f.metadata.get("transient") or f.name in SPECIAL_FIELDS.get(stage.key, ()):
            continue
        d = _default(f)
        kind = _kind(d)
        if d is None and str(f.type).replace(" ", "") in ("Optional[str]", "str|None"):
            kind = "optstr"
        out.append((f.name, stage.key + camel(f.name), kind, d))
    return out


def _to_json_text(value: Any) -> str:
    if value is None:
        return ""
    if dataclasses.is_dataclass(value):
        value = dataclasses.asdict(value)
    if isinstance(value, (set, frozenset)):
        value = sorted(value)
    return json.dumps(value)


def add_properties(obj, stage: StageOptions) -> List[str]:
    """Add the stage's option properties (with defaults) to ``obj``; returns names."""
    names = []
    cls = options_class(stage)
    docs = _field_docs(cls) if cls is not None else {}
    for fname, pname, ptype, default in fields_of(stage):
        names.append(pname)
        if pname in obj.PropertiesList:
            continue
        tip = docs.get(fname, f"{stage.key} option '{fname}'")
        if ptype == "json":
            obj.addProperty("App::PropertyString", pname, stage.key, tip + " (JSON; empty = none)")
            setattr(obj, pname, _to_json_text(default))
        elif ptype == "optstr":
            obj.addProperty("App::PropertyString", pname, stage.key, tip + " (empty = none)")
        else:
            obj.addProperty(ptype, pname, stage.key, tip)
            setattr(obj, pname, default)
    return names


def _field_docs(cls) -> Dict[str, str]:
    """Short per-field tips from the class docstring lines ``name: text`` (if any)."""
    out: Dict[str, str] = {}
    for line in (cls.__doc__ or "").splitlines():
        line = line.strip().lstrip("*- ")
        if ":" in line:
            head, _, text = line.partition(":")
            head = head.strip("` ")
            if head.isidentifier() and text.strip():
                out[head] = text.strip()
    return out


def read_options(obj, stage: StageOptions):
    """Build the stage's options dataclass from the Job's properties."""
    cls = options_class(stage)
    if cls is None:
        return None
    kwargs: Dict[str, Any] = {}
    base = cls()
    for fname, pname, ptype, default in fields_of(stage):
        if pname not in obj.PropertiesList:
            continue
        value = getattr(obj, pname)
        if ptype == "json":
            try:
                value = _from_json_text(value, getattr(base, fname))
            except ValueError as exc:
                from ..core.errors import InputError
                raise InputError(f"{pname}: not valid JSON ({exc})") from None
        elif ptype == "optstr":
            value = value.strip() or None
        kwargs[fname] = value
    return cls(**kwargs)


def _from_json_text(text: str, template: Any) -> Any:
    if not text.strip():
        return type(template)() if isinstance(template, (set, frozenset, list)) else None
    value = json.loads(text)
    if dataclasses.is_dataclass(template) and isinstance(value, dict):
        return type(template)(**value)
    if isinstance(template, tuple) and isinstance(value, list):
        return tuple(value)
    if isinstance(template, (set, frozenset)) and isinstance(value, list):
        return type(template)(value)
    return value


def write_options(obj, stage: StageOptions, options) -> None:
    """Store an options dataclass in the Job's properties."""
    for fname, pname, ptype, _default_value in fields_of(stage):
        if pname not in obj.PropertiesList:
            continue
        value = getattr(options, fname)
        if ptype == "json":
            value = _to_json_text(value)
        elif ptype == "optstr":
            value = value or ""
        if getattr(obj, pname) != value:
            setattr(obj, pname, value)


def stage_of_property(prop: str) -> Optional[str]:
    """The stage key whose option ``prop`` is (None for other properties)."""
    for st in STAGE_OPTIONS:
        if prop.startswith(st.key) and prop[len(st.key):][:1].isupper():
            return st.key
    if prop.startswith("Post") and prop[4:5].isupper():
        return "Post"
    return None


def preferences():
    """The workbench's parameter group (defaults edited on the preferences page)."""
    return FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/LeatherCut")
