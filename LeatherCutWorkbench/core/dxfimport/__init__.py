"""DXF import stage: ``read_drawing(path, options, progress) -> Drawing``.

Reads ASCII and binary DXF (R12 ... R2018) with ezdxf, repairs damaged files
with ``ezdxf.recover``, converts every supported entity (blocks exploded to any
depth) to edges in mm, recognises AAMA / ASTM D6673 pattern files, and cleans
up duplicates, overlaps and T-junctions.  See docs/CLI.md (``inspect``).
"""

from typing import Any

from .options import ImportOptions

__all__ = ["read_drawing", "ImportOptions"]


def __getattr__(name: str) -> Any:
    """``read_drawing`` is imported on first use: the importer loads ezdxf
    (~0.3 s), which a CLI verb that reads no DXF (``nest --esicup``) never needs."""
    if name == "read_drawing":
        from .importer import read_drawing
        return read_drawing
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
