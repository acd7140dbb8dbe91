"""LeatherCut jobs in FreeCAD documents.

``objects``   -- the FeaturePython Job group and its stage objects (pickling, out-of-date marks);
``tree``      -- finding objects in a document (roles, the job of an object, stored values);
``job_properties`` -- job properties that are not stage option fields (container, gate, ...);
``options``   -- stage options dataclasses <-> Job properties;
``pipeline``  -- run a stage on a job (prepare / compute / apply), the document's JobOptions
                 (decisions, kept layout, gate override) and headless helpers;
``shapes``    -- job model -> Part shapes for display;
``codec``     -- lossless storage of stage values in properties;
``importer``  -- File > Open / Import hook registered with ``FreeCAD.addImportType``;
``style`` / ``viewproviders`` -- colours and view providers (GUI only).

Imports FreeCAD and Part, never the GUI (except ``viewproviders``).
"""
