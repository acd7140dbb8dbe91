"""``read_drawing``: DXF file -> :class:`Drawing` (mm), the import stage's entry point.

Steps: open (:mod:`.reader`) -> decide units (:mod:`.units`) and whether this
is an AAMA/ASTM pattern file (:mod:`.aama`) -> convert model space with blocks
exploded (:mod:`.blocks`, :mod:`.entities`) -> local origin for huge
coordinates (:mod:`.extents`) -> clean-up (:mod:`.cleanup`) -> pieces
(:mod:`.pieces`) -> statistics for ``leathercut inspect``.
"""

from __future__ import annotations

from collections import Counter
from itertools import chain
from operator import attrgetter, methodcaller
from typing import Any, Dict, Iterable, List, Optional, Tuple

from ..errors import InputError
from ..gc_pause import collector_paused
from ..model import Drawing, Finding
from ..progress import ProgressFn, report
from . import aama
from .blocks import Rules, Walker
from .cleanup import clean
from .entities import Collector
from .extents import bounds, local_offset, translate
from .limits import check_geometry
from .options import ImportOptions
from .pieces import build_pieces
from .plain_reader import PlainDocument, convert_plain
from .reader import open_dxf
from .transform import scale_affine
from .units import MM_PER_UNIT, aama_units, header_units, parse_units, plausibility_warning

#: How many INSERTed blocks are looked into for ``Piece Name:`` when detecting AAMA.
_AAMA_PROBE_BLOCKS = 5


def read_drawing(path: str, options: ImportOptions = ImportOptions(),
                 progress: Optional[ProgressFn] = None) -> Drawing:
    """Read the DXF at ``path`` into a Drawing (edges, marks, texts in mm).

    Raises InputError (naming the file) when the file is missing, empty, not a
    DXF, unreadable even in recovery mode, or holds nothing usable; everything
    else that was odd, repaired or skipped is a Finding in ``drawing.findings``.
    ``progress(fraction, message)`` is called regularly (False cancels)."""
    options = (options or ImportOptions()).validated()
    with collector_paused():
        return _read(path, options, progress)


def _read(path: str, options: ImportOptions, progress: Optional[ProgressFn]) -> Drawing:
    report(progress, 0.0, f"reading {path}")
    opened = open_dxf(path)
    doc = opened.doc
    findings: List[Finding] = list(opened.findings)
    report(progress, 0.35, "analysing the drawing")

    entities = list(doc.modelspace())
    types = list(map(methodcaller("dxftype"), entities))
    found = Counter(types)
    ms_texts = _modelspace_texts(e for e, t in zip(entities, types) if t in ("TEXT", "MTEXT"))
    inserts = [e for e, t in zip(entities, types) if t == "INSERT"]
    is_aama = options.pattern_mode == "aama" or (
        options.pattern_mode == "auto" and aama.looks_like_aama(ms_texts, _probe_block_texts(doc, inserts)))
    unit, unit_source, insunits = _decide_units(doc, ms_texts, is_aama, options, path, findings,
                                                opened.info.get("has_insunits", True))
    scale = MM_PER_UNIT[unit]

    out = Collector(path)
    if is_aama:
        rules = Rules(aama.layer_role, aama.mark_kind, pieces_from_inserts=True)
        findings.append(Finding("info", "aama-pattern", "AAMA / ASTM D6673 pattern file: one piece "
                                "per block, layer numbers give cut/notch/drill/grain roles", path))
    else:
        rules = Rules(options.layer_selection().role_of, lambda layer: "point")
    walker = Walker(doc, out, rules)
    plain = isinstance(doc, PlainDocument)
    if plain:
        doc.drop_entities()          # walked and freed one by one (peak memory)
        convert_plain(entities, scale_affine(scale), out, walker._role, walker.visit,
                      progress, 0.35, 0.8)
    else:
        walker.walk(entities, scale_affine(scale), progress, 0.35, 0.8)
    del entities, types
    out.finish()
    findings.extend(out.findings)
    paper = _paper_space_notes(doc, path, findings)

    edges, marks, texts = out.edges, out.marks, out.texts
    if not is_aama:
        findings.extend(options.layer_selection().findings([e.src.layer for e in edges], path))
    box = bounds(edges, (m.position for m in marks))
    check_geometry(path, box, chain(edges, marks, texts))
    _check_usable(path, edges, marks, texts, found, out)
    if box is not None:
        warn = plausibility_warning(((box[2] - box[0]) / scale, (box[3] - box[1]) / scale), unit)
        if warn:
            findings.append(Finding("warning", "units-implausible", warn, path))

    offset = (0.0, 0.0)
    if options.local_origin:
        offset = local_offset(box, options.huge_coordinate_mm)
    if offset != (0.0, 0.0):
        edges, marks, texts = (translate(edges, *offset), translate(marks, *offset),
                               translate(texts, *offset))
        box = (box[0] - offset[0], box[1] - offset[1], box[2] - offset[0], box[3] - offset[1])
        findings.append(Finding("info", "local-origin", f"huge coordinates: moved by "
                                f"({-offset[0]:.0f}, {-offset[1]:.0f}) mm to a local origin "
                                f"(Drawing.offset restores them)", path))

    cleanup_json = None
    if options.cleanup:
        report(progress, 0.8, "cleaning up edges")
        edges, counts = clean(edges, options.tolerance,
                              lambda f, msg: report(progress, min(0.8 + 0.15 * f, 0.95), msg))
        cleanup_json = counts.to_json()
        if counts.edges_before != counts.edges_after or counts.t_junctions:
            findings.append(Finding(
                "info", "cleanup",
                f"clean-up ({options.tolerance} mm{', per piece' if is_aama else ''}): "
                f"{counts.zero_length} zero-length edges, {counts.duplicates} duplicates and "
                f"{counts.overlaps} collinear overlaps ({counts.overlap_length:.3f} mm) removed, "
                f"{counts.t_junctions} T-junction splits", path))
    report(progress, 0.95, "collecting pieces and statistics")

    drawing = Drawing(path=path, edges=edges, marks=marks, texts=texts, units=unit,
                      units_source=unit_source, dxf_version=doc.dxfversion, offset=offset,
                      findings=findings)
    if is_aama:
        drawing.pieces = build_pieces(walker.piece_inserts, edges, marks, texts)
    tol_hint = aama.parse_number(aama.style_value(ms_texts, "TOLERANCE")) if is_aama else None
    drawing.stats = _stats(doc, opened.info, found, out, walker, edges, marks, texts, box, offset,
                           unit, unit_source, insunits, scale, is_aama, cleanup_json, paper,
                           None if tol_hint is None else tol_hint * scale)
    report(progress, 1.0, "drawing imported")
    return drawing


def _modelspace_texts(entities: Iterable[Any]) -> List[str]:
    texts = []
    for e in entities:
        try:
            texts.append(e.plain_text() if e.dxftype() == "TEXT" else e.plain_text(split=False))
        except Exception:  # a broken text must not stop the import
            continue
    return texts


def _probe_block_texts(doc: Any, inserts: List[Any]) -> List[str]:
    texts: List[str] = []
    for ins in inserts[:_AAMA_PROBE_BLOCKS]:
        block = doc.blocks.get(ins.dxf.name)
        if block is not None:
            texts.extend(e.dxf.get("text", "") for e in block if e.dxftype() == "TEXT")
    return texts


def _decide_units(doc: Any, ms_texts: List[str], is_aama: bool, options: ImportOptions,
                  path: str, findings: List[Finding], has_insunits: bool = True
                  ) -> Tuple[str, str, Optional[int]]:
    """(unit, source, raw $INSUNITS) following the policy in :mod:`.units`.
    ``has_insunits`` False: the file has no ``$INSUNITS`` (ezdxf's default
    header value must not be taken for the file's statement)."""
    insunits = doc.header.get("$INSUNITS") if has_insunits else None
    from_header = header_units(insunits)
    text_value = aama.style_value(ms_texts, "Units") if is_aama else None
    from_text = aama_units(text_value) if text_value else None
    if options.units is not None:
        unit = parse_units(options.units)
        stated = from_header or from_text
        if stated and stated != unit:
            findings.append(Finding("warning", "units-overridden",
                                    f"the file states {stated}; read as {unit} as requested", path))
        return unit, "option", insunits
    if from_header:
        if from_text and from_text != from_header:
            findings.append(Finding("warning", "units-conflict",
                                    f"$INSUNITS says {from_header} but the text says "
                                    f"'Units: {text_value}'; using {from_header}", path))
        return from_header, "header", insunits
    if from_text:
        return from_text, "aama-text", insunits
    if text_value:
        findings.append(Finding("warning", "units-unknown",
                                f"unknown unit text 'Units: {text_value}'", path))
    why = ("$INSUNITS is 0 (unitless)" if insunits == 0 else "the file states no units"
           if insunits is None else f"unknown units code {insunits} in $INSUNITS")
    findings.append(Finding("warning", "units-missing",
                            f"{why}: read as mm; choose the unit with --units if it is wrong", path))
    return "mm", "assumed", insunits


def _paper_space_notes(doc: Any, path: str, findings: List[Finding]) -> Dict[str, int]:
    ignored: Dict[str, int] = {}
    for layout in doc.layouts:
        if layout.is_modelspace:
            continue
        kinds = Counter(e.dxftype() for e in layout if e.dxftype() != "VIEWPORT")
        n = sum(kinds.values())
        if n:
            ignored[layout.name] = n
            what = ", ".join(f"{k} x{v}" for k, v in sorted(kinds.items()))
            findings.append(Finding("info", "paper-space-ignored",
                                    f"paper space layout {layout.name!r}: {n} entities ignored "
                                    f"({what}); only model space is imported", path))
    return ignored


def _check_usable(path: str, edges: List[Any], marks: List[Any], texts: List[Any],
                  found: Counter, out: Collector) -> None:
    if edges or marks:
        return
    if not found:
        raise InputError("the drawing is empty: model space holds no entities", path)
    skipped = ", ".join(f"{n} {t} ({reason})" for (t, reason), n in sorted(out.skipped.items()))
    has = f"only {len(texts)} texts" if texts else "no geometry"
    raise InputError(f"nothing usable to cut: {has}"
                     f"{'; skipped: ' + skipped if skipped else ''}", path)


_RELEASES = {"AC1009": "R12", "AC1012": "R13", "AC1014": "R14", "AC1015": "R2000",
             "AC1018": "R2004", "AC1021": "R2007", "AC1024": "R2010", "AC1027": "R2013",
             "AC1032": "R2018"}


def _stats(doc: Any, info: Dict[str, Any], found: Counter, out: Collector, walker: Walker,
           edges: List[Any], marks: List[Any], texts: List[Any], box, offset, unit: str,
           unit_source: str, insunits, scale: float, is_aama: bool, cleanup_json,
           paper: Dict[str, int], tol_hint_mm: Optional[float]) -> Dict[str, Any]:
    kinds = Counter({t.__name__[:-4].lower(): n for t, n in Counter(map(type, edges)).items()})
    layer_roles = Counter(map(attrgetter("src.layer", "src.role"), edges))
    roles: Counter = Counter()
    edge_count: Counter = Counter()
    layer_role: Dict[str, str] = {}
    for (layer, role), n in layer_roles.items():
        roles[role] += n
        edge_count[layer] += n
        layer_role.setdefault(layer, role)
    mark_count = Counter(map(attrgetter("src.layer"), marks))
    text_count = Counter(map(attrgetter("src.layer"), texts))
    names = [layer.dxf.name for layer in doc.layers] + list(edge_count) + list(mark_count) + \
        list(text_count)
    layers = [{"name": name, "edges": edge_count[name], "marks": mark_count[name],
               "texts": text_count[name], "role": layer_role.get(name)}
              for name in dict.fromkeys(names)]
    blocks = []
    for name, n in sorted(walker.insert_counts.items()):
        block = doc.blocks.get(name)
        blocks.append({"name": name, "inserts": n, "entities": len(block) if block is not None else 0})
    return {
        "file": dict(info),
        "dxf_version": doc.dxfversion,
        "release": _RELEASES.get(doc.dxfversion, doc.dxfversion),
        "units": {"unit": unit, "source": unit_source, "mm_per_unit": scale,
                  "header_insunits": insunits},
        "pattern": "aama" if is_aama else "none",
        "entities_found": dict(sorted(found.items())),
        "entities_after_explosion": dict(sorted(out.exploded.items())),
        "entities_converted": dict(sorted(out.converted.items())),
        "skipped": [{"type": t, "reason": r, "count": n} for (t, r), n in sorted(out.skipped.items())],
        "skipped_entities": list(out.skipped_list),
        "paper_space_ignored": paper,
        "edges": {"total": len(edges), "by_kind": dict(sorted(kinds.items())),
                  "by_role": dict(sorted(roles.items()))},
        "marks": len(marks),
        "texts": len(texts),
        "layers": layers,
        "blocks": blocks,
        "bbox_mm": [round(v, 6) for v in box] if box else None,
        "size_mm": [round(box[2] - box[0], 6), round(box[3] - box[1], 6)] if box else None,
        "offset_mm": list(offset),
        "cleanup": cleanup_json,
        "join_tolerance_hint_mm": tol_hint_mm,
    }
