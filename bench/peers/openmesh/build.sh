#!/usr/bin/env bash
# Builds OpenMesh's C++ library from its PyPI source distribution and the subdivision driver
# against it (not part of CI). Usage: bench/peers/openmesh/build.sh [WORKDIR]
# WORKDIR (default /tmp/subcount-openmesh) receives the sdist, the build tree and the driver
# binary WORKDIR/subdivide_openmesh. Needs pip, cmake (apt-get install cmake) and a C++ compiler.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
work="${1:-/tmp/subcount-openmesh}"
mkdir -p "$work"
cd "$work"
if ! command -v cmake >/dev/null; then
  if command -v apt-get >/dev/null; then apt-get install -y cmake; else echo "error: cmake missing" >&2; exit 1; fi
fi
if ! ls openmesh-*.tar.gz >/dev/null 2>&1; then
  python3 -m pip download --no-binary :all: --no-deps openmesh -d .
fi
sdist="$(ls openmesh-*.tar.gz | sort | tail -n1)"
src="${sdist%.tar.gz}"
[ -d "$src" ] || tar xzf "$sdist"
# The sdist carries the C++ library in $src/OpenMesh; build only the core library.
cmake -S "$src/OpenMesh" -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_APPS=OFF \
  -DOPENMESH_DOCS=OFF -DOPENMESH_BUILD_UNIT_TESTS=OFF \
  -DCMAKE_CXX_FLAGS="-O3 -DNDEBUG" >cmake.log
cmake --build build --target OpenMeshCore -j "$(nproc)" >>cmake.log
libdir="$work/build/Build/lib"  # libOpenMeshCore.so (OpenMesh builds it shared)
g++ -O3 -DNDEBUG -std=c++17 -I"$src/OpenMesh/src" "$here/driver.cpp" \
  -L"$libdir" -lOpenMeshCore -Wl,-rpath,"$libdir" -o subdivide_openmesh
echo "$work/subdivide_openmesh"
