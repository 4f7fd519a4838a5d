// The preview: the library's picture of the last good answer, the editable
// outlines of the shapes over it, the root, and the view box (zoom, pan,
// fit). Zoom and pan move only the view: nothing is rendered again.

import { byId, el } from './dom.js';

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

export function createView(app) {
  const { state } = app;
  const preview = byId('preview');

  // Redraws everything from the last good answer.
  function draw() {
    const a = state.answer;
    if (!a || !a.ok) return;
    preview.innerHTML = '';
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
    el('g', { class: 'replay-layer' }, preview);
    if (grownNoLayout) app.replay.showStems(Infinity);
    el('g', { class: 'overlay' }, preview);
    drawOverlay();
    setViewBox();
    app.replay.show();
  }

  // An answer with errors: the last good picture stays, faded.
  function stale() {
    preview.querySelectorAll('.lib, .replay-layer').forEach((g) => g.classList.add('stale'));
  }

  // The editable outlines of the shapes, the selection's handles, the root.
  function drawOverlay() {
    const ov = overlay();
    if (!ov) return;
    ov.innerHTML = '';
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

  function setViewBox() {
    const v = state.view;
    preview.setAttribute('viewBox', `${v[0]} ${v[1]} ${v[2] - v[0]} ${v[3] - v[1]}`);
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

  return { element: preview, draw, stale, drawOverlay, overlay, unitsPerPixel, toCanvas, pan, fit };
}
