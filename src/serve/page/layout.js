// The one writer of the text's LAYOUT section and root: every drawing edit
// (a shape new, moved, resized, recoloured, duplicated, reordered or
// deleted, the root moved) becomes new text here. Pure functions.
//
// An edit rewrites only the text it is about: one shape's own text (the
// render answer gives each shape's span), or the root's `(x, y)`. Comments,
// line breaks and every other shape's spelling stay byte for byte, also in
// a layout written on one line as the paper prints it. A moved shape keeps
// its own spelling: only the numbers that changed are written anew.
//
// A `doc` is a text and where things are in it: `{text, shapes, layout,
// root, rootAt}`; `shapes` are the answer's shapes (geometry, `name`, and
// `start`/`end`), `layout` and `root` are `[start, end]` spans (or null),
// `rootAt` the root's `[x, y]`. Offsets are UTF-16 (JavaScript indices).
// Every edit returns a new doc whose spans are those of its new text, so
// edits can follow each other before the server has answered.

// A corner radius drawn is written to one decimal.
export function round(v) { return Math.round(v * 10) / 10; }
// Numbers are written with up to three decimals (the model keeps three).
export function num(v) { const r = Math.round(v * 1000) / 1000; return Object.is(r, -0) ? '0' : String(r); }

const NUMBER = /[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?/y;
const clone = (x) => JSON.parse(JSON.stringify(x));

// The parts of one shape's text `(colour) Name args` or `(colour)< Name args>`:
// where its colour and name are, and its numbers with the parenthesis group
// each is in (-1: none).
function parts(t) {
  const col = /^\(\s*([^\s)]+)\s*\)/.exec(t);
  if (!col) return null;
  const name = /[A-Za-z]\w*/g;
  name.lastIndex = col[0].length;
  const n = name.exec(t);
  if (!n) return null;
  const nums = [];
  let group = -1;
  let groups = 0;
  let firstParen = -1;
  for (let i = n.index + n[0].length; i < t.length;) {
    const ch = t[i];
    if (ch === '#') { const e = t.indexOf('\n', i); i = e < 0 ? t.length : e; continue; }
    if (ch === '(') { if (firstParen < 0) firstParen = i; group = groups++; i++; continue; }
    if (ch === ')') { group = -1; i++; continue; }
    NUMBER.lastIndex = i;
    const m = NUMBER.exec(t);
    if (m) { nums.push({ a: i, b: i + m[0].length, v: Number(m[0]), group }); i += m[0].length; continue; }
    i++;
  }
  const colourAt = t.indexOf(col[1], 1);
  return {
    colour: [colourAt, colourAt + col[1].length], colourEnd: col[0].length,
    name: n[0], nameAt: n.index, nameEnd: n.index + n[0].length, firstParen, nums,
  };
}

// Whether a box shape's numbers are Delphi's corners `(x1,y1,x2,y2[,rx2,ry2])`.
const isCorners = (p) => p.nums.length >= 4 && p.nums.every((n) => n.group === 0);

// The numbers of `s` in its spelling; `old`: the numbers written before
// (corners keep their order). Null when the spelling cannot say it (a
// start-point RoundRect has one radius).
function values(s, corners, old) {
  if (s.type === 'Polygon') return s.points.flat();
  if (corners) {
    const xs = old && old[0] > old[2] ? [s.x + s.w, s.x] : [s.x, s.x + s.w];
    const ys = old && old[1] > old[3] ? [s.y + s.h, s.y] : [s.y, s.y + s.h];
    const v = [xs[0], ys[0], xs[1], ys[1]];
    if (s.type === 'RoundRect') v.push(2 * s.rx, 2 * s.ry);
    return v;
  }
  const v = [s.x, s.y, s.w, s.h];
  if (s.type === 'RoundRect') {
    if (num(s.rx) !== num(s.ry)) return null;
    v.push(s.rx);
  }
  return v;
}

// How a shape's text is written: `(c)< Name (...)>` or `(c) Name (...)`,
// commas with or without a space, corners or start point. From `t`, the
// text of a shape of the file, or the page's own spelling.
function styleOf(t) {
  const st = { open: ' ', gap: ' ', close: '', sep: ', ', corners: false };
  const p = t && parts(t);
  if (!p) return st;
  const open = t.slice(p.colourEnd, p.nameAt);
  if (/^\s*<?\s*$/.test(open)) st.open = open.replace(/\n/g, ' ');
  if (open.includes('<')) st.close = '>';
  const gap = t.slice(p.nameEnd, p.firstParen);
  if (p.firstParen > 0 && /^[ \t]*$/.test(gap)) st.gap = gap;
  if (p.nums.length > 1) st.sep = /,[ \t]/.test(t.slice(p.nums[0].a)) ? ', ' : ',';
  st.corners = p.name !== 'Polygon' && isCorners(p);
  return st;
}

// A shape's text, written whole in style `st`.
function fresh(s, st) {
  const j = (a) => a.map(num).join(st.sep);
  let args;
  if (s.type === 'Polygon') {
    args = s.points.map((q) => `(${j(q)})`).join(st.sep);
  } else {
    let corners = st.corners;
    let v = values(s, corners, null);
    if (!v) { corners = true; v = values(s, true, null); }
    args = corners ? `(${j(v)})` : `(${j(v.slice(0, 2))})${st.sep}${j(v.slice(2))}`;
  }
  return `(${s.name})${st.open}${s.type}${st.gap}${args}${st.close}`;
}

// The text `t` of shape `old`, rewritten for `s` (its new geometry and
// colour): only the numbers that changed and the colour, if it changed, are
// written anew (`#0f0` stays so when only moved); a spelling that cannot say
// `s` is written whole in `t`'s style.
export function shapeText(t, s, old) {
  const p = parts(t);
  const v = p && p.name === s.type ? values(s, s.type !== 'Polygon' && isCorners(p), p.nums.map((n) => n.v)) : null;
  if (!v || v.length !== p.nums.length) return fresh(s, styleOf(t));
  let out = t;
  for (let k = p.nums.length - 1; k >= 0; k--) {
    const n = p.nums[k];
    if (Math.abs(v[k] - n.v) > 1e-9) out = out.slice(0, n.a) + num(v[k]) + out.slice(n.b);
  }
  const [a, b] = p.colour;
  if (!old || old.name !== s.name) out = out.slice(0, a) + s.name + out.slice(b);
  return out;
}

// `doc` with [a, b) of its text replaced by `s`; every span after it moves.
function splice(doc, a, b, s) {
  const d = s.length - (b - a);
  const start = (p) => (p >= b ? p + d : p);
  const end = (p) => (p > a && p >= b ? p + d : p);
  const span = (x) => (x ? [start(x[0]), end(x[1])] : x);
  return {
    text: doc.text.slice(0, a) + s + doc.text.slice(b),
    shapes: doc.shapes.map((sh) => Object.assign(clone(sh), { start: start(sh.start), end: end(sh.end) })),
    layout: span(doc.layout),
    root: span(doc.root),
    rootAt: doc.rootAt,
  };
}

// `doc` with `text`, a typed edit of its text, when the edit touched none of
// its spans (else null: wait for the answer to the new text).
export function rebase(doc, text) {
  const old = doc.text;
  let p = 0;
  while (p < old.length && p < text.length && old[p] === text[p]) p++;
  let s = 0;
  while (s < old.length - p && s < text.length - p && old[old.length - 1 - s] === text[text.length - 1 - s]) s++;
  const [a, b] = [p, old.length - s];
  const spans = doc.shapes.map((sh) => [sh.start, sh.end]).concat(doc.root ? [doc.root] : []);
  if (doc.layout) spans.push([doc.layout[0], doc.layout[0] + 6], [doc.layout[1] - 9, doc.layout[1]]);
  if (spans.some(([x, y]) => a < y && b > x)) return null;
  return splice(doc, a, b, text.slice(p, text.length - s));
}

// Shape `i` is now `s` (moved, resized, recoloured).
export function rewriteShape(doc, i, s) {
  const { start, end } = doc.shapes[i];
  const t = shapeText(doc.text.slice(start, end), s, doc.shapes[i]);
  const out = splice(doc, start, end, t);
  out.shapes[i] = Object.assign(clone(s), { start, end: start + t.length });
  return out;
}

// The line of `text` around `i`: [its start, its end (the `\n` or the end)].
function lineOf(text, i) {
  const a = text.lastIndexOf('\n', i - 1) + 1;
  const e = text.indexOf('\n', i);
  return [a, e < 0 ? text.length : e];
}

// A new shape `s`, painted last: one line before ENDLAYOUT, written as the
// file's last shape is (or a new section at the end of the text).
export function insertShape(doc, s) {
  const last = doc.shapes[doc.shapes.length - 1];
  const lastBox = [...doc.shapes].reverse().find((x) => x.type !== 'Polygon');
  const st = styleOf(last ? doc.text.slice(last.start, last.end) : null);
  st.corners = lastBox ? styleOf(doc.text.slice(lastBox.start, lastBox.end)).corners : false;
  const t = fresh(s, st);
  let out;
  let at;
  if (!doc.layout) {
    const sep = doc.text === '' || doc.text.endsWith('\n') ? '' : '\n';
    at = doc.text.length + sep.length + 'LAYOUT\n'.length;
    out = splice(doc, doc.text.length, doc.text.length, `${sep}LAYOUT\n${t}\nENDLAYOUT\n`);
    out.layout = [at - 'LAYOUT\n'.length, at + t.length + '\nENDLAYOUT'.length];
  } else {
    const e = doc.layout[1] - 'ENDLAYOUT'.length;
    const [ls] = lineOf(doc.text, e);
    let ins;
    if (doc.text.slice(ls, e).trim() === '') {
      // ENDLAYOUT on its own line: the shape on a line before it, indented
      // as the last shape's line is.
      let indent = '';
      if (last) {
        const [lls] = lineOf(doc.text, last.start);
        const before = doc.text.slice(lls, last.start);
        if (/^[ \t]*$/.test(before)) indent = before;
      }
      at = ls + indent.length;
      ins = [ls, `${indent}${t}\n`];
    } else {
      // The layout on one line: the shape before ENDLAYOUT on it.
      const space = /\s/.test(doc.text[e - 1]) ? '' : ' ';
      at = e + space.length;
      ins = [e, `${space}${t} `];
    }
    out = splice(doc, ins[0], ins[0], ins[1]);
  }
  out.shapes.push(Object.assign(clone(s), { start: at, end: at + t.length }));
  return out;
}

// A copy `s` of shape `i` (moved), painted just after it: on the next line
// when `i` ends its line, else beside it; written as `i` is.
export function duplicateShape(doc, i, s) {
  const { start, end } = doc.shapes[i];
  const t = shapeText(doc.text.slice(start, end), s, doc.shapes[i]);
  const [, le] = lineOf(doc.text, end);
  const rest = doc.text.slice(end, le);
  const [lls] = lineOf(doc.text, start);
  const indent = doc.text.slice(lls, start);
  let at;
  let out;
  if (/^\s*(#.*)?$/.test(rest) && /^[ \t]*$/.test(indent) && le < doc.text.length) {
    at = le + 1 + indent.length;
    out = splice(doc, le + 1, le + 1, `${indent}${t}\n`);
  } else {
    at = end + 1;
    out = splice(doc, end, end, ` ${t}`);
  }
  out.shapes.splice(i + 1, 0, Object.assign(clone(s), { start: at, end: at + t.length }));
  return out;
}

// Shape `i` removed: its text, and the line it leaves empty (or the spaces
// that joined it to the next shape). Comments stay.
export function deleteShape(doc, i) {
  const { start, end } = doc.shapes[i];
  const text = doc.text;
  const [ls, le] = lineOf(text, start);
  let a = start;
  let b = end;
  if (text.slice(ls, start).trim() === '' && text.slice(end, le).trim() === '' && le < text.length) {
    [a, b] = [ls, le + 1];
  } else {
    const after = /^[ \t]*/.exec(text.slice(end))[0].length;
    if (after > 0 && end + after < le) b = end + after;
    else { while (a > ls && /[ \t]/.test(text[a - 1])) a--; }
  }
  const out = splice(doc, a, b, '');
  out.shapes.splice(i, 1);
  return out;
}

// Shapes `i` < `j` trade places in painting order: their texts swap, the
// text between them stays.
export function swapShapes(doc, i, j) {
  if (i > j) return swapShapes(doc, j, i);
  const [A, B] = [doc.shapes[i], doc.shapes[j]];
  const t = doc.text;
  const mid = t.slice(A.end, B.start);
  const ta = t.slice(A.start, A.end);
  const tb = t.slice(B.start, B.end);
  const out = splice(doc, A.start, B.end, tb + mid + ta);
  out.shapes[i] = Object.assign(clone(B), { start: A.start, end: A.start + tb.length });
  const bj = A.start + tb.length + mid.length;
  out.shapes[j] = Object.assign(clone(A), { start: bj, end: bj + ta.length });
  for (let k = i + 1; k < j; k++) {
    out.shapes[k].start += tb.length - ta.length;
    out.shapes[k].end += tb.length - ta.length;
  }
  return out;
}

// The root moved to `[x, y]`: its `(x, y)` written anew.
export function moveRoot(doc, [x, y]) {
  const [a, b] = doc.root;
  const t = `(${num(x)}, ${num(y)})`;
  const out = splice(doc, a, b, t);
  out.root = [a, a + t.length];
  out.rootAt = [x, y];
  return out;
}
