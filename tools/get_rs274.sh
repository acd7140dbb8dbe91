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
apt-get download linuxcnc-uspace libboost-python1.74.0 2>/dev/null
for deb in *.deb; do dpkg-deb -x "$deb" "$dest/root"; done
echo "rs274 in $dest/root/usr/bin/rs274 (libraries in $dest/root/usr/lib)"
