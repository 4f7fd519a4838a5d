// The preview: the library's picture of the last good answer, the editable
// outlines of the shapes over it, the root, and the view box (zoom, pan,
// fit). Zoom and pan move only the view: nothing is rendered again.

import { byId, el } from './dom.js';
import { createTreeCanvas } from './bigtree.js';

// The box the picture lives in, in canvas units.
function pictureBox(answer) {
  if (answer.view) return answer.view;
  const g = answer.growth && answer.growth.stems;
  if (g && g.length) {
    let b = [Infinity, Infinity, -Infinity, -Infinity];
    for (let i = 0; i < g.length; i += 6) {
      b = [Math.min(b[0], g[i], g[i + 2]), Math.min(b[1], g[i + 1], g[i + 3]),
        Math.max(b[2], g[i], g[i + 2]), Math.max(b[3], g[i + 1], g[i + 3])];
    }
    const m = 0.04 * Math.max(b[2] - b[0], b[3] - b[1], 1);
    return [b[0] - m, b[1] - m, b[2] + m, b[3] + m];
  }
  return null;
}

// A shape's SVG element (an answer's layout shape or one being drawn).
export function shapeElement(s, parent) {
  switch (s.type) {
    case 'Rectangle': return el('rect', { x: s.x, y: s.y, width: s.w, height: s.h }, parent);
    case 'RoundRect': return el('rect', { x: s.x, y: s.y, width: s.w, height: s.h, rx: s.rx, ry: s.ry }, parent);
    case 'Ellipse': return el('ellipse', { cx: s.x + s.w / 2, cy: s.y + s.h / 2, rx: s.w / 2, ry: s.h / 2 }, parent);
    default: return el('polygon', { points: s.points.map((p) => p.join(',')).join(' ') }, parent);
  }
}

// The corners of a box shape, or a polygon's vertices: the resize handles.
export function handlesOf(s) {
  if (s.type === 'Polygon') return s.points;
  return [[s.x, s.y], [s.x + s.w, s.y], [s.x + s.w, s.y + s.h], [s.x, s.y + s.h]];
}

// The area of a shape, for picking the smallest under the pointer.
function area(s) {
  if (s.type === 'Polygon') {
    let a = 0;
    s.points.forEach(([x, y], i) => {
      const [u, v] = s.points[(i + 1) % s.points.length];
      a += x * v - u * y;
    });
    return Math.abs(a) / 2;
  }
  if (s.type === 'Ellipse') return Math.PI * s.w * s.h / 4;
  return s.w * s.h;
}

// The distance from `p` to segment a..b.
function segment(p, a, b) {
  const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
  const l = dx * dx + dy * dy;
  const t = l ? Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l)) : 0;
  return Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

// Whether `p` is inside `s` or within `tol` of its edge.
export function near(s, p, tol) {
  const [x, y] = p;
  if (s.type === 'Polygon') {
    let inside = false;
    const n = s.points.length;
    for (let i = 0, j = n - 1; i < n; j = i++) {
      const [xi, yi] = s.points[i];
      const [xj, yj] = s.points[j];
      if ((yi > y) !== (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
      if (segment(p, s.points[i], s.points[j]) <= tol) return true;
    }
    return inside;
  }
  if (s.type === 'Ellipse') {
    const rx = s.w / 2 + tol;
    const ry = s.h / 2 + tol;
    return ((x - s.x - s.w / 2) / rx) ** 2 + ((y - s.y - s.h / 2) / ry) ** 2 <= 1;
  }
  return x >= s.x - tol && x <= s.x + s.w + tol && y >= s.y - tol && y <= s.y + s.h + tol;
}

// A round step for grid lines about `span / 8` apart: 1, 2 or 5 times a power of ten.
function gridStep(span) {
  const raw = span / 8;
  const p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((k) => k * p).find((s) => s >= raw);
}

export function createView(app) {
  const { state } = app;
  const preview = byId('preview');
  // A big grown tree's canvas (bigtree.js): the answer's SVG has no tree.
  const tree = createTreeCanvas();

  // The shapes' places in the text come with each good answer (layout.js's
  // doc, the one drawing edits start from); an answer to a text older than
  // the last drawing edit leaves that edit's shapes shown.
  function takeAnswer() {
    const text = app.editor.text();
    const d = state.drawn;
    if (d && d.text === text && state.answerText !== text) {
      state.shapes = JSON.parse(JSON.stringify(d.shapes));
      state.root = d.rootAt;
      state.layoutSpan = d.layout;
      state.rootSpan = d.root;
      return;
    }
    state.drawn = {
      text: state.answerText, shapes: JSON.parse(JSON.stringify(state.shapes)),
      layout: state.layoutSpan, root: state.rootSpan, rootAt: state.root,
    };
  }

  // Redraws everything from the last good answer.
  function draw() {
    const a = state.answer;
    if (!a || !a.ok) return;
    takeAnswer();
    preview.innerHTML = '';
    // A 3D input: its own WebGL view (view3d.js) instead of this one.
    document.body.classList.toggle('space', !!a.space);
    if (a.space) {
      app.view3d.show(a, state.refit && app.session.inSync());
      if (app.session.inSync()) state.refit = false;
      app.replay.show();
      return;
    }
    app.view3d.hide();
    const lib = new DOMParser().parseFromString(a.svg, 'image/svg+xml').documentElement;
    const box = pictureBox(a);
    const libLayer = el('g', { class: 'lib' }, preview);
    // The library's picture (what `stlc render --show-layout` writes) placed
    // over the canvas box it shows; without a layout view it is shown in its
    // own pixels, except a grown tree without a layout, drawn from its stems.
    const grownNoLayout = !a.view && a.root;
    if (a.view) {
      lib.setAttribute('x', box[0]);
      lib.setAttribute('y', box[1]);
      lib.setAttribute('width', box[2] - box[0]);
      lib.setAttribute('height', box[3] - box[1]);
      lib.setAttribute('preserveAspectRatio', 'xMidYMid meet');
      libLayer.appendChild(document.importNode(lib, true));
    } else if (!grownNoLayout) {
      libLayer.appendChild(document.importNode(lib, true));
    }
    const content = a.view || grownNoLayout ? box : [0, 0, Number(lib.getAttribute('width')), Number(lib.getAttribute('height'))];
    state.fitView = content || [0, 0, 100, 100];
    // Refit once the answer is to the new text itself (not to one sent before).
    if (!state.view || (state.refit && app.session.inSync())) {
      state.view = state.fitView.slice();
      state.refit = false;
    }
    // A big tree is drawn from its stems, over the picture's box, at the
    // screen's resolution (replay.show below draws it).
    if (a.tree_in_svg === false) tree.place(libLayer, a, box, shownBox(), (window.devicePixelRatio || 1) / unitsPerPixel());
    el('g', { class: 'grid' }, preview);
    el('g', { class: 'replay-layer' }, preview);
    if (grownNoLayout && a.tree_in_svg !== false) app.replay.showStems(Infinity);
    el('g', { class: 'overlay' }, preview);
    drawOverlay();
    setViewBox();
    app.replay.show();
    app.tools.updateButtons();
  }

  // The empty canvas (an .od without layout shapes): a grid with its
  // coordinates over the view, so the first shape has a reference.
  function drawGrid() {
    const g = preview.querySelector('.grid');
    if (!g) return;
    g.innerHTML = '';
    const v = state.view;
    if (!v || byId('kind').value !== 'od' || state.shapes.length) return;
    const upp = unitsPerPixel();
    const box = shownBox();
    const step = gridStep(Math.max(box[2] - box[0], box[3] - box[1]));
    const font = 10 * upp;
    for (let x = Math.ceil(box[0] / step) * step; x <= box[2]; x += step) {
      el('line', { class: x === 0 ? 'axis' : '', x1: x, y1: box[1], x2: x, y2: box[3] }, g);
      el('text', { x: x + 2 * upp, y: box[1] + font * 1.2, 'font-size': font }, g).textContent = String(Math.round(x * 1000) / 1000);
    }
    for (let y = Math.ceil(box[1] / step) * step; y <= box[3]; y += step) {
      el('line', { class: y === 0 ? 'axis' : '', x1: box[0], y1: y, x2: box[2], y2: y }, g);
      el('text', { x: box[0] + 2 * upp, y: y - 2 * upp, 'font-size': font }, g).textContent = String(Math.round(y * 1000) / 1000);
    }
    g.dataset.step = step;
  }

  // The view box as shown (it keeps its aspect, so it may show more).
  function shownBox() {
    const v = state.view;
    const upp = unitsPerPixel();
    const r = preview.getBoundingClientRect();
    const [cx, cy] = [(v[0] + v[2]) / 2, (v[1] + v[3]) / 2];
    const [hw, hh] = [r.width * upp / 2 || (v[2] - v[0]) / 2, r.height * upp / 2 || (v[3] - v[1]) / 2];
    return [cx - hw, cy - hh, cx + hw, cy + hh];
  }

  // The shape under canvas point `p` (or within a few pixels of its
  // edge): the smallest of them by area, so a small shape is never lost
  // behind a big one, whichever is painted later; -1 for none.
  function hitTest(p) {
    const tol = 4 * unitsPerPixel();
    let best = -1;
    let bestArea = Infinity;
    state.shapes.forEach((s, i) => {
      if (!near(s, p, tol)) return;
      const a = area(s);
      if (a <= bestArea) { best = i; bestArea = a; }
    });
    return best;
  }

  // An answer with errors: the last good picture stays, faded.
  function stale() {
    app.view3d.stale();
    preview.querySelectorAll('.lib, .replay-layer').forEach((g) => g.classList.add('stale'));
  }

  // No picture: the one shown was of another file.
  function forget() {
    app.view3d.hide();
    preview.querySelectorAll('.lib, .replay-layer').forEach((g) => g.remove());
  }

  // The editable outlines of the shapes, the selection's handles, the root.
  function drawOverlay() {
    const ov = overlay();
    if (!ov) return;
    ov.innerHTML = '';
    drawGrid();
    if (byId('kind').value !== 'od') return;
    state.shapes.forEach((s, i) => {
      const e = shapeElement(s, ov);
      e.classList.add('outline');
      if (i === state.selected) e.classList.add('selected');
      e.dataset.index = i;
    });
    const s = state.shapes[state.selected];
    if (s) {
      handlesOf(s).forEach(([x, y], h) => {
        const r = 4 * unitsPerPixel();
        el('rect', { class: 'handle', x: x - r, y: y - r, width: 2 * r, height: 2 * r, 'data-handle': h }, ov);
      });
    }
    if (state.root) {
      el('circle', { class: 'root', cx: state.root[0], cy: state.root[1], r: 5 * unitsPerPixel(), 'data-testid': 'root' }, ov);
    }
    // A forest's further roots: shown, edited in the text.
    (state.others || []).forEach(([x, y], i) => {
      el('circle', { class: 'other-root', cx: x, cy: y, r: 4 * unitsPerPixel(), 'data-testid': `root-${i + 2}` }, ov);
    });
  }

  const overlay = () => preview.querySelector('.overlay');
  // Whether the answer shown is a 3D input's.
  const space = () => !!(state.answer && state.answer.ok && state.answer.space);

  function setViewBox() {
    const v = state.view;
    preview.setAttribute('viewBox', `${v[0]} ${v[1]} ${v[2] - v[0]} ${v[3] - v[1]}`);
    drawGrid();
    tree.viewChanged(shownBox(), (window.devicePixelRatio || 1) / unitsPerPixel());
  }

  function unitsPerPixel() {
    const v = state.view;
    if (!v) return 1;
    const r = preview.getBoundingClientRect();
    if (!r.width || !r.height) return 1;
    return Math.max((v[2] - v[0]) / r.width, (v[3] - v[1]) / r.height);
  }

  // The canvas point under a mouse event.
  function toCanvas(evt) {
    const pt = preview.createSVGPoint();
    pt.x = evt.clientX;
    pt.y = evt.clientY;
    const m = preview.getScreenCTM();
    const p = m ? pt.matrixTransform(m.inverse()) : pt;
    return [p.x, p.y];
  }

  function zoom(factor, at) {
    if (space()) { app.view3d.zoom(factor); return; }
    const v = state.view;
    if (!v) return;
    const [cx, cy] = at || [(v[0] + v[2]) / 2, (v[1] + v[3]) / 2];
    state.view = [cx + (v[0] - cx) * factor, cy + (v[1] - cy) * factor, cx + (v[2] - cx) * factor, cy + (v[3] - cy) * factor];
    setViewBox();
    drawOverlay();
  }

  function pan(from, dx, dy) {
    state.view = [from[0] - dx, from[1] - dy, from[2] - dx, from[3] - dy];
    setViewBox();
  }

  function fit() {
    if (space()) { app.view3d.reset(); return; }
    if (!state.fitView) return;
    state.view = state.fitView.slice();
    setViewBox();
    drawOverlay();
  }

  preview.addEventListener('wheel', (e) => {
    e.preventDefault();
    zoom(e.deltaY > 0 ? 1.15 : 1 / 1.15, toCanvas(e));
  }, { passive: false });
  byId('zoom-in').addEventListener('click', () => zoom(1 / 1.25));
  byId('zoom-out').addEventListener('click', () => zoom(1.25));
  byId('fit').addEventListener('click', fit);

  return { element: preview, tree, draw, stale, forget, drawOverlay, overlay, unitsPerPixel, toCanvas, pan, fit, hitTest };
}
