"""GRBL-family reply parsing: one function, one dataclass, the message tables.

Every line a GRBL 1.1 / grblHAL controller sends is one of: ``ok``,
``error:N``, ``ALARM:N``, a status report ``<State|MPos:..|..>``, the banner
(``Grbl 1.1h [...]`` or ``GrblHAL 1.1f [...]``), a bracketed push message
(``[MSG:..]``, ``[VER:..]``, ``[OPT:..]``, ``[AXS:..]``, ``[GC:..]``), a
setting ``$N=v`` or a startup-line echo ``>..:ok``.  Only ``ok`` and
``error:N`` answer a sent line; everything else is a push message.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Dict, List, Optional

#: GRBL 1.1 error texts (doc/csv/error_codes_en_US.csv, shortened).
ERROR_TEXT = {
    1: "G-code words consist of a letter and a value; letter was not found",
    2: "numeric value format is not valid or missing an expected value",
    3: "'$' system command was not recognized or supported",
    4: "negative value received for an expected positive value",
    5: "homing cycle is not enabled via settings",
    8: "'$' command valid only when Idle",
    9: "G-code locked out during alarm or jog state",
    10: "soft limits cannot be enabled without homing also enabled",
    11: "max characters per line exceeded; line was not processed",
    15: "jog target exceeds machine travel",
    20: "unsupported or invalid G-code command found in block",
    21: "more than one G-code command from the same modal group found in block",
    22: "feed rate has not yet been set or is undefined",
    23: "G-code command in block requires an integer value",
    24: "two G-code commands that both require axis words",
    25: "a G-code word was repeated in the block",
    26: "a G-code command implicitly or explicitly requires XYZ axis words; none found",
    27: "N line number value is not within the valid range",
    28: "a G-code command was sent but is missing required P or L value words",
    29: "system does not support G59.x work coordinate systems",
    33: "motion command has an invalid target (arc radius mismatch or unreachable)",
    34: "arc radius definition error",
    35: "G2/G3 arcs require at least one in-plane offset word",
    36: "unused value words found in block",
    37: "G43.1 dynamic tool length offset not assigned to the tool length axis",
    38: "tool number greater than max supported value",
}

#: GRBL 1.1 alarm texts (doc/csv/alarm_codes_en_US.csv, shortened).
ALARM_TEXT = {
    1: "hard limit triggered; machine position is likely lost, re-homing recommended",
    2: "soft limit: target exceeds machine travel; position retained",
    3: "reset while in motion; position is likely lost, re-homing recommended",
    4: "probe fail: not in the expected initial state",
    5: "probe fail: did not contact the workpiece",
    6: "homing fail: reset during the homing cycle",
    7: "homing fail: safety door opened during homing",
    8: "homing fail: pull-off failed to clear the limit switch",
    9: "homing fail: could not find the limit switch",
    10: "homing fail: second switch triggered (dual axis)",
}

_BANNER = re.compile(r"^(Grbl|GrblHAL)\s+(\S+)", re.IGNORECASE)


@dataclass
class Reply:
    """A parsed controller line.  ``kind``: ok | error | alarm | status | banner
    | msg | info | setting | echo | other."""

    kind: str
    raw: str
    code: int = 0
    state: str = ""
    fields: Dict[str, str] = field(default_factory=dict)
    text: str = ""
    epoch: int = 0            # banners (controller resets) seen before this line arrived
    seq: int = 0              # ok/error: its number; status: answers received before it
    written: int = -1         # status: line bytes the host had written when it polled
    written_rx: int = -1      # status: line bytes written (or being written) when it arrived
    at: float = 0.0           # ok/error: when it arrived (time.monotonic), 0 unknown
    rx_used: int = -1         # status: receive-buffer bytes unread (from Bf), -1 unknown


def parse_reply(line: str) -> Reply:
    """Classify one line (without its line end)."""
    s = line.strip()
    if s == "ok":
        return Reply("ok", s)
    if s.startswith("error:"):
        code = _int(s[6:])
        return Reply("error", s, code=code, text=ERROR_TEXT.get(code, "unknown error"))
    if s.startswith("ALARM:"):
        code = _int(s[6:])
        return Reply("alarm", s, code=code, text=ALARM_TEXT.get(code, "unknown alarm"))
    if s.startswith("<") and s.endswith(">"):
        parts = s[1:-1].split("|")
        fields = {}
        for p in parts[1:]:
            if ":" in p:
                k, v = p.split(":", 1)
                fields[k] = v
        return Reply("status", s, state=parts[0], fields=fields)
    m = _BANNER.match(s)
    if m and "[" in s:
        return Reply("banner", s, text=f"{m.group(1)} {m.group(2)}")
    if s.startswith("[") and s.endswith("]"):
        body = s[1:-1]
        key, _, val = body.partition(":")
        if key == "MSG":
            return Reply("msg", s, text=val)
        return Reply("info", s, fields={key: val}, text=val)
    if s.startswith("$") and "=" in s:
        return Reply("setting", s, text=s)
    if s.startswith(">"):
        return Reply("echo", s, text=s)
    return Reply("other", s, text=s)


def _int(text: str) -> int:
    try:
        return int(text.strip())
    except ValueError:
        return -1


def position(status: Reply, wco: Optional[List[float]] = None) -> Optional[List[float]]:
    """Work position from a status report: WPos, or MPos minus the cached WCO."""
    if "WPos" in status.fields:
        return [float(v) for v in status.fields["WPos"].split(",")]
    if "MPos" in status.fields:
        mpos = [float(v) for v in status.fields["MPos"].split(",")]
        if wco:
            return [a - b for a, b in zip(mpos, wco)]
        return mpos
    return None


#: Commands a host must send one at a time (EEPROM writes / reads on AVR GRBL).
EEPROM_PATTERN = re.compile(r"^(G10|G28|G30|\$\d+=|\$I|\$N|\$RST=|G5[4-9]|\$\$|\$#)")
