"""Opening a DXF file: checks before parsing, ``ezdxf.readfile`` and the
``ezdxf.recover`` fallback.

Everything a person must know about the file itself (damage repaired, decimal
commas converted, bytes after EOF) becomes a :class:`Finding`; anything that
leaves nothing to read raises :class:`InputError` naming the file and why.

Checks done here because ezdxf does not do them (or does them silently):

* not a DXF at all (DWG, PDF, images, SVG, other text) -- recognised from the
  first bytes so the message can say what the file is;
* decimal commas (files written under a comma locale): ezdxf's recover mode
  would silently turn ``-6,636`` into ``-6.0``.  Float values with commas are
  converted only when the file uses commas consistently; a mix is refused;
* bytes after the ``EOF`` marker (ezdxf ignores them; we say so).
"""

from __future__ import annotations

import logging
import os
import re
import tempfile
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import ezdxf
from ezdxf import recover

from ..errors import InputError
from ..model import Finding
from .limits import check_regular_file, scan_nonfinite
from .plain_reader import read_plain

# ezdxf logs repairs as warnings; with no handler Python prints them on stderr,
# which would break the CLI's one-line error rule.  They become findings here.
logging.getLogger("ezdxf").addHandler(logging.NullHandler())

BINARY_SENTINEL = b"AutoCAD Binary DXF"

#: Group codes whose values are floating point numbers (DXF reference).
_FLOAT_CODES = (r"(?:1[0-9]|[2-5][0-9]|1[1-4][0-9]|2[1-3][0-9]|46[0-9]|10[1-5][0-9])")
#: A float-coded pair whose value uses a decimal comma.
_COMMA_PAIR = re.compile(
    rb"^[ \t]*" + _FLOAT_CODES.encode() + rb"[ \t]*\r?\n[ \t]*(-?\d*,\d+(?:[eE][-+]?\d+)?)[ \t]*\r?$",
    re.M)
#: A float-coded pair whose value uses a decimal point.
_POINT_PAIR = re.compile(
    rb"^[ \t]*" + _FLOAT_CODES.encode() + rb"[ \t]*\r?\n[ \t]*-?\d*\.\d", re.M)
#: Any value line that is a comma-number with more than one separator ("1.234,5").
_MIXED_NUMBER = re.compile(
    rb"^[ \t]*" + _FLOAT_CODES.encode() + rb"[ \t]*\r?\n[ \t]*-?[\d.,]*[.,][\d.,]*[.,][\d.,]*[ \t]*\r?$",
    re.M)
_EOF_MARK = re.compile(rb"(?:^|\n)[ \t]*0[ \t]*\r?\n[ \t]*EOF[ \t]*(?:\r?\n|$)")

#: ezdxf errors after which recover mode would invent or truncate a number.
_LOST_NUMBER = re.compile(r"Missing required|Invalid floating point|invalid floating point", re.I)

#: How many recover fixes are quoted in the finding (all are counted).
_QUOTED_FIXES = 5


@dataclass
class OpenedFile:
    """An opened DXF document plus what was noticed while opening it.

    ``info`` keys: ``binary`` (bool), ``recovered`` (bool), ``recover_fixes`` (int),
    ``recover_errors`` (int), ``decimal_commas_fixed`` (int), ``trailing_bytes`` (int),
    ``size_bytes`` (int), ``reader`` ("plain": :mod:`.plain_reader`, else "ezdxf"),
    ``has_insunits`` (bool: the file itself sets ``$INSUNITS``;
    ezdxf fills a default header for files without one)."""

    doc: Any
    findings: List[Finding] = field(default_factory=list)
    info: Dict[str, Any] = field(default_factory=dict)


def open_dxf(path: str) -> OpenedFile:
    """Open ``path`` as a DXF document (ASCII or binary), repairing it if needed.

    Raises InputError for a missing, empty, unreadable or non-DXF file, for
    inconsistent decimal commas, and when even ``ezdxf.recover`` cannot read it."""
    data = _read_bytes(path)
    findings: List[Finding] = []
    info: Dict[str, Any] = {"binary": False, "recovered": False, "recover_fixes": 0,
                            "recover_errors": 0, "decimal_commas_fixed": 0,
                            "trailing_bytes": 0, "size_bytes": len(data),
                            "has_insunits": b"$INSUNITS" in data}
    if data.startswith(BINARY_SENTINEL):
        info["binary"] = True
        findings.append(Finding("info", "binary-dxf", "binary DXF file", path))
        return _parse(path, path, findings, info)

    _check_is_dxf_text(path, data)
    scan_nonfinite(path, data)
    info["trailing_bytes"] = _trailing_bytes(path, data, findings)
    fixed = _decimal_comma_fix(path, data)
    if fixed is None:
        return _parse(path, path, findings, info, data)
    new_data, count = fixed
    info["decimal_commas_fixed"] = count
    findings.append(Finding(
        "warning", "decimal-commas",
        f"{count} numbers were written with a decimal comma (comma locale); "
        f"read as decimal points (e.g. '-6,5' as -6.5)", path))
    plain = _plain(new_data, findings, info)
    if plain is not None:
        return plain
    fd, tmp = tempfile.mkstemp(suffix=".dxf", prefix="leathercut-")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(new_data)
        return _parse(path, tmp, findings, info)
    finally:
        os.unlink(tmp)


def _read_bytes(path: str) -> bytes:
    check_regular_file(path)
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise InputError(f"cannot read the file: {exc.strerror or exc}", path) from exc
    if not data.strip():
        raise InputError("the file is empty (0 bytes of drawing data): not a DXF drawing", path)
    return data


def _check_is_dxf_text(path: str, data: bytes) -> None:
    """Refuse files that are clearly not ASCII DXF, saying what they look like."""
    head = data[:4096]
    known = [(b"%PDF", "a PDF document"), (b"\x89PNG", "a PNG image"), (b"\xff\xd8\xff", "a JPEG image"),
             (b"PK\x03\x04", "a ZIP archive (or an office document)"), (b"GIF8", "a GIF image"),
             (b"\x1f\x8b", "a gzip archive")]
    for magic, what in known:
        if head.startswith(magic):
            raise InputError(f"not a DXF file: it is {what}", path)
    if re.match(rb"AC10\d\d|AC1\.\d|AC2\.\d", head[:6]) and b"\n" not in head[:6]:
        raise InputError(f"not a DXF file: it is an AutoCAD DWG drawing ({head[:6].decode()}); "
                         f"export it as DXF from the CAD program", path)
    text = head.lstrip(b"\xef\xbb\xbf \t\r\n")
    if text.startswith((b"<?xml", b"<svg", b"<!DOCTYPE", b"<html")):
        raise InputError("not a DXF file: it is an XML/SVG/HTML document", path)
    if b"\x00" in head:
        raise InputError("not a DXF file: binary data without the 'AutoCAD Binary DXF' header", path)
    lines = text.splitlines()[:2]
    code = lines[0].strip() if lines else b""
    if not re.fullmatch(rb"-?\d+", code) or len(lines) < 2:
        shown = code[:40].decode("latin-1", "replace")
        raise InputError(f"not a DXF file: a DXF starts with a group code line ('0'), "
                         f"this one starts with {shown!r}", path)


def _trailing_bytes(path: str, data: bytes, findings: List[Finding]) -> int:
    """Bytes after the last ``0 / EOF`` pair (0 when none); adds findings."""
    last = None
    pos = len(data)
    while last is None:  # search backwards: the marker is near the end
        pos = data.rfind(b"EOF", 0, pos)
        if pos < 0:
            break
        last = _EOF_MARK.match(data, max(data.rfind(b"\n", 0, max(data.rfind(b"\n", 0, pos), 0)), 0))
        if last is not None and last.end() < pos:
            last = None
    if last is None:
        findings.append(Finding("warning", "no-eof", "no '0 EOF' end marker: the file may be "
                                "truncated; whatever could be read is used", path))
        return 0
    rest = data[last.end():]
    if rest.strip(b" \t\r\n\x00\x1a"):
        findings.append(Finding("warning", "trailing-data",
                                f"{len(rest)} bytes after the EOF marker were ignored", path))
        return len(rest)
    return 0


def _decimal_comma_fix(path: str, data: bytes) -> Optional["tuple[bytes, int]"]:
    """None when the file has no decimal commas; otherwise (fixed bytes, count).

    Raises InputError when commas and points are mixed in numbers (the file's
    numbers cannot be trusted either way)."""
    if b"," not in data:
        return None
    mixed = _MIXED_NUMBER.search(data)
    if mixed:
        line = data.count(b"\n", 0, mixed.start()) + 2
        value = mixed.group(0).split(b"\n")[-1].strip().decode("latin-1")
        raise InputError(f"the number {value!r} at line {line} mixes decimal points and commas: "
                         f"it cannot be read reliably; export the file again with '.' as "
                         f"decimal separator", path)
    commas = list(_COMMA_PAIR.finditer(data))
    if not commas:
        return None
    first_line = data.count(b"\n", 0, commas[0].start(1)) + 1
    example = commas[0].group(1).decode()
    if _POINT_PAIR.search(data) or _MIXED_NUMBER.search(data):
        raise InputError(
            f"numbers with decimal commas (e.g. {example!r} at line {first_line}) are mixed with "
            f"decimal points: the file was written under a comma locale and cannot be read "
            f"reliably; export it again with '.' as decimal separator", path)
    parts: List[bytes] = []
    pos = 0
    for m in commas:
        parts.append(data[pos:m.start(1)])
        parts.append(m.group(1).replace(b",", b"."))
        pos = m.end(1)
    parts.append(data[pos:])
    return b"".join(parts), len(commas)


def _plain(data: bytes, findings: List[Finding], info: Dict[str, Any]) -> Optional[OpenedFile]:
    """The drawing read by the fast reader (:mod:`.plain_reader`), None when it is not plain."""
    doc = read_plain(data)
    if doc is None:
        return None
    info["reader"] = "plain"
    return OpenedFile(doc, findings, info)


def _parse(path: str, real_path: str, findings: List[Finding], info: Dict[str, Any],
           data: Optional[bytes] = None) -> OpenedFile:
    """The fast reader for plain ASCII ``data``, else readfile falling back to
    recover; ``real_path`` is what ezdxf parses."""
    plain = _plain(data, findings, info) if data is not None else None
    if plain is not None:
        return plain
    info["reader"] = "ezdxf"
    try:
        doc = ezdxf.readfile(real_path)
        return OpenedFile(doc, findings, info)
    except OSError as exc:
        raise InputError(f"cannot read the file: {exc}", path) from exc
    except Exception as exc:  # any ezdxf parse failure: try recover mode
        first_error = f"{type(exc).__name__}: {exc}"
        if _LOST_NUMBER.search(str(exc)):
            # recover would read the value as 0 (or truncate it): data silently changed
            raise InputError(f"{first_error.rstrip('.')}: a coordinate is missing or not a "
                             f"number; refused rather than read as 0", path) from exc
    try:
        doc, auditor = recover.readfile(real_path)
    except Exception as exc:
        raise InputError(f"not a readable DXF file: {first_error}; recovery also failed "
                         f"({type(exc).__name__}: {exc})", path) from exc
    fixes = list(getattr(auditor, "fixes", []))
    errors = list(getattr(auditor, "errors", []))
    info.update(recovered=True, recover_fixes=len(fixes), recover_errors=len(errors))
    quoted = "; ".join(str(getattr(f, "message", f)) for f in fixes[:_QUOTED_FIXES])
    more = f" (and {len(fixes) - _QUOTED_FIXES} more)" if len(fixes) > _QUOTED_FIXES else ""
    msg = (f"damaged DXF ({first_error}); opened in recovery mode and repaired: "
           f"{len(fixes)} fixes{': ' + quoted + more if fixes else ''}")
    findings.append(Finding("warning", "recovered", msg, path))
    for err in errors[:_QUOTED_FIXES]:
        findings.append(Finding("warning", "recover-error",
                                f"unrepaired damage: {getattr(err, 'message', err)}", path))
    return OpenedFile(doc, findings, info)
