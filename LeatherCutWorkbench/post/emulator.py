"""A fake GRBL-family controller on a pseudo-terminal, for tests and dry runs.

:class:`FakeController` opens a pty pair (``os.openpty`` + ``tty.setraw``); a
host opens :attr:`FakeController.port` with pyserial exactly like a real port.
A thread on the master side behaves like the firmware as far as a sender can
see (facts: docs in /work/shared/notes/machine.md, GRBL 1.1h and grblHAL):

* a real receive buffer of ``rx_size`` bytes (128 GRBL, 1024 grblHAL): bytes
  beyond it are dropped and :attr:`overflows` counts them (a correct
  character-counting host never overflows it);
* lines end at ``\\n`` or ``\\r``; one ``ok``/``error:N`` per line, in order;
  lines are executed by the project's G-code interpreter (so a ``C`` word on a
  3-axis GRBL is ``error:20`` and a bad arc ``error:33``); longer than 80
  bytes -> ``error:11``; in Alarm every G-code line -> ``error:9``;
* realtime bytes bypass the buffer: ``?`` status ``<Idle|MPos:..|Bf:..|FS:..>``
  (``Bf:`` planner blocks and receive-buffer bytes free, left out with
  ``report_buffer=False`` like stock GRBL's ``$10=1``; ``WCO:`` in the first
  report and every tenth, as GRBL),
  ``!`` feed hold (``Hold:0``), ``~`` resume, ``0x18`` soft reset (flushes
  the buffer, ``ALARM:3`` if motion was queued, then the banner);
* ``$I`` ``$$`` ``$G`` ``$C`` (check mode; leaving it resets) ``$X`` ``$H``;
* grblHAL flavour: banner ``GrblHAL 1.1f``, ``[AXS:..]``, and after a G-code
  error the same ``error:N`` to every line until a reset.

Faults (:class:`Fault`) fire when the controller is about to process the
N-th G-code line it receives (1-based, counted over the emulator's life):
``error`` (answer ``error:code`` instead), ``alarm`` (``ALARM:code``, lock),
``reset`` (power cycle: buffer and queue lost, bytes arriving during
``boot_time`` lost, then the banner; the position counters restart at 0
where the machine stands, locked when homing is on; with
``after`` > 0 the line is processed and the power fails ``after`` seconds
later), ``stall`` (silent for ``seconds``: no acks, no status), ``disconnect``
(the port goes away; :meth:`FakeController.reconnect` is the controller seen
again, with or without a power loss), ``garble`` (the line arrives
corrupted), ``garble_reply`` (its answer arrives as ``o\xffk``), ``spurious``
(an extra ``ok`` arrives before its answer), ``drop_ack`` (processed, never
answered) and ``drop_status`` (the next ``?`` goes unanswered).  A
``disconnect`` with ``after`` > 0 answers the line and loses the port
``after`` seconds later, the machine finishing its queue.  ``split`` writes
every reply byte by byte (split reads); ``settings`` adds ``$$`` settings
(e.g. grblHAL ``$701``).

Where the machine really is: :attr:`offset` is the physical position minus
the position counters (0 until a power cycle; ``$H`` and :meth:`rezero` -- the
operator setting the work zero at the machine -- bring it back to 0).
:attr:`misplaced` counts motion lines executed while the offset was not 0
(cut in the wrong place); :attr:`max_rx` is the most bytes ever waiting in
the receive buffer.

Planner: with ``planner_blocks`` > 0 the controller behaves like the real
firmware's look-ahead queue -- a motion line is acknowledged when it enters
the queue (waiting in the receive buffer while the queue is full) and is
*executed* ``block_time`` seconds per block later; lines that switch outputs
or dwell (``M3 M4 M5 M7 M8 M9 G4``) wait until the queue is empty, as GRBL
synchronises them.  A feed hold stops execution (``Hold:0``), a reset flushes
the queue (``ALARM:3`` when it was moving).  With 0 (default) every line is
executed when it is acknowledged.

Written here by hand: PyPI has no GRBL emulator (the serial mocks there only
replay canned bytes, without a receive buffer, planner or realtime commands).

``executed`` lists every G-code line the machine executed outside check mode,
in order.  ``results`` holds, for every G-code line it processed, a list
``[session, block, reply, executed]`` where ``session`` counts resets,
``reply`` is ``ok``, ``error:N`` or ``ALARM:N`` and ``executed`` tells
whether the machine really made the move.  ``exec_log`` holds those
entries in the order they were executed and ``report_marks`` how many had
been executed when each status report was made (what a report could prove).
"""

from __future__ import annotations

import copy
import os
import select
import threading
import time
import tty
from dataclasses import dataclass, field
from typing import List, Optional

from .gcode_reader import GcodeError, Interpreter, strip_line

LINE_BUFFER = 80          # GRBL LINE_BUFFER_SIZE: longer lines get error:11
REALTIME = {ord("?"), ord("!"), ord("~"), 0x18}


@dataclass
class Fault:
    """An injected fault; see the module docstring.  ``at_line`` counts G-code
    lines received by the controller (1-based)."""

    kind: str                 # error | alarm | reset | stall | disconnect | garble
    at_line: int
    code: int = 20            # error / alarm number
    seconds: float = 1.0      # stall length
    wait_full: bool = False   # hold the line until the RX buffer is half full (busy machine)
    long_move: bool = False   # planner: the machine is in a long move from planner_blocks
                              # lines before the fault until a hold/reset (or 3 s), so the
                              # queue holds acknowledged, unexecuted lines when it fires
    after: float = 0.0        # reset: power fails this long after processing the line
    fired: bool = False


@dataclass
class FakeController:
    flavour: str = "grbl"                 # grbl | grblhal
    axes: str = "XYZ"
    rx_size: int = 0                      # 0 = flavour default (128 / 1024)
    line_time: float = 0.0                # s per processed line (lets the buffer fill)
    homing: bool = False                  # $22=1: locked at power-up until $H / $X
    wrapped: str = ""
    planner_blocks: int = 0               # look-ahead queue length (0 = execute at once)
    block_time: float = 0.002             # s to execute one queued motion block
    faults: List[Fault] = field(default_factory=list)
    executed: List[str] = field(default_factory=list)
    checked: List[str] = field(default_factory=list)
    log: List[str] = field(default_factory=list)
    results: List[list] = field(default_factory=list)
    session: int = 0
    overflows: int = 0
    gcode_lines: int = 0
    split: bool = False                   # write replies byte by byte
    boot_time: float = 0.05               # s after a power cycle before the banner
    settings: dict = field(default_factory=dict)   # extra $$ settings, e.g. {"701": "1"}
    report_buffer: bool = True            # Bf: in status reports (GRBL $10 bit 1)
    offset: dict = field(default_factory=dict)
    misplaced: int = 0
    max_rx: int = 0
    exec_log: List[list] = field(default_factory=list)    # results entries, as executed
    report_marks: List[tuple] = field(default_factory=list)   # (session, len(exec_log))
                                                          # when each status report was made

    def __post_init__(self) -> None:
        if not self.rx_size:
            self.rx_size = 1024 if self.flavour == "grblhal" else 128
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave)
        tty.setraw(self.master)
        self.port = os.ttyname(self.slave)
        self._rx = bytearray()
        self._stop = threading.Event()
        self._state = "Alarm" if self.homing else "Idle"
        self._check = False
        self._latched: Optional[int] = None
        self._interp = Interpreter(self.axes, self.wrapped)
        self._saved_interp: Optional[Interpreter] = None
        self._stall_until = 0.0
        self._next_time = 0.0
        self._closed = False
        self._queue: List[tuple] = []       # (results entry, block, end position)
        self._next_exec = 0.0
        self._mpos = dict(self._interp.pos)
        self._frozen_until = 0.0
        self._power_fail_at = 0.0
        self._boot_until = 0.0
        self._disconnect_at = 0.0
        self._drop_status = 0
        self._wco_count = 0                 # status reports since the last WCO field
        self.offset = {a: float(self.offset.get(a, 0.0)) for a in self.axes}
        self._thread = threading.Thread(target=self._run, name="fake-grbl", daemon=True)

    # ------------------------------------------------------------ lifecycle
    def start(self) -> "FakeController":
        self._thread.start()
        self._send(self._banner())
        if self._state == "Alarm":
            self._send("[MSG:'$H'|'$X' to unlock]")
        return self

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=2)
        for fd in (self.master, self.slave):
            try:
                os.close(fd)
            except OSError:
                pass

    def __enter__(self) -> "FakeController":
        return self.start()

    def __exit__(self, *exc) -> None:
        self.close()

    def reconnect(self, power_lost: bool) -> "FakeController":
        """The controller as a host sees it after this one's port went away
        (``disconnect``): a new port; without a power loss it kept its state
        and position (Idle, buffered lines executed), with one it restarted
        (counters at 0 where the machine stands, locked when homing is on).
        Not started."""
        phys = self.physical()
        emu = FakeController(flavour=self.flavour, axes=self.axes, rx_size=self.rx_size,
                             homing=self.homing, wrapped=self.wrapped,
                             planner_blocks=self.planner_blocks, block_time=self.block_time,
                             split=self.split)
        emu.session = self.session + 1
        if power_lost:
            emu.offset = dict(phys)
        else:
            emu.offset = dict(self.offset)
            emu._interp.pos = {a: phys[a] - self.offset[a] for a in self.axes}
            emu._mpos = dict(emu._interp.pos)
            emu._state = "Idle"
        return emu

    def physical(self) -> dict:
        """Where the machine physically is (counters + offset)."""
        pos = self.position
        return {a: pos[a] + self.offset.get(a, 0.0) for a in self.axes}

    def rezero(self) -> None:
        """The operator sets the work zero at the machine again: the counters
        agree with the physical position (offset 0)."""
        phys = self.physical()
        self._interp.pos = dict(phys)
        self._mpos = dict(phys)
        self.offset = {a: 0.0 for a in self.axes}

    def unlock(self) -> None:
        """The operator unlocks the controller at the machine (``$X`` from a
        terminal, after clearing the cause of an alarm)."""
        if self._state == "Alarm":
            self._state = "Idle"

    def _placed(self, block: str) -> None:
        if any(abs(v) > 1e-9 for v in self.offset.values()) and \
                any(a in block for a in "XYZABC"):
            self.misplaced += 1

    @property
    def state(self) -> str:
        return self._state

    @property
    def position(self) -> dict:
        """Where the machine is (mm / axis units): the end of the last executed move."""
        return dict(self._mpos if self.planner_blocks else self._interp.pos)

    @property
    def spindle(self) -> str:
        """``M3``/``M4``/``M5``: the spindle output (servo lift, torch, oscillator)."""
        return self._interp.state.spindle

    # ------------------------------------------------------------- internals
    def _banner(self) -> str:
        if self.flavour == "grblhal":
            return "GrblHAL 1.1f ['$' or '$HELP' for help]"
        return "Grbl 1.1h ['$' for help]"

    def _send(self, text: str) -> None:
        self._send_raw((text + "\r\n").encode("ascii"))

    def _send_raw(self, data: bytes) -> None:
        if self._closed:
            return
        try:
            if self.split:
                for i in range(len(data)):
                    os.write(self.master, data[i:i + 1])
                    time.sleep(0.0002)
            else:
                os.write(self.master, data)
        except OSError:
            self._closed = True

    def _run(self) -> None:
        while not self._stop.is_set() and not self._closed:
            now = time.monotonic()
            if now < self._stall_until:
                time.sleep(min(0.01, self._stall_until - now))
                continue
            if self._boot_until:
                if now < self._boot_until:
                    self._discard_input(self._boot_until - now)
                    continue
                self._boot_until = 0.0
                self._discard_input(0.0)
                self._greet_after_reset()
            if self._power_fail_at and now >= self._power_fail_at:
                self._power_fail_at = 0.0
                self._reset(moving=False, power_cycle=True)
                continue                     # boots first (see _boot_until)
            if self._disconnect_at and now >= self._disconnect_at:
                self._closed = True          # the cable goes; the machine runs on
                try:
                    os.close(self.master)
                except OSError:
                    pass
                while self._queue:           # it finishes what it had queued
                    self._execute_queue()
                    time.sleep(self.block_time)
                break
            busy = self._has_line() and not self._state.startswith("Hold")
            wait = max(0.001, min(0.02, self._next_time - now)) if busy else 0.02
            try:
                ready, _, _ = select.select([self.master], [], [], wait)
            except (OSError, ValueError):
                break
            if ready:
                try:
                    data = os.read(self.master, 4096)
                except OSError:
                    data = b""
                if not data:                 # host side closed: wait for a reopen
                    time.sleep(0.005)
                for b in data:
                    if b in REALTIME:
                        self._realtime(b)
                    elif len(self._rx) < self.rx_size - 1:
                        self._rx.append(b)
                    else:
                        self.overflows += 1
                self.max_rx = max(self.max_rx, len(self._rx))
            if self._state.startswith("Hold"):
                continue
            self._execute_queue()
            while self._has_line() and time.monotonic() >= self._next_time:
                if self._waiting_for_full_buffer():
                    break
                if not self._planner_accepts():
                    if not self._queue or self._needs_empty_queue():
                        self._frozen_until = 0.0  # an output/dwell line waits: move on
                    break
                self._next_time = time.monotonic() + self.line_time
                self._process_one()
                if self._closed or time.monotonic() < self._stall_until:
                    break
                if self.line_time > 0:
                    break

    def _discard_input(self, wait: float) -> None:
        """Read and drop what the host sends while the controller boots."""
        try:
            ready, _, _ = select.select([self.master], [], [], max(0.0, min(wait, 0.01)))
            if ready:
                os.read(self.master, 4096)
        except (OSError, ValueError):
            self._closed = True

    def _execute_queue(self) -> None:
        """Run queued motion blocks, one per ``block_time``."""
        nxt = self.gcode_lines + 1
        for f in self.faults:
            # the long move starts once the queue has room for every line up to
            # the fault, so the fault line still gets in behind the queued ones
            if f.long_move and not f.fired and not hasattr(f, "_moving") \
                    and f.at_line - self.planner_blocks < nxt <= f.at_line \
                    and len(self._queue) + (f.at_line - nxt) < self.planner_blocks:
                f._moving = True
                self._frozen_until = time.monotonic() + 3.0
        if time.monotonic() < self._frozen_until:
            return
        while self._queue and time.monotonic() >= self._next_exec:
            entry, block, end = self._queue.pop(0)
            entry[3] = True
            self.exec_log.append(entry)
            self.executed.append(block)
            self._placed(block)
            self._mpos = end
            self._next_exec = time.monotonic() + self.block_time

    def _next_block(self) -> str:
        cut = [i for i in (self._rx.find(b"\n"), self._rx.find(b"\r")) if i >= 0]
        return strip_line(bytes(self._rx[:min(cut)]).decode("ascii", "replace"))

    def _needs_empty_queue(self) -> bool:
        block = self._next_block()
        return block.startswith("$") or any(m in block for m in ("M3", "M4", "M5", "M7", "M8",
                                                                  "M9", "G4"))

    def _planner_accepts(self) -> bool:
        """Whether the next received line may be processed now: a motion line
        needs room in the queue, an output/dwell line an empty queue."""
        if not self.planner_blocks or self._check:
            return True
        block = self._next_block()
        if self._needs_empty_queue():
            return not self._queue
        if any(a in block for a in "XYZABC"):
            if not self._queue:
                self._next_exec = time.monotonic() + self.block_time
            return len(self._queue) < self.planner_blocks
        return True

    def _waiting_for_full_buffer(self) -> bool:
        """A ``wait_full`` fault is next: let the host fill the buffer first (as
        while a long move runs), for at most one second."""
        nxt = self.gcode_lines + 1
        for f in self.faults:
            if f.wait_full and not f.fired and f.at_line == nxt:
                if not hasattr(f, "_since"):
                    f._since = time.monotonic()
                full = len(self._rx) >= self.rx_size // 2
                return not full and time.monotonic() - f._since < 3.0
        return False

    def _has_line(self) -> bool:
        return b"\n" in self._rx or b"\r" in self._rx

    def _pop_line(self) -> bytes:
        idx = [i for i in (self._rx.find(b"\n"), self._rx.find(b"\r")) if i >= 0]
        cut = min(idx)
        line = bytes(self._rx[:cut])
        del self._rx[:cut + 1]
        return line

    def _realtime(self, b: int) -> None:
        if b == ord("?"):
            if self._drop_status:
                self._drop_status -= 1       # line noise ate this poll
                return
            self.report_marks.append((self.session, len(self.exec_log)))
            self._send(self._status())
        elif b == ord("!"):
            self._frozen_until = 0.0
            if self._state in ("Idle", "Run"):
                self._state = "Hold:0"
        elif b == ord("~"):
            if self._state == "Hold:0":
                self._state = "Idle"
        elif b == 0x18:
            # lines still queued while not held = the machine is running the job
            self._reset(moving=self._state in ("Idle", "Run") and self._has_line())

    def _status(self) -> str:
        pos = self.position
        mpos = ",".join(f"{pos[a]:.3f}" for a in self.axes)
        state = self._state
        if state == "Idle" and (self._has_line() or self._queue):
            state = "Run"
        if self._check:
            state = "Check"
        feed = self._interp.state.feed or 0
        free = (self.planner_blocks or 15) - len(self._queue)
        # like GRBL: the work offset now and then (first report after a start),
        # always 0 here (the position counters are the work coordinates)
        wco = "|WCO:" + ",".join("0.000" for _ in self.axes) if not self._wco_count else ""
        self._wco_count = (self._wco_count + 1) % 10
        bf = f"|Bf:{free},{self.rx_size - len(self._rx)}" if self.report_buffer else ""
        return f"<{state}|MPos:{mpos}{bf}|FS:{feed:g},0{wco}>"

    def _reset(self, moving: bool, power_cycle: bool = False) -> None:
        self.session += 1
        self._wco_count = 0
        self._frozen_until = 0.0
        self._rx.clear()
        self._latched = None
        if self._check and self._saved_interp is not None:
            self._interp = self._saved_interp
        self._check = False
        keep = self.position                 # queued moves are dropped, not made
        if power_cycle:                      # counters restart at 0 where the machine is
            self.offset = {a: keep[a] + self.offset.get(a, 0.0) for a in self.axes}
            keep = {a: 0.0 for a in self.axes}
        if not power_cycle:                  # a power cycle says nothing, it reboots
            moving = moving or (bool(self._queue) and not self._state.startswith("Hold"))
        self._queue.clear()
        self._interp = Interpreter(self.axes, self.wrapped)
        self._interp.pos = dict(keep)
        self._mpos = dict(keep)
        if moving and self._state not in ("Alarm",):
            self._send("ALARM:3")
            self._state = "Alarm"
        if power_cycle:
            self._state = "Alarm" if self.homing else "Idle"
        elif self._state != "Alarm":
            self._state = "Idle"
        if power_cycle:
            # the bootloader runs first: bytes arriving meanwhile are lost, the
            # banner comes when the firmware starts
            self._boot_until = time.monotonic() + self.boot_time
            return
        self._greet_after_reset()

    def _greet_after_reset(self) -> None:
        self._send(self._banner())
        if self._state == "Alarm":
            self._send("[MSG:'$H'|'$X' to unlock]")

    def _fault_for(self, n: int) -> Optional[Fault]:
        """The fault that decides how line ``n`` is answered.  Faults that only
        add something (a spurious ``ok``, a dropped ``?``, a power cut or a
        disconnect some time after the line) fire alongside it, so several
        faults may share one line."""
        main = None
        for f in self.faults:
            if f.fired or f.at_line != n:
                continue
            if f.kind == "spurious":
                f.fired = True
                self._send("ok")
            elif f.kind == "drop_status":
                f.fired = True
                self._drop_status = 1
            elif f.kind == "reset" and f.after > 0:
                f.fired = True
                self._power_fail_at = time.monotonic() + f.after
            elif f.kind == "disconnect" and f.after > 0:
                f.fired = True
                self._disconnect_at = time.monotonic() + f.after
            elif main is None:
                f.fired = True
                main = f
        return main

    def _process_one(self) -> None:
        raw = self._pop_line()
        try:
            text = raw.decode("ascii")
        except UnicodeDecodeError:
            self._send("error:1")
            return
        block = strip_line(text)
        self.log.append(block)
        if block.startswith("$"):
            self._system(block)
            return
        if not block:
            self._send("ok")
            return
        self.gcode_lines += 1
        fault = self._fault_for(self.gcode_lines)
        if fault is not None:
            if fault.kind == "stall":
                self._stall_until = time.monotonic() + fault.seconds
                self._rx[:0] = raw + b"\n"     # processed after the stall
                self.gcode_lines -= 1
                return
            if fault.kind == "disconnect":
                self._closed = True
                try:
                    os.close(self.master)
                except OSError:
                    pass
                return
            if fault.kind == "reset":
                self._reset(moving=False, power_cycle=True)
                return
            if fault.kind == "alarm":
                # soft limit: hold, queue flushed, position kept, locked
                self.results.append([self.session, block, f"ALARM:{fault.code}", False])
                self._queue.clear()
                self._interp.pos = dict(self.position)
                self._send(f"ALARM:{fault.code}")
                self._state = "Alarm"        # later lines get error:9
                return
            if fault.kind == "error":
                self._answer_error(fault.code, block)
                return
            if fault.kind == "garble":
                block = "#" + block[1:]           # line noise hit the first byte
        if len(raw) > LINE_BUFFER - 1:
            self._answer_error(11, block)
            return
        if self._state == "Alarm":
            self._answer_error(9, block, latch=False)
            return
        if self._latched is not None:
            self._answer_error(self._latched, block)
            return
        try:
            moves = self._interp.execute(block, self.gcode_lines)
        except GcodeError as exc:
            self._answer_error(exc.code, block)
            return
        if self._check:
            self.checked.append(block)
        else:
            motion = [m for m in moves if m.kind in ("rapid", "line", "arc")]
            entry = [self.session, block, "ok", not (self.planner_blocks and motion)]
            self.results.append(entry)
            if entry[3]:
                self.exec_log.append(entry)
                self.executed.append(block)
                self._placed(block)
                self._mpos = dict(self._interp.pos)
            else:
                self._queue.append((entry, block, dict(motion[-1].end)))
        if fault is not None and fault.kind == "drop_ack":
            return
        if fault is not None and fault.kind == "garble_reply":
            self._send_raw(b"o\xffk\r\n")
            return
        self._send("ok")

    def _answer_error(self, code: int, block: str, latch: bool = True) -> None:
        if self.flavour == "grblhal" and latch:
            self._latched = code
        if not self._check:
            self.results.append([self.session, block, f"error:{code}", False])
        self._send(f"error:{code}")

    def _system(self, block: str) -> None:
        cmd = block[1:]
        if cmd == "I":
            if self.flavour == "grblhal":
                self._send("[VER:1.1f.20240101:]")
                self._send(f"[OPT:VNML+,100,{self.rx_size},3,0]")
                self._send(f"[AXS:{len(self.axes)}:{self.axes}]")
                self._send("[NEWOPT:ENUMS,RT+,HOME,TC]")
                self._send("[FIRMWARE:grblHAL]")
            else:
                self._send("[VER:1.1h.20190830:]")
                self._send(f"[OPT:V,15,{self.rx_size}]")
        elif cmd == "$":
            for k, v in (("13", "0"), ("20", "0"), ("22", "1" if self.homing else "0"),
                         ("32", "0"), ("130", "2500.000"), ("131", "1600.000"),
                         ("132", "100.000"), *sorted(self.settings.items())):
                self._send(f"${k}={v}")
        elif cmd == "G":
            s = self._interp.state
            cool = " ".join(sorted(s.coolant)) or "M9"
            self._send(f"[GC:{s.motion} G54 {s.plane} {s.units} {s.distance} {s.feed_mode} "
                       f"{s.spindle} {cool} T0 F{s.feed or 0:g} S{s.speed:g}]")
        elif cmd == "C":
            if self._check:
                self._send("[MSG:Disabled]")
                self._send("ok")
                self._reset(moving=False)
                return
            if self._state == "Alarm":
                self._send("error:9")
                return
            self._check = True
            self._saved_interp = copy.deepcopy(self._interp)
            self._send("[MSG:Enabled]")
        elif cmd == "X":
            if self._state == "Alarm":
                self._state = "Idle"
                self._send("[MSG:Caution: Unlocked]")
        elif cmd == "H":
            if not self.homing:
                self._send("error:5")
                return
            self._interp.pos = {a: 0.0 for a in self.axes}
            self._mpos = dict(self._interp.pos)
            self.offset = {a: 0.0 for a in self.axes}    # at the switches: true zero
            self._state = "Idle"
        else:
            self._send("error:3")
            return
        self._send("ok")
