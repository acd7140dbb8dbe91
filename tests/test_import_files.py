"""DXF import: awkward and bad files (generated in tmp_path) and the unit policy."""


import ezdxf
import pytest

from LeatherCutWorkbench.core.dxfimport import ImportOptions, read_drawing
from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.model import LineEdge


def _simple(tmp_path, name="ok.dxf", insunits=4, fmt="asc", version="R2010"):
    doc = ezdxf.new(version)
    if insunits is not None:
        doc.header["$INSUNITS"] = insunits
    msp = doc.modelspace()
    msp.add_line((0, 0), (-6.63671875, 3.5))
    msp.add_circle((10, 10), 2.25)
    p = str(tmp_path / name)
    doc.saveas(p, fmt=fmt)
    return p


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="file not found"):
        read_drawing(str(tmp_path / "nope.dxf"))


def test_empty_file(tmp_path):
    p = tmp_path / "empty.dxf"
    p.write_bytes(b"")
    with pytest.raises(InputError, match="empty"):
        read_drawing(str(p))


def test_directory_is_refused(tmp_path):
    with pytest.raises(InputError, match="directory"):
        read_drawing(str(tmp_path))


@pytest.mark.parametrize("content, what", [
    (b"\x89PNG\r\n\x1a\n" + b"\x00" * 20, "PNG image"),
    (b"%PDF-1.4\n%...", "PDF document"),
    (b"AC1032\x00\x00\x00\x00\x00\x00binary", "DWG"),
    (b"<?xml version='1.0'?><svg></svg>", "SVG"),
    (b"hello world\nthis is a text file\n", "starts with 'hello world'"),
])
def test_not_a_dxf_says_what_it_is(tmp_path, content, what):
    p = tmp_path / "x.dxf"
    p.write_bytes(content)
    with pytest.raises(InputError) as exc:
        read_drawing(str(p))
    assert "not a DXF file" in str(exc.value) and what in str(exc.value)
    assert str(p) in str(exc.value)


def test_binary_dxf_is_read(tmp_path):
    asc = read_drawing(_simple(tmp_path, "a.dxf"), ImportOptions(cleanup=False))
    binary = read_drawing(_simple(tmp_path, "b.dxf", fmt="bin"), ImportOptions(cleanup=False))
    assert open(tmp_path / "b.dxf", "rb").read(18) == b"AutoCAD Binary DXF"
    assert binary.stats["file"]["binary"] and not asc.stats["file"]["binary"]
    assert [type(e) for e in binary.edges] == [type(e) for e in asc.edges]
    assert binary.edges[0].end == asc.edges[0].end == pytest.approx((-6.63671875, 3.5))


def test_decimal_commas_are_converted_consistently(tmp_path):
    p = _simple(tmp_path, "comma.dxf")
    text = open(p).read()
    # a comma-locale writer: every float value written with ","
    lines = text.splitlines()
    out = []
    float_codes = set(range(10, 60)) | set(range(110, 150)) | set(range(210, 240)) | set(range(460, 470)) \
        | set(range(1010, 1060))
    for code, value in zip(lines[0::2], lines[1::2]):
        if code.strip().lstrip("-").isdigit() and int(code) in float_codes and "." in value:
            value = value.replace(".", ",")
        out += [code, value]
    open(p, "w").write("\n".join(out) + "\n")
    assert "-6,63671875" in open(p).read()
    with pytest.raises((ezdxf.DXFError, ValueError)):
        ezdxf.readfile(p)  # ezdxf alone refuses (and recover would truncate to -6.0)
    d = read_drawing(p, ImportOptions(cleanup=False))
    line = next(e for e in d.edges if isinstance(e, LineEdge))
    assert line.end == pytest.approx((-6.63671875, 3.5))    # never -6
    assert d.stats["file"]["decimal_commas_fixed"] > 10
    assert any(f.code == "decimal-commas" for f in d.findings)


def test_mixed_decimal_commas_are_refused(tmp_path):
    p = _simple(tmp_path, "mixed.dxf")
    text = open(p).read().replace("-6.63671875", "-6,63671875")
    open(p, "w").write(text)
    with pytest.raises(InputError, match="decimal comma") as exc:
        read_drawing(p)
    assert "-6,63671875" in str(exc.value) and "line" in str(exc.value)


def test_text_with_commas_is_not_a_decimal_comma(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    doc.modelspace().add_line((0, 0), (1.5, 0))
    doc.modelspace().add_text("1,5")
    p = str(tmp_path / "t.dxf")
    doc.saveas(p)
    d = read_drawing(p)
    assert d.texts[0].text == "1,5" and d.stats["file"]["decimal_commas_fixed"] == 0


def test_trash_after_eof_is_ignored_with_warning(tmp_path):
    p = _simple(tmp_path)
    with open(p, "ab") as fh:
        fh.write(b"\x00\x00some trailing garbage from a mailer\r\n" * 3)
    d = read_drawing(p)
    assert len(d.edges) == 2
    assert d.stats["file"]["trailing_bytes"] > 90
    assert any(f.code == "trailing-data" for f in d.findings)


def test_recover_only_file_reports_repairs(tmp_path):
    p = _simple(tmp_path, "broken.dxf", version="R12")
    text = open(p).read()
    # damage: an ENDSEC without SECTION before the ENTITIES section
    i = text.index("  0\nSECTION\n  2\nENTITIES")
    open(p, "w").write(text[:i] + "  0\nENDSEC\n" + text[i:])
    with pytest.raises(ezdxf.DXFStructureError):
        ezdxf.readfile(p)
    d = read_drawing(p)
    assert d.stats["file"]["recovered"] is True
    rec = [f for f in d.findings if f.code == "recovered"]
    assert rec and "ENDSEC" in rec[0].message and "recovery mode" in rec[0].message
    assert len(d.edges) == 2


def test_unreadable_even_by_recover_is_refused(tmp_path):
    p = tmp_path / "garbage.dxf"
    p.write_text("  0\nSECTION\n  2\nENTITIES\n  0\nLINE\n 10\nabc\n 20\n\x01\x02\n")
    with pytest.raises(InputError) as exc:
        read_drawing(str(p))
    assert str(p) in str(exc.value)


def test_empty_drawing_is_refused(tmp_path):
    doc = ezdxf.new("R2010")
    p = str(tmp_path / "nothing.dxf")
    doc.saveas(p)
    with pytest.raises(InputError, match="empty"):
        read_drawing(p)


def test_drawing_with_only_unusable_entities_is_refused_naming_them(tmp_path):
    doc = ezdxf.new("R2010")
    doc.modelspace().add_3dface([(0, 0, 0), (1, 0, 1), (1, 1, 2)])
    doc.modelspace().add_text("just a title")
    p = str(tmp_path / "3d.dxf")
    doc.saveas(p)
    with pytest.raises(InputError) as exc:
        read_drawing(p)
    assert "nothing usable" in str(exc.value) and "3DFACE" in str(exc.value)


def test_huge_coordinates_moved_to_local_origin(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    x0, y0 = 3_150_123.25, 5_800_456.5
    msp.add_lwpolyline([(x0, y0), (x0 + 100, y0), (x0 + 100, y0 + 50), (x0, y0 + 50)], close=True)
    msp.add_arc((x0 + 50, y0 + 25), 10, 0, 180)
    p = str(tmp_path / "huge.dxf")
    doc.saveas(p)
    d = read_drawing(p)
    assert d.offset == (3_150_000.0, 5_800_000.0)
    assert d.stats["bbox_mm"] == pytest.approx([123.25, 456.5, 223.25, 506.5])
    arc = next(e for e in d.edges if hasattr(e, "radius"))
    assert arc.center == pytest.approx((173.25, 481.5))
    assert any(f.code == "local-origin" for f in d.findings)


# ---------------------------------------------------------------- units

@pytest.mark.parametrize("code, unit, factor", [(1, "inch", 25.4), (2, "foot", 304.8),
                                                (4, "mm", 1.0), (5, "cm", 10.0), (6, "m", 1000.0)])
def test_insunits_converted_to_mm(tmp_path, code, unit, factor):
    d = read_drawing(_simple(tmp_path, insunits=code), ImportOptions(cleanup=False))
    assert (d.units, d.units_source) == (unit, "header")
    assert d.edges[0].end == pytest.approx((-6.63671875 * factor, 3.5 * factor))


def test_missing_units_assumed_mm_with_warning_and_option_override(tmp_path):
    p = _simple(tmp_path, insunits=0)
    d = read_drawing(p)
    assert (d.units, d.units_source) == ("mm", "assumed")
    assert any(f.code == "units-missing" and "--units" in f.message for f in d.findings)
    d2 = read_drawing(p, ImportOptions(units="inch"))
    assert (d2.units, d2.units_source) == ("inch", "option")
    assert d2.edges[0].end == pytest.approx((-6.63671875 * 25.4, 3.5 * 25.4))


def test_units_option_overrides_header_with_note(tmp_path):
    d = read_drawing(_simple(tmp_path, insunits=6), ImportOptions(units="mm"))
    assert d.units == "mm" and d.edges[0].end == pytest.approx((-6.63671875, 3.5))
    assert any(f.code == "units-overridden" and "m;" in f.message for f in d.findings)


def test_bad_option_values_are_input_errors(tmp_path):
    p = _simple(tmp_path)
    with pytest.raises(InputError, match="unknown unit"):
        read_drawing(p, ImportOptions(units="furlong"))
    with pytest.raises(InputError, match="pattern mode"):
        read_drawing(p, ImportOptions(pattern_mode="gerber"))
    with pytest.raises(InputError, match="tolerance"):
        read_drawing(p, ImportOptions(tolerance=0))


def test_implausible_units_are_flagged(tmp_path):
    d = read_drawing(_simple(tmp_path, insunits=7))   # kilometres: an 18.9 km drawing
    assert any(f.code == "units-implausible" and "--units mm" in f.message for f in d.findings)
