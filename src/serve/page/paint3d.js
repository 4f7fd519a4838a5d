// The colours and leaves of a 3D answer (`answer.space`: `colors`,
// `stem_colors`, `leaves`; docs/serve.md) as the 3D view's WebGL arrays
// (view3d.js): each stem's colour, and each leaf a fan of triangles with
// its polygon's normal and its colour. An answer without them (an input
// that does not paint) gives every stem the stroke colour and no leaves.

// `#rrggbb` as three numbers from 0 to 1, `fallback` if it is not one.
export function rgb(hex, fallback) {
  const m = /^#([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})$/i.exec(hex || '');
  return m ? [1, 2, 3].map((i) => parseInt(m[i], 16) / 255) : fallback;
}

// Three numbers a stem: its colour from `space.colors` by
// `space.stem_colors`, else `stroke` (an index past the colours too).
export function stemColours(space, stroke) {
  const count = space.stems.length / 8;
  const out = new Float32Array(count * 3);
  const colours = (space.colors || []).map((c) => rgb(c, stroke));
  const index = space.stem_colors || [];
  for (let i = 0; i < count; i++) {
    const c = colours[index[i]] || stroke;
    out.set(c, i * 3);
  }
  return out;
}

// A polygon's normal by Newell's method (any winding, any vertex count),
// unit length; straight up the view for a polygon of no area.
function newell(p, n) {
  let [x, y, z] = [0, 0, 0];
  for (let i = 0; i < n; i++) {
    const j = (i + 1) % n;
    const [a, b] = [i * 3, j * 3];
    x += (p[a + 1] - p[b + 1]) * (p[a + 2] + p[b + 2]);
    y += (p[a + 2] - p[b + 2]) * (p[a] + p[b]);
    z += (p[a] - p[b]) * (p[a + 1] + p[b + 1]);
  }
  const len = Math.hypot(x, y, z);
  return len > 0 ? [x / len, y / len, z / len] : [0, 0, 1];
}

// The leaves as triangles (a fan from each polygon's first vertex: n - 2
// of them for n vertices), nine numbers a triangle in each of `pos`,
// `nrm` (the polygon's normal) and `col`; `count` vertices in all.
export function leafTriangles(space, stroke) {
  const leaves = space.leaves || [];
  const colours = (space.colors || []).map((c) => rgb(c, stroke));
  let count = 0;
  for (const l of leaves) count += 3 * Math.max(0, l.points.length / 3 - 2);
  const [pos, nrm, col] = [0, 0, 0].map(() => new Float32Array(count * 3));
  let at = 0;
  for (const l of leaves) {
    const p = l.points;
    const n = p.length / 3;
    if (n < 3) continue;
    const normal = newell(p, n);
    const c = colours[l.color] || stroke;
    for (let k = 1; k + 1 < n; k++) {
      for (const v of [0, k, k + 1]) {
        pos.set([p[v * 3], p[v * 3 + 1], p[v * 3 + 2]], at * 3);
        nrm.set(normal, at * 3);
        col.set(c, at * 3);
        at++;
      }
    }
  }
  return { pos, nrm, col, count };
}
