"""The validity checker on hand-made layouts: it accepts valid ones and names
what is wrong with invalid ones."""

from LeatherCutWorkbench.core.model import Container, Layout, Placement
from LeatherCutWorkbench.core.nesting.checker import check_layout
from LeatherCutWorkbench.core.nesting.containers import rectangle

from nest_shapes import disc, frame, l_shape, rect


def sheet(defects=(), zones=(), base_grade=0):
    return Container(id="s", kind="sheet", outline=rectangle(0, 0, 100, 50),
                     defects=list(defects), zones=list(zones), base_grade=base_grade)


def lay(*pls, container=None):
    return Layout(containers=[container or sheet()], placements=list(pls))


def test_accepts_touching_parts_inside_the_sheet():
    parts = [rect("a", 40, 50, q=2)]
    layout = lay(Placement("a", 0, "s", 0, 0), Placement("a", 1, "s", 40, 0))
    assert check_layout(parts, layout) == []


def test_rejects_overlap():
    parts = [rect("a", 40, 50, q=2)]
    layout = lay(Placement("a", 0, "s", 0, 0), Placement("a", 1, "s", 39, 0))
    probs = check_layout(parts, layout)
    assert len(probs) == 1 and "a#0 overlaps a#1" in probs[0]


def test_overlap_within_tolerance_is_accepted():
    parts = [rect("a", 40, 50, q=2)]
    layout = lay(Placement("a", 0, "s", 0, 0), Placement("a", 1, "s", 40 - 1e-5, 0))
    assert check_layout(parts, layout, tol=1e-3) == []


def test_rejects_part_outside_container():
    parts = [rect("a", 40, 50)]
    probs = check_layout(parts, lay(Placement("a", 0, "s", 70, 0)))
    assert any("outside container s" in p for p in probs)


def test_rejects_part_on_defect_and_margin_to_defect():
    parts = [rect("a", 20, 20)]
    c = sheet(defects=[rectangle(50, 20, 55, 25)])
    assert any("covers defect 0" in p
               for p in check_layout(parts, lay(Placement("a", 0, "s", 40, 10), container=c)))
    # 2 mm from the defect: fine without margin, rejected with a 5 mm margin
    ok = lay(Placement("a", 0, "s", 28, 10), container=c)
    assert check_layout(parts, ok) == []
    assert any("margin" in p for p in check_layout(parts, ok, margin=5))


def test_rejects_disallowed_rotation_and_mirroring():
    parts = [l_shape("L", 30, 20, 5, rotations=[0, 180])]
    # turned 180 degrees about its origin the L spans x 10..40, y 10..30
    assert check_layout(parts, lay(Placement("L", 0, "s", 40, 30, angle=180))) == []
    probs = check_layout(parts, lay(Placement("L", 0, "s", 40, 10, angle=90)))
    assert any("angle 90 not allowed" in p for p in probs)
    probs = check_layout(parts, lay(Placement("L", 0, "s", 40, 10, mirrored=True)))
    assert any("mirroring is not allowed" in p for p in probs)
    parts[0].mirror_allowed = True
    assert check_layout(parts, lay(Placement("L", 0, "s", 40, 10, mirrored=True))) == []
    assert check_layout(parts, lay(Placement("L", 0, "s", 20, 10, mirrored=True)))  # x < 0


def test_rejects_spacing_shortfall():
    parts = [rect("a", 20, 20, q=2)]
    layout = lay(Placement("a", 0, "s", 0, 0), Placement("a", 1, "s", 22, 0))
    assert check_layout(parts, layout, spacing=2.0) == []
    probs = check_layout(parts, layout, spacing=3.0)
    assert len(probs) == 1 and "apart (spacing 3 mm)" in probs[0]


def test_part_inside_hole_of_another_is_valid():
    parts = [frame("F", 60, 40, 5), rect("r", 20, 20)]
    layout = lay(Placement("F", 0, "s", 0, 0), Placement("r", 0, "s", 10, 10))
    assert check_layout(parts, layout) == []
    layout = lay(Placement("F", 0, "s", 0, 0), Placement("r", 0, "s", 2, 10))
    assert any("overlaps" in p for p in check_layout(parts, layout))


def test_quality_zones():
    # sheet base grade 1, a grade-3 zone on the left half
    c = sheet(zones=[(3, rectangle(0, 0, 50, 50))], base_grade=1)
    parts = [rect("good", 20, 20, grade=3), rect("any", 20, 20, grade=0)]
    assert check_layout(parts, lay(Placement("good", 0, "s", 10, 10), container=c)) == []
    probs = check_layout(parts, lay(Placement("good", 0, "s", 40, 10), container=c))
    assert any("below grade 3" in p for p in probs)
    assert check_layout(parts, lay(Placement("any", 0, "s", 70, 10), container=c)) == []
    # nested zone: a grade-0 patch inside the grade-3 zone is off limits for grade 3
    c2 = sheet(zones=[(3, rectangle(0, 0, 50, 50)), (0, rectangle(20, 20, 30, 30))], base_grade=1)
    probs = check_layout(parts, lay(Placement("good", 0, "s", 15, 15), container=c2))
    assert any("below grade 3" in p for p in probs)


def test_rejects_bookkeeping_errors():
    parts = [disc("d", 5, q=1)]
    layout = lay(Placement("d", 0, "s", 0, 0), Placement("d", 0, "s", 20, 0),
                 Placement("d", 3, "s", 40, 0), Placement("x", 0, "s", 60, 0),
                 Placement("d", 0, "nowhere", 0, 0))
    text = "\n".join(check_layout(parts, layout))
    assert "placed twice" in text
    assert "copy index outside quantity" in text
    assert "x#0: unknown part" in text
    assert "unknown container 'nowhere'" in text


def test_safety_net_moves_rejected_placements_to_unplaced():
    from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, _drop_invalid
    from LeatherCutWorkbench.core.nesting.checker import check_layout as check
    parts = [rect("a", 40, 50, q=2)]
    layout = Layout(containers=[Container(id="strip", kind="strip", outline=rectangle(0, 0, 100, 50))],
                    placements=[Placement("a", 0, "strip", 0, 0), Placement("a", 1, "strip", 30, 0)])
    opts = NestOptions(container=ContainerSpec.strip(50))
    problems = check(parts, layout)
    _drop_invalid(parts, layout, problems, opts)
    assert len(layout.placements) == 1 and len(layout.unplaced) == 1
    kept = layout.placements[0]
    assert {(kept.part_id, kept.copy)} | set(layout.unplaced) == {("a", 0), ("a", 1)}
    assert any(f.code == "invalid-placement-removed" and f.level == "error" for f in layout.findings)
    # figures are recomputed for what is left: one 40 x 50 part, strip up to its right edge
    length = kept.x + 40
    assert layout.metrics["strip_length_mm"] == length
    assert layout.metrics["density"] == round(2000 / (length * 50), 6)
    assert layout.metrics["placed_count"] == 1 and layout.metrics["unplaced_count"] == 1
    assert check(parts, layout) == []


def test_hide_zones_and_defects_are_built_once_per_check(monkeypatch):
    """Baldacci Scarpa (240 copies, 2 hides with ~30 holes and ~20 zones): the
    check rebuilt the zone region of a grade for every copy (~30 ms each) and
    overran a 10 s budget by 2.6 s.  Each (hide, grade) region is now built
    once, and the verdicts stay those of the full test."""
    from LeatherCutWorkbench.core.nesting import checker
    calls = []
    real = checker._zone_grade_region
    monkeypatch.setattr(checker, "_zone_grade_region",
                        lambda c, g: calls.append((c.id, g)) or real(c, g))
    holes = [rectangle(x, 40, x + 4, 44) for x in range(2, 98, 8)]     # 12 small defects
    c = Container(id="h", kind="hide", outline=rectangle(0, 0, 100, 50), defects=holes,
                  zones=[(1, rectangle(0, 0, 20, 30)), (2, rectangle(80, 0, 100, 30))],
                  base_grade=3)
    parts = [rect("a", 5, 5, q=20, grade=3), rect("b", 5, 5, q=20, grade=2)]
    pls = [Placement("a", k, "h", 22 + 6 * (k % 9), 2 + 6 * (k // 9)) for k in range(18)]
    pls += [Placement("b", k, "h", 81 + 6 * (k % 3), 2 + 6 * (k // 3)) for k in range(12)]
    assert check_layout(parts, lay(*pls, container=c)) == []
    assert sorted(set(calls)) == sorted(calls) == [("h", 2), ("h", 3)]
    # the same layout with one copy on the grade-1 zone, one on a defect and one 1 mm
    # from a defect under a 2 mm margin: each still found
    bad = pls[:-3] + [Placement("b", 17, "h", 2, 2), Placement("b", 18, "h", 9, 38),
                      Placement("b", 19, "h", 40, 34)]
    probs = check_layout(parts, lay(*bad, container=c), margin=2)
    assert any(p.startswith("b#17:") and "below grade 2" in p for p in probs)
    assert any(p.startswith("b#18:") and "covers defect 1" in p for p in probs)
    assert any(p.startswith("b#19:") and "margin 2 mm to defect 5" in p for p in probs)
