#!/usr/bin/env bash
# Writes the third-party tet meshes of benchmark_frame_quality
# (doc/benchmarks.md): CGAL's closed CAD surfaces fandisk, anchor and joint
# (Debian's libcgal-demo) tetrahedralised by TetGen and by Gmsh, as a user
# of either tool would. Installs libcgal-demo, tetgen and gmsh if missing.
# Idempotent: a mesh that exists is kept.
#
#   bash scripts/make_benchmark_meshes.sh [OUT]     (default: build/benchmark-meshes)
#
# OUT/data/meshes   CGAL's surfaces (CGAL_DATA_MESHES for the benchmark)
# OUT/tetgen/M.1.mesh   tetgen -pq1.6gQ M.off: the input triangles kept,
#                       radius-edge ratio at most 1.6
# OUT/gmsh/M.mesh       Gmsh's surface remeshing of the triangles (creases
#                       beyond 40 degrees kept as curves), then its volume
#                       mesh: sizes from the curvature (12 elements per turn,
#                       so that a fillet's facets do not meet at more than the
#                       feature angle and read as creases), between the
#                       bounding-box diagonal / 80 and / 20
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-$root/build/benchmark-meshes}"
models=(fandisk anchor joint)

bash "$root/scripts/install_dependencies.sh" libcgal-demo tetgen gmsh python3

mkdir -p "$out/tetgen" "$out/gmsh"
if [ ! -d "$out/data/meshes" ]; then
  tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$out" data/meshes
fi

# An OFF surface as ASCII STL (Gmsh reads no OFF), and its bounding-box diagonal.
off_to_stl() {
  python3 - "$1" "$2" <<'EOF'
import math, sys
tokens = []
for line in open(sys.argv[1]):
    tokens += line.split('#', 1)[0].split()
if tokens[0] != 'OFF':
    sys.exit(f'{sys.argv[1]}: not an OFF file')
nv, nf = int(tokens[1]), int(tokens[2])
at = 4
points = []
for _ in range(nv):
    points.append(tuple(float(x) for x in tokens[at:at + 3]))
    at += 3
with open(sys.argv[2], 'w') as stl:
    stl.write('solid surface\n')
    for _ in range(nf):
        k = int(tokens[at])
        face = [int(x) for x in tokens[at + 1:at + 1 + k]]
        at += 1 + k
        for j in range(1, k - 1):  # a fan of triangles
            stl.write('facet normal 0 0 0\n outer loop\n')
            for v in (face[0], face[j], face[j + 1]):
                stl.write('  vertex %r %r %r\n' % points[v])
            stl.write(' endloop\nendfacet\n')
    stl.write('endsolid surface\n')
low = [min(p[i] for p in points) for i in range(3)]
high = [max(p[i] for p in points) for i in range(3)]
print(math.dist(low, high))
EOF
}

for m in "${models[@]}"; do
  surface="$out/data/meshes/$m.off"
  if [ ! -s "$out/tetgen/$m.1.mesh" ]; then
    cp "$surface" "$out/tetgen/$m.off"
    (cd "$out/tetgen" && tetgen -pq1.6gQ "$m.off")
    echo "[meshes] $out/tetgen/$m.1.mesh (TetGen)" >&2
  fi
  if [ ! -s "$out/gmsh/$m.mesh" ]; then
    diagonal=$(off_to_stl "$surface" "$out/gmsh/$m.stl")
    cat > "$out/gmsh/$m.geo" <<EOF
Merge "$m.stl";
ClassifySurfaces{40 * Pi / 180, 1, 1, Pi};
CreateGeometry;
Surface Loop(1) = Surface{:};
Volume(1) = {1};
Mesh.MeshSizeMax = $diagonal / 20;
Mesh.MeshSizeMin = $diagonal / 80;
Mesh.MeshSizeFromCurvature = 12;
EOF
    (cd "$out/gmsh" && gmsh "$m.geo" -3 -format mesh -o "$m.mesh" > "$m.log" 2>&1) ||
      { echo "[meshes] gmsh failed on $m: see $out/gmsh/$m.log" >&2; exit 1; }
    echo "[meshes] $out/gmsh/$m.mesh (Gmsh)" >&2
  fi
done
echo "[meshes] CGAL_DATA_MESHES=$out/data/meshes; $out/tetgen/{fandisk,anchor,joint}.1.mesh; $out/gmsh/{fandisk,anchor,joint}.mesh" >&2
