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
from .progress import proof_for
from .protocol import EEPROM_PATTERN, Reply, parse_reply, position

MODES = ("send-response", "char-count")
_SYNC = re.compile(r"^(N\d+)?G4P0(\.0*)?$")
_DWELL = re.compile(r"G4P(\d+\.?\d*)")


def _dwell(block: str) -> float:
    """How long (s) the controller may report Idle while ``block`` is unanswered:
    0.25 s, plus the dwell of a ``G4 P..`` (GRBL reports Idle while dwelling)."""
    m = _DWELL.search(block)
    return 0.25 + (float(m.group(1)) if m else 0.0)


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
    buffer_reported: bool = False  # status reports carry Bf: (GRBL $10 bit 1): the hard
                                   # receive-buffer bound against spurious oks is on

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
    stopped_safely: bool = False      # verified: Idle, knife up, spindle off (status + $G)
    position: Optional[Dict[str, float]] = None   # where the tool stopped (work coordinates)
    position_trusted: bool = False                # reported after a clean stop
    position_lost: bool = False       # reset we did not ask for, power loss, link lost,
                                      # ALARM:1/3: a resume must home or confirm the zero
    verified: Dict = field(default_factory=dict)  # what status reports showed after the stop
    spurious_acks: int = 0            # answers with no line in flight (discarded)
    buffer_resyncs: int = 0           # reports whose Bf showed more unread bytes than counted
    strict_buffer: bool = False       # a spurious ok was seen: the Bf bound was on since

    @property
    def ok(self) -> bool:
        return self.status in ("done", "check-ok")

    def to_json(self) -> Dict:
        return dict(self.__dict__)

    def stop_summary(self) -> str:
        """What the controller showed after the stop, and what the operator must
        do -- from status reports, never from what was intended."""
        v = self.verified
        if not v:
            return ("NOT verified stopped: no status report after the stop (link lost); the "
                    "knife, oscillator and vacuum may still be on: use the machine's E-stop")
        state = v.get("state") or "no status"
        knife = v.get("knife", "unknown")
        where = (f"{v['lift_axis']} {v['lift']:.3f}" if v.get("lift") is not None
                 else "servo lift")
        seen = f"controller {state}, knife {knife} ({where}), spindle {v.get('spindle', '?')}"
        if self.stopped_safely:
            return f"Stopped safely, verified by status after the stop: {seen}."
        todo = ("unlock ($X) or home ($H) once the cause is cleared, lift the knife, "
                "then re-zero" if state == "Alarm" else "lift the knife at the machine")
        why = "the controller is locked in Alarm: the knife-up lines were not executed; " \
            if state == "Alarm" else ""
        return f"NOT stopped safely: {why}status after the stop shows {seen}. At the machine: {todo}."


ProgressFn = Callable[[Dict], None]


class GrblLink:
    """One connection.  Times in seconds."""

    def __init__(self, url: str, baud: int = 115200, *, status_interval: float = 0.2,
                 link_timeout: float = 3.0, greet_timeout: float = 5.0,
                 hold_timeout: float = 5.0, reset_timeout: float = 5.0,
                 command_timeout: float = 10.0, progress: Optional[ProgressFn] = None,
                 cut_window: int = 0, min_poll_interval: float = 0.05):
        self.url = url
        self.baud = baud
        self.status_interval = status_interval
        self.link_timeout = link_timeout
        self.greet_timeout = greet_timeout
        self.hold_timeout = hold_timeout
        self.reset_timeout = reset_timeout
        self.command_timeout = command_timeout
        self.progress = progress
        self.cut_window = cut_window                # segments with unproven cuts in flight
        self.min_poll_interval = min_poll_interval  # s between extra polls (fence, buffer)
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
        self.profile = None                         # lift axis / z_up for the stop check
        self.stop_verified: Dict = {}
        self.max_in_flight = 0                      # bytes the host counted in flight
        self._poll_times: Deque[Tuple[float, int]] = deque()   # '?' written (time, bytes
                                                    # written then), not yet answered
        self._written = 0                           # line bytes written to the port
        self._ack_seq = 0                           # ok/error answers received
        self._bf_seen = False                       # the reports carry Bf: (RX unread)
        self._status_time = 0.0                     # when the poll of the last report was written
        self._status_rx_time = 0.0                  # when the last report arrived
        self._garbled_seen = 0
        self._stop_lost = False
        self.homed = False                          # $H done on this connection

    # ----------------------------------------------------------- connection
    def open(self) -> "GrblLink":
        import serial

        from .portlock import PortBusy, PortLock

        try:
            self._lock = PortLock(self.url).acquire()
        except PortBusy as exc:
            raise LinkError(exc.message, source=self.url)
        kw = {} if "://" in self.url else {"exclusive": True}
        try:
            self.ser = serial.serial_for_url(self.url, baudrate=self.baud, timeout=0.02,
                                             write_timeout=2.0, **kw)
        except (serial.SerialException, ValueError, OSError) as exc:
            self._lock.release()
            busy = "busy" in str(exc).lower() or "lock" in str(exc).lower()
            raise LinkError(("the port is in use by another program: " if busy else
                             "cannot open the port: ") + str(exc), source=self.url)
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
        lock = getattr(self, "_lock", None)
        if lock is not None:
            lock.release()

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
            r.at = time.monotonic()
            r.epoch = self._banners
            self._ack_seq += 1
            r.seq = self._ack_seq
            self._acks.put(r)
        elif r.kind == "status":
            if "WCO" in r.fields:
                try:
                    self._wco = [float(v) for v in r.fields["WCO"].split(",")]
                except ValueError:
                    pass
            # the report answers the oldest unanswered '?' (reports are never
            # pushed unasked); it describes the controller after that write
            self._status_time, r.written = (self._poll_times.popleft() if self._poll_times
                                            else (0.0, -1))
            self._poll_times.clear()
            r.epoch, r.seq = self._banners, self._ack_seq
            r.written_rx = self._written      # an upper bound: a write in progress counts
            bf = r.fields.get("Bf", "").split(",")
            if len(bf) == 2 and bf[1].strip().isdigit():
                # GRBL: available = RX size - unread (or one less): RX - free is an upper bound
                r.rx_used = max(0, self.info.rx_size - int(bf[1]))
                self._bf_seen = True
            self._status = r
            self._status_rx_time = time.monotonic()
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
                if data.endswith(b"\n"):
                    self._written += len(data)    # before: the reader's bound includes it
                self.ser.write(data)
        except (serial.SerialException, OSError) as exc:
            self._lost = f"write failed: {exc}"
            raise LinkError(self._lost, source=self.url)

    # ------------------------------------------------------------- commands
    def _poll(self) -> None:
        self._poll_times.append((time.monotonic(), self._written))
        self._write(b"?")

    def status(self, timeout: Optional[float] = None) -> Optional[Reply]:
        """Poll ``?`` and wait for the report (None when none arrives)."""
        seq = self._status_seq
        self._poll()
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
        self.info.buffer_reported = self._bf_seen
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

    def ready_for_job(self, profile: MachineProfile, home: bool = True,
                      force_home: bool = False) -> None:
        """Refuse a controller in Door/Hold; home (``$H``) when locked in Alarm and
        the profile homes, else refuse.  ``force_home``: home even when Idle
        (a resume after the position was lost)."""
        st = self.status()
        if st is None:
            raise LinkError("no status reply", source=self.url)
        state = st.state
        if state.startswith("Door") or state.startswith("Hold") or state in ("Jog", "Home"):
            raise LinkError(f"controller is in {state}; clear it at the machine first",
                            source=self.url)
        if state == "Alarm" or (force_home and home and profile.homing):
            if not (home and profile.homing):
                raise LinkError("controller is locked in Alarm: home or unlock it at the machine "
                                "($H / $X) and re-zero before sending", source=self.url)
            r, _ = self.command("$H", timeout=120.0)
            if r.kind != "ok":
                raise LinkError(f"homing failed: {r.raw} {r.text}", source=self.url)
            self.homed = True
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
        st = self.status()
        if st is not None and st.state == "Check":     # a safe stop already reset it
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
        self.stop_verified, self._stop_lost = {}, False
        res = self._stream(job, journal, mode, check=False)
        if not res.ok:
            res.position, res.position_trusted = self.stop_position, self.stop_position_trusted
            res.verified = dict(self.stop_verified)
            res.position_lost = res.position_lost or self._stop_lost or not res.position_trusted
        if journal is not None:
            journal.event(res.status, **{k: v for k, v in res.to_json().items() if k != "status"})
        return res

    def _stream(self, job: SendJob, journal: Optional[Journal], mode: str,
                check: bool) -> StreamResult:
        """The streaming loop.  Invariants (docs/LINK.md, "Acknowledgements"):

        * an ``ok``/``error`` answers the oldest line in flight; one with no line
          in flight is spurious: counted, journaled, discarded -- never more acks
          than lines sent;
        * character counting keeps ``bytes in flight + margin <= RX - 1``, the
          margin being the longest line (one spurious ``ok`` fits in it); and,
          whenever a status report carries ``Bf:``, its unread bytes are
          compared with what the count believed in flight when it was made
          (bytes written by its arrival - bytes of the lines answered before
          it): more unread than that proves spurious oks were counted --
          the excess is counted in flight again and, from then on, the stream
          also keeps the strict bound ``unread bytes at the last report +
          bytes written since its poll + line <= RX - 1``, which no ``ok``
          enters (when it binds, the link polls again, at most every
          ``min_poll_interval``, 0.05 s).  Journaled as ``resync``.  The
          strict bound is never on before a spurious ``ok`` is seen: it
          starves the planner on short lines (docs/LINK.md, "Buffer");
        * every status report is turned into proof of executed lines
          (:mod:`.progress`, journaled as ``exec``), and cutting lines of a new
          segment wait while ``cut_window`` segments have cuts in flight that
          no report has proven executed;
        * nothing is sent after a ``G4 P0`` sync until its ``ok`` *and* a status
          report received after it shows Idle: then the counters are exactly
          zero (resynchronised) and the journal's ``sync`` record is proof;
        * Idle reported twice with lines unanswered (an answer was garbled or
          lost), a garbled reply, or a status in Alarm are faults -> safe stop;
        * an unanswered ``?`` is polled again before the link counts as lost."""
        total = len(job.blocks)
        longest = max((len(b) + 1 for b in job.blocks), default=0)
        budget = max(16, self.info.rx_size - 1 - longest)
        pending: Deque[Tuple[int, int, float]] = deque()
        in_buffer = 0
        sent = acked = 0
        spurious = 0
        banners = self._banners
        self._alarm = None
        self._abort.clear()
        self._drain_acks()
        self._garbled_seen = len(self._garbled)
        self.max_in_flight = 0
        last_poll = 0.0
        first_unanswered: Optional[float] = None
        repolls = 0
        status_seq = self._status_seq
        proof = None if check else proof_for(job, self.profile, self.cut_window)
        w0 = self._written                    # stream bytes start here
        # an upper bound on the receive buffer's unread bytes that no ok can
        # fake: (unread at the last report with Bf, bytes written when it was
        # polled); every line before the stream was answered, so it starts empty
        rx_known: Optional[Tuple[int, int]] = (0, w0) if self._bf_seen else None
        strict = False                        # a spurious ok was seen: rx_known binds
        resyncs = 0
        answered_bytes = 0                    # bytes of the lines answered so far
        answered_at: Deque[Tuple[int, int]] = deque([(self._ack_seq, 0)], maxlen=256)
        resync_wait: Optional[Reply] = None   # a Bf report to check the count against
        want_poll = False                     # a fence or the buffer bound waits for a report
        proof_wait: Optional[Reply] = None    # a report to take proofs from
        proof_snap: Optional[Tuple[int, bool]] = None
        fenced = fence_pass = False           # the window held a line back / may pass one
        fence_idle = (0.0, 0)                 # (since when Idle at a full window, proven then)
        taken_seq = self._ack_seq             # answers taken (in arrival order)
        sync_wait: Optional[int] = None       # sync line sent, waiting for ok + Idle
        sync_ok_at: Optional[float] = None    # when its ok arrived
        idle_mark: Optional[Tuple[float, int]] = None   # (first Idle report time, acks then)

        def result(status: str, k: Optional[int] = None, message: str = "", safe: bool = False
                   ) -> StreamResult:
            line = job.index[k] + 1 if k is not None and job.index[k] is not None else None
            return StreamResult(status, acked, total, line, job.blocks[k] if k is not None else "",
                                message, job.segs[k] if k is not None else "", safe,
                                spurious_acks=spurious, buffer_resyncs=resyncs,
                                strict_buffer=strict)

        def take(r: Reply) -> Optional[StreamResult]:
            nonlocal acked, in_buffer, spurious, sync_ok_at, taken_seq, proof_snap
            nonlocal answered_bytes
            taken_seq = max(taken_seq, r.seq)
            if proof_wait is not None and r.seq == proof_wait.seq and pending:
                proof_snap = (acked + (r.kind == "ok"), len(pending) == 1)
            early = bool(pending) and 0.0 < r.at < pending[0][2]
            if not pending or early:
                # no line in flight, or the answer arrived before the oldest
                # line in flight was written: it answers none of them
                spurious += 1
                answered_at.append((r.seq, answered_bytes))
                go_strict("an answer before its line was written" if early
                          else "an answer with no line in flight")
                if journal is not None:
                    journal.event("spurious", reply=r.raw, acked=acked)
                return None
            k, n, _ = pending.popleft()
            answered_bytes += n
            answered_at.append((r.seq, answered_bytes))
            in_buffer = in_buffer - n if pending else 0
            if r.kind != "ok" and proof is not None:
                proof.stopped = True          # refused: later reports prove nothing
            if r.kind == "ok":
                acked += 1
                if journal is not None and job.index[k] is not None:
                    journal.ack(job.index[k], job.segs[k])
                if k == sync_wait:
                    sync_ok_at = time.monotonic()
                self._report(acked, total, job.segs[k], check)
                return None
            return result("error", k, f"{r.raw}: {r.text}")

        def go_strict(why: str) -> None:
            """A spurious ok was seen: with Bf, the strict bound binds from now on."""
            nonlocal strict
            if rx_known is not None and not strict:
                strict = True
                if journal is not None:
                    journal.event("strict", why=why, acked=acked)

        def resync(st: Reply) -> None:
            """Compare report ``st``'s unread bytes with the count (all answers
            before it taken): more unread than counted in flight = spurious oks
            were counted; count the excess in flight again, go strict."""
            nonlocal in_buffer, resyncs
            done = next((b for q, b in reversed(answered_at) if q <= st.seq), None)
            if done is None:
                return                        # too old to compare (256 answers since)
            believed = st.written_rx - w0 - done
            # Bf's free count is RX - 1 - unread on GRBL (RX - unread elsewhere):
            # rx_used - 1 never exceeds the true unread bytes
            excess = st.rx_used - 1 - believed
            if excess > 0 and pending:
                resyncs += 1
                in_buffer += excess
                if journal is not None:
                    journal.event("resync", unread=st.rx_used - 1, counted=believed,
                                  acked=acked)
                go_strict(f"status report: {st.rx_used - 1} bytes unread, {believed} counted")

        def take_received() -> None:
            """Journal the answers that arrived before the reset or the loss of
            the link; answers after a banner come from the reset controller and
            acknowledge nothing of this stream.  (A sync ``ok`` among them is
            not verified -- no Idle report followed -- so it proves nothing.)"""
            while pending:
                try:
                    r = self._acks.get_nowait()
                except queue.Empty:
                    return
                if r.epoch == banners:
                    take(r)

        def last_proof() -> None:
            """Before giving up on a reset or a lost link: what the last report
            of this controller session proves (it may have arrived with the
            banner, before the loop took it)."""
            st = self._status
            if proof is not None and st is not None and st.epoch == banners \
                    and st.seq <= taken_seq:
                self._take_proof(proof, st, sent, w0, journal, None)

        def head() -> Optional[int]:
            return pending[0][0] if pending else (sent - 1 if sent else None)

        def stop(status: str, message: str, k: Optional[int], **kw) -> StreamResult:
            safe = self._stop_safely(take, **kw)
            res = result(status, k, message, safe)
            res.acked, res.spurious_acks = acked, spurious
            return res

        while True:
            now = time.monotonic()
            if self._lost:
                take_received()
                last_proof()
                res = result("lost", head(), f"link lost: {self._lost}; job state unknown")
                res.position_lost = True
                return res
            if self._alarm is not None:
                a = self._alarm
                return stop("alarm", f"{a.raw}: {a.text}", head(), trust_alarm=a.code == 2,
                            lost=a.code in (1, 3))
            if self._banners != banners:
                take_received()
                last_proof()
                k = head()
                safe = self._after_reset(spontaneous=True)
                res = result("reset", k, "the controller reset itself (banner received): lines "
                             "in flight are lost, position may be lost", safe)
                res.position_lost = True
                return res
            if len(self._garbled) > self._garbled_seen:
                bad = self._garbled[self._garbled_seen]
                return stop("check-failed" if check else "garbled",
                            f"garbled reply {bad!r} from the controller: it may have "
                            "been an ok or an error, the stream cannot go on", head())
            if self._abort.is_set():
                return stop("aborted", "stopped by the operator", head())
            # link supervision: re-poll an unanswered '?', lost only after link_timeout
            if self._status_seq != status_seq:
                status_seq = self._status_seq
                first_unanswered, repolls = None, 0
                st = self._status
                if st.epoch == banners and st.rx_used >= 0 and st.written >= 0:
                    rx_known = (st.rx_used, st.written)
                    if st.written_rx >= w0:
                        resync_wait = st
                # a machine Idle for half a second at a full cut window that no
                # report can prove (a position on two blocks' paths, no Bf, a
                # spurious ok seen) may pass one segment: never a hang, only a
                # weaker bound (journaled as "window")
                if not (fenced and st.state == "Idle") or (
                        proof is not None and proof.proven != fence_idle[1]):
                    fence_idle = (now, proof.proven if proof is not None else 0)
                elif now - fence_idle[0] >= max(0.5, 2 * self.status_interval):
                    fence_pass = True
                if proof is not None and st.epoch == banners:
                    proof_wait = st           # once the answers before it are taken
                    # (lines answered, all answered) when the report came
                    proof_snap = (acked, not pending) if taken_seq == st.seq else None
                if st.state == "Alarm" and not check:
                    return stop("alarm", "the controller reports Alarm (its ALARM message was "
                                "not received)", head(), lost=True)
                if sync_wait is not None and sync_ok_at is not None and \
                        self._status_rx_time > sync_ok_at and st.state in ("Idle", "Check"):
                    take_received()          # the sync's own ok, when an early one was spurious
                    if not pending:
                        if journal is not None and job.index[sync_wait] is not None:
                            journal.event("sync", i=job.index[sync_wait])
                        sync_wait, sync_ok_at, in_buffer = None, None, 0
                if pending and st.state == ("Check" if check else "Idle") \
                        and self._status_time > pending[0][2]:
                    if idle_mark is None or idle_mark[1] != acked:
                        idle_mark = (self._status_time, acked)
                    elif self._status_time - idle_mark[0] >= _dwell(job.blocks[pending[0][0]]):
                        return stop("check-failed" if check else "unanswered",
                                    f"the controller is {st.state} but {len(pending)} "
                                    "line(s) were never answered (an ok or error was lost or "
                                    "garbled)", pending[0][0])
                else:
                    idle_mark = None
            if resync_wait is not None and taken_seq >= resync_wait.seq:
                resync(resync_wait)
                resync_wait = None
            if proof_wait is not None and taken_seq >= proof_wait.seq and self._alarm is None:
                done_ok = proof_snap[0] if proof_snap and proof_snap[1] and not spurious \
                    else None
                self._take_proof(proof, proof_wait, sent, w0, journal, done_ok)
                proof_wait = None
            if first_unanswered is not None:
                waited = now - first_unanswered
                if waited > self.link_timeout and repolls >= 2:
                    k = head()
                    safe = self._stop_safely(take, quick=True)
                    res = result("stalled" if self.stop_verified else "lost", k,
                                 f"no status reply for {waited:.1f} s ({repolls + 1} polls): "
                                 "link lost" + ("; the controller answered after the reset"
                                                if self.stop_verified else "; job state unknown"),
                                 safe)
                    res.acked, res.spurious_acks = acked, spurious
                    return res
                if waited > self.link_timeout * (repolls + 1) / 3.0:
                    try:
                        self._poll()
                        repolls += 1
                    except LinkError:
                        continue
            elif now - last_poll >= self.status_interval or (
                    sync_ok_at is not None and last_poll < sync_ok_at) or (
                    want_poll and now - last_poll >= self.min_poll_interval):
                try:
                    self._poll()
                except LinkError:
                    continue
                last_poll = now
                first_unanswered = now
            # send as much as the mode allows
            want_poll = False
            fenced = False
            while (sent < total and not self._paused.is_set() and sync_wait is None
                   and self._banners == banners and self._alarm is None):
                block = job.blocks[sent]
                n = len(block) + 1
                single = mode == "send-response" or bool(EEPROM_PATTERN.match(block))
                if pending and (single or in_buffer + n > budget
                                or EEPROM_PATTERN.match(job.blocks[pending[-1][0]])):
                    break
                if strict and \
                        rx_known[0] + self._written - rx_known[1] + n > self.info.rx_size - 1:
                    want_poll = True          # oks may be spurious: wait for a report
                    break
                if proof is not None and not proof.allows(sent, sent):
                    if not fence_pass:
                        want_poll = fenced = True     # the cut window is full
                        break
                    fence_pass = False        # no proof came though the machine waits
                    fence_idle = (now, proof.proven)
                    if journal is not None:
                        journal.event("window", i=job.index[sent], seg=job.segs[sent],
                                      proven=proof.proven)

                begun = time.monotonic()      # an answer that arrived before answers another
                try:
                    self._write(block.encode("ascii") + b"\n")
                except LinkError:
                    break
                pending.append((sent, n, begun))
                in_buffer += n
                self.max_in_flight = max(self.max_in_flight, in_buffer)
                if _SYNC.match(block):
                    sync_wait, sync_ok_at = sent, None
                sent += 1
            if acked == total and sync_wait is None and not pending:
                res = result("check-ok" if check else "done")
                res.spurious_acks = spurious
                return res
            try:
                r = self._acks.get(timeout=0.005)
            except queue.Empty:
                continue
            if r.epoch != banners:
                continue                      # handled as a reset above
            bad = take(r)
            if bad is not None:
                if check:
                    bad.status = "check-failed"
                    return bad
                if self._alarm is not None:
                    # ALARM arrived first: later lines answer error:9 and the
                    # alarmed line has no answer of its own -- report the alarm
                    a = self._alarm
                    res = stop("alarm", f"{a.raw}: {a.text}", None,
                               trust_alarm=a.code == 2, lost=a.code in (1, 3))
                    res.line, res.block, res.segment = bad.line, bad.block, bad.segment
                    return res
                if self._banners != banners:
                    bad.status = "reset"
                    bad.message = ("the controller reset itself (banner received): lines in "
                                   "flight are lost, position may be lost")
                    bad.stopped_safely = self._after_reset(spontaneous=True)
                    bad.position_lost = True
                    return bad
                # any error is fatal to the job: stop, keep taking late acks
                safe = self._stop_safely(take)
                bad.stopped_safely, bad.acked, bad.spurious_acks = safe, acked, spurious
                return bad

    def _take_proof(self, proof, st: Reply, sent: int, w0: int,
                    journal: Optional[Journal], answered: Optional[int]) -> None:
        """Journal what status report ``st`` proves executed (:mod:`.progress`)."""
        pos = position(st, self._wco)
        if "WPos" not in st.fields and self._wco is None:
            pos = None                 # MPos without the work offset: no position proof
        here = dict(zip(self.info.axes, pos)) if pos is not None else None
        read = None
        if st.rx_used >= 0 and st.written >= w0:
            read = st.written - st.rx_used - w0
        # with Bf the read count proves Idle's lines without trusting any ok;
        # the answered count only stands in for it on controllers without Bf
        lines = proof.update(here, sent, idle=st.state == "Idle", read_bytes=read,
                             answered=answered if read is None else None)
        if lines and journal is not None:
            journal.proof(lines)

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
                     quick: bool = False, trust_alarm: bool = False, lost: bool = False) -> bool:
        """Feed hold, wait Hold:0/Idle, soft reset, wait banner, knife up, then
        *verify* (status report and ``$G``).  Acks that arrive meanwhile are
        still journaled (``take``).  Returns True only when the reports after
        the stop show the controller Idle, the knife up and the spindle off;
        :attr:`stop_verified` holds what they showed."""
        self.stop_verified = {}
        self._stop_lost = lost
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
            self._alarm = None
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
            if self._alarm is not None and self._alarm.code == 3:
                self._stop_lost = True      # reset while moving: position lost
            return self._after_reset(trust_alarm=trust_alarm)
        except LinkError:
            return False

    def _after_reset(self, spontaneous: bool = False, trust_alarm: bool = False) -> bool:
        """After a banner: forget lines in flight, note where the tool stopped
        (trusted when the controller is Idle -- it kept its position -- or after
        a soft-limit alarm, never after a reset we did not ask for), lift the
        knife when the controller accepts G-code, then verify the result from a
        status report and ``$G``.  True only when verified Idle, knife up and
        spindle off."""
        self.stop_verified = {}
        try:
            time.sleep(0.05)          # let the banner's follow-up messages arrive
            self._drain_acks()        # lines in flight were flushed by the reset
            if self._alarm is not None and self._alarm.code == 3:
                self._stop_lost = True
            self._alarm = None
            st = self.status(timeout=1.0)
            if st is not None:
                pos = position(st, self._wco)
                if pos is not None:
                    self.stop_position = dict(zip(self.info.axes, pos))
                    self.stop_position_trusted = not spontaneous and not self._stop_lost and (
                        st.state == "Idle" or (st.state == "Alarm" and trust_alarm))
            lifted = False
            if st is not None and st.state == "Idle":
                # knife up, then G4 P0: its ok comes once the lift has been made
                lifted = True
                for line in list(self.profile_up_lines) + ["G4 P0"]:
                    r, _ = self.command(strip_line(line), timeout=10.0)
                    if r.kind != "ok":
                        lifted = False
                        break
            return self._verify_stop(lifted)
        except LinkError:
            return False

    def _verify_stop(self, lifted: bool) -> bool:
        """Read back the state after a stop: a status report (state, lift axis
        position) and ``$G`` (spindle, coolant).  Fills :attr:`stop_verified`."""
        st = self.status(timeout=1.0)
        if st is None:
            self.stop_verified = {"state": None, "knife": "unknown"}
            return False
        v: Dict = {"state": st.state, "knife_up_sent": lifted, "spindle": "?", "coolant": "?"}
        pos = position(st, self._wco)
        prof = self.profile
        lift = prof.lift_axis if prof is not None else ""
        if pos is not None:
            here = dict(zip(self.info.axes, pos))
            v["position"] = here
            if lift and lift in here:
                v["lift_axis"], v["lift"] = lift, here[lift]
        try:
            r, push = self.command("$G", timeout=2.0)
            for p in push:
                if "GC" in p.fields:
                    words = p.fields["GC"].split()
                    v["spindle"] = next((w for w in words if w in ("M3", "M4", "M5")), "?")
                    v["coolant"] = " ".join(w for w in words if w in ("M7", "M8", "M9")) or "?"
        except LinkError:
            pass
        if lift and v.get("lift") is not None:
            up = v["lift"] >= prof.z_up - 0.01
            v["knife"] = "up" if up else "down"
        elif lift:
            v["knife"] = "unknown"
        else:                              # servo / spindle lift: the spindle word is the lift
            v["knife"] = "up" if lifted and v["spindle"] == "M5" else "unknown"
        self.stop_verified = v
        return st.state == "Idle" and v["knife"] == "up" and v["spindle"] == "M5"

    def use_profile(self, profile: MachineProfile) -> None:
        """Lift the knife with this profile's lines after a safe stop (and check
        the lift axis against its ``z_up``)."""
        self.profile_up_lines = knife_up_lines(profile)
        self.profile = profile

    @property
    def feed_linear_only(self) -> bool:
        """grblHAL ``$701=1``: F applies to the linear axes only (read by greet)."""
        return self.info.settings.get("$701", "0").strip() in ("1", "1.0")
