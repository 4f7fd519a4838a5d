#!/usr/bin/env python3
"""An independent check of a binary STL (benches/solid.sh): welds corners
by their exact f32 bits, then reports triangles, vertices, whether every
edge is shared by exactly two triangles in opposite directions
(watertight, consistently oriented), connected components, the signed
volume and the Euler characteristic V - E + F with the genus it implies.
Standard library only (no trimesh on the CI machine)."""
import struct, sys
from collections import defaultdict

def check(path):
    data = open(path, 'rb').read()
    n, = struct.unpack_from('<I', data, 80)
    assert len(data) == 84 + 50 * n, 'size does not match the count'
    index, tris = {}, []
    for i in range(n):
        off = 84 + 50 * i + 12
        corners = []
        for k in range(3):
            key = data[off + 12 * k: off + 12 * k + 12]
            corners.append(index.setdefault(key, len(index)))
        tris.append(corners)
    pts = [struct.unpack('<3f', k) for k in index]
    directed = defaultdict(int)
    for a, b, c in tris:
        for e in ((a, b), (b, c), (c, a)):
            directed[e] += 1
    closed = all(v == 1 and directed.get((e[1], e[0])) == 1 for e, v in directed.items())
    edges = len(directed) // 2
    parent = list(range(len(pts)))
    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for a, b, c in tris:
        parent[find(b)] = find(a); parent[find(c)] = find(a)
    comps = len({find(v) for v in range(len(pts))})
    vol = 0.0
    for a, b, c in tris:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = pts[a], pts[b], pts[c]
        vol += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6
    chi = len(pts) - edges + n
    print(f'{path}: {n} triangles, {len(pts)} vertices, watertight and oriented {closed}, '
          f'components {comps}, volume {vol:.3f} mm^3, Euler {chi} (genus {(2 - chi) / 2 if comps == 1 else "n/a"})')
    return closed and comps == 1 and vol > 0

if __name__ == '__main__':
    sys.exit(0 if all([check(p) for p in sys.argv[1:]]) else 1)
