#!/usr/bin/env python3
"""Two subcount binaries' `subdivide -o` outputs, equal up to numbering?

    tools/renumbered.py OLD_BIN NEW_BIN MESH_DIR [SCHEME ...]

For every `*.obj` of MESH_DIR (and the non-manifold ones of MESH_DIR/broken), every scheme
given (default: the face-list schemes) and levels 1 and 2, runs both binaries and compares
their outputs: byte-identical, or the same values (`v`, `vt`, `vn`: matched exactly or, for
a value rounded otherwise by its new numbering, within 1e-12 of the bounding-box diagonal)
and the same faces under that matching, each face as the cycle of its corners' values (any
vertex numbering, face order and starting corner), and the same other lines. Exit 1 on a mismatch. The check
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
    """`{kind: [coordinates]}` for `v`, `vt`, `vn`; the faces as lists of index tuples; the
    other lines."""
    values = {"v": [], "vt": [], "vn": []}
    faces, other = [], collections.Counter()
    for line in text.splitlines():
        kind, _, rest = line.partition(" ")
        if kind in values:
            values[kind].append(tuple(float(x) for x in rest.split()))
        elif kind == "f":
            faces.append([tuple(int(p) - 1 if p else None for p in t.split("/"))
                          for t in rest.split()])
        else:
            other[line] += 1
    return values, faces, other


def matching(a, b):
    """A map from the indices of `b` to those of `a`, the same values exactly or, for the
    few that round otherwise (a midpoint computed from its other end), within 1e-12 of the
    bounding-box diagonal; None when there is none."""
    if len(a) != len(b):
        return None
    exact = collections.defaultdict(list)
    for i, x in enumerate(a):
        exact[x].append(i)
    out, left = [None] * len(b), []
    for j, y in enumerate(b):
        if exact[y]:
            out[j] = exact[y].pop()
        else:
            left.append(j)
    spare = [i for ids in exact.values() for i in ids]
    if not left:
        return out
    lo = [min(c) for c in zip(*a)]
    hi = [max(c) for c in zip(*a)]
    tol = 1e-12 * max(sum((h - l) ** 2 for l, h in zip(lo, hi)) ** 0.5, 1e-300)
    for j in left:
        dist = [(max(abs(p - q) for p, q in zip(a[i], b[j])), i) for i in spare]
        if not dist:
            return None
        d, i = min(dist)
        if d > tol:
            return None
        out[j] = i
        spare.remove(i)
    return out


def same_up_to_numbering(text_a, text_b):
    (va, fa, oa), (vb, fb, ob) = parse(text_a), parse(text_b)
    if oa != ob or len(fa) != len(fb):
        return False
    maps = {k: matching(va[k], vb[k]) for k in va}
    if any(m is None for m in maps.values()):
        return False

    def cycle(face, to_a):
        # Each corner as its values (not its indices: a file may repeat a value).
        corners = [tuple(None if p is None else va[k][to_a[k][p] if to_a else p]
                         for k, p in zip(("v", "vt", "vn"), c)) for c in face]
        # The least rotation (a face may repeat a value: a degenerate triangle).
        return min(tuple(corners[i:] + corners[:i]) for i in range(len(corners)))

    mine = collections.Counter(cycle(f, None) for f in fa)
    theirs = collections.Counter(cycle(f, maps) for f in fb)
    return mine == theirs


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
                    elif not same_up_to_numbering(a[1], b[1]):
                        print(f"different: {what}")
                        bad += 1
    renumbered = compared - identical - bad
    print(f"{compared} outputs: {identical} byte-identical, {renumbered} equal up to numbering, "
          f"{bad} different")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
