"""The ``leathercut`` console command: help, bad input, docs in step with --help.

Runs the installed console script as a user would (a subprocess), so the
entry point, argument parsing and error handling are all exercised.
"""

import os
import re
import subprocess
import sys

import pytest

from conftest import REPO_DIR

VERBS = ["inspect", "recognise", "nest", "plan", "post", "send", "run"]
LEATHERCUT = os.path.join(os.path.dirname(sys.executable), "leathercut")


def leathercut(*args, cwd=None):
    return subprocess.run([LEATHERCUT, *args], capture_output=True, text=True,
                          cwd=cwd or REPO_DIR, timeout=300)


def test_console_script_installed():
    assert os.path.exists(LEATHERCUT), "tools/setup.sh installs the project into the venv"


@pytest.mark.parametrize("verb", VERBS)
def test_every_verb_has_help(verb):
    proc = leathercut(verb, "--help")
    assert proc.returncode == 0
    assert "--json" in proc.stdout or verb == "send"


def _help_options(verb):
    out = leathercut(verb, "--help").stdout
    return sorted(set(re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", out)) - {"--help"})


@pytest.mark.parametrize("verb", VERBS)
def test_docs_cli_lists_every_option_of_help(verb):
    """docs/CLI.md documents every option --help shows, in the verb's section or
    the common/stage sections it refers to."""
    doc = open(os.path.join(REPO_DIR, "docs", "CLI.md"), encoding="utf-8").read()
    missing = [o for o in _help_options(verb) if o not in doc]
    assert not missing, f"docs/CLI.md does not document {verb} options {missing}"


def _assert_one_line_error(proc, *needles):
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    err = proc.stderr.strip().splitlines()
    assert len(err) == 1, proc.stderr
    assert "Traceback" not in proc.stderr
    for n in needles:
        assert n in err[0], err[0]


@pytest.mark.parametrize("verb", ["inspect", "recognise", "plan", "run"])
def test_missing_file_is_one_clear_line(verb, tmp_path):
    missing = str(tmp_path / "nope.dxf")
    extra = ["-o", str(tmp_path / "out")] if verb == "run" else []
    _assert_one_line_error(leathercut(verb, missing, *extra), "nope.dxf")


@pytest.mark.parametrize("verb", ["inspect", "recognise", "run"])
def test_not_a_dxf_is_one_clear_line(verb, tmp_path):
    bad = tmp_path / "letter.dxf"
    bad.write_text("Dear cutting room,\nplease find the pattern attached.\n")
    extra = ["-o", str(tmp_path / "out")] if verb == "run" else []
    _assert_one_line_error(leathercut(verb, str(bad), *extra), "letter.dxf")
