"""Layer selection for plain drawings: which layers are cut, which only drawn."""

import ezdxf
import pytest

from LeatherCutWorkbench.core.dxfimport import ImportOptions, read_drawing


@pytest.fixture
def layered_dxf(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (50, 0), (50, 30), (0, 30)], close=True,
                       dxfattribs={"layer": "Outline"})
    msp.add_line((5, 5), (45, 5), dxfattribs={"layer": "Sew Line"})
    msp.add_line((5, 25), (45, 25), dxfattribs={"layer": "ENGRAVING"})
    msp.add_circle((25, 15), 3, dxfattribs={"layer": "Holes"})
    path = tmp_path / "layered.dxf"
    doc.saveas(path)
    return str(path)


def roles_by_layer(drawing):
    out = {}
    for e in drawing.edges:
        out.setdefault(e.src.layer, set()).add(e.src.role)
    return out


def test_default_keeps_stitch_and_engraving_layers_uncut_and_says_so(layered_dxf):
    d = read_drawing(layered_dxf)
    roles = roles_by_layer(d)
    assert roles["Outline"] == {"cut"} and roles["Holes"] == {"cut"}
    assert roles["Sew Line"] == {"internal"} and roles["ENGRAVING"] == {"internal"}
    warned = {f.source.split(" layer ", 1)[1] for f in d.findings if f.code == "layer-not-cut"}
    assert warned == {"Sew Line", "ENGRAVING"}


def test_cut_layers_selects_only_matching_layers(layered_dxf):
    d = read_drawing(layered_dxf, ImportOptions(cut_layers=("outl*",)))
    roles = roles_by_layer(d)
    assert roles["Outline"] == {"cut"}
    assert roles["Holes"] == {"internal"} and roles["Sew Line"] == {"internal"}


def test_empty_not_cut_list_cuts_every_layer(layered_dxf):
    d = read_drawing(layered_dxf, ImportOptions(not_cut_layers=()))
    assert all(r == {"cut"} for r in roles_by_layer(d).values())
    assert not [f for f in d.findings if f.code == "layer-not-cut"]
