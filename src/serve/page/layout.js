// The one writer of the text's LAYOUT section and root: every drawing edit
// (new, moved, resized, recoloured, reordered or deleted shapes, the root
// moved) becomes new text here. Pure functions of the text.
//
// Spans are the render answer's `start`/`end`: UTF-16 offsets, JavaScript
// string indices. A span is only valid for the text it was answered for;
// callers pass `null` when the text has changed since, and the section is
// then found by its keywords.

// Coordinates are written to one decimal.
export function round(v) { return Math.round(v * 10) / 10; }
export function num(v) { const r = round(v); return Object.is(r, -0) ? '0' : String(r); }

// One shape's line, in the start-point spelling:
// `(clGreen) Rectangle (x, y), w, h`.
export function shapeLine(s) {
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

// The whole section, one shape a line, in painting order.
export function layoutSection(shapes) {
  return 'LAYOUT\n' + shapes.map((s) => shapeLine(s) + '\n').join('') + 'ENDLAYOUT';
}

// `text` with its LAYOUT section replaced by `shapes` (or a new section at
// the end). `span` is where the section is in `text`, or null.
export function withLayout(text, shapes, span) {
  let a;
  let b;
  if (span) {
    [a, b] = span;
  } else {
    const m = /\bLAYOUT\b[\s\S]*?(\bENDLAYOUT\b|$)/.exec(text);
    if (m) { a = m.index; b = m.index + m[0].length; }
  }
  if (a === undefined) return text.replace(/\s*$/, '') + '\n' + layoutSection(shapes) + '\n';
  // A layout on one line with the rules (2dtree.od) starts on its own line now.
  const before = text.slice(0, a);
  const sep = before === '' || before.endsWith('\n') ? '' : '\n';
  return before + sep + layoutSection(shapes) + text.slice(b);
}

// `text` with the root written at `span` replaced by `(x, y)`.
export function withRoot(text, [x, y], span) {
  const [a, b] = span;
  return text.slice(0, a) + `(${num(x)}, ${num(y)})` + text.slice(b);
}
