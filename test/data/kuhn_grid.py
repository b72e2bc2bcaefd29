#!/usr/bin/env python3
"""Writes a Medit .mesh of an n x n x n Kuhn (Freudenthal) grid: each unit cube
split into 6 tetrahedra around its main diagonal. Used to make test fixtures.

usage: kuhn_grid.py N OUT.mesh [--drop i,j,k ...] [--negate-every K] [--scale S]
  --drop: omit the cube at (i,j,k) (non-convex domains)
  --negate-every K: write every K-th tetrahedron with negative orientation
"""
import itertools, sys

def main():
    n = int(sys.argv[1]); out = sys.argv[2]
    drops = set(); negate = 0; scale = 1.0
    args = sys.argv[3:]
    while args:
        a = args.pop(0)
        if a == '--drop': drops.add(tuple(int(x) for x in args.pop(0).split(',')))
        elif a == '--negate-every': negate = int(args.pop(0))
        elif a == '--scale': scale = float(args.pop(0))
        else: sys.exit('unknown argument ' + a)
    vid = lambda i, j, k: (i * (n + 1) + j) * (n + 1) + k
    verts = [(i * scale, j * scale, k * scale) for i in range(n + 1) for j in range(n + 1) for k in range(n + 1)]
    tets = []
    for i, j, k in itertools.product(range(n), repeat=3):
        if (i, j, k) in drops: continue
        for perm in itertools.permutations(range(3)):
            c = [i, j, k]; path = [vid(*c)]
            for ax in perm:
                c[ax] += 1; path.append(vid(*c))
            # odd permutations give negatively oriented tets: swap to fix
            inversions = sum(1 for x in range(3) for y in range(x + 1, 3) if perm[x] > perm[y])
            if inversions % 2: path[0], path[1] = path[1], path[0]
            tets.append(path)
    used = sorted({v for t in tets for v in t})
    remap = {v: r for r, v in enumerate(used)}
    with open(out, 'w') as f:
        f.write('MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n' % len(used))
        for v in used: f.write('%.17g %.17g %.17g 0\n' % verts[v])
        f.write('Tetrahedra\n%d\n' % len(tets))
        for t, tet in enumerate(tets):
            a, b, c, d = (remap[v] + 1 for v in tet)
            if negate and t % negate == 0: a, b = b, a
            f.write('%d %d %d %d 1\n' % (a, b, c, d))
        f.write('End\n')

main()
