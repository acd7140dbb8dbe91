"""Shared pytest set-up: make FreeCAD importable and name the test data folders.

The venv made by tools/setup.sh already has FreeCAD on its path (a .pth file);
this keeps plain ``/usr/bin/python3 -m pytest`` working too.
"""

import os
import sys

import pytest

TESTS_DIR = os.path.dirname(os.path.abspath(__file__))
REPO_DIR = os.path.dirname(TESTS_DIR)

# Import the package from this checkout before FreeCAD is imported: FreeCAD puts
# its user Mod folders (where set-up links *a* LeatherCut checkout) on sys.path,
# and tests must exercise the code they sit beside, not whatever that link names.
sys.path.insert(0, REPO_DIR)
import LeatherCutWorkbench  # noqa: E402

assert os.path.dirname(os.path.dirname(os.path.abspath(LeatherCutWorkbench.__file__))) == REPO_DIR

FREECAD_LIB = "/usr/lib/freecad-python3/lib"
if os.path.isdir(FREECAD_LIB) and FREECAD_LIB not in sys.path:
    sys.path.append(FREECAD_LIB)
DATA_DIR = os.path.join(TESTS_DIR, "data")
SAMPLES_DIR = os.path.join(DATA_DIR, "samples")


@pytest.fixture
def data_dir() -> str:
    """tests/data: small real and generated fixtures (see its README for licences)."""
    return DATA_DIR


@pytest.fixture
def samples_dir() -> str:
    """tests/data/samples: real DXF files from public projects (licences in README.md)."""
    return SAMPLES_DIR


@pytest.fixture
def doc():
    """A fresh FreeCAD document, closed after the test (if the test left it open)."""
    import FreeCAD
    d = FreeCAD.newDocument("LCTest")
    name = d.Name
    yield d
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)
