#!/usr/bin/env python3
"""An independent check of a solid (benches/solid.sh, benches/leaves.sh):
a binary STL, a 3MF or a .glb, by its extension. Reads the triangles
with Python's standard library (struct, zipfile, xml.etree, json):
an STL's corners welded by their exact f32 bits, a 3MF's and a glb's
vertices by their indices (a 3MF's package checked too: its three parts,
the relationship to the model, millimetres, one object of type model).
Then reports triangles, vertices, whether every edge is shared by exactly
two triangles in opposite directions (watertight, consistently oriented),
connected components, the signed volume and the Euler characteristic
V - E + F with the genus it implies. Where trimesh imports (not on the CI
machine), it reads the file too and reports its own watertightness,
bodies and volume."""
import io, json, struct, sys, zipfile
import xml.etree.ElementTree as ET
from collections import defaultdict

CORE = '{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}'


def read_stl(data):
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
    return [struct.unpack('<3f', k) for k in index], tris, 'mm'


def read_3mf(data):
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        assert z.testzip() is None, 'a part fails its CRC'
        names = set(z.namelist())
        assert names == {'[Content_Types].xml', '_rels/.rels', '3D/3dmodel.model'}, names
        rel = ET.fromstring(z.read('_rels/.rels'))[0].attrib
        assert rel['Target'] == '/3D/3dmodel.model', rel
        assert rel['Type'].endswith('/3dmanufacturing/2013/01/3dmodel'), rel
        types = ET.fromstring(z.read('[Content_Types].xml'))
        assert any(t.attrib.get('ContentType') == 'application/vnd.ms-package.3dmanufacturing-3dmodel+xml'
                   for t in types), 'no model content type'
        model = ET.fromstring(z.read('3D/3dmodel.model'))
    assert model.attrib.get('unit') == 'millimeter', model.attrib
    objects = model.findall(f'{CORE}resources/{CORE}object')
    assert len(objects) == 1 and objects[0].attrib['type'] == 'model', 'not one model object'
    items = model.findall(f'{CORE}build/{CORE}item')
    assert [i.attrib['objectid'] for i in items] == [objects[0].attrib['id']], 'build'
    mesh = objects[0].find(f'{CORE}mesh')
    pts = [tuple(float(v.attrib[a]) for a in 'xyz') for v in mesh.iter(f'{CORE}vertex')]
    tris = [[int(t.attrib[a]) for a in ('v1', 'v2', 'v3')] for t in mesh.iter(f'{CORE}triangle')]
    assert len(set(pts)) == len(pts), 'a position listed twice'
    return pts, tris, 'mm'


def read_glb(data):
    magic, version, total = struct.unpack_from('<4sII', data, 0)
    assert magic == b'glTF' and version == 2 and total == len(data), 'not a glb'
    jlen, jtype = struct.unpack_from('<I4s', data, 12)
    doc = json.loads(data[20:20 + jlen])
    blen, btype = struct.unpack_from('<I4s', data, 20 + jlen)
    assert jtype == b'JSON' and btype == b'BIN\0'
    buf = data[28 + jlen: 28 + jlen + blen]
    prims = [p for m in doc['meshes'] for p in m['primitives']]
    assert len(prims) == 1 and len(doc.get('materials', [])) == 1, 'not one primitive and material'
    p = prims[0]
    assert 'TEXCOORD_0' not in p['attributes'], 'a solid has no texture coordinates'

    def accessor(i, fmt, width):
        a = doc['accessors'][i]
        v = doc['bufferViews'][a['bufferView']]
        off = v.get('byteOffset', 0) + a.get('byteOffset', 0)
        flat = struct.unpack_from(f'<{a["count"] * width}{fmt}', buf, off)
        return [tuple(flat[k:k + width]) for k in range(0, len(flat), width)]
    pts = accessor(p['attributes']['POSITION'], 'f', 3)
    normals = accessor(p['attributes']['NORMAL'], 'f', 3)
    assert all(abs(sum(c * c for c in n) - 1) < 1e-5 for n in normals), 'a normal not unit'
    idx = accessor(p['indices'], 'I', 1)
    tris = [[idx[k][0], idx[k + 1][0], idx[k + 2][0]] for k in range(0, len(idx), 3)]
    assert len(set(pts)) == len(pts), 'a position listed twice'
    return pts, tris, 'm'


def check(path):
    data = open(path, 'rb').read()
    ext = path.rsplit('.', 1)[-1].lower()
    pts, tris, unit = {'stl': read_stl, '3mf': read_3mf, 'glb': read_glb}[ext](data)
    n = len(tris)
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
          f'components {comps}, volume {vol:.9g} {unit}^3, Euler {chi} (genus {(2 - chi) / 2 if comps == 1 else "n/a"})')
    try:
        import trimesh
    except ImportError:
        return closed and comps == 1 and vol > 0
    m = trimesh.load(path, force='mesh')
    bodies = len(m.split(only_watertight=False))
    print(f'  trimesh {trimesh.__version__}: {len(m.faces)} faces, watertight {m.is_watertight}, '
          f'bodies {bodies}, volume {m.volume:.9g}, bounds {m.bounds.tolist()}')
    return closed and comps == 1 and vol > 0 and m.is_watertight and bodies == 1


if __name__ == '__main__':
    sys.exit(0 if all([check(p) for p in sys.argv[1:]]) else 1)
