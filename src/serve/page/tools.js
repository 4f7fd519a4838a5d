// Drawing with the mouse: the tool bar (Select, Rectangle, RoundRect,
// Ellipse, Polygon, Root), the paint colour, moving and resizing shapes,
// panning, Raise / Lower / Delete. Every edit is written into the text by
// layout.js; the answer to the new text then redraws everything.

import { byId, el } from './dom.js';
import { round, withLayout, withRoot } from './layout.js';
import { handlesOf, shapeElement } from './view.js';

export const COLOURS = ['clGreen', 'clWhite', 'clLime', 'clOlive', 'clTeal', 'clNavy', 'clBlue',
  'clAqua', 'clMaroon', 'clRed', 'clPurple', 'clFuchsia', 'clYellow', 'clBlack', 'clGray',
  'clSilver', 'clMoneyGreen', 'clSkyBlue', 'clCream'];

// Drawn coordinates snap to whole canvas units: short, readable text.
const snap = (p) => [Math.round(p[0]), Math.round(p[1])];
const clone = (s) => JSON.parse(JSON.stringify(s));

function box(a, b) {
  return { x: Math.min(a[0], b[0]), y: Math.min(a[1], b[1]), w: Math.abs(a[0] - b[0]), h: Math.abs(a[1] - b[1]) };
}

function translate(s, dx, dy) {
  const t = clone(s);
  if (t.type === 'Polygon') t.points = t.points.map(([x, y]) => [x + dx, y + dy]);
  else { t.x += dx; t.y += dy; }
  return t;
}

// `s` with its handle `h` dragged to `p`.
function resize(s, h, p) {
  const t = clone(s);
  if (t.type === 'Polygon') { t.points[h] = p; return t; }
  const opposite = handlesOf(s)[(h + 2) % 4];
  Object.assign(t, box(opposite, p));
  if (t.type === 'RoundRect') { t.rx = Math.min(t.rx, t.w / 2); t.ry = Math.min(t.ry, t.h / 2); }
  return t;
}

export function createTools(app) {
  const { state, view } = app;
  const preview = view.element;
  const colour = byId('colour');
  let drag = null; // what the mouse is doing
  let poly = null; // the polygon being clicked

  // Writes the shapes into the text's LAYOUT section.
  function commitShapes() {
    const text = app.editor.text();
    const span = app.session.inSync() ? state.layoutSpan : null;
    // Spans of the new text are known only after the next answer; until
    // then, edits locate the section by its keywords.
    app.editor.rewrite(withLayout(text, state.shapes, span));
    view.drawOverlay();
  }

  function moveRoot(p) {
    state.root = snap(p);
    if (app.session.inSync() && state.rootSpan) {
      app.editor.rewrite(withRoot(app.editor.text(), state.root, state.rootSpan));
    }
    view.drawOverlay();
  }

  function setTool(t) {
    state.tool = t;
    cancelPolygon();
    // A new shape gets the paint colour; the selection keeps its own.
    if (t !== 'select' && state.selected >= 0) { state.selected = -1; view.drawOverlay(); }
    document.querySelectorAll('.tool').forEach((b) => b.classList.toggle('active', b.dataset.tool === t));
    preview.classList.toggle('select', t === 'select');
  }

  const ghostParent = () => view.overlay() || preview;
  const removeGhost = () => preview.querySelectorAll('.ghost').forEach((g) => g.remove());

  function drawGhostBox(a, b) {
    removeGhost();
    const bx = box(a, b);
    const r = Math.min(bx.w, bx.h) / 8;
    shapeElement({ type: state.tool, x: bx.x, y: bx.y, w: bx.w, h: bx.h, rx: r, ry: r }, ghostParent()).classList.add('ghost');
  }

  function drawGhostPolygon(p) {
    removeGhost();
    const pts = poly.points.concat([p]);
    el('polyline', { class: 'ghost', points: pts.map((q) => q.join(',')).join(' ') }, ghostParent());
  }

  function cancelPolygon() { poly = null; removeGhost(); }

  function finishPolygon() {
    const pts = poly.points;
    poly = null;
    removeGhost();
    if (pts.length < 3) return;
    addShape({ type: 'Polygon', points: pts, name: colour.value });
  }

  function addShape(s) {
    state.shapes.push(s);
    state.selected = state.shapes.length - 1;
    commitShapes();
  }

  function deleteSelected() {
    if (state.selected < 0) return;
    state.shapes.splice(state.selected, 1);
    state.selected = -1;
    commitShapes();
  }

  function reorder(by) {
    const i = state.selected;
    const j = i + by;
    if (i < 0 || j < 0 || j >= state.shapes.length) return;
    const s = state.shapes;
    [s[i], s[j]] = [s[j], s[i]];
    state.selected = j;
    commitShapes();
  }

  preview.addEventListener('mousedown', (e) => {
    if (e.button !== 0 || byId('kind').value !== 'od' && state.tool !== 'select') return;
    const p = view.toCanvas(e);
    const t = e.target;
    e.preventDefault();
    if (t.classList.contains('root') || state.tool === 'root') {
      drag = { kind: 'root' };
      if (state.tool === 'root') moveRoot(p);
      return;
    }
    if (state.tool === 'select') {
      if (t.classList.contains('handle')) {
        drag = { kind: 'resize', handle: Number(t.dataset.handle), start: p, orig: clone(state.shapes[state.selected]) };
        return;
      }
      if (t.classList.contains('outline')) {
        state.selected = Number(t.dataset.index);
        const s = state.shapes[state.selected];
        colour.value = COLOURS.includes(s.name) ? s.name : colour.value;
        drag = { kind: 'move', start: p, orig: clone(s), moved: false };
        view.drawOverlay();
        return;
      }
      state.selected = -1;
      view.drawOverlay();
      drag = { kind: 'pan', start: [e.clientX, e.clientY], view: state.view.slice(), upp: view.unitsPerPixel() };
      return;
    }
    if (state.tool === 'Polygon') {
      if (!poly) {
        poly = { points: [snap(p)] };
      } else {
        const first = poly.points[0];
        const near = Math.hypot(first[0] - p[0], first[1] - p[1]) < 8 * view.unitsPerPixel();
        if (near && poly.points.length >= 3) { finishPolygon(); return; }
        poly.points.push(snap(p));
      }
      drawGhostPolygon(p);
      return;
    }
    drag = { kind: 'draw', start: p, now: p };
  });

  window.addEventListener('mousemove', (e) => {
    if (poly && !drag) { drawGhostPolygon(view.toCanvas(e)); return; }
    if (!drag) return;
    const p = view.toCanvas(e);
    if (drag.kind === 'pan') {
      view.pan(drag.view, (e.clientX - drag.start[0]) * drag.upp, (e.clientY - drag.start[1]) * drag.upp);
    } else if (drag.kind === 'root') {
      state.root = snap(p);
      view.drawOverlay();
    } else if (drag.kind === 'move') {
      const dx = Math.round(p[0] - drag.start[0]);
      const dy = Math.round(p[1] - drag.start[1]);
      drag.moved = drag.moved || Math.hypot(dx, dy) > 0;
      state.shapes[state.selected] = translate(drag.orig, dx, dy);
      view.drawOverlay();
    } else if (drag.kind === 'resize') {
      state.shapes[state.selected] = resize(drag.orig, drag.handle, snap(p));
      view.drawOverlay();
    } else if (drag.kind === 'draw') {
      drag.now = p;
      drawGhostBox(drag.start, p);
    }
  });

  window.addEventListener('mouseup', (e) => {
    if (!drag) return;
    const d = drag;
    drag = null;
    if (d.kind === 'root') {
      moveRoot(state.root);
    } else if (d.kind === 'move') {
      if (d.moved) commitShapes();
    } else if (d.kind === 'resize') {
      commitShapes();
    } else if (d.kind === 'draw') {
      const b = box(snap(d.start), snap(view.toCanvas(e)));
      removeGhost();
      const upp = view.unitsPerPixel();
      if (b.w * b.h > 0 && b.w / upp >= 3 && b.h / upp >= 3) {
        const s = { type: state.tool, x: b.x, y: b.y, w: b.w, h: b.h, name: colour.value };
        if (s.type === 'RoundRect') { s.rx = s.ry = round(Math.min(b.w, b.h) / 8); }
        addShape(s);
      }
    }
  });

  preview.addEventListener('dblclick', (e) => {
    if (state.tool === 'Polygon' && poly) {
      // The double click's second click added a point on the first's place.
      if (poly.points.length > 3) poly.points.pop();
      finishPolygon();
      e.preventDefault();
    }
  });

  document.querySelectorAll('.tool').forEach((b) => b.addEventListener('click', () => setTool(b.dataset.tool)));
  for (const c of COLOURS) {
    const o = document.createElement('option');
    o.value = c;
    o.textContent = c + (c === 'clGreen' ? ' (grows)' : c === 'clWhite' ? ' (erases)' : '');
    colour.appendChild(o);
  }
  colour.addEventListener('change', () => {
    const s = state.shapes[state.selected];
    if (s) { s.name = colour.value; commitShapes(); }
  });
  byId('delete').addEventListener('click', deleteSelected);
  byId('raise').addEventListener('click', () => reorder(1));
  byId('lower').addEventListener('click', () => reorder(-1));

  return { setTool, cancelPolygon, deleteSelected };
}
