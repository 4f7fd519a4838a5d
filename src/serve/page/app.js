// stlc serve: the Tree Maker and Tree Renderer page. No framework, no
// request leaves 127.0.0.1. The text is the source of truth: every drawing
// edit rewrites the LAYOUT section (and the root) in the text, and every
// text change is sent to /api/render, whose answer redraws everything.
'use strict';

const $ = (id) => document.getElementById(id);
const SVGNS = 'http://www.w3.org/2000/svg';
const TOKEN = document.querySelector('meta[name="stlc-token"]').content;
const COLOURS = ['clGreen', 'clWhite', 'clLime', 'clOlive', 'clTeal', 'clNavy', 'clBlue',
  'clAqua', 'clMaroon', 'clRed', 'clPurple', 'clFuchsia', 'clYellow', 'clBlack', 'clGray',
  'clSilver', 'clMoneyGreen', 'clSkyBlue', 'clCream'];
const DEBOUNCE_MS = 40;

const src = $('source');
const gutter = $('gutter');
const preview = $('preview');

const state = {
  name: 'untitled.od',
  canSave: false,
  tool: 'select',
  // The last answer and the text it answers.
  answer: null,
  answerText: null,
  // Shapes and root of the last good .od answer (page coordinates = canvas units).
  shapes: [],
  layoutSpan: null,
  root: null,
  rootSpan: null,
  // A forest's roots after the first (shown, not dragged).
  others: [],
  selected: -1,
  view: null, // [minx, miny, maxx, maxy] shown
  fitView: null,
  inFlight: false,
  again: false,
  editedAt: 0,
  timings: [],
  replayTimer: null,
  // Show the whole new picture when its answer comes (a file opened, the
  // kind changed, a description pasted over the old one); drawing never
  // moves the view.
  refit: true,
  // Earlier texts for Ctrl-Z, later ones for Ctrl-Shift-Z / Ctrl-Y.
  undo: [],
  redo: [],
  typedAt: -Infinity,
};
window.stlc = state; // for scripts and the browser test

// ------------------------------------------------------------ editor --

function updateGutter(marks) {
  const lines = src.value.split('\n').length;
  const parts = [];
  for (let i = 1; i <= lines; i++) {
    const m = marks && marks.get(i);
    parts.push(m ? `<span class="${m.cls}" title="${escapeHtml(m.title)}">${i}</span>` : `<span>${i}</span>`);
  }
  gutter.innerHTML = parts.join('');
  gutter.scrollTop = src.scrollTop;
}

function escapeHtml(s) {
  return String(s).replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c]));
}

src.addEventListener('scroll', () => { gutter.scrollTop = src.scrollTop; });
src.addEventListener('beforeinput', (e) => {
  if (e.inputType === 'historyUndo' || e.inputType === 'historyRedo') {
    e.preventDefault();
    if (e.inputType === 'historyUndo') undo(); else redo();
    return;
  }
  // A burst of typing is one undo step: the text before it is kept.
  const now = performance.now();
  if (now - state.typedAt > 1000) remember();
  state.typedAt = now;
  // Pasting over most of the text is a new description: fit it.
  if (e.inputType === 'insertFromPaste' || e.inputType === 'insertFromDrop') {
    const replaced = src.selectionEnd - src.selectionStart;
    if (replaced >= src.value.trim().length / 2) state.refit = true;
  }
});
src.addEventListener('input', () => {
  state.editedAt = performance.now();
  updateGutter(currentMarks);
  schedule();
});
src.addEventListener('keydown', (e) => {
  if (e.key === 'Tab') {
    e.preventDefault();
    src.setRangeText('    ', src.selectionStart, src.selectionEnd, 'end');
    src.dispatchEvent(new Event('input'));
  }
});

let currentMarks = new Map();
let timer = null;
function schedule() {
  clearTimeout(timer);
  timer = setTimeout(refresh, DEBOUNCE_MS);
}

// Keeps `src.value` for Ctrl-Z before an edit replaces it.
function remember() {
  const u = state.undo;
  if (u.length && u[u.length - 1] === src.value) return;
  u.push(src.value);
  if (u.length > 100) u.shift();
  state.redo = [];
}

function undo() { travel(state.undo, state.redo); }
function redo() { travel(state.redo, state.undo); }
function travel(from, to) {
  if (!from.length) return;
  to.push(src.value);
  const text = from.pop();
  state.selected = -1;
  state.typedAt = -Infinity;
  cancelPolygon();
  setText(text);
}

function setText(text) {
  // Keep the caret where it was, as far as possible.
  const pos = src.selectionStart;
  src.value = text;
  src.selectionStart = src.selectionEnd = Math.min(pos, text.length);
  state.editedAt = performance.now();
  updateGutter(currentMarks);
  schedule();
}

// ----------------------------------------------------------- requests --

function request() {
  const r = { source: src.value, kind: $('kind').value, strategy: $('strategy').value };
  const num = (id) => $(id).value.trim();
  if (r.kind === 'od') {
    if (num('clearance') !== '') r.clearance = Number(num('clearance'));
    if (num('max-stems') !== '') r.max_stems = Math.floor(Number(num('max-stems')));
  }
  if (r.kind === 'lsys' && num('depth') !== '') r.depth = Math.floor(Number(num('depth')));
  // A BED has its choices written out: the seed changes nothing there.
  // As a string: a seed is any 64-bit number, more than a JS number holds.
  if (r.kind !== 'bed' && num('seed') !== '') r.seed = num('seed');
  return r;
}

async function post(path, body) {
  return fetch(path, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json', 'X-Stlc-Token': TOKEN },
    body: JSON.stringify(body),
  });
}

// One request at a time; edits made meanwhile are sent when it returns.
async function refresh() {
  if (state.inFlight) { state.again = true; return; }
  state.inFlight = true;
  const req = request();
  const started = state.editedAt || performance.now();
  try {
    const res = await post('/api/render', req);
    const answer = await res.json();
    if (!res.ok) {
      showDiagnostics([{ severity: 'error', message: answer.error || res.statusText, line: null }], req.source);
    } else {
      apply(answer, req.source);
      const ms = performance.now() - started;
      state.timings.push(ms);
      status(answer, ms);
    }
  } catch (e) {
    $('status').textContent = 'The server does not answer: is stlc serve still running? (' + e + ')';
  } finally {
    state.inFlight = false;
    if (state.again) { state.again = false; refresh(); }
  }
}

function status(answer, ms) {
  const parts = [];
  if (answer.ok) {
    parts.push(`${answer.stems} stems`);
    if (answer.growth && answer.growth.decisions) parts.push(`${answer.growth.decisions} growth decisions`);
  } else {
    parts.push('errors: the last good picture is shown');
  }
  parts.push(`${Math.round(ms)} ms from edit to picture`);
  $('status').textContent = parts.join(' · ');
}

// ------------------------------------------------------- diagnostics --

function showDiagnostics(list, text) {
  const ul = $('diagnostics');
  ul.innerHTML = '';
  currentMarks = new Map();
  for (const d of list) {
    const li = document.createElement('li');
    li.className = d.severity;
    li.dataset.line = d.line == null ? '' : d.line;
    const where = d.line == null ? '' : `line ${d.line}, column ${d.column}: `;
    li.innerHTML = `<b>${d.severity}</b> ${escapeHtml(where)}${escapeHtml(d.message)}` +
      (d.label && d.label !== d.message ? ` <i>(${escapeHtml(d.label)})</i>` : '') +
      (d.help ? `<span class="help">help: ${escapeHtml(d.help)}</span>` : '');
    if (d.line != null) {
      li.addEventListener('click', () => goTo(d.line, d.column));
      const prev = currentMarks.get(d.line);
      if (!prev || d.severity === 'error') currentMarks.set(d.line, { cls: d.severity, title: d.message });
    }
    ul.appendChild(li);
  }
  updateGutter(currentMarks);
}

function goTo(line, column) {
  const lines = src.value.split('\n');
  let p = 0;
  for (let i = 0; i < line - 1 && i < lines.length; i++) p += lines[i].length + 1;
  p += Math.max(0, column - 1);
  src.focus();
  src.setSelectionRange(p, p + 1);
}

// ------------------------------------------------------------ answers --

function apply(answer, text) {
  state.answer = answer;
  state.answerText = text;
  if (!answer.ok) {
    showDiagnostics(answer.diagnostics, text);
    preview.querySelectorAll('.lib, .replay-layer').forEach((g) => g.classList.add('stale'));
    return;
  }
  showDiagnostics(answer.warnings, text);
  if (answer.root) {
    state.root = [answer.root.x, answer.root.y];
    state.rootSpan = [answer.root.start, answer.root.end];
    state.others = (answer.root.others || []).map((r) => [r.x, r.y]);
    state.layoutSpan = answer.layout ? [answer.layout.start, answer.layout.end] : null;
    state.shapes = answer.layout ? answer.layout.shapes.map((s) => Object.assign({}, s)) : [];
  } else {
    state.root = null;
    state.others = [];
    state.shapes = [];
    state.layoutSpan = null;
  }
  if (state.selected >= state.shapes.length) state.selected = -1;
  const step = $('step');
  const decisions = answer.growth ? answer.growth.decisions : 0;
  step.max = decisions;
  step.value = decisions;
  stopReplay();
  draw();
}

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

// ------------------------------------------------------------- drawing --

function el(name, attrs, parent) {
  const e = document.createElementNS(SVGNS, name);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (parent) parent.appendChild(e);
  return e;
}

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
  if (!state.view || (state.refit && state.answerText === src.value)) {
    state.view = state.fitView.slice();
    state.refit = false;
  }
  el('g', { class: 'replay-layer' }, preview);
  if (grownNoLayout) showStems(Infinity);
  el('g', { class: 'overlay' }, preview);
  drawOverlay();
  setViewBox();
  replayTo(Number($('step').value), false);
}

function strokeColour() {
  const p = preview.querySelector('.lib path[fill="none"]');
  return p ? p.getAttribute('stroke') : '#4a2c12';
}

// Draws the stems of decisions 0..k from the growth order.
function showStems(k) {
  const layer = preview.querySelector('.replay-layer');
  layer.innerHTML = '';
  const g = state.answer.growth.stems;
  const byWidth = new Map();
  for (let i = 0; i < g.length; i += 6) {
    if (g[i + 5] > k) continue;
    const w = g[i + 4];
    const d = byWidth.get(w) || [];
    d.push(`M${g[i]} ${g[i + 1]}L${g[i + 2]} ${g[i + 3]}`);
    byWidth.set(w, d);
  }
  const colour = strokeColour();
  for (const [w, d] of byWidth) {
    el('path', {
      d: d.join(''), fill: 'none', stroke: colour, 'stroke-width': Math.max(w, 0.3),
      'stroke-linecap': 'round', 'stroke-linejoin': 'round',
    }, layer);
  }
}

function replayTo(k, fromUser) {
  const a = state.answer;
  if (!a || !a.ok || !a.growth) return;
  const max = a.growth.decisions;
  const partial = k < max;
  const grownNoLayout = !a.view && a.root;
  preview.classList.toggle('replaying', partial && !grownNoLayout);
  if (partial || grownNoLayout) showStems(k);
  else preview.querySelector('.replay-layer').innerHTML = '';
  const stems = countStems(k);
  $('step-label').textContent = max ? `decision ${k} of ${max} · ${stems} stems` : '';
  if (fromUser) stopReplay(true);
}

function countStems(k) {
  const g = state.answer.growth.stems;
  let n = 0;
  for (let i = 5; i < g.length; i += 6) if (g[i] <= k) n++;
  return n;
}

function stopReplay(keep) {
  if (state.replayTimer) clearInterval(state.replayTimer);
  state.replayTimer = null;
  $('play').textContent = '▶ Replay';
  if (!keep) preview.classList.remove('replaying');
}

$('step').addEventListener('input', () => replayTo(Number($('step').value), true));
$('play').addEventListener('click', () => {
  if (state.replayTimer) { stopReplay(true); return; }
  const step = $('step');
  const max = Number(step.max);
  if (!max) return;
  if (Number(step.value) >= max) step.value = 0;
  // About four seconds whatever the size.
  const per = Math.max(1, Math.ceil(max / 120));
  $('play').textContent = '❚❚ Pause';
  state.replayTimer = setInterval(() => {
    const v = Math.min(max, Number(step.value) + per);
    step.value = v;
    replayTo(v, false);
    if (v >= max) stopReplay(false);
  }, 33);
});

// The editable outlines of the shapes, the selection's handles, the root.
function drawOverlay() {
  const ov = preview.querySelector('.overlay');
  if (!ov) return;
  ov.innerHTML = '';
  if ($('kind').value !== 'od') return;
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

function shapeElement(s, parent) {
  switch (s.type) {
    case 'Rectangle': return el('rect', { x: s.x, y: s.y, width: s.w, height: s.h }, parent);
    case 'RoundRect': return el('rect', { x: s.x, y: s.y, width: s.w, height: s.h, rx: s.rx, ry: s.ry }, parent);
    case 'Ellipse': return el('ellipse', { cx: s.x + s.w / 2, cy: s.y + s.h / 2, rx: s.w / 2, ry: s.h / 2 }, parent);
    default: return el('polygon', { points: s.points.map((p) => p.join(',')).join(' ') }, parent);
  }
}

function handlesOf(s) {
  if (s.type === 'Polygon') return s.points;
  return [[s.x, s.y], [s.x + s.w, s.y], [s.x + s.w, s.y + s.h], [s.x, s.y + s.h]];
}

// ------------------------------------------------------- view: zoom, pan --

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

preview.addEventListener('wheel', (e) => {
  e.preventDefault();
  zoom(e.deltaY > 0 ? 1.15 : 1 / 1.15, toCanvas(e));
}, { passive: false });
$('zoom-in').addEventListener('click', () => zoom(1 / 1.25));
$('zoom-out').addEventListener('click', () => zoom(1.25));
$('fit').addEventListener('click', fit);
function fit() {
  if (!state.fitView) return;
  state.view = state.fitView.slice();
  setViewBox();
  drawOverlay();
}

// ------------------------------------------------------------- tools --

document.querySelectorAll('.tool').forEach((b) => b.addEventListener('click', () => setTool(b.dataset.tool)));
function setTool(t) {
  state.tool = t;
  cancelPolygon();
  // A new shape gets the paint colour; the selection keeps its own.
  if (t !== 'select' && state.selected >= 0) { state.selected = -1; drawOverlay(); }
  document.querySelectorAll('.tool').forEach((b) => b.classList.toggle('active', b.dataset.tool === t));
  preview.classList.toggle('select', t === 'select');
}

for (const c of COLOURS) {
  const o = document.createElement('option');
  o.value = c;
  o.textContent = c + (c === 'clGreen' ? ' (grows)' : c === 'clWhite' ? ' (erases)' : '');
  $('colour').appendChild(o);
}
$('colour').addEventListener('change', () => {
  const s = state.shapes[state.selected];
  if (s) { s.name = $('colour').value; commitShapes(); }
});

let drag = null; // what the mouse is doing
let poly = null; // the polygon being clicked

preview.addEventListener('mousedown', (e) => {
  if (e.button !== 0 || $('kind').value !== 'od' && state.tool !== 'select') return;
  const p = toCanvas(e);
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
      $('colour').value = COLOURS.includes(s.name) ? s.name : $('colour').value;
      drag = { kind: 'move', start: p, orig: clone(s), moved: false };
      drawOverlay();
      return;
    }
    state.selected = -1;
    drawOverlay();
    drag = { kind: 'pan', start: [e.clientX, e.clientY], view: state.view.slice(), upp: unitsPerPixel() };
    return;
  }
  if (state.tool === 'Polygon') {
    if (!poly) {
      poly = { points: [snap(p)] };
    } else {
      const first = poly.points[0];
      const near = Math.hypot(first[0] - p[0], first[1] - p[1]) < 8 * unitsPerPixel();
      if (near && poly.points.length >= 3) { finishPolygon(); return; }
      poly.points.push(snap(p));
    }
    drawGhostPolygon(p);
    return;
  }
  drag = { kind: 'draw', start: p, now: p };
});

window.addEventListener('mousemove', (e) => {
  if (poly && !drag) { drawGhostPolygon(toCanvas(e)); return; }
  if (!drag) return;
  const p = toCanvas(e);
  if (drag.kind === 'pan') {
    const dx = (e.clientX - drag.start[0]) * drag.upp;
    const dy = (e.clientY - drag.start[1]) * drag.upp;
    const v = drag.view;
    state.view = [v[0] - dx, v[1] - dy, v[2] - dx, v[3] - dy];
    setViewBox();
  } else if (drag.kind === 'root') {
    state.root = snap(p);
    drawOverlay();
  } else if (drag.kind === 'move') {
    const dx = Math.round(p[0] - drag.start[0]);
    const dy = Math.round(p[1] - drag.start[1]);
    drag.moved = drag.moved || Math.hypot(dx, dy) > 0;
    state.shapes[state.selected] = translate(drag.orig, dx, dy);
    drawOverlay();
  } else if (drag.kind === 'resize') {
    state.shapes[state.selected] = resize(drag.orig, drag.handle, snap(p));
    drawOverlay();
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
    const b = box(snap(d.start), snap(toCanvas(e)));
    removeGhost();
    if (b.w * b.h > 0 && b.w / unitsPerPixel() >= 3 && b.h / unitsPerPixel() >= 3) {
      const s = { type: state.tool, x: b.x, y: b.y, w: b.w, h: b.h, name: $('colour').value };
      if (s.type === 'RoundRect') { s.rx = s.ry = round(Math.min(b.w, b.h) / 8); }
      state.shapes.push(s);
      state.selected = state.shapes.length - 1;
      commitShapes();
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

window.addEventListener('keydown', (e) => {
  // Number fields keep their own undo; the editor and the rest share ours.
  if (e.target === src || e.target.tagName === 'INPUT') {
    if ((e.ctrlKey || e.metaKey) && e.key === 's') { e.preventDefault(); save(); }
    else if (e.target === src) undoKey(e);
    return;
  }
  if ((e.ctrlKey || e.metaKey) && e.key === 's') { e.preventDefault(); save(); return; }
  if (undoKey(e)) return;
  if (e.key === 'Escape') cancelPolygon();
  else if (e.key === 'Delete' || e.key === 'Backspace') deleteSelected();
  else if (e.key === 'f') fit();
  else if (e.key === 's') setTool('select');
  else if (e.key === 'r') setTool('Rectangle');
  else if (e.key === 'o') setTool('RoundRect');
  else if (e.key === 'e') setTool('Ellipse');
  else if (e.key === 'p') setTool('Polygon');
});

// Ctrl-Z, Ctrl-Shift-Z and Ctrl-Y, in the editor and out of it: one
// history for typing and drawing (the browser's own is lost whenever a
// drawing edit rewrites the text).
function undoKey(e) {
  if (!(e.ctrlKey || e.metaKey) || e.altKey) return false;
  const k = e.key.toLowerCase();
  if (k === 'z' && !e.shiftKey) undo();
  else if ((k === 'z' && e.shiftKey) || k === 'y') redo();
  else return false;
  e.preventDefault();
  return true;
}

$('delete').addEventListener('click', deleteSelected);
$('raise').addEventListener('click', () => reorder(1));
$('lower').addEventListener('click', () => reorder(-1));

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

// Drawn coordinates snap to whole canvas units: short, readable text.
function snap(p) { return [Math.round(p[0]), Math.round(p[1])]; }

function clone(s) { return JSON.parse(JSON.stringify(s)); }

function translate(s, dx, dy) {
  const t = clone(s);
  if (t.type === 'Polygon') t.points = t.points.map(([x, y]) => [x + dx, y + dy]);
  else { t.x += dx; t.y += dy; }
  return t;
}

function resize(s, h, p) {
  const t = clone(s);
  if (t.type === 'Polygon') { t.points[h] = p; return t; }
  const corners = handlesOf(s);
  const opposite = corners[(h + 2) % 4];
  const b = box(opposite, p);
  Object.assign(t, b);
  if (t.type === 'RoundRect') { t.rx = Math.min(t.rx, t.w / 2); t.ry = Math.min(t.ry, t.h / 2); }
  return t;
}

function box(a, b) {
  return { x: Math.min(a[0], b[0]), y: Math.min(a[1], b[1]), w: Math.abs(a[0] - b[0]), h: Math.abs(a[1] - b[1]) };
}

function drawGhostBox(a, b) {
  removeGhost();
  const bx = box(a, b);
  const s = { type: state.tool, x: bx.x, y: bx.y, w: bx.w, h: bx.h, rx: Math.min(bx.w, bx.h) / 8, ry: Math.min(bx.w, bx.h) / 8 };
  const e = shapeElement(s, preview.querySelector('.overlay') || preview);
  e.classList.add('ghost');
}

function drawGhostPolygon(p) {
  removeGhost();
  const pts = poly.points.concat([p]);
  el('polyline', { class: 'ghost', points: pts.map((q) => q.join(',')).join(' ') }, preview.querySelector('.overlay') || preview);
}

function removeGhost() { preview.querySelectorAll('.ghost').forEach((g) => g.remove()); }

function cancelPolygon() { poly = null; removeGhost(); }

function finishPolygon() {
  const pts = poly.points;
  poly = null;
  removeGhost();
  if (pts.length < 3) return;
  state.shapes.push({ type: 'Polygon', points: pts, name: $('colour').value });
  state.selected = state.shapes.length - 1;
  commitShapes();
}

function moveRoot(p) {
  state.root = snap(p);
  const text = src.value;
  const inSync = text === state.answerText && state.rootSpan;
  if (!inSync) { drawOverlay(); return; }
  const [a, b] = state.rootSpan;
  remember();
  state.typedAt = -Infinity;
  setText(text.slice(0, a) + `(${num(state.root[0])}, ${num(state.root[1])})` + text.slice(b));
  drawOverlay();
}

// --------------------------------------------------- writing the text --

function round(v) { return Math.round(v * 10) / 10; }
function num(v) { const r = round(v); return Object.is(r, -0) ? '0' : String(r); }

function shapeLine(s) {
  const c = `(${s.name})`;
  switch (s.type) {
    case 'Rectangle': return `${c} Rectangle (${num(s.x)}, ${num(s.y)}), ${num(s.w)}, ${num(s.h)}`;
    case 'Ellipse': return `${c} Ellipse (${num(s.x)}, ${num(s.y)}), ${num(s.w)}, ${num(s.h)}`;
    case 'RoundRect':
      if (round(s.rx) === round(s.ry)) return `${c} RoundRect (${num(s.x)}, ${num(s.y)}), ${num(s.w)}, ${num(s.h)}, ${num(s.rx)}`;
      return `${c} RoundRect (${num(s.x)}, ${num(s.y)}, ${num(s.x + s.w)}, ${num(s.y + s.h)}, ${num(2 * s.rx)}, ${num(2 * s.ry)})`;
    default: return `${c} Polygon ${s.points.map(([x, y]) => `(${num(x)}, ${num(y)})`).join(', ')}`;
  }
}

function layoutText() {
  return 'LAYOUT\n' + state.shapes.map((s) => shapeLine(s) + '\n').join('') + 'ENDLAYOUT';
}

// Writes the shapes into the text's LAYOUT section (or a new one at the end).
function commitShapes() {
  const text = src.value;
  let a;
  let b;
  if (text === state.answerText && state.layoutSpan) {
    [a, b] = state.layoutSpan;
  } else {
    const m = /\bLAYOUT\b[\s\S]*?(\bENDLAYOUT\b|$)/.exec(text);
    if (m) { a = m.index; b = m.index + m[0].length; }
  }
  let next;
  if (a === undefined) {
    next = text.replace(/\s*$/, '') + '\n' + layoutText() + '\n';
  } else {
    // A layout on one line with the rules (2dtree.od) starts on its own line now.
    const before = text.slice(0, a);
    const sep = before === '' || before.endsWith('\n') ? '' : '\n';
    next = before + sep + layoutText() + text.slice(b);
  }
  // Spans of the new text are known only after the next answer; until
  // then, edits locate the section by its keywords.
  remember();
  state.typedAt = -Infinity;
  setText(next);
  drawOverlay();
}

// ------------------------------------------------------- kind, files --

function setKind(kind) {
  $('kind').value = kind;
  document.body.classList.toggle('renderer', kind !== 'od');
  document.body.classList.toggle('lsys', kind === 'lsys');
  document.body.classList.toggle('bed', kind === 'bed');
  $('mode-name').textContent = kind === 'od' ? 'Tree Maker' : 'Tree Renderer';
  state.refit = true;
}

$('kind').addEventListener('change', () => { setKind($('kind').value); schedule(); });
$('reseed').addEventListener('click', () => {
  const now = $('seed').value.trim();
  let next = 1n;
  try { if (now !== '') next = BigInt(now) + 1n; } catch (e) { next = 1n; }
  $('seed').value = String(next);
  state.editedAt = performance.now();
  schedule();
});
['strategy', 'clearance', 'max-stems', 'depth', 'seed'].forEach((id) => $(id).addEventListener('input', () => {
  state.editedAt = performance.now();
  schedule();
}));
$('strategy').addEventListener('change', () => { state.editedAt = performance.now(); schedule(); });

$('open').addEventListener('click', () => $('open-file').click());
$('open-file').addEventListener('change', async () => {
  const input = $('open-file');
  const f = input.files[0];
  if (!f) return;
  const text = await f.text();
  // Cleared, so that opening the same file again reads it again.
  input.value = '';
  const ext = (f.name.split('.').pop() || '').toLowerCase();
  setKind(ext === 'bed' ? 'bed' : ext === 'lsys' || ext === 'ls' ? 'lsys' : 'od');
  state.name = f.name;
  state.canSave = false;
  $('file-name').textContent = f.name + ' (Save downloads)';
  document.title = `${f.name} - stlc`;
  state.selected = -1;
  cancelPolygon();
  // A new file starts a new history.
  state.undo = [];
  state.redo = [];
  state.typedAt = -Infinity;
  src.selectionStart = src.selectionEnd = 0;
  setText(text);
});

function download(blob, name) {
  // What was offered last, for scripts and tests.
  state.lastDownload = { name, size: blob.size, type: blob.type };
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

function baseName() { return state.name.replace(/\.[^.]*$/, ''); }

async function exportAs(format) {
  const res = await post('/api/export?format=' + format, request());
  const type = res.headers.get('Content-Type') || '';
  if (type.startsWith('application/json')) {
    const a = await res.json();
    showDiagnostics(a.diagnostics || [{ severity: 'error', message: a.error, line: null }], src.value);
    return;
  }
  download(await res.blob(), `${baseName()}.${format}`);
}
$('export-png').addEventListener('click', () => exportAs('png'));
$('export-svg').addEventListener('click', () => exportAs('svg'));
$('export-bed').addEventListener('click', () => exportAs('bed'));

$('save').addEventListener('click', save);
async function save() {
  if (!state.canSave) {
    download(new Blob([src.value], { type: 'text/plain' }), state.name);
    return;
  }
  const res = await post('/api/save', { source: src.value });
  const a = await res.json().catch(() => ({}));
  if (res.ok && a.ok) {
    $('saved').textContent = `Saved ${state.name} at ${new Date().toLocaleTimeString()}.`;
    document.title = `${state.name} - stlc`;
  } else {
    $('saved').textContent = 'Not saved: ' + (a.error || (a.diagnostics && a.diagnostics.map((d) => d.message).join('; ')) || res.statusText);
  }
}

// ------------------------------------------------------------- start --

(async function start() {
  setTool('select');
  const res = await fetch('/api/file');
  const f = await res.json();
  state.name = f.name;
  state.canSave = f.can_save;
  $('file-name').textContent = f.name + (f.can_save ? '' : ' (example; Save downloads)');
  document.title = `${f.name} - stlc`;
  setKind(f.kind);
  src.value = f.text;
  updateGutter();
  refresh();
}());
