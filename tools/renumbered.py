#!/usr/bin/env python3
"""Two subcount binaries' `subdivide -o` outputs, equal up to numbering?

    tools/renumbered.py OLD_BIN NEW_BIN MESH_DIR [SCHEME ...]

For every `*.obj` of MESH_DIR (and the non-manifold ones of MESH_DIR/broken), every scheme
given (default: the face-list schemes) and levels 1 and 2, runs both binaries and compares
their outputs: byte-identical, or the same `v`/`vt`/`vn` lines (as multisets) and the same
faces, each face taken as the cycle of its corners' lines (so any vertex numbering, face
order and starting corner), and the same other lines. Exit 1 on a mismatch. The check
behind a change of numbering in CHANGELOG.md (`cargo xtask golden` lists such outputs as
differences).
"""
import collections
import glob
import os
import subprocess
import sys
import tempfile

FACE_LIST_SCHEMES = ["loop-general", "tri-split-2", "tri-split-3", "catmull-clark-general",
                     "catmull-clark-quad"]


def parse(text):
    lines = text.splitlines()
    table = {k: [l for l in lines if l.startswith(k + " ")] for k in ("v", "vt", "vn")}
    other = collections.Counter(l for l in lines if not l.startswith(("v ", "vt ", "vn ", "f ")))
    faces = collections.Counter()
    for l in lines:
        if not l.startswith("f "):
            continue
        corners = []
        for token in l.split()[1:]:
            parts = token.split("/")
            key = tuple(table[k][int(p) - 1] for k, p in zip(("v", "vt", "vn"), parts) if p)
            corners.append(key)
        i = min(range(len(corners)), key=lambda k: corners[k])
        faces[tuple(corners[i:] + corners[:i])] += 1
    values = collections.Counter(table["v"] + table["vt"] + table["vn"])
    return values, faces, other


def run(binary, mesh, scheme, level, out):
    if os.path.exists(out):
        os.remove(out)
    r = subprocess.run([binary, "subdivide", "--mesh", mesh, "--scheme", scheme, "--levels",
                        str(level), "-o", out], capture_output=True)
    text = open(out).read() if os.path.exists(out) else None
    return r.returncode, text


def main():
    old, new, folder = sys.argv[1:4]
    schemes = sys.argv[4:] or FACE_LIST_SCHEMES
    meshes = sorted(glob.glob(os.path.join(folder, "*.obj"))
                    + glob.glob(os.path.join(folder, "broken", "*nonmanifold*.obj")))
    compared = identical = bad = 0
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in meshes:
            for scheme in schemes:
                for level in (1, 2):
                    a = run(old, mesh, scheme, level, os.path.join(tmp, "old.obj"))
                    b = run(new, mesh, scheme, level, os.path.join(tmp, "new.obj"))
                    what = f"{os.path.basename(mesh)} {scheme} L{level}"
                    if a[0] != b[0]:
                        print(f"exit {a[0]} vs {b[0]}: {what}")
                        bad += 1
                        continue
                    if a[1] is None:
                        continue
                    compared += 1
                    if a[1] == b[1]:
                        identical += 1
                    elif parse(a[1]) != parse(b[1]):
                        print(f"different: {what}")
                        bad += 1
    renumbered = compared - identical - bad
    print(f"{compared} outputs: {identical} byte-identical, {renumbered} equal up to numbering, "
          f"{bad} different")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
