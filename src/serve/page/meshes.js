// Triangle meshes of a 3D layout's volumes, for the 3D view (view3d.js):
// each volume of the answer's `space.volumes` (Box, Sphere, Ellipsoid,
// Cylinder, Extrude and Revolve of a 2D shape; stl-language.md section
// 11) as flat-shaded triangles, positions and normals in canvas units.
// A picture to see the volumes by, not the growth's geometry: curves are
// cut into 32 segments around, and a Revolve is its shape's outline
// turned about the axis when the shape lies on one side of it (a ring
// shows its hole), else the surface of its profile's outer edge (the
// farthest point of the shape from the axis at each height), as a
// modeller's lathe draws it.

const AROUND = 32;

// The outline of a 2D shape of the answer (shapes.rs's geometry) as points.
export function outline(s) {
  const pts = [];
  const arc = (cx, cy, rx, ry, from, n) => {
    for (let i = 0; i <= n; i++) {
      const t = from + (i / n) * Math.PI / 2;
      pts.push([cx + rx * Math.cos(t), cy + ry * Math.sin(t)]);
    }
  };
  switch (s.type) {
    case 'Rectangle':
      return [[s.x, s.y], [s.x + s.w, s.y], [s.x + s.w, s.y + s.h], [s.x, s.y + s.h]];
    case 'RoundRect': {
      const [rx, ry] = [Math.min(s.rx, s.w / 2), Math.min(s.ry, s.h / 2)];
      arc(s.x + s.w - rx, s.y + s.h - ry, rx, ry, 0, 8);
      arc(s.x + rx, s.y + s.h - ry, rx, ry, Math.PI / 2, 8);
      arc(s.x + rx, s.y + ry, rx, ry, Math.PI, 8);
      arc(s.x + s.w - rx, s.y + ry, rx, ry, 3 * Math.PI / 2, 8);
      return pts;
    }
    case 'Ellipse':
      for (let i = 0; i < 2 * AROUND; i++) {
        const t = (i / (2 * AROUND)) * 2 * Math.PI;
        pts.push([s.x + s.w / 2 * (1 + Math.cos(t)), s.y + s.h / 2 * (1 + Math.sin(t))]);
      }
      return pts;
    default:
      return s.points.map((p) => p.slice());
  }
}

const cross2 = (a, b, c) => (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);

// A simple polygon cut into triangles (ear clipping): index triples.
export function triangulate(pts) {
  let area = 0;
  pts.forEach((p, i) => { area += cross2([0, 0], p, pts[(i + 1) % pts.length]); });
  const sign = area < 0 ? -1 : 1;
  const idx = pts.map((_, i) => i);
  const tris = [];
  const inside = (p, a, b, c) => cross2(a, b, p) * sign >= 0 && cross2(b, c, p) * sign >= 0 && cross2(c, a, p) * sign >= 0;
  while (idx.length > 3) {
    let cut = false;
    for (let i = 0; i < idx.length && !cut; i++) {
      const [a, b, c] = [idx[(i + idx.length - 1) % idx.length], idx[i], idx[(i + 1) % idx.length]];
      if (cross2(pts[a], pts[b], pts[c]) * sign <= 0) continue;
      if (idx.some((k) => k !== a && k !== b && k !== c && inside(pts[k], pts[a], pts[b], pts[c]))) continue;
      tris.push([a, b, c]);
      idx.splice(i, 1);
      cut = true;
    }
    // A self-crossing outline has no ear left: what is cut is shown.
    if (!cut) return tris;
  }
  if (idx.length === 3) tris.push(idx);
  return tris;
}

// Triangles, nine numbers each, with a flat normal per triangle.
function withNormals(tri) {
  const pos = new Float32Array(tri);
  const nrm = new Float32Array(tri.length);
  for (let i = 0; i < tri.length; i += 9) {
    const u = [tri[i + 3] - tri[i], tri[i + 4] - tri[i + 1], tri[i + 5] - tri[i + 2]];
    const v = [tri[i + 6] - tri[i], tri[i + 7] - tri[i + 1], tri[i + 8] - tri[i + 2]];
    const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    const l = Math.hypot(...n) || 1;
    for (let k = 0; k < 9; k += 3) {
      nrm[i + k] = n[0] / l;
      nrm[i + k + 1] = n[1] / l;
      nrm[i + k + 2] = n[2] / l;
    }
  }
  return { pos, nrm };
}

// A grid of points `at(i, j)` (i < rows, j around, closed) as triangles.
function sheet(tri, rows, at) {
  for (let i = 0; i + 1 < rows; i++) {
    for (let j = 0; j < AROUND; j++) {
      const [a, b, c, d] = [at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)];
      tri.push(...a, ...b, ...c, ...a, ...c, ...d);
    }
  }
}

function box(tri, [x, y, z], [w, h, d]) {
  const p = (i) => [x + (i & 1 ? w : 0), y + (i & 2 ? h : 0), z + (i & 4 ? d : 0)];
  for (const [a, b, c, e] of [[0, 1, 3, 2], [4, 5, 7, 6], [0, 1, 5, 4], [2, 3, 7, 6], [0, 2, 6, 4], [1, 3, 7, 5]]) {
    tri.push(...p(a), ...p(b), ...p(c), ...p(a), ...p(c), ...p(e));
  }
}

function ellipsoid(tri, c, r) {
  const rows = AROUND / 2 + 1;
  sheet(tri, rows, (i, j) => {
    const t = (i / (rows - 1)) * Math.PI;
    const f = (j / AROUND) * 2 * Math.PI;
    return [c[0] + r[0] * Math.sin(t) * Math.cos(f), c[1] + r[1] * Math.cos(t), c[2] + r[2] * Math.sin(t) * Math.sin(f)];
  });
}

// A surface of revolution about the vertical line through (ax, az): the
// profile's points are [radius, y], top to bottom, ends on the axis.
function lathe(tri, [ax, az], profile) {
  sheet(tri, profile.length, (i, j) => {
    const f = (j / AROUND) * 2 * Math.PI;
    const [r, y] = profile[i];
    return [ax + r * Math.cos(f), y, az + r * Math.sin(f)];
  });
}

// A shape's outer radius about x = ax at each of its heights.
function profileOf(pts, ax) {
  const ys = pts.map((p) => p[1]);
  const [lo, hi] = [Math.min(...ys), Math.max(...ys)];
  const rows = 48;
  const profile = [[0, lo]];
  for (let k = 0; k <= rows; k++) {
    const y = lo + (hi - lo) * Math.min(Math.max(k / rows, 1e-6), 1 - 1e-6);
    let r = -1;
    pts.forEach((a, i) => {
      const b = pts[(i + 1) % pts.length];
      if ((a[1] <= y) === (b[1] <= y)) return;
      const x = a[0] + (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]);
      r = Math.max(r, Math.abs(x - ax));
    });
    if (r >= 0) profile.push([r, y]);
  }
  profile.push([0, hi]);
  return profile;
}

function extrude(tri, pts, z1, z2) {
  pts.forEach((a, i) => {
    const b = pts[(i + 1) % pts.length];
    tri.push(a[0], a[1], z1, b[0], b[1], z1, b[0], b[1], z2, a[0], a[1], z1, b[0], b[1], z2, a[0], a[1], z2);
  });
  for (const [a, b, c] of triangulate(pts)) {
    for (const z of [z1, z2]) tri.push(pts[a][0], pts[a][1], z, pts[b][0], pts[b][1], z, pts[c][0], pts[c][1], z);
  }
}

/**
 * The triangles of one volume.
 *
 * @param {object} v a volume of `space.volumes` (`type` and its numbers)
 * @param {number[]} axis `[x, z]` of the first root, a Revolve's axis
 * @returns {{pos: Float32Array, nrm: Float32Array}}
 */
export function volumeMesh(v, axis) {
  const tri = [];
  switch (v.type) {
    case 'Box': box(tri, v.corner, v.size); break;
    case 'Sphere': ellipsoid(tri, v.centre, [v.r, v.r, v.r]); break;
    case 'Ellipsoid': ellipsoid(tri, v.centre, v.radii); break;
    case 'Cylinder': {
      const [x, y, z] = v.base;
      lathe(tri, [x, z], [[0, y - v.h], [v.r, y - v.h], [v.r, y], [0, y]]);
      break;
    }
    case 'Extrude': extrude(tri, outline(v.shape), v.z1, v.z2); break;
    case 'Revolve': {
      // A shape on one side of the axis turns as it is (a ring's hole
      // shows: a torus); one across it as its outer edge.
      const pts = outline(v.shape);
      const side = pts.map((p) => Math.sign(p[0] - axis[0])).filter((s) => s !== 0);
      const oneSide = side.every((s) => s === side[0]);
      const ring = pts.concat([pts[0]]).map(([x, y]) => [Math.abs(x - axis[0]), y]);
      lathe(tri, axis, oneSide ? ring : profileOf(pts, axis[0]));
      break;
    }
    default: break;
  }
  return withNormals(tri);
}
