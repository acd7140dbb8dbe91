"""Issue #16 item 8: hostile DXF input ends in one clear line naming the file and
the entity, exit 2, no traceback, bounded time and memory.  Each test is a case
that crashed, hung, ran out of memory or silently changed data before."""

import math
import os
import stat

import ezdxf
import pytest

from LeatherCutWorkbench.cli import main
from LeatherCutWorkbench.core.dxfimport import read_drawing
from LeatherCutWorkbench.core.dxfimport import limits
from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.geometry import LineSeg
from LeatherCutWorkbench.core.pathplan.candidates import entry_positions

LINE = "0\nLINE\n5\n{h}\n8\n0\n10\n{x1}\n20\n{y1}\n11\n{x2}\n21\n{y2}\n"


def _r12(entities, header=""):
    head = f"0\nSECTION\n2\nHEADER\n{header}0\nENDSEC\n" if header else ""
    return f"{head}0\nSECTION\n2\nENTITIES\n{entities}0\nENDSEC\n0\nEOF\n"


def _square(x0=10.0, size=100.0, h0=0x40):
    pts = [(x0, x0), (x0 + size, x0), (x0 + size, x0 + size), (x0, x0 + size), (x0, x0)]
    return "".join(LINE.format(h=f"{h0 + k:X}", x1=a[0], y1=a[1], x2=b[0], y2=b[1])
                   for k, (a, b) in enumerate(zip(pts, pts[1:])))


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


def _cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _refused(capsys, *argv):
    code, _, err = _cli(capsys, *argv)
    assert code == 2, err
    assert err.count("\n") == 1 and "Traceback" not in err and "internal error" not in err
    return err


# --------------------------------------------------------------------- numbers
@pytest.mark.parametrize("value", ["nan", "NaN", "inf", "-inf", "-Infinity", "1e999"])
def test_nonfinite_coordinate_is_refused_with_line_and_entity(tmp_path, capsys, value):
    path = _write(tmp_path, "nan.dxf", _r12(_square() + LINE.format(h="2F", x1=0, y1=0,
                                                                   x2=value, y2=5)))
    err = _refused(capsys, "inspect", path)
    assert "LINE #2F" in err and "group code 11" in err and path in err


def test_names_and_handles_that_look_like_numbers_are_not_refused(tmp_path):
    text = _r12(_square().replace("5\n40\n8\n0\n", "5\n1E309\n8\nNaN\n", 1))
    d = read_drawing(_write(tmp_path, "names.dxf", text))
    assert "NaN" in {e.src.layer for e in d.edges}


def test_nonfinite_header_variable_is_named(tmp_path, capsys):
    path = _write(tmp_path, "h.dxf", _r12(_square(), header="9\n$DIMSCALE\n40\nnan\n"))
    assert "header variable $DIMSCALE" in _refused(capsys, "inspect", path)


def test_nonfinite_in_binary_dxf_is_refused_naming_the_entity(tmp_path, capsys):
    doc = ezdxf.new("R2000")
    doc.modelspace().add_line((0, 0), (100, 0))
    bad = doc.modelspace().add_line((math.nan, 0), (1, 1))
    path = str(tmp_path / "nan_bin.dxf")
    doc.saveas(path, fmt="bin")
    err = _refused(capsys, "recognise", path)
    assert f"LINE #{bad.dxf.handle}" in err and "not a finite number" in err


def test_far_coordinate_is_refused_quickly(tmp_path, capsys):
    """One LINE to x = 1e300 beside a 100 mm square grew to 5.8 GB in the
    segment index before; now the import refuses it at once."""
    path = _write(tmp_path, "far.dxf", _r12(_square() + LINE.format(h="2F", x1=0, y1=0,
                                                                   x2="1e300", y2=0)))
    err = _refused(capsys, "recognise", path)
    assert "LINE #2F" in err and "limit" in err


def test_coordinates_of_1e17_are_refused(tmp_path, capsys):
    path = _write(tmp_path, "e17.dxf", _r12(_square(x0=1e17)))
    err = _refused(capsys, "run", path, "-o", str(tmp_path / "out"), "--plan-method", "nn")
    assert "beyond the limit" in err and not (tmp_path / "out" / "job.nc").exists()


def test_drawing_wider_than_the_limit_names_the_farthest_entity(tmp_path):
    far = limits.MAX_DRAWING_SIZE_MM * 2
    path = _write(tmp_path, "wide.dxf", _r12(_square() + LINE.format(
        h="77", x1=far / 2, y1=0, x2=far / 2 + 10, y2=0) + LINE.format(
        h="78", x1=-far / 2, y1=0, x2=-far / 2 - 10, y2=0)))
    with pytest.raises(InputError) as err:
        read_drawing(path)
    assert "km limit" in err.value.message and "LINE #7" in err.value.message


def test_mixed_separators_are_refused(tmp_path, capsys):
    path = _write(tmp_path, "mixed.dxf", _r12(_square().replace("110.0\n", "1.234,5\n", 1)))
    err = _refused(capsys, "inspect", path)
    assert "'1.234,5'" in err


def test_missing_y_is_an_error_not_zero(tmp_path, capsys):
    broken = "0\nLINE\n8\n0\n10\n5\n11\n100\n21\n7\n"
    path = _write(tmp_path, "noy.dxf", _r12(broken + _square()))
    err = _refused(capsys, "inspect", path)
    assert "y coordinate" in err and "refused rather than read as 0" in err


@pytest.mark.parametrize("code", [99, -5])
def test_unknown_insunits_code_is_named(tmp_path, code):
    path = _write(tmp_path, "u.dxf", _r12(_square(), header=f"9\n$INSUNITS\n70\n{code}\n"))
    d = read_drawing(path)
    assert any(f"unknown units code {code}" in f.message for f in d.findings)
    assert d.units == "mm"


def test_file_without_header_is_not_read_as_metres(tmp_path):
    """ezdxf fills a default header ($INSUNITS 6 = metres) for files without
    one: a headerless R12 drawing was read 1000 times too large."""
    d = read_drawing(_write(tmp_path, "nohead.dxf", _r12(_square())))
    assert d.units == "mm" and d.units_source == "assumed"
    assert d.stats["size_mm"] == [100.0, 100.0]


# --------------------------------------------------------------------- curves
@pytest.mark.parametrize("knots,weights", [
    ([0, 0, 0, 0, 2, 1, 1, 1, 1], None),          # decreasing
    ([0, 0, 0, 0, 0.5, 1, 1, 1, 1], [1, -2, 1, 1, 1]),
    ([0, 0, 0, 0, 0.5, 1, 1, 1, 1], [0, 0, 0, 0, 0]),
    ([0, 0, 0, 0, 1e300, 1e300, 1e300, 1e300, 1e300], None),
])
def test_bad_spline_knots_or_weights_become_a_bad_edge_finding(tmp_path, capsys, knots, weights):
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    msp.add_lwpolyline([(200, 0), (300, 0), (300, 100), (200, 100)], close=True)
    sp = msp.add_open_spline([(0, 0), (10, 20), (30, -5), (50, 15), (70, 0)], degree=3)
    sp.knots = knots
    if weights:
        sp.dxf.flags = sp.dxf.flags | 4
        sp.weights = weights
    path = str(tmp_path / "spline.dxf")
    doc.saveas(path)
    code, out, err = _cli(capsys, "recognise", path, "--json")
    assert code == 0, err
    import json
    rep = json.loads(out)
    assert rep["counts"]["parts"] == 1
    assert any(f["code"] == "bad-edge" for f in rep["findings"])


def test_zero_major_axis_ellipse_is_skipped_with_a_warning(tmp_path):
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    msp.add_lwpolyline([(200, 0), (300, 0), (300, 100), (200, 100)], close=True)
    e = msp.add_ellipse((50, 50), major_axis=(30.125, 0.0625, 0), ratio=0.4375)
    path = str(tmp_path / "ell.dxf")
    doc.saveas(path)
    text = open(path).read().replace("\n30.125\n", "\n0\n").replace("\n0.0625\n", "\n0\n")
    open(path, "w").write(text)
    d = read_drawing(path)
    assert any(f.code == "skipped-entity" and f"#{e.dxf.handle}" in f.message
               and "degenerate" in f.message for f in d.findings)


# --------------------------------------------------------------------- expansion
def _saved_refusal(capsys, tmp_path, doc):
    path = str(tmp_path / "blocks.dxf")
    doc.saveas(path)
    return _refused(capsys, "inspect", path)


def test_huge_minsert_is_refused_before_expansion(tmp_path, capsys):
    """10000 x 10000 cells took > 120 s and 4.3 GB before."""
    doc = ezdxf.new("R2000")
    doc.blocks.new("C").add_circle((0, 0), 1)
    ref = doc.modelspace().add_blockref("C", (0, 0))
    ref.dxf.row_count, ref.dxf.column_count = 10000, 10000
    ref.dxf.row_spacing = ref.dxf.column_spacing = 3.0
    err = _saved_refusal(capsys, tmp_path, doc)
    assert f"MINSERT #{ref.dxf.handle}" in err and "100000000 cells" in err


def test_nested_fan_out_is_refused_before_expansion(tmp_path, capsys):
    """10 levels x fan-out 10 never ended before."""
    doc = ezdxf.new("R2000")
    doc.blocks.new("L0").add_circle((0, 0), 1)
    for lvl in range(1, 11):
        blk = doc.blocks.new(f"L{lvl}")
        for k in range(10):
            blk.add_blockref(f"L{lvl - 1}", (3.0 * k, 0.0))
    top = doc.modelspace().add_blockref("L10", (0, 0))
    err = _saved_refusal(capsys, tmp_path, doc)
    assert f"INSERT #{top.dxf.handle}" in err and "1e+10 entities" in err


# --------------------------------------------------------------------- file nodes
def test_fifo_is_refused_without_blocking(tmp_path, capsys):
    fifo = str(tmp_path / "pipe.dxf")
    os.mkfifo(fifo)
    err = _refused(capsys, "inspect", fifo)
    assert "FIFO" in err and "only regular files" in err


@pytest.mark.parametrize("node,what", [("/dev/zero", "character device"),
                                       ("/dev/null", "character device")])
def test_devices_are_refused(capsys, node, what):
    err = _refused(capsys, "inspect", node)
    assert what in err


def test_directory_is_refused(tmp_path, capsys):
    err = _refused(capsys, "recognise", str(tmp_path))
    assert "directory" in err


# --------------------------------------------------------------------- outputs
def test_nothing_cuttable_exits_2_and_writes_no_job(tmp_path, capsys):
    path = _write(tmp_path, "pt.dxf", _r12("0\nPOINT\n8\n0\n10\n5\n20\n5\n"))
    out = tmp_path / "out"
    err = _refused(capsys, "run", path, "-o", str(out), "--plan-method", "nn")
    assert "nothing to cut" in err and not (out / "job.nc").exists()
    err = _refused(capsys, "post", path, "-o", str(tmp_path / "job.nc"))
    assert not (tmp_path / "job.nc").exists()


def test_post_onto_a_fifo_or_device_keeps_the_node(tmp_path, capsys):
    path = _write(tmp_path, "sq.dxf", _r12(_square()))
    fifo = str(tmp_path / "out.nc")
    os.mkfifo(fifo)
    err = _refused(capsys, "post", path, "-o", fifo, "--plan-method", "nn")
    assert "FIFO" in err and stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert not os.path.exists(fifo + ".part")
    err = _refused(capsys, "post", path, "-o", "/dev/null", "--plan-method", "nn")
    assert "character device" in err and stat.S_ISCHR(os.stat("/dev/null").st_mode)


@pytest.mark.parametrize("name", ["job.nc", "preview.svg"])
def test_run_exits_2_when_an_output_is_a_directory(tmp_path, capsys, name):
    path = _write(tmp_path, "sq.dxf", _r12(_square()))
    out = tmp_path / "out"
    (out / name).mkdir(parents=True)
    err = _refused(capsys, "run", path, "-o", str(out), "--plan-method", "nn")
    assert "directory" in err and name in err


# --------------------------------------------------------------------- guards
def test_segment_index_keeps_huge_segments_out_of_the_grid():
    from LeatherCutWorkbench.core.recognition.segments import MAX_CELLS_PER_SEGMENT, SegmentIndex

    class P:
        def __init__(self, seg):
            self.seg = seg
    pieces = [P(LineSeg((i, 0.0), (i + 1.0, 0.0))) for i in range(100)]
    pieces.append(P(LineSeg((0.0, 0.0), (1e8, 1e8))))
    idx = SegmentIndex(pieces, 0.01)
    assert idx.big == [100]
    assert sum(len(v) for v in idx.cells.values()) < 100 * 4 + MAX_CELLS_PER_SEGMENT
    assert 100 in idx.near((5e7, 5e7)) and 3 in idx.near((3.5, 0.0))


def test_entry_candidates_stay_bounded_on_a_huge_contour():
    segs = [LineSeg((0.0, 0.0), (1e17, 0.0)), LineSeg((1e17, 0.0), (0.0, 0.0))]
    pos = entry_positions(segs, 20.0)     # asked numpy for 284 PiB before
    assert 2 <= len(pos) <= 64


@pytest.mark.parametrize("option,value", [("--chord-tol", "1e-12"), ("--gap-tol", "nan"),
                                          ("--join-tol", "inf")])
def test_recognition_tolerances_are_bounded(tmp_path, capsys, option, value):
    path = _write(tmp_path, "sq.dxf", _r12(_square()))
    try:                        # refused by the option's type (argparse) or by validate()
        code = main(["recognise", path, option, value])
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2 and option in err and "Traceback" not in err
