#!/usr/bin/env bash
# Fetch the real LinuxCNC 2.9 G-code interpreter (the standalone `rs274` of the
# Debian 12 package linuxcnc-uspace) WITHOUT installing LinuxCNC: the .deb
# files are downloaded with apt-get and unpacked into a private folder, so the
# system (systemd, udev, ...) is untouched.  tests/test_post_rs274.py uses it
# to check that the LinuxCNC output is accepted and traced like our reader
# traces it; the test is skipped when the folder is missing.
#
#   bash tools/get_rs274.sh            # -> ~/.cache/leathercut/rs274
set -euo pipefail
dest="${LEATHERCUT_RS274_DIR:-$HOME/.cache/leathercut/rs274}"
mkdir -p "$dest/debs"
cd "$dest/debs"
pkgs=(linuxcnc-uspace libboost-python1.74.0)
if ! apt-get download "${pkgs[@]}" 2>/dev/null; then
  # empty or stale package lists (fresh images): refresh them once, then retry
  sudo_cmd=""; [ "$(id -u)" = "0" ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -q >/dev/null
  apt-get download "${pkgs[@]}"
fi
for deb in *.deb; do dpkg-deb -x "$deb" "$dest/root"; done
echo "rs274 in $dest/root/usr/bin/rs274 (libraries in $dest/root/usr/lib)"
