"""Link this checkout into FreeCAD's user Mod folder as ``LeatherCut``.

The folder comes from ``FreeCAD.getUserAppDataDir()`` so versioned layouts
(FreeCAD 1.1: ``.../v1-1/Mod``) are honoured.  Idempotent: an existing correct
link is kept, a stale link is replaced, a real folder is never touched.
"""

import os
import sys

import FreeCAD  # noqa: F401  (made importable by tools/setup.sh)


def main() -> int:
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    mod_dir = os.path.join(FreeCAD.getUserAppDataDir(), "Mod")
    os.makedirs(mod_dir, exist_ok=True)
    link = os.path.join(mod_dir, "LeatherCut")
    if os.path.islink(link):
        if os.path.realpath(link) == repo:
            return 0
        os.unlink(link)
    elif os.path.exists(link):
        print(f"setup: {link} exists and is not a link; leaving it alone", file=sys.stderr)
        return 0
    os.symlink(repo, link)
    print(f"setup: workbench linked at {link}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
