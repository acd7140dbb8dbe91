"""A person's decisions on recognition flags, applied the same way everywhere.

The workbench stores one decision per flag (``Undecided``, ``Include``,
``Exclude``, ``Accept``, ``Reject``); the CLI takes ``--accept-fix`` /
``--reject-fix``.  :func:`apply_decisions` turns the recognition of the
proposal run plus the decisions into the recognition that is cut, for the
stage-by-stage flow and for *Run job* / ``leathercut run`` alike
(:func:`core.job.run_job` with ``JobOptions.decisions``).
"""

from __future__ import annotations

from copy import deepcopy
from dataclasses import replace
from typing import Callable, Dict, FrozenSet, Optional

from .errors import InputError, LeatherCutError
from .model import Drawing, Recognition

#: recognise_again(accepted fix ids, rejected fix ids) -> recognition with exactly those fixes
Rerun = Callable[[FrozenSet[str], FrozenSet[str]], Recognition]


def rerun_with_fixes(drawing: Drawing, options) -> Rerun:
    """The ``recognise_again`` of :func:`apply_decisions` for ``drawing`` recognised
    with ``options`` (RecogniseOptions): the core's recognition with exactly the
    given fixes applied (no blanket ``close_gaps``)."""
    def again(accept: FrozenSet[str], reject: FrozenSet[str]) -> Recognition:
        from .recognition import recognise
        return recognise(drawing, replace(options, close_gaps=False, accept_fixes=accept,
                                          reject_fixes=reject))
    return again


def apply_decisions(rec: Recognition, decisions: Dict[str, str],
                    recognise_again: Optional[Rerun] = None) -> Recognition:
    """Apply decisions (flag id -> Include / Exclude / Accept / Reject / Undecided).

    Over-recognised: Include clears ``excluded`` on the flagged parts, Exclude
    sets it.  Under-recognised: the fixes to apply (Accept, or Undecided on a
    flag the stored run already applied, e.g. with ``close_gaps``) and to reject
    are passed to ``recognise_again(accept_ids, reject_ids)``, which returns the
    core's recognition with exactly those fixes applied; it is called only when
    the geometry must change.  Returns a new recognition."""
    under = [f for f in rec.flags if f.kind == "under"]
    accept = frozenset(f.id for f in under if decisions.get(f.id) == "Accept"
                       or (decisions.get(f.id, "Undecided") == "Undecided" and f.accepted is True))
    reject = frozenset(f.id for f in under if decisions.get(f.id) == "Reject")
    if any((f.id in accept) != (f.accepted is True) for f in under):
        if recognise_again is None:
            raise LeatherCutError("accepting or rejecting a fix needs the drawing: "
                                  "recognise again")
        out = deepcopy(recognise_again(accept, reject))
        _check_same_flags(rec, out, accept | reject)
    else:
        out = deepcopy(rec)
        for f in out.flags:
            if f.kind == "under" and f.id in reject:
                f.accepted = False
    for flag in out.flags:
        d = decisions.get(flag.id, "Undecided")
        if flag.kind == "over" and d in ("Include", "Exclude"):
            flag.accepted = d == "Exclude"
            ids = set(flag.ids)
            for p in out.parts:
                if p.id in ids or p.outer.id in ids:
                    p.excluded = d == "Exclude"
    return out


def _check_same_flags(old: Recognition, new: Recognition, decided) -> None:
    """The decided flags must be the same flags in the new run (else the stored
    recognition no longer matches the drawing or the options)."""
    got = {f.id: f for f in new.flags}
    for f in old.flags:
        if f.id not in decided:
            continue
        g = got.get(f.id)
        if g is None or (g.kind, g.action) != (f.kind, f.action) or \
                abs((g.gap or 0.0) - (f.gap or 0.0)) > 1e-9:
            raise InputError(f"flag {f.id} is not the same after recognising again: the "
                             "recognition is out of date, run Recognise again")
