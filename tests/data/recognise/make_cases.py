"""Write cases.dxf: every canonical recognition case side by side (mm).

Run from the repository root:  .venv/bin/python tests/data/recognise/make_cases.py
The expected result is listed in README.md and checked by tests/test_recognise_blocks.py.
"""

import os

import ezdxf


def main() -> str:
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()

    def rect(x, y, w, h):
        msp.add_lwpolyline([(x, y), (x + w, y), (x + w, y + h), (x, y + h)], close=True)

    # 1. part with a round hole and a straight lead-in (x 0..40)
    rect(0, 0, 40, 30)
    msp.add_circle((20, 15), 5)
    msp.add_line((5, -3), (5, 0))
    # 2. part with an arc lead-in into the bottom edge (x 60..100)
    rect(60, 0, 40, 30)
    msp.add_arc((65, -3), 3, 90, 180)
    # 3. pinwheel of four parts drawn as closed outlines around a scrap square (x 120..150)
    for x, y, w, h in [(0, 0, 20, 10), (20, 0, 10, 20), (10, 20, 20, 10), (0, 10, 10, 20)]:
        rect(120 + x, y, w, h)
    # 4. 3 x 2 common-edge grid drawn as single lines (x 170..200)
    rect(170, 0, 30, 20)
    for x in (180, 190):
        msp.add_line((x, 0), (x, 20))
    msp.add_line((170, 10), (200, 10))
    # 5. square left open by a 0.3 mm gap (x 220..240): flagged under
    msp.add_lwpolyline([(220, 0.3), (220, 0), (240, 0), (240, 20), (220, 20), (220, 0.6)])
    # 6. square left open by a 2 mm gap (x 260..280): stays an open chain
    msp.add_lwpolyline([(260, 2), (260, 0), (280, 0), (280, 20), (260, 20), (260, 4)])
    # 7. island: frame part with a big hole holding a part (x 300..360)
    rect(300, 0, 60, 60)
    rect(310, 10, 40, 40)
    rect(320, 20, 20, 20)
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cases.dxf")
    doc.saveas(path)
    return path


if __name__ == "__main__":
    print(main())
