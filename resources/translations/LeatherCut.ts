<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1">
<context>
    <name>AutoNest</name>
    <message>
        <source> mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source> s</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source> °</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Allowed angles for all parts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Auto-nest</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Checker tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Chord tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Engine</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Hide DXF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>JSON list, e.g. [0, 180]; empty = per part</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Margin to edges / defects</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Material</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Max evaluations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Mirroring for all parts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Nest now (preview)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Nest on</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Parts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Processes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Rotation step (free parts)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Search</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Search time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Sheet height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Sheet width</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Sheets at most (0 = as needed)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Spacing between parts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Strip width</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>empty = all cores</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>empty = time budget only</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>false</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>hide</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>none</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>own</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>sheet</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>sparrow</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>strip</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>true</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>…</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Flags</name>
    <message>
        <source> mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Accept all fixes up to</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>All at once (one undo step)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Each decision is one undo step and is saved with the document.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Exclude</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Fit the 3D view to the gap (under-recognised) or the region (over-recognised)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Flags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Include</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Next ▶</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Undecided (stage default)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Zoom to it</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>◀ Previous</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportDXF</name>
    <message>
        <source> mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Clean up (zero-length, duplicate, overlapping edges, T-junctions)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Clean-up tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>DXF file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Huge coordinate above</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Import DXF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Import now (preview)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Leave Units empty to use the units the file states ($INSUNITS or an AAMA 'Units:' text).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Move huge coordinates to a local origin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Pattern files</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Units</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>What the import found</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>aama</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>auto</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>cm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>foot</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>inch</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>off</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>…</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="227"/>
        <source>(post-process the job first)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="169"/>
        <source>1 segment: exact resume, stops at segment ends</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="168"/>
        <source>2 segments</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="99"/>
        <source>Accept all fixes up to</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="27"/>
        <source>Accept fix (close the gap)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="24"/>
        <source>Auto-nest</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/panel.py" line="244"/>
        <source>Cancelled.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/panel.py" line="182"/>
        <source>Cancelled. Change the options and press OK, or Cancel.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/panel.py" line="117"/>
        <source>Cannot set {0}: {1}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="201"/>
        <source>Choose a port…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="333"/>
        <source>Container</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="82"/>
        <source>Contours cut</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="116"/>
        <source>Copied to {0}; edit it here (Save edits) or with any text editor.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="107"/>
        <source>Copy profile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="18"/>
        <source>Cut length</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/objects.py" line="459"/>
        <source>Cut path</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/panel.py" line="108"/>
        <source>DXF drawings (*.dxf *.DXF)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="133"/>
        <source>DXF drawings (*.dxf *.DXF);;All files (*)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="339"/>
        <source>Defects</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="139"/>
        <source>Drawing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="70"/>
        <source>Drawing size {0} × {1} mm, units {2} ({3})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="273"/>
        <source>Enter the port (e.g. /dev/ttyUSB0 or socket://host:23), or choose emulator:grblhal for a dry run.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="20"/>
        <source>Estimated time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="26"/>
        <source>Exclude (not a part)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="96"/>
        <source>Exclude all over-recognised regions</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="242"/>
        <source>Excluded</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="184"/>
        <source>Flags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="157"/>
        <source>Gap: {0} mm. {1}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="239"/>
        <source>Holes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="17"/>
        <source>Idle travel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="23"/>
        <source>Idle travel lower bound</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="21"/>
        <source>Idle travel, drawing order</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="22"/>
        <source>Idle travel, nearest neighbour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="23"/>
        <source>Import DXF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="25"/>
        <source>Include (it is a part)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="19"/>
        <source>Knife lifts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="147"/>
        <source>Layer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="329"/>
        <source>Layout</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="240"/>
        <source>Lead-ins</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/base.py" line="53"/>
        <source>LeatherCut: cancelled</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/post_process.py" line="104"/>
        <source>LeatherCut: the cut path is out of date; plan the path again first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/run_job.py" line="63"/>
        <source>Machine file written: {0}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/manual_nest.py" line="27"/>
        <source>Manual nest</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="150"/>
        <source>Marks</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="83"/>
        <source>Method</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/manual_nest.py" line="80"/>
        <source>Moving: {0}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="108"/>
        <source>Name of the copy:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/manual_nest.py" line="91"/>
        <source>No collisions.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="84"/>
        <source>Not valid JSON: {0} at line {1}; not saved.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="241"/>
        <source>Open chains</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="238"/>
        <source>Outer contours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="33"/>
        <source>Part</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/part_objects.py" line="57"/>
        <source>Parts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="59"/>
        <source>Plan path</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="90"/>
        <source>Planned {0} contours.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="25"/>
        <source>Planning time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/post_process.py" line="25"/>
        <source>Post-process</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="269"/>
        <source>Post-process the job as G-code first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="34"/>
        <source>Qty</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="111"/>
        <source>Quantity must be a whole number.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="24"/>
        <source>Recognise</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="178"/>
        <source>Recognition</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="28"/>
        <source>Reject fix (leave open)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/run_job.py" line="55"/>
        <source>Run job</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="91"/>
        <source>Saved {0}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="24"/>
        <source>Saving vs drawing order</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="49"/>
        <source>Search ended</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="365"/>
        <source>Send to cutter streams G-code: post-process as gcode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="74"/>
        <source>Shipped profiles are read-only: copy this one to the user folder to edit it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="33"/>
        <source>Size</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="55"/>
        <source>Stop (keep the best layout)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="339"/>
        <source>Stop the job before closing.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="326"/>
        <source>Stopped ({0}) at line {1}: {2}. Choose where to resume.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="584"/>
        <source>Tool paths</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/pipeline.py" line="588"/>
        <source>Tool {0}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/post_process.py" line="58"/>
        <source>Tools: {0}. Roles: {1}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/post_process.py" line="86"/>
        <source>Wrote {0} ({1} lines).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="83"/>
        <source>chosen in this panel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="31"/>
        <source>converged</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/simulate.py" line="69"/>
        <source>cutting {0} of {1}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="117"/>
        <source>density {0:.1f} %</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="36"/>
        <source>excluded (not a part)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/panel.py" line="329"/>
        <source>finish or cancel the open task panel first</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="37"/>
        <source>fix accepted</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="38"/>
        <source>fix rejected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="82"/>
        <source>from the AAMA 'Units:' text</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="167"/>
        <source>full look-ahead (fastest)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/simulate.py" line="71"/>
        <source>idle move (knife up)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="35"/>
        <source>included (a part)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="32"/>
        <source>iteration budget reached</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="84"/>
        <source>not stated: assumed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/objects.py" line="424"/>
        <source>over-recognised</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="45"/>
        <source>shipped</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="60"/>
        <source>size {0}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="247"/>
        <source>start of the job</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="81"/>
        <source>stated in the file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="119"/>
        <source>strip length {0:.1f} mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/simulate.py" line="72"/>
        <source>t = {0:.1f} s of {1:.1f} s – {2}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="33"/>
        <source>time budget reached (not converged)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="34"/>
        <source>undecided</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/document/objects.py" line="425"/>
        <source>under-recognised</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="45"/>
        <source>user</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="114"/>
        <source>utilisation {0:.1f} %</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="120"/>
        <source>{0} containers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="49"/>
        <source>{0} edges on {1} layers, {2} marks, units {3} ({4})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="92"/>
        <source>{0} of {1} parts to cut, {2} copies in all.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="153"/>
        <source>{0} parts ({1} excluded), {2} holes, {3} lead-ins, {4} open chains; flags: {5} over-recognised, {6} under-recognised</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="74"/>
        <source>{0} pattern pieces</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="111"/>
        <source>{0} placed, {1} unplaced</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/manual_nest.py" line="92"/>
        <source>{0} problems: colliding parts are red.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="100"/>
        <source>{0} uses {1}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="205"/>
        <source>{0} – dry run, no machine</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="75"/>
        <source>{0}, net area {1}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="51"/>
        <source>{0}: gap {1} mm at {2} – {3}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flags.py" line="53"/>
        <source>{0}: region {1} – {2}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/simulate.py" line="67"/>
        <source>{0}: {1} of {2}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="319"/>
        <source>{0}: {1}/{2} lines, segment {3}, controller {4}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="88"/>
        <source>{0}; not saved.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCutPreferences</name>
    <message>
        <source>Defaults for new jobs. A job keeps its own values in its properties (Job &gt; Property view).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Folder for machine files when a job names none (empty: beside the saved .FCStd document, or your home folder before it is saved; never next to the DXF)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Gap tolerance for under-recognition flags (mm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Import clean-up tolerance (mm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Join tolerance (mm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>LeatherCut</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Machine profile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Margin to material edges and defects (mm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Nesting search time (s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Path planning method (ga, aco or nn)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Path planning time budget (s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Spacing between parts (mm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>beside the saved document</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>ga</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>grblhal_tangential</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_AutoNest</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="161"/>
        <source>Auto-nest</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/auto_nest.py" line="162"/>
        <source>Nest the recognised parts on sheets, a strip or a leather hide with defects</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_FlagOver</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flag_over.py" line="14"/>
        <source>Flag over-recognised</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flag_over.py" line="15"/>
        <source>Step through closed regions that are probably not parts (scrap between common-edge parts, group outlines) and include or exclude each</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_FlagUnder</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flag_under.py" line="14"/>
        <source>Flag under-recognised</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/flag_under.py" line="15"/>
        <source>Step through outlines left open by a small gap and accept or reject the proposed bridging segment for each</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_ImportDXF</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="120"/>
        <source>Import DXF…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/import_dxf.py" line="121"/>
        <source>Import a DXF drawing into a new LeatherCut job (edges grouped by layer)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_MachineProfiles</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="129"/>
        <source>Browse machine profiles (table, speeds, knife, I/O), choose the job's machine or copy a profile to edit it</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/machine_profiles.py" line="128"/>
        <source>Machine profiles…</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_ManualNest</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/manual_nest.py" line="113"/>
        <source>Manual nest</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/manual_nest.py" line="114"/>
        <source>Move and rotate placed parts by hand; colliding parts turn red</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_PlanPath</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="97"/>
        <source>Order the cuts and choose entry points (holes first, lead-ins respected); shows cutting moves, idle moves dashed, order numbers and entry points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/plan_path.py" line="96"/>
        <source>Plan path</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_PostProcess</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/post_process.py" line="92"/>
        <source>Post-process…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/post_process.py" line="93"/>
        <source>Write the planned job as a machine file (G-code, HPGL or DXF) for a machine profile; moves outside the table or unsafe feeds are refused</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_Recognise</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="163"/>
        <source>Recognise</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/recognise.py" line="164"/>
        <source>Recognise closed part contours, holes, lead-ins and open chains and flag doubtful contours</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_RunJob</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/run_job.py" line="42"/>
        <source>Run job</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/run_job.py" line="43"/>
        <source>Run the whole job from the DXF to the machine file with the job's options (asks for a DXF when there is no job)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_SendToCutter</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="352"/>
        <source>Send to cutter…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/send_to_cutter.py" line="353"/>
        <source>Stream the posted G-code to a GRBL / grblHAL controller over a serial port, with check mode, pause, stop and resume from the journal</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>LeatherCut_Simulate</name>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/simulate.py" line="115"/>
        <source>Animate the knife along the planned cut path at the machine's speeds</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../LeatherCutWorkbench/commands/simulate.py" line="114"/>
        <source>Simulate</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>MachineProfiles</name>
    <message>
        <source>Check the edited profile (every field, e.g. blade_offset, tools, tool_map) and save it; user profiles only</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Copy to user folder…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Machine profiles</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Open user folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Save edits</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Use for this job</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ManualNest</name>
    <message>
        <source> mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source> °</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Angle step</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Manual nest</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Moving: –</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Select parts in the 3D view or tree. Move them here, edit their Placement, or use Transform. Colliding parts turn red.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Step</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>←</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>↑</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>→</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>↓</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>⟲ CCW</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>⟳ CW</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>PlanPath</name>
    <message>
        <source> mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source> mm/min</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source> mm/s²</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source> s</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Acceleration</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Cut open chains too</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Cut speed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Entry candidate spacing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Knife lift angle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Machine</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Machine zero [x, y]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Max candidates per contour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Method</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Move the drawing to the machine origin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Plan now (preview, shows metrics)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Plan path</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Rapid speed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Take speeds and lift angle from the machine profile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Time budget</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Time per lift</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>[0, 0]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>aco</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>degrees; empty = no tangential knife</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>ga</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>nn</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>PostProcess</name>
    <message>
        <source>Format</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Machine profile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Moves outside the table, feeds outside the profile or words unknown to the dialect are refused; nothing is written then.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Output file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Post-process</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Tool map</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Write now</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>dxf</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>gcode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>hpgl</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>role=tool, e.g. stitch=pen,drill=punch4 (on top of the profile)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>…</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Recognise</name>
    <message>
        <source> mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Chord tolerance (curves)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Close gaps within the gap tolerance automatically</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Fuzzy value (common edges)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Gap tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Join tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Parts are blue, holes red, lead-ins orange, open chains grey, flagged contours magenta. Review flags with Flag over-/under-recognised.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Parts to cut</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Recognise</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Recognise now (preview)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Sizes (tick the sizes to cut):</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Tick a part to cut it; Qty is the number of copies nesting places</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SendToCutter</name>
    <message>
        <source>/dev/ttyUSB0, socket://host:23, emulator:grblhal</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Cut window</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Cycle start</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Every acknowledged line is journalled next to the G-code file. After a fault choose the segment to resume from; nothing is resent automatically.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>How much cutting may run ahead of the controller's status reports. After a power loss the job resumes at the first segment no report proved cut: full look-ahead re-cuts the interrupted segment plus at most what ran since the last report; 1 segment re-cuts only the interrupted segment, but the head stops at every segment end</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Port</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Run the whole job in check mode ($C) first</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Send to cutter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Serial ports found on this computer, and the built-in controller emulator for a dry run without hardware</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Start at</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Streaming</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>The work zero was set again at the machine (needed to resume after a lost position on a machine that does not home)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>char-count</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>send-response</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>■ Stop safely</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>▶ Start</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>❚❚ Feed hold</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Simulate</name>
    <message>
        <source> ×</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Simulate</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>Speed-up</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>■ Stop</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>▶ Play</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <source>❚❚ Pause</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
