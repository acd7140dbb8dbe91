#!/usr/bin/env python3
"""Write resources/translations/LeatherCut.ts: every user-visible string of the
workbench, for Qt Linguist.

Collects ``translate("Context", "text")``, ``QT_TRANSLATE_NOOP("Context", "text")``
and ``FreeCAD.Qt.*`` variants from LeatherCutWorkbench/commands and
LeatherCutWorkbench/document (with the context each call names), plus the
texts of the task panels in resources/ui (context = the form's class).
Translators copy LeatherCut.ts to LeatherCut_<lang>.ts, translate it in Qt
Linguist and compile it with ``lrelease`` into LeatherCut_<lang>.qm next to
it; InitGui.py registers this folder with ``Gui.addLanguagePath``.
(Used instead of lupdate, which cannot see through ``FreeCAD.Qt.translate``.)
"""

import ast
import glob
import os
import xml.etree.ElementTree as ET
from collections import defaultdict
from xml.sax.saxutils import escape

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
NAMES = {"translate", "QT_TRANSLATE_NOOP"}


def python_strings(messages):
    for folder in ("commands", "document"):
        for path in sorted(glob.glob(os.path.join(REPO, "LeatherCutWorkbench", folder, "*.py"))):
            tree = ast.parse(open(path, encoding="utf-8").read())
            for node in ast.walk(tree):
                if not isinstance(node, ast.Call) or len(node.args) < 2:
                    continue
                fn = node.func
                name = fn.attr if isinstance(fn, ast.Attribute) else getattr(fn, "id", "")
                ctx, text = node.args[:2]
                if name in NAMES and isinstance(ctx, ast.Constant) and isinstance(text, ast.Constant) \
                        and isinstance(text.value, str):
                    messages[ctx.value].add((text.value, os.path.relpath(path, HERE), node.lineno))


def ui_strings(messages):
    for path in sorted(glob.glob(os.path.join(REPO, "resources", "ui", "*.ui"))):
        root = ET.parse(path).getroot()
        ctx = root.findtext("class")
        for s in root.iter("string"):
            if s.text and s.text.strip():
                messages[ctx].add((s.text, os.path.relpath(path, HERE), 0))


def main():
    messages = defaultdict(set)
    python_strings(messages)
    ui_strings(messages)
    out = ['<?xml version="1.0" encoding="utf-8"?>', "<!DOCTYPE TS>", '<TS version="2.1">']
    for ctx in sorted(messages):
        out.append(f"<context>\n    <name>{escape(ctx)}</name>")
        seen = set()
        for text, where, line in sorted(messages[ctx]):
            if text in seen:
                continue
            seen.add(text)
            loc = f'        <location filename="{escape(where)}" line="{line}"/>\n' if line else ""
            out.append(f"    <message>\n{loc}        <source>{escape(text)}</source>\n"
                       f'        <translation type="unfinished"></translation>\n    </message>')
        out.append("</context>")
    out.append("</TS>")
    path = os.path.join(HERE, "LeatherCut.ts")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(out) + "\n")
    print(f"wrote {path}: {sum(len(v) for v in messages.values())} strings in {len(messages)} contexts")


if __name__ == "__main__":
    main()
