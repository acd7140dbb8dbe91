#!/usr/bin/env bash
# Set up everything LeatherCut needs on Debian 12, idempotently:
#   1. Debian packages (FreeCAD, Xvfb for GUI tests) -- only when missing;
#   2. a venv in .venv made from /usr/bin/python3 with --system-site-packages;
#   3. the pinned Python dependencies and the project itself (editable);
#   4. FreeCAD importable inside the venv (a .pth file);
#   5. the nesting engine's numba kernels compiled once (tools/warm_jit.py: both cache folders);
#   6. the workbench linked into FreeCAD's user Mod folder.
# Re-running only redoes a step whose inputs changed.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

sudo_cmd=""
if [ "$(id -u)" != "0" ]; then sudo_cmd="sudo"; fi

# libedit2, libtirpc3, libpython3.11: runtime of the LinuxCNC rs274 interpreter the post tests use
debs=(freecad-python3 xvfb xauth python3-venv libedit2 libtirpc3 libpython3.11)
missing=()
for p in "${debs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

venv="$here/.venv"
if [ ! -x "$venv/bin/python" ]; then
  echo "setup: creating $venv"
  /usr/bin/python3 -m venv --system-site-packages "$venv"
fi

stamp="$venv/.leathercut-stamp"
want="$(cat requirements.txt pyproject.toml | sha256sum | cut -d' ' -f1)"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  echo "setup: installing Python dependencies"
  "$venv/bin/pip" install -q --disable-pip-version-check -r requirements.txt
  "$venv/bin/pip" install -q --disable-pip-version-check --no-deps --no-build-isolation -e .
  echo "$want" > "$stamp"
fi

site="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
echo "/usr/lib/freecad-python3/lib" > "$site/leathercut-freecad.pth"

# The real LinuxCNC G-code interpreter for the post-processor tests, unpacked
# privately (LinuxCNC itself is not installed). Optional: a failure only warns.
if [ ! -x "${LEATHERCUT_RS274_DIR:-$HOME/.cache/leathercut/rs274}/root/usr/bin/rs274" ]; then
  echo "setup: fetching the LinuxCNC rs274 interpreter for the post-processor tests"
  bash "$here/tools/get_rs274.sh" || echo "setup: warning: could not fetch rs274 (tests/test_post_rs274.py needs it)" >&2
fi

# Compile the nesting engine's numba kernels now, not inside the first nest's time
# budget (~8-15 s CPU); redone only when their sources changed (numba's cache keys
# on the files' contents and times). Optional: without a writable cache folder it warns.
jit_stamp="$venv/.leathercut-jit-stamp"
jit_want="$( (cat LeatherCutWorkbench/core/nesting/*.py; stat -c '%n %Y' LeatherCutWorkbench/core/nesting/*.py) | sha256sum | cut -d' ' -f1)"
if [ ! -f "$jit_stamp" ] || [ "$(cat "$jit_stamp")" != "$jit_want" ]; then
  echo "setup: compiling the nesting kernels (numba)"
  if "$venv/bin/python" "$here/tools/warm_jit.py"; then
    echo "$jit_want" > "$jit_stamp"
  else
    echo "setup: warning: nesting kernels not compiled ahead (the first nest compiles them)" >&2
  fi
fi

# Link the workbench into FreeCAD's user Mod folder (FreeCAD computes the folder).
"$venv/bin/python" "$here/tools/install_workbench.py"
