#!/usr/bin/env bash
# Set everything up (tools/setup.sh: Debian packages, venv, pinned Python packages,
# workbench link) and then run one action:
#   bash bootstrap.sh demo    the main job on the bundled example (outputs in out/demo/)
#   bash bootstrap.sh test    the whole test suite (unit, freecadcmd, GUI under Xvfb)
#   bash bootstrap.sh bench   the benchmarks in bench/ (results: docs/BENCHMARKS.md)
# Works on a fresh Debian 12 machine as root or with sudo; re-running is fast.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"
action="${1:-demo}"
bash tools/setup.sh
case "$action" in
  demo)
    out="${LEATHERCUT_DEMO_OUT:-out/demo}"
    .venv/bin/leathercut run examples/bag.dxf -o "$out"
    echo "demo: outputs in $out/ -- job.nc (G-code), preview.svg (picture), report.json (figures)"
    ;;
  test)
    exec .venv/bin/python -m pytest -ra -q tests
    ;;
  bench)
    for b in bench/bench_*.py; do echo "== $b"; .venv/bin/python "$b"; done
    ;;
  *)
    echo "usage: bash bootstrap.sh [demo|test|bench]" >&2; exit 2
    ;;
esac
