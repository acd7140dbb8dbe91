"""Writing job files so that a machine never receives half of one.

:func:`write_file` is the one way LeatherCut writes an output file (``job.nc``,
``preview.svg``, ``report.json``, ``post -o``, the workbench's post): the data
goes to a temporary file in the same folder, is ``fsync``-ed and renamed over
the target with ``os.replace`` (atomic on POSIX and Windows), and the folder
is ``fsync``-ed.  A failed write (full disk, quota, I/O error) removes the
temporary file and leaves the target as it was.  An existing target that is
not a regular file (a folder, a character device, a FIFO, a socket) is
refused: it is never replaced by a regular file.  A symbolic link is written
through (its target is replaced).

G-code job files are *sealed*: :func:`seal` appends one last comment line

    (LEATHERCUT END lines=N sha256=HEX)

-- ``N`` lines before it, ``HEX`` the SHA-256 of their bytes (ASCII, ``\\n``
line ends).  A parenthesised comment is a comment in every dialect we write
(GRBL and grblHAL strip it, LinuxCNC reads ``( .. )`` as a comment -- it does
not start with ``MSG,``/``DEBUG,``/``PRINT,``/``LOG`` -- and it comes after
the program end, which LinuxCNC does not read past).  :func:`check_sealed`
verifies it before a job is streamed: a missing marker or a wrong checksum
means a truncated or edited file and is refused.  Hand-written G-code has no
seal; it is accepted only with an explicit ``allow_unsealed`` and only when it
does not look like a LeatherCut job (header or ``(seg ..)`` comments), so a
truncated LeatherCut file never streams.
"""

from __future__ import annotations

import hashlib
import os
import re
import stat
import tempfile
from typing import List, Union

from ..core.errors import InputError

SEAL = re.compile(r"^\(LEATHERCUT END lines=(\d+) sha256=([0-9a-f]{64})\)$")


def seal(text: str) -> str:
    """``text`` (G-code, ``\\n`` line ends) with its end marker appended."""
    body = text if text.endswith("\n") else text + "\n"
    digest = hashlib.sha256(body.encode("ascii")).hexdigest()
    return body + f"(LEATHERCUT END lines={body.count(chr(10))} sha256={digest})\n"


def looks_like_leathercut(lines: List[str]) -> bool:
    """Whether the lines carry LeatherCut's header or segment comments."""
    for line in lines:
        s = line.strip().upper()
        if s.startswith("(LEATHERCUT") or s.startswith("(SEG ") or s.startswith("(END ITEM"):
            return True
    return False


def check_sealed(data: bytes, path: str, allow_unsealed: bool = False) -> None:
    """Refuse a G-code file whose end marker is missing or whose checksum or
    line count does not match (raises InputError naming the file)."""
    text = data.decode("ascii", "replace")
    lines = text.splitlines()
    last = len(lines) - 1
    while last >= 0 and not lines[last].strip():
        last -= 1
    m = SEAL.match(lines[last].strip()) if last >= 0 else None
    if m is None:
        if allow_unsealed and not looks_like_leathercut(lines):
            return
        if looks_like_leathercut(lines):
            raise InputError("the job file has no LeatherCut end marker: it is truncated (an "
                             "interrupted or failed write?) and is not streamed; post the job "
                             "again", source=path)
        raise InputError("the G-code file has no LeatherCut end marker (LEATHERCUT END "
                         "lines=.. sha256=..): it may be truncated; post the job again, or "
                         "pass --allow-unsealed for a hand-written file", source=path)
    pos = 0
    for _ in range(last):
        pos = data.index(b"\n", pos) + 1
    body = data[:pos]
    n, want = int(m.group(1)), m.group(2)
    got = hashlib.sha256(body).hexdigest()
    have = body.count(b"\n")
    if have != n or got != want:
        raise InputError(f"the job file does not match its end marker (lines {have} of {n}, "
                         f"checksum {'ok' if got == want else 'wrong'}): it was edited "
                         "or damaged and is not streamed; post the job again", source=path)


_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
          (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISSOCK, "a socket"))


def refuse_special(path: str) -> str:
    """The real path to replace; InputError when ``path`` exists and is not a
    regular file (a directory, FIFO, device or socket is never replaced nor
    written into).  ``leathercut post`` / ``run`` call it before planning too."""
    real = os.path.realpath(path)
    try:
        st = os.stat(real)
    except FileNotFoundError:
        return real
    except OSError as exc:
        raise InputError(f"cannot write: {exc.strerror or exc}", source=path)
    if not stat.S_ISREG(st.st_mode):
        kind = next((w for test, w in _KINDS if test(st.st_mode)), "not a regular file")
        raise InputError(f"cannot write: the path is {kind}, not a regular file; "
                         "LeatherCut only writes job files as regular files", source=path)
    return real


def write_file(path: str, data: Union[str, bytes], encoding: str = "utf-8") -> None:
    """Write ``data`` to ``path`` atomically (see the module docstring);
    raises InputError naming the path when it cannot."""
    raw = data.encode(encoding) if isinstance(data, str) else data
    real = refuse_special(path)
    folder = os.path.dirname(real) or "."
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(real) + ".",
                                   suffix=".part")
    except OSError as exc:
        raise InputError(f"cannot write: {exc.strerror}", source=path)
    try:
        try:
            mode = stat.S_IMODE(os.stat(real).st_mode)
        except FileNotFoundError:
            umask = os.umask(0)
            os.umask(umask)
            mode = 0o666 & ~umask
        if hasattr(os, "fchmod"):            # POSIX; Windows keeps its default ACL
            os.fchmod(fd, mode)
        view = memoryview(raw)
        while view:
            n = os.write(fd, view)
            view = view[n:]
        os.fsync(fd)
        os.close(fd)
        fd = -1
        os.replace(tmp, real)
    except OSError as exc:
        if fd >= 0:
            os.close(fd)
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise InputError(f"cannot write: {exc.strerror or exc}", source=path)
    try:
        dfd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(dfd)
        finally:
            os.close(dfd)
    except OSError:
        pass                          # some file systems cannot fsync a folder


def write_job_file(path: str, text: str, gcode: bool) -> None:
    """Write a post's output: G-code sealed (:func:`seal`), other formats as
    they are; atomically (:func:`write_file`)."""
    write_file(path, seal(text) if gcode else text, "ascii" if gcode else "utf-8")
