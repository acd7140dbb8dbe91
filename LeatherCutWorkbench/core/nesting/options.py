"""Options of the nesting stage.

Units: mm for every length, degrees for every angle, seconds for times.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

from ..errors import InputError
from ..model import Container


@dataclass
class ContainerSpec:
    """What to nest on.

    ``kind`` is ``"sheet"`` (``width`` x ``height`` mm rectangles, ``count``
    sheets at most -- None opens new sheets as long as parts remain),
    ``"strip"`` (``height`` mm wide, open length along +X: the used length is
    minimised) or ``"hide"`` (``hide``: an irregular :class:`Container` with
    defects and quality zones, e.g. from :func:`containers.read_hide_dxf`;
    several hides may be given in ``hides`` and are filled in order)."""

    kind: str = "sheet"
    width: float = 0.0
    height: float = 0.0
    count: Optional[int] = None
    hides: List[Container] = field(default_factory=list)

    @staticmethod
    def sheet(width: float, height: float, count: Optional[int] = None) -> "ContainerSpec":
        return ContainerSpec(kind="sheet", width=float(width), height=float(height), count=count)

    @staticmethod
    def strip(width: float) -> "ContainerSpec":
        """A strip ``width`` mm wide (its Y extent) with open length along X."""
        return ContainerSpec(kind="strip", height=float(width))

    @staticmethod
    def hide(*hides: Container) -> "ContainerSpec":
        return ContainerSpec(kind="hide", hides=list(hides))

    def validate(self) -> None:
        if self.kind == "sheet":
            if not (self.width > 0 and self.height > 0):
                raise InputError(f"sheet size must be positive, got {self.width} x {self.height} mm")
            if self.count is not None and self.count < 1:
                raise InputError(f"sheet count must be at least 1, got {self.count}")
        elif self.kind == "strip":
            if not self.height > 0:
                raise InputError(f"strip width must be positive, got {self.height} mm")
        elif self.kind == "hide":
            if not self.hides:
                raise InputError("hide nesting needs at least one hide outline")
        else:
            raise InputError(f"unknown container kind {self.kind!r} (sheet, strip or hide)")


@dataclass
class NestOptions:
    """Everything the nesting stage needs besides the parts.

    * ``container`` -- see :class:`ContainerSpec`.
    * ``spacing`` -- minimum gap between two parts (knife width / kerf), mm.
    * ``margin`` -- minimum distance from a part to the container edge and to
      defects, mm.
    * ``rotation_step`` -- degrees between tried angles for parts whose
      ``rotations`` is None (any angle); ``rotations_override`` (a list of
      degrees) replaces every part's own setting when given; ``free_rotation``
      lets every part turn to any angle (tried every ``rotation_step``).
    * ``mirror_override`` -- when not None, replaces every part's
      ``mirror_allowed``.
    * ``time_budget`` -- seconds for the whole nest, counted from
      ``started_at``: shapes, no-fit polygons, the first fill and the search
      (0 = the first fill only, without a limit).
    * ``max_evaluations`` -- when set, every worker stops after this many
      candidate layouts: the result is then identical for the same seed on any
      machine (see docs/CLI.md, determinism).  The time budget still caps the
      run.
    * ``seed`` -- random seed; ``workers`` -- processes (None = all cores).
    * ``engine`` -- ``"own"`` or ``"sparrow"`` (spyrrow, strip jobs without
      holes or quality zones only).
    * ``chord_tol`` -- arcs are flattened with this chord error (mm) and
      spacing offsets use it as arc tolerance.
    * ``tolerance`` -- the validity checker's length tolerance (mm): overlaps,
      protrusions and spacing shortfalls thinner than this are accepted.
    * ``grades`` -- grade per part id or part name (a whole number or a letter
      A-D, A best; see :mod:`core.dxfimport.grades`), replacing the part's own.
    * ``started_at`` -- ``time.monotonic()`` when the user asked for the nest
      (the CLI: before reading the drawing); the time budget counts from there.
      None: from the call of :func:`nest`.  Transient (field metadata): a
      moment of this process, so it is not a document property; it survives
      :func:`dataclasses.replace`.
    """

    container: ContainerSpec = field(default_factory=ContainerSpec)
    spacing: float = 0.0
    margin: float = 0.0
    rotation_step: float = 30.0
    rotations_override: Optional[List[float]] = None
    free_rotation: bool = False
    mirror_override: Optional[bool] = None
    time_budget: float = 10.0
    max_evaluations: Optional[int] = None
    seed: int = 1
    workers: Optional[int] = None
    engine: str = "own"
    chord_tol: float = 0.05
    tolerance: float = 1e-3
    grades: Dict[str, Any] = field(default_factory=dict)
    started_at: Optional[float] = field(default=None, metadata={"transient": True})

    def part_grade(self, part_id: str, name: str, own: int) -> int:
        """The grade a part nests with: ``grades`` by id, then by name, else its own."""
        from ..dxfimport.grades import parse_grade
        for key in (part_id, name):
            if key and key in self.grades:
                return parse_grade(self.grades[key], f"grade of part {key}")
        return own

    def part_rotations(self, own: Optional[List[float]]) -> Optional[List[float]]:
        """The allowed angles of a part under these options (None = any angle)."""
        if self.free_rotation:
            return None
        return self.rotations_override if self.rotations_override is not None else own

    def validate(self) -> None:
        self.container.validate()
        if self.spacing < 0 or self.margin < 0:
            raise InputError(f"spacing and margin must be >= 0 mm, got {self.spacing} / {self.margin}")
        if not 0 < self.rotation_step <= 360:
            raise InputError(f"rotation step must be in (0, 360] degrees, got {self.rotation_step}")
        if self.time_budget < 0:
            raise InputError(f"time budget must be >= 0 s, got {self.time_budget}")
        if self.engine not in ("own", "sparrow"):
            raise InputError(f"unknown nesting engine {self.engine!r} (own or sparrow)")
        if self.workers is not None and self.workers < 1:
            raise InputError(f"workers must be >= 1, got {self.workers}")
        for key in self.grades:
            self.part_grade(key, "", 0)
        if self.chord_tol <= 0 or self.tolerance <= 0:
            raise InputError("chord tolerance and checker tolerance must be > 0 mm")


def parse_rotations(text: str) -> Tuple[Optional[List[float]], Optional[float]]:
    """Parse a ``--rotations`` value: ``any`` -> (None, None); ``0,180`` ->
    ([0, 180], None); ``step:90`` -> ([0, 90, 180, 270], 90); a grain
    direction with a tolerance, ``0+-5`` (or ``0±5``; several: ``0+-5,180+-5``)
    -> the angles from -5 to 5 degrees in equal steps of at most 2.5."""
    t = text.strip().lower().replace("±", "+-")
    if t == "any":
        return None, None
    try:
        if t.startswith("step:"):
            step = float(t[5:])
            if not 0 < step <= 360:
                raise ValueError
            n = max(1, int(round(360.0 / step)))
            return [round(i * step, 9) % 360.0 for i in range(n) if i * step < 360.0 - 1e-9], step
        vals: List[float] = []
        for v in (v.strip() for v in t.split(",")):
            if not v:
                continue
            if "+-" in v:
                base, tol = (float(x) for x in v.split("+-"))
                if not 0 <= tol < 180:
                    raise ValueError
                n = int(math.ceil(tol / 2.5)) if tol > 0 else 0
                vals += [round((base + tol * k / max(n, 1)) % 360.0, 9) for k in range(-n, n + 1)]
            else:
                vals.append(float(v) % 360.0)
        if not vals:
            raise ValueError
        return sorted(set(vals)), None
    except ValueError:
        raise InputError(f"bad --rotations value {text!r}: use any, a list like 0,180, step:90 "
                         "or a grain tolerance like 0+-5") from None
