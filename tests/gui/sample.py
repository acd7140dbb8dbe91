"""A small generated drawing with every case the workbench shows (mm):

* a pinwheel of four closed rectangles around an empty 20 x 20 mm square
  (the square is an over-recognised region);
* a 40 x 30 mm rectangle drawn as an open polyline missing 0.3 mm
  (under-recognised, within the default 0.5 mm gap tolerance);
* a 50 x 40 mm plate with a 16 mm hole and a 10 mm lead-in line;
* a stray open line.
"""

from __future__ import annotations

import ezdxf


def write_sample(path: str) -> str:
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4  # mm
    msp = doc.modelspace()
    for layer in ("PARTS", "LEADIN", "STRAY"):
        doc.layers.add(layer)
    rects = [((0, 0), (30, 10)), ((30, 0), (40, 30)), ((10, 30), (40, 40)), ((0, 10), (10, 40))]
    for (x0, y0), (x1, y1) in rects:
        msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                           dxfattribs={"layer": "PARTS"})
    msp.add_lwpolyline([(60, 0.3), (60, 30), (100, 30), (100, 0), (60, 0)], close=False,
                       dxfattribs={"layer": "PARTS"})
    msp.add_lwpolyline([(120, 0), (170, 0), (170, 40), (120, 40)], close=True,
                       dxfattribs={"layer": "PARTS"})
    msp.add_circle((145, 20), 8, dxfattribs={"layer": "PARTS"})
    msp.add_line((110, 20), (120, 20), dxfattribs={"layer": "LEADIN"})
    msp.add_line((0, 70), (50, 80), dxfattribs={"layer": "STRAY"})
    doc.saveas(path)
    return path
