"""Write examples/bag.dxf: the bundled demo drawing (a small leather bag).

Seven parts drawn the way a pattern designer draws them, in mm ($INSUNITS 4):
a front panel with rounded corners (bulged polyline) and an elliptical handle
slot, a back panel, a flap whose curved edge is a B-spline, a strap with
punched circular holes, two gussets, and a card pocket with a thumb notch; the
flap carries a straight lead-in and the strap a lead-in arc; a stitch guide
line stays open.  Run:  .venv/bin/python tools/make_example.py
"""

import math
import os

import ezdxf


def rounded_rect(msp, x, y, w, h, r, layer):
    """Closed LWPOLYLINE rectangle with quarter-circle corners (bulge = tan(90/4))."""
    b = math.tan(math.radians(90) / 4)
    pts = [(x + r, y, 0, 0, 0), (x + w - r, y, 0, 0, b), (x + w, y + r, 0, 0, 0),
           (x + w, y + h - r, 0, 0, b), (x + w - r, y + h, 0, 0, 0), (x + r, y + h, 0, 0, b),
           (x, y + h - r, 0, 0, 0), (x, y + r, 0, 0, b)]
    msp.add_lwpolyline(pts, format="xyseb", close=True, dxfattribs={"layer": layer})


def main() -> str:
    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = 4
    for name, colour in (("CUT", 7), ("HOLES", 1), ("LEADIN", 30), ("STITCH", 8)):
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()

    # Front panel 240 x 180 with rounded corners and an elliptical handle slot.
    rounded_rect(msp, 20, 20, 240, 180, 15, "CUT")
    msp.add_ellipse((140, 170), major_axis=(45, 0), ratio=0.25, dxfattribs={"layer": "HOLES"})

    # Back panel 240 x 180, plain rectangle drawn as four LINEs.
    x0, y0 = 290, 20
    corners = [(x0, y0), (x0 + 240, y0), (x0 + 240, y0 + 180), (x0, y0 + 180)]
    for a, b in zip(corners, corners[1:] + corners[:1]):
        msp.add_line(a, b, dxfattribs={"layer": "CUT"})

    # Flap: straight top and sides, B-spline bottom edge; lead-in from outside.
    fx, fy = 20, 230
    msp.add_line((fx, fy + 40), (fx, fy + 120), dxfattribs={"layer": "CUT"})
    msp.add_line((fx, fy + 120), (fx + 240, fy + 120), dxfattribs={"layer": "CUT"})
    msp.add_line((fx + 240, fy + 120), (fx + 240, fy + 40), dxfattribs={"layer": "CUT"})
    msp.add_spline([(fx + 240, fy + 40), (fx + 200, fy + 5), (fx + 120, fy - 10),
                    (fx + 40, fy + 5), (fx, fy + 40)], dxfattribs={"layer": "CUT"})
    msp.add_line((fx - 12, fy + 130), (fx, fy + 120), dxfattribs={"layer": "LEADIN"})

    # Strap 420 x 30 with rounded ends and five punched holes; lead-in arc.
    sx, sy = 290, 250
    msp.add_lwpolyline([(sx, sy, 0, 0, 0), (sx + 420, sy, 0, 0, 1), (sx + 420, sy + 30, 0, 0, 0),
                        (sx, sy + 30, 0, 0, 1)], format="xyseb", close=True,
                       dxfattribs={"layer": "CUT"})
    for i in range(5):
        msp.add_circle((sx + 310 + 20 * i, sy + 15), 2.5, dxfattribs={"layer": "HOLES"})
    msp.add_arc((sx + 210, sy - 8), 8, 90, 180, dxfattribs={"layer": "LEADIN"})

    # Two gussets 60 x 180 with a stitch guide line (open, on its own layer).
    for gx in (560, 640):
        rounded_rect(msp, gx, 20, 60, 180, 8, "CUT")
    msp.add_line((570, 30), (570, 190), dxfattribs={"layer": "STITCH"})

    # Card pocket 110 x 80 with a semicircular thumb notch in the top edge.
    px, py = 290, 310
    msp.add_line((px, py), (px + 110, py), dxfattribs={"layer": "CUT"})
    msp.add_line((px + 110, py), (px + 110, py + 80), dxfattribs={"layer": "CUT"})
    msp.add_line((px + 110, py + 80), (px + 70, py + 80), dxfattribs={"layer": "CUT"})
    msp.add_arc((px + 55, py + 80), 15, 180, 360, dxfattribs={"layer": "CUT"})
    msp.add_line((px + 40, py + 80), (px, py + 80), dxfattribs={"layer": "CUT"})
    msp.add_line((px, py + 80), (px, py), dxfattribs={"layer": "CUT"})

    out = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                       "examples", "bag.dxf")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    doc.saveas(out)
    return out


if __name__ == "__main__":
    print(main())
