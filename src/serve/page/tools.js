// Drawing with the mouse, as in a painting program: the tool bar (Select,
// Rectangle, RoundRect, Ellipse, Polygon, Root), the paint colour (for the
// next shape only) and Recolour (the selection, on purpose), moving and
// resizing shapes, panning, Raise / Lower / Delete, arrow keys to nudge,
// Ctrl-D to duplicate, Shift to constrain. Every edit is written into the
// text by layout.js, which rewrites only the shape (or root) it is about;
// the answer to the new text then redraws everything.

import { byId, el } from './dom.js';
import {
  deleteShape, duplicateShape, insertShape, moveRoot as writeRoot, rebase, rewriteShape, round,
  swapShapes,
} from './layout.js';
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

// Shift held: `b` moved so that a..b is a square's diagonal.
function square(a, b) {
  const d = Math.max(Math.abs(b[0] - a[0]), Math.abs(b[1] - a[1]));
  return [a[0] + Math.sign(b[0] - a[0] || 1) * d, a[1] + Math.sign(b[1] - a[1] || 1) * d];
}

// Shift held: `b` moved so that a..b is horizontal, vertical or at 45 degrees.
function angle45(a, b) {
  const dx = b[0] - a[0];
  const dy = b[1] - a[1];
  const t = Math.tan(Math.PI * 3 / 8);
  if (Math.abs(dx) > t * Math.abs(dy)) return [b[0], a[1]];
  if (Math.abs(dy) > t * Math.abs(dx)) return [a[0], b[1]];
  const d = (Math.abs(dx) + Math.abs(dy)) / 2;
  return [a[0] + Math.sign(dx) * d, a[1] + Math.sign(dy) * d];
}

export function translate(s, dx, dy) {
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
  const recolourButton = byId('recolour');
  let drag = null; // what the mouse is doing
  let poly = null; // the polygon being clicked

  // The text now and where its shapes and root are (layout.js's doc): the
  // last drawing edit's, or the last good answer's moved past typing that
  // touched no shape; null until the answer to a typed shape comes.
  function current() {
    const text = app.editor.text();
    const d = state.drawn;
    if (!d) return null;
    return d.text === text ? d : rebase(d, text);
  }

  // Applies a drawing edit `fn(doc)` to the text; `select` picks the
  // selection after it (an index, or a function of the new doc).
  function edit(fn, select) {
    const d = current();
    if (!d) {
      byId('status').textContent = 'Waiting for the picture of the text as typed; draw again in a moment.';
      return false;
    }
    const out = fn(d);
    if (out.text === d.text) { view.drawOverlay(); return false; } // nothing changed: no undo step
    state.drawn = out;
    state.shapes = clone(out.shapes);
    state.layoutSpan = out.layout;
    state.rootSpan = out.root;
    state.root = out.rootAt;
    if (select !== undefined) state.selected = typeof select === 'function' ? select(out) : select;
    app.editor.rewrite(out.text);
    view.drawOverlay();
    updateButtons();
    return true;
  }

  function setTool(t) {
    state.tool = t;
    cancelPolygon();
    document.querySelectorAll('.tool').forEach((b) => b.classList.toggle('active', b.dataset.tool === t));
    preview.classList.toggle('select', t === 'select');
  }

  // Recolour is for a selected shape whose colour is not the paint's.
  function updateButtons() {
    const s = state.shapes[state.selected];
    recolourButton.disabled = !s || s.name === colour.value;
    ['raise', 'lower', 'delete'].forEach((id) => { byId(id).disabled = !s; });
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

  // The polygon's next point for the pointer at `p`: on 45 degrees from
  // the last point with Shift.
  function polygonPoint(p, shift) {
    const last = poly && poly.points[poly.points.length - 1];
    return snap(last && shift ? angle45(last, p) : p);
  }

  function finishPolygon() {
    const pts = poly.points;
    poly = null;
    removeGhost();
    if (pts.length < 3) return;
    addShape({ type: 'Polygon', points: pts, name: colour.value });
  }

  // A new shape, painted last, selected (the paint colour stays the paint
  // colour: choosing the next one never touches this shape).
  function addShape(s) {
    edit((d) => insertShape(d, s), (d) => d.shapes.length - 1);
  }

  function deleteSelected() {
    if (state.selected < 0 || !state.shapes[state.selected]) return;
    const i = state.selected;
    edit((d) => deleteShape(d, i), -1);
  }

  function reorder(by) {
    const i = state.selected;
    const j = i + by;
    if (i < 0 || j < 0 || j >= state.shapes.length) return;
    edit((d) => swapShapes(d, i, j), j);
  }

  function recolour() {
    const i = state.selected;
    const s = state.shapes[i];
    if (!s || s.name === colour.value) return;
    edit((d) => rewriteShape(d, i, Object.assign(clone(d.shapes[i]), { name: colour.value })), i);
  }

  function nudge(dx, dy) {
    const i = state.selected;
    if (!state.shapes[i]) return;
    edit((d) => rewriteShape(d, i, translate(d.shapes[i], dx, dy)), i);
  }

  function duplicate() {
    const i = state.selected;
    if (!state.shapes[i]) return;
    edit((d) => duplicateShape(d, i, translate(d.shapes[i], 10, 10)), i + 1);
  }

  preview.addEventListener('mousedown', (e) => {
    if (e.button !== 0 || byId('kind').value !== 'od' && state.tool !== 'select') return;
    const p = view.toCanvas(e);
    const t = e.target;
    e.preventDefault();
    // Keys (arrows, Ctrl-D, Delete) are for the canvas now.
    preview.focus({ preventScroll: true });
    if (t.classList.contains('root') || state.tool === 'root') {
      drag = { kind: 'root' };
      if (state.tool === 'root') { state.root = snap(p); view.drawOverlay(); }
      return;
    }
    if (state.tool === 'select') {
      if (t.classList.contains('handle')) {
        drag = { kind: 'resize', handle: Number(t.dataset.handle), start: p, orig: clone(state.shapes[state.selected]) };
        return;
      }
      const hit = byId('kind').value === 'od' ? view.hitTest(p) : -1;
      if (hit >= 0) {
        state.selected = hit;
        drag = { kind: 'move', start: p, orig: clone(state.shapes[hit]), moved: false };
        view.drawOverlay();
        updateButtons();
        return;
      }
      state.selected = -1;
      view.drawOverlay();
      updateButtons();
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
        poly.points.push(polygonPoint(p, e.shiftKey));
      }
      drawGhostPolygon(polygonPoint(p, e.shiftKey));
      return;
    }
    drag = { kind: 'draw', start: p };
  });

  window.addEventListener('mousemove', (e) => {
    if (poly && !drag) { drawGhostPolygon(polygonPoint(view.toCanvas(e), e.shiftKey)); return; }
    if (!drag) return;
    const p = view.toCanvas(e);
    if (drag.kind === 'pan') {
      view.pan(drag.view, (e.clientX - drag.start[0]) * drag.upp, (e.clientY - drag.start[1]) * drag.upp);
    } else if (drag.kind === 'root') {
      state.root = snap(p);
      view.drawOverlay();
    } else if (drag.kind === 'move') {
      let dx = Math.round(p[0] - drag.start[0]);
      let dy = Math.round(p[1] - drag.start[1]);
      // Shift: along one axis only.
      if (e.shiftKey) { if (Math.abs(dx) > Math.abs(dy)) dy = 0; else dx = 0; }
      drag.moved = drag.moved || Math.hypot(dx, dy) > 0;
      drag.now = translate(drag.orig, dx, dy);
      state.shapes[state.selected] = drag.now;
      view.drawOverlay();
    } else if (drag.kind === 'resize') {
      drag.now = resize(drag.orig, drag.handle, snap(p));
      state.shapes[state.selected] = drag.now;
      view.drawOverlay();
    } else if (drag.kind === 'draw') {
      drawGhostBox(drag.start, e.shiftKey ? square(drag.start, p) : p);
    }
  });

  window.addEventListener('mouseup', (e) => {
    if (!drag) return;
    const d = drag;
    drag = null;
    const i = state.selected;
    if (d.kind === 'root') {
      const at = state.root;
      edit((doc) => (doc.root ? writeRoot(doc, at) : doc));
    } else if ((d.kind === 'move' && d.moved) || (d.kind === 'resize' && d.now)) {
      edit((doc) => rewriteShape(doc, i, d.now), i);
    } else if (d.kind === 'draw') {
      const end = view.toCanvas(e);
      const b = box(snap(d.start), snap(e.shiftKey ? square(d.start, end) : end));
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

  // Arrow keys nudge the selection by 1 unit (Shift: 10); Ctrl-D
  // duplicates it. Not while typing in the editor or a field.
  const ARROWS = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] };
  window.addEventListener('keydown', (e) => {
    const t = e.target;
    if (t === app.editor.element || ['INPUT', 'SELECT', 'TEXTAREA'].includes(t.tagName)) return;
    if (byId('kind').value !== 'od' || !state.shapes[state.selected] || e.altKey) return;
    const arrow = ARROWS[e.key];
    if (arrow && !e.ctrlKey && !e.metaKey) {
      const k = e.shiftKey ? 10 : 1;
      nudge(arrow[0] * k, arrow[1] * k);
      e.preventDefault();
    } else if ((e.ctrlKey || e.metaKey) && e.key.toLowerCase() === 'd') {
      duplicate();
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
  // The paint colour is for the next shape: picking it changes no shape.
  colour.addEventListener('change', updateButtons);
  recolourButton.addEventListener('click', recolour);
  byId('delete').addEventListener('click', deleteSelected);
  byId('raise').addEventListener('click', () => reorder(1));
  byId('lower').addEventListener('click', () => reorder(-1));

  return { setTool, cancelPolygon, deleteSelected, updateButtons };
}
