#!/usr/bin/env bash
# Builds the OpenSubdiv driver (tools/osd-driver/osd_driver.cpp) against Debian's libosd-dev.
# Usage: tools/osd-driver/build.sh [OUT]; OUT defaults to $CARGO_TARGET_DIR/osd-driver/osd_driver
# (target/osd-driver/osd_driver). Prints the binary's path. The compiler is $CXX, else c++.
# The differential tests (crates/halfedge/tests/opensubdiv.rs) find the binary through
# SUBCOUNT_OSD_DRIVER, bench/peers/compare.py through --osd; cargo never builds it.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
case "$target" in /*) ;; *) target="$root/$target" ;; esac
out="${1:-$target/osd-driver/osd_driver}"
mkdir -p "$(dirname "$out")"
if [ ! -d /usr/include/opensubdiv ]; then
  echo "error: OpenSubdiv's headers are not in /usr/include/opensubdiv (apt-get install libosd-dev)" >&2
  exit 1
fi
"${CXX:-c++}" -O2 -DNDEBUG -std=c++17 -Wall -Wextra -o "$out" "$root/tools/osd-driver/osd_driver.cpp" -losdCPU
echo "$out"
