# LeatherCut workbench: console and GUI start-up (FreeCAD runs this file with exec).
#
# Kept tiny: no Qt, no function definitions (exec scope), nothing slow.
# 1. When this checkout has a .venv (made by tools/setup.sh) for FreeCAD's own
#    Python version, its site-packages is APPENDED to sys.path so FreeCAD finds
#    ezdxf 1.4.5 and shapely 2.x; appended, so FreeCAD's own modules and the
#    system numpy keep precedence (the venv holds no numpy of its own).
# 2. File > Import / Open offer LeatherCut's DXF importer next to FreeCAD's.
import glob as _lc_glob
import os as _lc_os
import sys as _lc_sys

import FreeCAD
import LeatherCutWorkbench as _lc_pkg

_lc_root = _lc_os.path.dirname(_lc_os.path.dirname(_lc_os.path.abspath(_lc_pkg.__file__)))
for _lc_site in _lc_glob.glob(_lc_os.path.join(
        _lc_root, ".venv", "lib", "python%d.%d" % _lc_sys.version_info[:2], "site-packages")):
    if _lc_site not in _lc_sys.path:
        _lc_sys.path.append(_lc_site)

FreeCAD.addImportType("LeatherCut DXF drawing (*.dxf)", "LeatherCutWorkbench.document.importer")
