"""The nested DXF (``nest --dxf-out``, :func:`outputs.write_dxf`): each placed
contour is one entity whose geometry is the placed contour itself -- arcs as
exact bulges, a lone circle as a CIRCLE, mirrored and rotated copies included."""

import ezdxf
from ezdxf import path as ezpath
from shapely.geometry import Polygon

from LeatherCutWorkbench.core.geometry import ArcSeg, LineSeg
from LeatherCutWorkbench.core.model import Container, Contour, Layout, Part, Placement
from LeatherCutWorkbench.core.nesting import placed_parts
from LeatherCutWorkbench.core.nesting.outputs import write_dxf

from nest_shapes import circle


def slot_part() -> Part:
    """A 60 x 30 mm plate with a half-round end (radius 15), a round hole and
    a slot hole with two half-round ends (clockwise)."""
    outer = Contour("p/o", [LineSeg((0, 0), (45, 0)), ArcSeg((45, 15), 15.0, -90.0, 180.0),
                            LineSeg((45, 30), (0, 30)), LineSeg((0, 30), (0, 0))])
    slot = Contour("p/s", [ArcSeg((10, 11), 3.0, 270.0, -180.0),
                           LineSeg((10, 14), (25, 14)), ArcSeg((25, 11), 3.0, 90.0, -180.0),
                           LineSeg((25, 8), (10, 8))])
    return Part(id="p", outer=outer, holes=[circle("p/h", 5.0, 45.0, 15.0, ccw=False), slot],
                quantity=2, rotations=[0.0, 90.0], mirror_allowed=True)


def test_each_contour_is_one_entity_with_the_placed_geometry(tmp_path):
    part = slot_part()
    layout = Layout(containers=[Container(id="sheet1", kind="sheet",
                                          outline=[(0, 0), (200, 0), (200, 100), (0, 100)])],
                    placements=[Placement("p", 0, "sheet1", 10.0, 10.0),
                                Placement("p", 1, "sheet1", 150.0, 20.0, 90.0, True)])
    out = str(tmp_path / "nest.dxf")
    write_dxf(out, [part], layout)
    msp = ezdxf.readfile(out).modelspace()
    polys = msp.query("LWPOLYLINE[layer=='PARTS']")
    circles = msp.query("CIRCLE[layer=='PARTS']")
    assert len(msp.query("LINE ARC")) == 0
    assert len(polys) == 4 and len(circles) == 2           # outer + slot, round hole, per copy
    drawn = [Polygon(ezpath.make_path(e).flattening(0.005)) for e in polys] + \
        [Polygon(ezpath.make_path(e).flattening(0.005)) for e in circles]
    for pp in placed_parts([part], layout):
        for cont in pp.contours():
            want = Polygon(cont.points(0.005))
            best = min(drawn, key=lambda g: g.symmetric_difference(want).area)
            # same region up to the flattening of both sides (0.005 mm chords)
            assert best.symmetric_difference(want).area < 0.02 * want.length
