"""Run many CLI calls in a few worker processes, each call capped in time and memory.

A worker (``python tests/hostile_runner.py``) imports the workbench and FreeCAD
once, caps its address space (``RLIMIT_AS`` = its size after the imports plus
:data:`MEMORY_CAP_MB`), then reads one JSON request per line on stdin
(``{"argv": [...], "timeout": s}``), runs ``leathercut`` ``main(argv)``
in-process under a ``SIGALRM`` timeout with stdout/stderr captured, and
answers one JSON line: exit code, stderr, whether a traceback was printed,
wall time and peak memory of that call (``VmHWM`` after resetting it through
``/proc/self/clear_refs``).  :func:`run_calls` drives the workers from the
test: a call that does not answer within its timeout plus a grace period (a
hang inside C code, where the alarm cannot interrupt) kills the worker, is
reported as a hang, and a fresh worker takes the remaining calls.
"""

from __future__ import annotations

import io
import json
import os
import resource
import signal
import subprocess
import sys
import threading
import time
import traceback
from contextlib import redirect_stderr, redirect_stdout
from typing import Dict, List, Optional

#: Address space a call may add to the worker (MiB).
MEMORY_CAP_MB = 1536
#: Seconds the parent waits beyond a call's own timeout before killing the worker.
GRACE_S = 10.0


class CallTimeout(BaseException):
    """Raised by the alarm: BaseException so the CLI's ``except Exception`` does
    not turn it into an internal error."""


def _status_kb(key: str) -> int:
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return 0


def _reset_peak() -> None:
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")
    except OSError:
        pass


def _on_alarm(signum, frame):
    raise CallTimeout()


def worker() -> None:  # pragma: no cover - runs in the child
    out = os.fdopen(os.dup(1), "w", buffering=1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)        # stray C-level prints must not corrupt the protocol
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    import importlib
    importlib.import_module("conftest")       # FreeCAD on the path, this checkout first
    from LeatherCutWorkbench.cli import main
    importlib.import_module("LeatherCutWorkbench.core.recognition")   # FreeCAD Part loaded now

    base_kb = _status_kb("VmSize")
    cap = (base_kb + MEMORY_CAP_MB * 1024) * 1024
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
    signal.signal(signal.SIGALRM, _on_alarm)
    base_rss = _status_kb("VmRSS")
    out.write(json.dumps({"ready": True, "base_rss_mb": base_rss / 1024}) + "\n")
    for raw in sys.stdin:
        req = json.loads(raw)
        buf_out, buf_err = io.StringIO(), io.StringIO()
        _reset_peak()
        t0 = time.monotonic()
        result: Dict = {"id": req.get("id")}
        signal.setitimer(signal.ITIMER_REAL, float(req.get("timeout", 20)))
        try:
            with redirect_stdout(buf_out), redirect_stderr(buf_err):
                code = main(list(req["argv"]))
            result["code"] = code
        except CallTimeout:
            result["code"] = "timeout"
        except SystemExit as exc:          # argparse errors
            result["code"] = exc.code if isinstance(exc.code, int) else 2
        except BaseException as exc:       # a crash outside main's own handling
            result["code"] = "crash"
            buf_err.write(traceback.format_exc())
            del exc
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        result["seconds"] = time.monotonic() - t0
        result["peak_mb"] = max(_status_kb("VmHWM") - base_rss, 0) / 1024
        err = buf_err.getvalue()
        result["stderr"] = err[-2000:]
        result["traceback"] = "Traceback (most recent call last)" in err
        out.write(json.dumps(result) + "\n")


class _Worker:
    def __init__(self, env: Dict[str, str]):
        self.proc = subprocess.Popen([sys.executable, os.path.abspath(__file__)],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, text=True, env=env)
        self.lines: List[Optional[str]] = []
        self.ready = threading.Event()
        self.cond = threading.Condition()
        self.info = {}
        threading.Thread(target=self._reader, daemon=True).start()

    def _reader(self) -> None:
        for line in self.proc.stdout:
            with self.cond:
                self.lines.append(line)
                self.cond.notify_all()
        with self.cond:
            self.lines.append(None)
            self.cond.notify_all()

    def next_line(self, timeout: float) -> Optional[str]:
        end = time.monotonic() + timeout
        with self.cond:
            while not self.lines:
                left = end - time.monotonic()
                if left <= 0:
                    return ""
                self.cond.wait(left)
            return self.lines.pop(0)

    def call(self, req: Dict, timeout: float) -> Optional[Dict]:
        self.proc.stdin.write(json.dumps(req) + "\n")
        self.proc.stdin.flush()
        line = self.next_line(timeout)
        return json.loads(line) if line else None

    def kill(self) -> None:
        self.proc.kill()
        self.proc.wait()


def _start(env: Dict[str, str]) -> _Worker:
    w = _Worker(env)
    line = w.next_line(120)
    if not line:
        raise RuntimeError("hostile worker did not start")
    w.info = json.loads(line)
    return w


def run_calls(calls: List[Dict], workers: int = 2, timeout: float = 20.0,
              env: Optional[Dict[str, str]] = None) -> List[Dict]:
    """Run ``calls`` (``{"argv": [...]}`` each) over ``workers`` processes; the
    results come back in order, each with ``code`` (int, ``"timeout"``,
    ``"crash"`` or ``"hang"``), ``stderr``, ``traceback``, ``seconds`` and
    ``peak_mb``."""
    env = dict(os.environ if env is None else env)
    results: List[Optional[Dict]] = [None] * len(calls)
    lock = threading.Lock()
    queue = list(range(len(calls)))

    def drive() -> None:
        w = _start(env)
        while True:
            with lock:
                if not queue:
                    break
                i = queue.pop(0)
            req = dict(calls[i], id=i, timeout=timeout)
            res = w.call(req, timeout + GRACE_S)
            if res is None:               # hung in C code or died: replace the worker
                dead = w.proc.poll() is not None
                w.kill()
                res = {"id": i, "code": "died" if dead else "hang", "stderr": "",
                       "traceback": False, "seconds": timeout + GRACE_S, "peak_mb": None}
                w = _start(env)
            results[i] = res
        w.proc.stdin.close()
        w.kill()

    threads = [threading.Thread(target=drive) for _ in range(max(1, workers))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return [r for r in results if r is not None]


if __name__ == "__main__":
    worker()
