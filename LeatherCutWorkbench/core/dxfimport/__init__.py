"""DXF import stage: ``read_drawing(path, options, progress) -> Drawing``.

Reads ASCII and binary DXF (R12 ... R2018) with ezdxf, repairs damaged files
with ``ezdxf.recover``, converts every supported entity (blocks exploded to any
depth) to edges in mm, recognises AAMA / ASTM D6673 pattern files, and cleans
up duplicates, overlaps and T-junctions.  See docs/CLI.md (``inspect``).
"""

from .importer import read_drawing
from .options import ImportOptions

__all__ = ["read_drawing", "ImportOptions"]
