"""Measured kerf check: the band a torch removes (traced back from the written
G-code, buffered by half the kerf) against the drawn parts, for the jobs the
tests check (tests/test_post_kerf.py, tests/test_post_kerf_rs274.py).

    .venv/bin/python bench/kerf_check.py

Prints, per job: the deepest reach of the band into a part (penetration), the
largest distance from a reachable outline point to the band (gap), and how
many outline points only a tool without kerf could reach (inside corners of
the scrap)."""

import os
import pathlib
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

from kerf_helpers import kerf_deviation, swept_band, traced_moves  # noqa: E402
from test_post_kerf import ARCS, BAG, job, spread, torch  # noqa: E402

from LeatherCutWorkbench.core.job import JobOptions, load_and_recognise  # noqa: E402
from LeatherCutWorkbench.core.pathplan import PlanOptions, plan  # noqa: E402
from LeatherCutWorkbench.post import gcode  # noqa: E402
from LeatherCutWorkbench.post.compensation import compensate  # noqa: E402
from LeatherCutWorkbench.post.profiles import load_profile, profile_from_dict  # noqa: E402


def row(name, parts, moves, prof):
    dev = kerf_deviation(parts, swept_band(moves, prof.kerf / 2, prof.origin), prof.kerf / 2)
    print(f"| {name} | {prof.kerf:g} | {dev['penetration']:.4f} | {dev['gap']:.4f} | "
          f"{dev['unreachable']} / {dev['points']} |")


def main():
    print("| job | kerf mm | penetration mm | gap mm | unreachable / checked points |")
    print("|---|---|---|---|---|")
    for corners in ("round", "extended"):
        prof = torch(kerf_corners=corners)
        res = job(BAG, prof)
        row(f"bag.dxf, flame_plasma, {corners} corners", res.parts_to_cut,
            traced_moves(gcode.export(res.plan, prof), prof), prof)
    _, rec = load_and_recognise(ARCS, JobOptions())
    parts = spread(rec.active_parts())
    for kerf in (0.5, 1.5):
        prof = torch(kerf=kerf)
        cut = plan(compensate(parts, prof)[0], [], PlanOptions(method="nn"))
        row("deepnest sample (119 arcs), spread apart", parts,
            traced_moves(gcode.export(cut, prof), prof), prof)
    try:
        from test_post_kerf_rs274 import RS274, canon_feeds
        from test_post_rs274 import run_rs274
    except ImportError:
        return
    if not os.path.isfile(RS274):
        return
    for mode in ("controller", "path"):
        prof = load_profile("linuxcnc_plasma")
        prof = profile_from_dict({**prof.to_json(), "kerf_mode": mode}, source="bench")
        res = job(BAG, prof)
        rc, out, canon = run_rs274(pathlib.Path(tempfile.mkdtemp()), gcode.export(res.plan, prof))
        assert rc == 0, out
        row(f"bag.dxf, linuxcnc_plasma {mode}, traced by rs274", res.parts_to_cut,
            canon_feeds(canon), prof)


if __name__ == "__main__":
    main()
