"""LeatherCut jobs in FreeCAD documents.

``objects``   -- the FeaturePython Job group and its stage objects (pickling, out-of-date marks);
``options``   -- stage options dataclasses <-> Job properties;
``pipeline``  -- run a stage on a job (prepare / compute / apply) and headless helpers;
``shapes``    -- job model -> Part shapes for display;
``codec``     -- lossless storage of stage values in properties;
``importer``  -- File > Open / Import hook registered with ``FreeCAD.addImportType``;
``style`` / ``viewproviders`` -- colours and view providers (GUI only).

Imports FreeCAD and Part, never the GUI (except ``viewproviders``).
"""
