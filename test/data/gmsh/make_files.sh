#!/usr/bin/env bash
# Writes the .msh test files from box_with_hole_physical.geo with Gmsh (Debian's
# gmsh), one mesh in every format the reader takes, and Gmsh's own Medit
# export of the same mesh to compare with. The tests do not need Gmsh.
set -euo pipefail
cd "$(dirname "$0")"
gmsh -3 box_with_hole_physical.geo -format msh41 -o box_41.msh >/dev/null
gmsh box_41.msh -0 -bin -format msh41 -o box_41_binary.msh >/dev/null
gmsh box_41.msh -0 -format msh22 -o box_22.msh >/dev/null
gmsh box_41.msh -0 -bin -format msh22 -o box_22_binary.msh >/dev/null
gmsh box_41.msh -0 -format mesh -o box.mesh >/dev/null
# Node tags with gaps and out of order (3 t + 5, each block's nodes in
# reverse), as a mesh renumbered or cut out of a larger one has them.
python3 - <<'PY'
lines = open("box_41.msh").read().split("\n")
tag = lambda t: str(3 * int(t) + 5)
out, i = [], 0
while i < len(lines):
    line = lines[i]
    out.append(line)
    i += 1
    if line == "$Nodes":
        blocks, n, lo, hi = map(int, lines[i].split())
        out.append("%d %d %d %d" % (blocks, n, 3 * lo + 5, 3 * hi + 5))
        i += 1
        for _ in range(blocks):
            m = int(lines[i].split()[3])
            out.append(lines[i])
            tags, coords = lines[i + 1:i + 1 + m], lines[i + 1 + m:i + 1 + 2 * m]
            out += [tag(t) for t in reversed(tags)] + list(reversed(coords))
            i += 1 + 2 * m
    elif line == "$Elements":
        blocks = int(lines[i].split()[0])
        out.append(lines[i])
        i += 1
        for _ in range(blocks):
            m = int(lines[i].split()[3])
            out.append(lines[i])
            for e in lines[i + 1:i + 1 + m]:
                w = e.split()
                out.append(" ".join([w[0]] + [tag(t) for t in w[1:]]))
            i += 1 + m
open("box_41_gaps.msh", "w").write("\n".join(out))
PY
