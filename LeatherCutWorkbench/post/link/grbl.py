"""Live link to a GRBL 1.1 / grblHAL controller over any pyserial URL.

:class:`GrblLink` opens the port with ``serial.serial_for_url`` (device path,
``socket://host:port``, ``rfc2217://``, ``loop://``), greets the controller
without resetting it (status polls first), identifies it (``$I``: version,
receive buffer size, axes), and streams a :class:`~.job.SendJob` in
send-response or character-counting mode, recording every acknowledged line
in the :class:`~.journal.Journal`.

Any ``error:N``, ``ALARM:N``, an unexpected banner (the controller reset), a
lost link (no status reply within ``link_timeout``) or an abort stops the job:
no further line is sent, then feed hold ``!``, wait for ``Hold:0``/``Idle``,
soft reset ``0x18``, wait for the banner and — when the controller is not
locked in Alarm — the profile's knife-up lines.  The result names the line and
the controller's message.  Nothing is ever re-sent automatically: resuming is
the operator's decision (:func:`~.job.resume_job`).

A reader thread owns the port's input; the caller's thread sends.  ``pause``,
``resume`` and ``abort`` may be called from any thread (GUI, signal handler).
"""

from __future__ import annotations

import queue
import re
import threading
import time
from collections import deque
from dataclasses import dataclass, field
from typing import Callable, Deque, Dict, List, Optional, Tuple

from ...core.errors import LeatherCutError
from ..gcode import knife_up_lines
from ..gcode_reader import strip_line
from ..profiles import MachineProfile
from .job import SendJob
from .journal import Journal
from .protocol import EEPROM_PATTERN, Reply, parse_reply, position

MODES = ("send-response", "char-count")
_SYNC = re.compile(r"^(N\d+)?G4P0$")


class LinkError(LeatherCutError):
    """The controller cannot be used (no answer, wrong axes, locked)."""


@dataclass
class ControllerInfo:
    flavour: str = "grbl"          # grbl | grblhal
    banner: str = ""
    version: str = ""
    rx_size: int = 128
    blocks: int = 0
    axes: str = "XYZ"
    settings: Dict[str, str] = field(default_factory=dict)
    state: str = ""

    def to_json(self) -> Dict:
        return dict(self.__dict__)


@dataclass
class StreamResult:
    """How a stream ended.  ``status``: done | error | alarm | reset | stalled |
    lost | aborted | check-ok | check-failed."""

    status: str
    acked: int = 0
    total: int = 0
    line: Optional[int] = None        # 1-based line in the job file of the offending line
    block: str = ""
    message: str = ""
    segment: str = ""
    stopped_safely: bool = False
    position: Optional[Dict[str, float]] = None   # where the tool stopped (work coordinates)
    position_trusted: bool = False                # reported after a clean stop

    @property
    def ok(self) -> bool:
        return self.status in ("done", "check-ok")

    def to_json(self) -> Dict:
        return dict(self.__dict__)


ProgressFn = Callable[[Dict], None]


class GrblLink:
    """One connection.  Times in seconds."""

    def __init__(self, url: str, baud: int = 115200, *, status_interval: float = 0.2,
                 link_timeout: float = 3.0, greet_timeout: float = 5.0,
                 hold_timeout: float = 5.0, reset_timeout: float = 5.0,
                 command_timeout: float = 10.0, progress: Optional[ProgressFn] = None):
        self.url = url
        self.baud = baud
        self.status_interval = status_interval
        self.link_timeout = link_timeout
        self.greet_timeout = greet_timeout
        self.hold_timeout = hold_timeout
        self.reset_timeout = reset_timeout
        self.command_timeout = command_timeout
        self.progress = progress
        self.info = ControllerInfo()
        self.ser = None
        self._acks: "queue.Queue[Reply]" = queue.Queue()
        self._push: List[Reply] = []
        self._status: Optional[Reply] = None
        self._status_seq = 0
        self._banners = 0
        self._alarm: Optional[Reply] = None
        self._lost: Optional[str] = None
        self._garbled: List[str] = []
        self._abort = threading.Event()
        self._paused = threading.Event()
        self._stop_reader = threading.Event()
        self._wlock = threading.Lock()
        self._reader: Optional[threading.Thread] = None
        self._wco: Optional[List[float]] = None
        self.stop_position: Optional[Dict[str, float]] = None
        self.stop_position_trusted = False
        self.profile_up_lines: List[str] = []       # knife up after a safe stop

    # ----------------------------------------------------------- connection
    def open(self) -> "GrblLink":
        import serial

        try:
            self.ser = serial.serial_for_url(self.url, baudrate=self.baud, timeout=0.02,
                                             write_timeout=2.0)
        except (serial.SerialException, ValueError, OSError) as exc:
            raise LinkError(f"cannot open the port: {exc}", source=self.url)
        self._reader = threading.Thread(target=self._read_loop, name="grbl-reader", daemon=True)
        self._reader.start()
        return self

    def close(self) -> None:
        self._stop_reader.set()
        if self._reader is not None:
            self._reader.join(timeout=1.0)
        if self.ser is not None:
            try:
                self.ser.close()
            except Exception:
                pass

    def __enter__(self) -> "GrblLink":
        return self.open()

    def __exit__(self, *exc) -> None:
        self.close()

    def _read_loop(self) -> None:
        import serial

        buf = b""
        while not self._stop_reader.is_set():
            try:
                data = self.ser.read(self.ser.in_waiting or 1)
            except (serial.SerialException, OSError, TypeError, AttributeError) as exc:
                self._lost = f"port closed or unplugged: {exc}"
                return
            if not data:
                continue
            buf += data
            while True:
                cut = [i for i in (buf.find(b"\n"), buf.find(b"\r")) if i >= 0]
                if not cut:
                    break
                k = min(cut)
                raw, buf = buf[:k], buf[k + 1:]
                if raw.strip():
                    self._handle(raw.decode("ascii", "replace"))

    def _handle(self, line: str) -> None:
        r = parse_reply(line)
        if r.kind in ("ok", "error"):
            r.epoch = self._banners
            self._acks.put(r)
        elif r.kind == "status":
            if "WCO" in r.fields:
                self._wco = [float(v) for v in r.fields["WCO"].split(",")]
            self._status = r
            self._status_seq += 1
        elif r.kind == "alarm":
            self._alarm = r
        elif r.kind == "banner":
            self.info.banner = r.text
            self._banners += 1
        elif r.kind == "other":
            self._garbled.append(line)
        else:
            self._push.append(r)

    def _write(self, data: bytes) -> None:
        import serial

        if self._lost:
            raise LinkError(self._lost, source=self.url)
        try:
            with self._wlock:
                self.ser.write(data)
        except (serial.SerialException, OSError) as exc:
            self._lost = f"write failed: {exc}"
            raise LinkError(self._lost, source=self.url)

    # ------------------------------------------------------------- commands
    def status(self, timeout: Optional[float] = None) -> Optional[Reply]:
        """Poll ``?`` and wait for the report (None when none arrives)."""
        seq = self._status_seq
        self._write(b"?")
        end = time.monotonic() + (self.link_timeout if timeout is None else timeout)
        while time.monotonic() < end and not self._lost:
            if self._status_seq != seq:
                return self._status
            time.sleep(0.005)
        return None

    def command(self, block: str, timeout: Optional[float] = None) -> Tuple[Reply, List[Reply]]:
        """Send one line and wait for its ``ok``/``error`` (send-response).
        Returns the answer and the push messages that arrived meanwhile."""
        self._drain_acks()
        start = len(self._push)
        self._write(block.encode("ascii") + b"\n")
        wait = self.command_timeout if timeout is None else timeout
        end = time.monotonic() + wait
        while time.monotonic() < end:
            if self._lost:
                raise LinkError(self._lost, source=self.url)
            try:
                r = self._acks.get(timeout=0.01)
                return r, self._push[start:]
            except queue.Empty:
                continue
        raise LinkError(f"no answer to {block!r} within {wait:g} s", source=self.url)

    def _drain_acks(self) -> None:
        while True:
            try:
                self._acks.get_nowait()
            except queue.Empty:
                return

    def greet(self) -> ControllerInfo:
        """Find the controller without resetting it and identify it."""
        end = time.monotonic() + self.greet_timeout
        st = None
        while time.monotonic() < end and st is None and not self._lost:
            st = self.status(timeout=0.25)
        if st is None:
            raise LinkError(self._lost or f"no controller answers on {self.url} "
                            f"(no status report within {self.greet_timeout:g} s)", source=self.url)
        self.info.state = st.state
        r, push = self.command("$I")
        flavour = "grblhal" if "GrblHAL" in self.info.banner else "grbl"
        axes = ""
        for p in push:
            for key, val in p.fields.items():
                if key == "VER":
                    self.info.version = val.rstrip(":")
                elif key == "OPT":
                    parts = val.split(",")
                    if len(parts) >= 3 and parts[2].isdigit():
                        self.info.blocks = int(parts[1]) if parts[1].isdigit() else 0
                        self.info.rx_size = int(parts[2])
                elif key == "AXS":
                    axes = val.split(":")[-1]
                    flavour = "grblhal"
                elif key == "FIRMWARE" and "grblhal" in val.lower():
                    flavour = "grblhal"
        self.info.flavour = flavour
        self.info.axes = axes or "XYZ"
        r, push = self.command("$$")
        for p in push:
            if p.kind == "setting":
                k, _, v = p.text.partition("=")
                self.info.settings[k] = v
        self.command("$G")
        return self.info

    def check_axes(self, job: SendJob) -> None:
        missing = [a for a in job.axes_used() if a not in self.info.axes]
        if missing:
            raise LinkError(f"the job uses axis {''.join(missing)} but the controller has only "
                            f"{self.info.axes} ({self.info.flavour} {self.info.version})",
                            source=self.url)

    def ready_for_job(self, profile: MachineProfile, home: bool = True) -> None:
        """Refuse a controller in Door/Hold; home (``$H``) when locked in Alarm and
        the profile homes, else refuse."""
        st = self.status()
        if st is None:
            raise LinkError("no status reply", source=self.url)
        state = st.state
        if state.startswith("Door") or state.startswith("Hold") or state in ("Jog", "Home"):
            raise LinkError(f"controller is in {state}; clear it at the machine first",
                            source=self.url)
        if state == "Alarm":
            if not (home and profile.homing):
                raise LinkError("controller is locked in Alarm: home or unlock it at the machine "
                                "($H / $X) and re-zero before sending", source=self.url)
            r, _ = self.command("$H", timeout=120.0)
            if r.kind != "ok":
                raise LinkError(f"homing failed: {r.raw} {r.text}", source=self.url)
        self._alarm = None

    # ----------------------------------------------------------- realtime
    def pause(self) -> None:
        """Feed hold; no new lines are sent until :meth:`resume`."""
        self._paused.set()
        self._write(b"!")

    def resume(self) -> None:
        """Cycle start once the hold has finished decelerating (Hold:0)."""
        end = time.monotonic() + self.hold_timeout
        while time.monotonic() < end:
            st = self.status(timeout=0.5)
            if st is not None and st.state in ("Hold:0", "Idle"):
                break
        self._write(b"~")
        self._paused.clear()

    def abort(self) -> None:
        """Stop the job safely (feed hold, reset, knife up) at the next chance."""
        self._abort.set()

    # --------------------------------------------------------------- stream
    def run_check(self, job: SendJob, mode: str = "send-response") -> StreamResult:
        """Run the whole job in the controller's check mode ``$C``: parsed and
        acknowledged, nothing moves.  Leaves check mode (which resets)."""
        r, push = self.command("$C")
        if r.kind != "ok" or not any(p.text == "Enabled" for p in push):
            return StreamResult("check-failed", message=f"cannot enter check mode: {r.raw}")
        res = self._stream(job, None, mode, check=True)
        banners = self._banners
        r, push = self.command("$C")
        self._wait_banner(banners)
        self._drain_acks()
        self._alarm = None
        return res

    def stream(self, job: SendJob, journal: Optional[Journal] = None,
               mode: str = "send-response") -> StreamResult:
        """Stream ``job``; returns how it ended (never raises for controller faults)."""
        if mode not in MODES:
            raise LinkError(f"mode must be one of {', '.join(MODES)}")
        self.stop_position, self.stop_position_trusted = None, False
        res = self._stream(job, journal, mode, check=False)
        if not res.ok:
            res.position, res.position_trusted = self.stop_position, self.stop_position_trusted
        if journal is not None:
            journal.event(res.status, **{k: v for k, v in res.to_json().items() if k != "status"})
        return res

    def _stream(self, job: SendJob, journal: Optional[Journal], mode: str,
                check: bool) -> StreamResult:
        total = len(job.blocks)
        budget = max(16, self.info.rx_size - 1)
        pending: Deque[Tuple[int, int]] = deque()
        in_buffer = 0
        sent = acked = 0
        banners = self._banners
        self._alarm = None
        self._abort.clear()
        self._drain_acks()
        last_poll = 0.0
        waiting_status_since: Optional[float] = None
        status_seq = self._status_seq

        def result(status: str, k: Optional[int] = None, message: str = "", safe: bool = False
                   ) -> StreamResult:
            line = job.index[k] + 1 if k is not None and job.index[k] is not None else None
            return StreamResult(status, acked, total, line, job.blocks[k] if k is not None else "",
                                message, job.segs[k] if k is not None else "", safe)

        def take(r: Reply) -> Optional[StreamResult]:
            nonlocal acked, in_buffer
            if not pending:
                return result("error", None, f"unexpected reply {r.raw!r} with no line in flight")
            k, n = pending.popleft()
            in_buffer -= n
            if r.kind == "ok":
                acked += 1
                if journal is not None and job.index[k] is not None:
                    journal.ack(job.index[k], job.segs[k])
                    if _SYNC.match(job.blocks[k]):
                        journal.event("sync", i=job.index[k])
                self._report(acked, total, job.segs[k], check)
                return None
            return result("error", k, f"{r.raw}: {r.text}")

        def take_received() -> None:
            """Journal the answers that arrived before the reset or the loss of
            the link (they may acknowledge a sync line: proof of execution);
            answers after a banner come from the reset controller and
            acknowledge nothing of this stream."""
            while pending:
                try:
                    r = self._acks.get_nowait()
                except queue.Empty:
                    return
                if r.epoch == banners:
                    take(r)

        while True:
            now = time.monotonic()
            if self._lost:
                take_received()
                return result("lost", pending[0][0] if pending else None,
                              f"link lost: {self._lost}; job state unknown")
            if self._alarm is not None:
                a = self._alarm
                k = pending[0][0] if pending else None
                safe = self._stop_safely(lambda r: take(r), trust_alarm=a.code == 2)
                return result("alarm", k, f"{a.raw}: {a.text}", safe)
            if self._banners != banners:
                take_received()
                k = pending[0][0] if pending else None
                safe = self._after_reset(spontaneous=True)
                return result("reset", k, "the controller reset itself (banner received): lines "
                              "in flight are lost, position may be lost", safe)
            if self._abort.is_set():
                k = pending[0][0] if pending else None
                safe = self._stop_safely(lambda r: take(r))
                return result("aborted", k, "stopped by the operator", safe)
            # link supervision: one outstanding status poll at a time
            if self._status_seq != status_seq:
                status_seq = self._status_seq
                waiting_status_since = None
            if waiting_status_since is not None and now - waiting_status_since > self.link_timeout:
                k = pending[0][0] if pending else None
                safe = self._stop_safely(lambda r: take(r), quick=True)
                status = "stalled" if safe else "lost"
                return result(status, k, f"no status reply for {self.link_timeout:g} s: link lost"
                              + ("; the controller answered the reset" if safe else
                                 "; job state unknown"), safe)
            if waiting_status_since is None and now - last_poll >= self.status_interval:
                try:
                    self._write(b"?")
                except LinkError:
                    continue
                last_poll = now
                waiting_status_since = now
            # send as much as the mode allows
            while sent < total and not self._paused.is_set():
                block = job.blocks[sent]
                n = len(block) + 1
                single = mode == "send-response" or bool(EEPROM_PATTERN.match(block))
                if pending and (single or in_buffer + n > budget
                                or EEPROM_PATTERN.match(job.blocks[pending[-1][0]])):
                    break
                try:
                    self._write(block.encode("ascii") + b"\n")
                except LinkError:
                    break
                pending.append((sent, n))
                in_buffer += n
                sent += 1
            if acked == total:
                return result("check-ok" if check else "done")
            try:
                r = self._acks.get(timeout=0.005)
            except queue.Empty:
                continue
            bad = take(r)
            if bad is not None:
                if check:
                    bad.status = "check-failed"
                    return bad
                if self._alarm is not None:
                    # ALARM arrived first: later lines answer error:9 and the
                    # alarmed line has no answer of its own -- report the alarm
                    a = self._alarm
                    bad.status, bad.message = "alarm", f"{a.raw}: {a.text}"
                    bad.stopped_safely = self._stop_safely(lambda r: take(r),
                                                           trust_alarm=a.code == 2)
                    bad.acked = acked
                    return bad
                if self._banners != banners:
                    bad.status = "reset"
                    bad.message = ("the controller reset itself (banner received): lines in "
                                   "flight are lost, position may be lost")
                    bad.stopped_safely = self._after_reset(spontaneous=True)
                    return bad
                # any error is fatal to the job: stop, keep taking late acks
                bad.stopped_safely = self._stop_safely(lambda r: take(r))
                bad.acked = acked
                return bad

    def _report(self, acked: int, total: int, seg: str, check: bool) -> None:
        if self.progress is not None:
            st = self._status.state if self._status else ""
            self.progress({"acked": acked, "total": total,
                           "percent": 100.0 * acked / total if total else 100.0,
                           "state": "Check" if check else st, "segment": seg})

    def _wait_banner(self, banners: int) -> bool:
        end = time.monotonic() + self.reset_timeout
        while time.monotonic() < end and not self._lost:
            if self._banners != banners:
                return True
            time.sleep(0.005)
        return False

    def _stop_safely(self, take: Callable[[Reply], Optional[StreamResult]],
                     quick: bool = False, trust_alarm: bool = False) -> bool:
        """Feed hold, wait Hold:0/Idle, soft reset, wait banner, knife up.
        Acks that arrive meanwhile are still journaled (``take``).  Returns True
        when the controller confirmed the reset."""
        if self._lost:
            return False

        def drain() -> None:
            while True:
                try:
                    r = self._acks.get_nowait()
                except queue.Empty:
                    return
                take(r)

        try:
            self._write(b"!")
            end = time.monotonic() + (self.link_timeout if quick else self.hold_timeout)
            while time.monotonic() < end and not self._lost:
                st = self.status(timeout=0.2)
                drain()
                if st is not None and st.state in ("Hold:0", "Idle", "Alarm", "Check"):
                    break
            drain()
            banners = self._banners
            self._write(b"\x18")
            wait = self.reset_timeout * (3 if quick else 1)
            end = time.monotonic() + wait
            got = False
            while time.monotonic() < end and not self._lost:
                if self._banners != banners:
                    got = True
                    break
                time.sleep(0.005)
            if not got:
                return False
            drain()         # oks that came before the banner: executed before the reset
            self._after_reset(trust_alarm=trust_alarm)
            return True
        except LinkError:
            return False

    def _after_reset(self, spontaneous: bool = False, trust_alarm: bool = False) -> bool:
        """After a banner: forget lines in flight, note where the tool stopped
        (trusted when the controller is Idle -- it kept its position -- or after
        a soft-limit alarm, never after a reset we did not ask for) and lift the
        knife when the controller accepts G-code.  True when lifted."""
        try:
            time.sleep(0.05)          # let the banner's follow-up messages arrive
            self._drain_acks()        # lines in flight were flushed by the reset
            self._alarm = None
            st = self.status(timeout=1.0)
            if st is not None:
                pos = position(st, self._wco)
                if pos is not None:
                    self.stop_position = dict(zip(self.info.axes, pos))
                    self.stop_position_trusted = not spontaneous and (
                        st.state == "Idle" or (st.state == "Alarm" and trust_alarm))
            if st is None or st.state != "Idle":
                return False
            # knife up, then G4 P0: its ok comes once the lift has been made
            for line in list(self.profile_up_lines) + ["G4 P0"]:
                r, _ = self.command(strip_line(line), timeout=10.0)
                if r.kind != "ok":
                    return False
            return True
        except LinkError:
            return False

    def use_profile(self, profile: MachineProfile) -> None:
        """Lift the knife with this profile's lines after a safe stop."""
        self.profile_up_lines = knife_up_lines(profile)
