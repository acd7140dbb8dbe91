"""The tail of a nest: the work after the search, and the time kept free for it.

After the search the engine builds the layout (:func:`engine._to_layout`,
:func:`engine.fill_metrics`), :func:`nest` runs the independent checker, the
caller writes its outputs (layout JSON, DXF, SVG) and the CLI exits.  All of
it must fit in the budget (T + 10 % + 1 s promised), so the search ends
:meth:`Tail.reserve` seconds before ``started + T``:

* the build and the check are timed the first time they run (the engine does
  both on its first layout while the search goes on) and their CPU time is
  kept ``FACTOR`` times, scaled to the number of copies; before that, an
  estimate per copy;
* their wall time at the end is that CPU time times the contention expected
  once the search's own processes have stopped.  Measured: the engine samples
  the machine's runnable tasks (:func:`runnable`, Linux ``/proc/loadavg``)
  while it searches; those that are not its own (the parent and its busy
  workers) are other programs, and the tail, one process, then gets a share
  max(1, (1 + others) / cores) -- before the build and check are timed at
  least ``PRIOR_CONTENTION`` (the engine samples once before its deadlines:
  a visibly loaded machine moves the first fill's last resort earlier;
  Baldacci Test10 with 4 extra busy processes ended 0.06 s inside the limit
  with the prior alone).  Without samples: the wall / CPU ratio r of
  the timed build and check less the search's share, max(1, r - busy /
  cores), which counts the workers' sharing and every other program's as if
  they had been running all along -- on Baldacci hides at T = 60 the
  searches ended 7-10 s before T + 10 % + 1 s with a 1-2 s real tail;
* the outputs the caller declared with :func:`writing` cost a CPU time per
  file and per written vertex (measured, ``OUTPUT_CPU_S``), plus importing
  the library that writes them when it is not imported yet
  (``OUTPUT_IMPORT``; the engine's parent imports it while the workers
  search, :meth:`Tail.preload`, so the DXF then costs the document only),
  times the same contention (``PRIOR_CONTENTION``
  until measured), plus ``EXIT_S``.

:meth:`Tail.check` remembers its verdicts: the same layout under the same
options is checked once (the strip phase checks its result, :func:`nest`
would check it again).

A :class:`Tail` lives for one :func:`nest` call (:func:`session`); code run
outside one (benchmarks, tests calling the engine directly) gets a fresh
one from :func:`current`.  Seconds throughout; ``time.monotonic()`` clock.
"""

from __future__ import annotations

import contextvars
import math
import os
import sys
import time
from contextlib import contextmanager
from typing import Dict, Iterator, List, Optional, Sequence, Tuple

from ..geometry import signed_area
from ..model import Layout, Part
from .checker import check_layout
from .options import NestOptions

#: the measured build + check cost (its CPU time at the expected contention,
#: see the module doc) and the outputs' are kept this many times
FACTOR = 1.25
#: build + check seconds per copy assumed until measured, sheets and strips
#: (measured: DXF parts ~0.4 ms -- GMX, 150 copies, 0.06 s)
PRIOR_PER_COPY_S = {"sheet": 0.001, "strip": 0.001}
#: hides: build + check CPU seconds per copy assumed until measured, (base, per
#: hide vertex x part vertex: outline, holes and zones of an average hide times
#: the segments of an average copy), times ``PRIOR_CONTENTION``, at most
#: ``PRIOR_HIDE_MAX_S``.  Measured (CPU ms per copy): Baldacci Test7 0.3
#: (172 x 6 vertices), Scarpa 0.8 (896 x 36), Test3 3.6 (1,488 x 39), Test10 10
#: (1,023 x 217, part regions); it was 15 ms wall for every hide job, 4.2 s of
#: reserve for Test7's 280 rectangles, whose first fill then gave up on every
#: copy at load 9
PRIOR_HIDE_CPU_S = (0.2e-3, 0.06e-6)
PRIOR_HIDE_MAX_S = 0.015
#: the report and the process exit (the CLI ends with ``os._exit``)
EXIT_S = 0.15
#: CPU seconds of each output: (per file -- the document --, per written vertex
#: of the placed outlines and the containers), measured with the writer's
#: library imported on Baldacci Test2 / Test10 layouts (2,800 / 17,000
#: vertices; DXF one LWPOLYLINE per contour: 0.07 / 0.44 s; layout JSON
#: 0.02 / 0.15 s; a one-part layout: DXF 0.008 s, JSON 0.001 s, SVG 0.001 s)
OUTPUT_CPU_S = {"dxf": (0.03, 0.025e-3), "layout": (0.01, 0.012e-3), "svg": (0.01, 0.005e-3)}
#: outputs whose writer imports a library first: (module, CPU seconds to import it)
OUTPUT_IMPORT = {"dxf": ("ezdxf", 0.27)}
#: CPU seconds per file the first fill's last resort keeps free (:meth:`Tail.files_s`:
#: importing the writer's library and opening the document, cold caches, as
#: measured before the output cost was split by what is already imported)
FILE_WORST_CPU_S = {"dxf": 0.25, "layout": 0.12, "svg": 0.02}
#: wall / CPU of the tail assumed until measured (a loaded 2-core machine)
PRIOR_CONTENTION = 2.5
#: weight of a new runnable-task sample in the running mean of other
#: programs' tasks (the engine samples every ~50 ms: about 2.5 s of memory)
LOAD_WEIGHT = 0.02
#: at least this many seconds between two samples
LOAD_EVERY_S = 0.05

_CURRENT: contextvars.ContextVar[Optional["Tail"]] = contextvars.ContextVar("nest_tail", default=None)
_OUTPUTS: contextvars.ContextVar[Tuple[str, ...]] = contextvars.ContextVar("nest_outputs", default=())


class Tail:
    """Cost model and check memo of one nest (see module doc)."""

    def __init__(self, parts: Sequence[Part], options: NestOptions,
                 outputs: Sequence[str] = ()) -> None:
        self.started = options.started_at if options.started_at is not None else time.monotonic()
        self.budget = options.time_budget
        self.outputs = tuple(outputs)
        #: measured (build + check) seconds per copy, None until measured
        self.per_copy: Optional[float] = None
        #: worker processes searching while the build and check are timed
        #: (the engine sets it; 0: the machine is the measurement's own)
        self.busy = 0
        #: wall / CPU expected for the tail once the search has stopped
        self.contention = PRIOR_CONTENTION
        #: running mean of other programs' runnable tasks (None: not sampled)
        self.others: Optional[float] = None
        self._sampled_at = -math.inf
        self._build: Optional[Tuple[float, float]] = None     # (wall, CPU) s per copy
        self._check: Optional[Tuple[float, float]] = None
        self._memo: Dict[tuple, List[str]] = {}
        #: copies of the job and the segments of an average copy
        self._copies = sum(max(p.quantity, 0) for p in parts)
        self._copy_vertices = (sum(_vertices(p) * max(p.quantity, 0) for p in parts)
                               / self._copies if self._copies else 0.0)
        spec = options.container
        self._prior = PRIOR_PER_COPY_S.get(spec.kind, PRIOR_PER_COPY_S["sheet"])
        if spec.kind == "hide" and spec.hides:
            # the hides used: about twice the parts' bounding-box area (at most all)
            verts = sum(len(h.outline) + sum(map(len, h.defects)) + sum(len(z) for _g, z in h.zones)
                        for h in spec.hides)
            hide_area = sum(abs(signed_area(h.outline)) for h in spec.hides) or 1.0
            part_area = sum(_box_area(p) * max(p.quantity, 0) for p in parts)
            self._container_vertices = verts * min(1.0, 2.0 * part_area / hide_area)
            base, rate = PRIOR_HIDE_CPU_S
            self._prior = min(PRIOR_HIDE_MAX_S, PRIOR_CONTENTION
                              * (base + rate * self._copy_vertices * verts / len(spec.hides)))
        else:
            self._container_vertices = 4 * max(spec.count or 1, 1)

    # ------------------------------------------------------------ cost model
    def note_build(self, seconds: float, copies: int, cpu: Optional[float] = None) -> None:
        """A layout of ``copies`` placements took ``seconds`` (wall; ``cpu``:
        CPU seconds of the thread, None = unknown) to build."""
        if self._build is None and copies > 0:
            self._build = (seconds / copies, (seconds if cpu is None else cpu) / copies)
            self._update()

    def note_check(self, seconds: float, copies: int, cpu: Optional[float] = None) -> None:
        """As :meth:`note_build`, for the check."""
        if self._check is None and copies > 0:
            self._check = (seconds / copies, (seconds if cpu is None else cpu) / copies)
            self._update()

    def note_load(self, ours: int) -> None:
        """Sample the machine's runnable tasks while ``ours`` of them are this
        nest's (the calling process and its busy workers); at most every
        ``LOAD_EVERY_S``.  Updates the expected contention (module doc)."""
        now = time.monotonic()
        if now - self._sampled_at < LOAD_EVERY_S:
            return
        self._sampled_at = now
        n = runnable()
        if n is None:
            return
        other = max(0.0, float(n - ours))
        self.others = other if self.others is None else self.others + LOAD_WEIGHT * (other - self.others)
        self._update()

    def _update(self) -> None:
        known = [c for c in (self._build, self._check) if c is not None]
        wall = sum(w for w, _c in known)
        cpu = sum(c for _w, c in known)
        if self.others is not None:
            self.contention = max(1.0, (1.0 + self.others) / _cores())
            if not known:               # before the first layout: the prior is a floor
                self.contention = max(self.contention, PRIOR_CONTENTION)
        elif cpu > 0:
            self.contention = max(1.0, wall / cpu - self.busy / _cores())
        if not known:
            return
        if cpu > 0:
            wall = cpu * self.contention
        # one of the two measured: the other assumed alike
        self.per_copy = wall * (2.0 / len(known))

    def reserve(self, copies: int, rounds: int = 1, outputs: bool = True) -> float:
        """Seconds to keep free after the search for a nest of ``copies``
        that still builds and checks its layout ``rounds`` times (and writes
        the declared outputs, unless ``outputs`` is False)."""
        per = FACTOR * self.per_copy if self.per_copy is not None else self._prior
        out = FACTOR * self.contention * self._output_cpu_s(copies) if outputs else 0.0
        return EXIT_S + per * copies * rounds + out

    def files_s(self) -> float:
        """Seconds of the declared outputs whatever the layout (opening each
        file: importing ezdxf, the document), at the expected wall / CPU
        (Baldacci Test1 at load ~9: a first fill given up with its last resort
        end kept free for the build and check only ended 0.8 s past T + 10 % + 1 s;
        the worst case ``FILE_WORST_CPU_S``, whatever is imported)."""
        return self.contention * sum(FILE_WORST_CPU_S.get(k, 0.0) for k in self.outputs)

    def _output_cpu_s(self, copies: int) -> float:
        """CPU seconds of the declared outputs of ``copies`` average copies and
        the containers (hides: in proportion to the copies placed)."""
        costs = [OUTPUT_CPU_S[k] for k in self.outputs if k in OUTPUT_CPU_S]
        n = self._copies
        if not costs or not n:
            return 0.0
        share = min(copies, n) / n
        vertices = self._copy_vertices * min(copies, n) + share * self._container_vertices
        imports = {OUTPUT_IMPORT[k] for k in self.outputs if k in OUTPUT_IMPORT}
        return (sum(fixed + rate * vertices for fixed, rate in costs)
                + sum(cpu for module, cpu in imports if module not in sys.modules))

    def preload(self) -> None:
        """Import the declared outputs' writer libraries now (the engine's parent
        does it while its workers search), so the tail no longer pays for it."""
        import importlib
        for module, _cpu in {OUTPUT_IMPORT[k] for k in self.outputs if k in OUTPUT_IMPORT}:
            importlib.import_module(module)

    def promised_end(self) -> float:
        """``started`` + T + 10 % + 1 s of the whole nest (inf without a budget)."""
        return self.started + 1.1 * self.budget + 1.0 if self.budget > 0 else math.inf

    # ------------------------------------------------------------ check memo
    def check(self, parts: Sequence[Part], layout: Layout, options: NestOptions) -> List[str]:
        """:func:`checker.check_layout` of ``layout`` under ``options`` (timed;
        the same layout, parts and options again: the remembered verdict)."""
        key = (id(parts), _options_key(options), _layout_key(layout))
        hit = self._memo.get(key)
        if hit is not None:
            return list(hit)
        t, c = time.monotonic(), time.thread_time()
        problems = check_layout(parts, layout, spacing=options.spacing, margin=options.margin,
                                tol=options.tolerance, chord_tol=options.chord_tol,
                                rotations_override=options.rotations_override,
                                mirror_override=options.mirror_override,
                                free_rotation=options.free_rotation)
        self.note_check(time.monotonic() - t, len(layout.placements), time.thread_time() - c)
        self._memo[key] = list(problems)
        return problems


def runnable() -> Optional[int]:
    """Tasks running or ready to run on the whole machine now, the caller
    included (Linux: ``/proc/loadavg``'s fourth field); None elsewhere."""
    try:
        with open("/proc/loadavg", encoding="ascii") as fh:
            return int(fh.read().split()[3].split("/")[0])
    except (OSError, ValueError, IndexError):
        return None


def _cores() -> int:
    """CPU cores this process may run on."""
    try:
        return max(len(os.sched_getaffinity(0)), 1)
    except AttributeError:                      # not Linux
        return max(os.cpu_count() or 1, 1)


def _vertices(p: Part) -> int:
    return sum(len(c.segments) for c in [p.outer, *p.holes])


def _box_area(p: Part) -> float:
    x0, y0, x1, y1 = p.outer.bbox
    return (x1 - x0) * (y1 - y0)


def _options_key(o: NestOptions) -> tuple:
    return (o.spacing, o.margin, o.tolerance, o.chord_tol,
            None if o.rotations_override is None else tuple(o.rotations_override),
            o.mirror_override, o.free_rotation)


def _layout_key(layout: Layout) -> tuple:
    """Everything of ``layout`` the checker reads."""
    conts = tuple((c.id, c.kind, tuple(map(tuple, c.outline)),
                   tuple(tuple(map(tuple, d)) for d in c.defects),
                   tuple((g, tuple(map(tuple, z))) for g, z in c.zones), c.base_grade)
                  for c in layout.containers)
    pls = tuple((p.part_id, p.copy, p.container, p.x, p.y, p.angle, p.mirrored)
                for p in layout.placements)
    return conts, pls, tuple(layout.unplaced)


@contextmanager
def session(parts: Sequence[Part], options: NestOptions) -> Iterator[Tail]:
    """The :class:`Tail` of one nest, :func:`current` until the block ends."""
    tail = Tail(parts, options, _OUTPUTS.get())
    token = _CURRENT.set(tail)
    try:
        yield tail
    finally:
        _CURRENT.reset(token)


def current(parts: Sequence[Part], options: NestOptions) -> Tail:
    """The running nest's :class:`Tail`, or a new one (no outputs declared)."""
    tail = _CURRENT.get()
    return tail if tail is not None else Tail(parts, options)


@contextmanager
def writing(kinds: Sequence[str]) -> Iterator[None]:
    """Declare the outputs (``dxf``, ``layout``, ``svg``) the caller writes after
    the nests started in this block: their time is kept free too."""
    token = _OUTPUTS.set(tuple(kinds))
    try:
        yield
    finally:
        _OUTPUTS.reset(token)
