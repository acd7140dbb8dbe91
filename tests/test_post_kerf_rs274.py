"""The kerf check through LinuxCNC's own interpreter (rs274, see
test_post_rs274.py): the ``linuxcnc_plasma`` job on examples/bag.dxf, written
with controller compensation (G41.1/G42.1 D1.5 ... G40: LinuxCNC offsets the
drawn path itself) and pre-offset (kerf_mode path).  The centre line LinuxCNC
actually moves along, buffered by half the kerf, must touch every drawn
outline within 0.02 mm and enter no part."""

import math
import os
from types import SimpleNamespace

import pytest

from LeatherCutWorkbench.core.job import JobOptions, run_job
from LeatherCutWorkbench.core.pathplan import PlanOptions
from LeatherCutWorkbench.post import gcode
from LeatherCutWorkbench.post.compensation import apply_to_job
from LeatherCutWorkbench.post.profiles import load_profile, profile_from_dict

from kerf_helpers import kerf_deviation, swept_band
from test_post_rs274 import CANON, RS274, run_rs274

pytestmark = pytest.mark.skipif(not os.path.isfile(RS274) and os.environ.get("CI") != "true",
                                reason="real LinuxCNC interpreter not unpacked "
                                       "(bash tools/get_rs274.sh)")

BAG = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                   "examples", "bag.dxf")
TOL = 0.02


def canon_feeds(canon):
    """Feed moves (the torch is on during every feed of our programs) as
    objects with ``start``/``end`` dicts, ``kind``, ``center`` and ``ccw``."""
    here = (0.0, 0.0)
    out = []
    for name, args in CANON.findall(canon):
        v = [float(a) for a in args.split(",")]
        end = (v[0], v[1])
        if name == "STRAIGHT_FEED":
            out.append(SimpleNamespace(kind="line", start={"X": here[0], "Y": here[1]},
                                       end={"X": end[0], "Y": end[1]}, center=None, ccw=True))
        elif name == "ARC_FEED":
            out.append(SimpleNamespace(kind="arc", start={"X": here[0], "Y": here[1]},
                                       end={"X": end[0], "Y": end[1]}, center=(v[2], v[3]),
                                       ccw=int(v[4]) > 0))
        here = end
    return out


@pytest.mark.parametrize("mode", ["controller", "path"])
def test_linuxcnc_kerf_check(tmp_path, mode):
    prof = load_profile("linuxcnc_plasma")
    if mode == "path":
        prof = profile_from_dict({**prof.to_json(), "kerf_mode": "path"}, source="test")
    opts = JobOptions(plan=PlanOptions(method="nn"), move_to_origin=20.0)
    apply_to_job(opts, prof)
    res = run_job(BAG, opts)
    text = gcode.export(res.plan, prof)
    comp_words = sum(1 for ln in text.splitlines() if ln.startswith(("G41.1", "G42.1")))
    assert comp_words == (len(res.plan.items) if mode == "controller" else 0)
    rc, out, canon = run_rs274(tmp_path, text)
    assert rc == 0, out
    moves = canon_feeds(canon)
    assert sum(1 for m in moves if m.kind == "arc") > 20
    band = swept_band(moves, prof.kerf / 2, prof.origin)
    dev = kerf_deviation(res.parts_to_cut, band, prof.kerf / 2, TOL)
    assert dev["penetration"] <= TOL, dev
    assert dev["gap"] <= TOL, dev
    assert math.isfinite(dev["gap"]) and dev["points"] > 10000
