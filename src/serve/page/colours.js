// Colours in the text (pure; tested in Node): a colour as `#rrggbb` for a
// colour field, a stem colour with a ramp's far end kept, and an .lsys's
// `palette` line, where each colour is and the line with one of them
// rewritten (docs/lsys.md, *Colours, widths and organs*). Nothing else of
// the text changes.

// Delphi's standard colours, as src/color.rs reads them (a Node test
// holds this table to that one).
const DELPHI = {
  clblack: '#000000', clmaroon: '#800000', clgreen: '#008000', clolive: '#808000',
  clnavy: '#000080', clpurple: '#800080', clteal: '#008080', clgray: '#808080',
  clsilver: '#c0c0c0', clred: '#ff0000', cllime: '#00ff00', clyellow: '#ffff00',
  clblue: '#0000ff', clfuchsia: '#ff00ff', claqua: '#00ffff', clwhite: '#ffffff',
  clmoneygreen: '#c0dcc0', clskyblue: '#a6caf0', clcream: '#fffbf0', clmedgray: '#a4a0a0',
  cldkgray: '#808080', clltgray: '#c0c0c0',
};

/**
 * A colour of the text (`#rrggbb`, `#rgb` or a Delphi name, any case) as
 * a colour field's `#rrggbb`, or null when it is none.
 *
 * @param {string} text
 * @returns {string|null}
 */
export function hexOf(text) {
  const t = text.trim().toLowerCase();
  if (/^#[0-9a-f]{6}$/.test(t)) return t;
  if (/^#[0-9a-f]{3}$/.test(t)) return '#' + [...t.slice(1)].map((c) => c + c).join('');
  return Object.hasOwn(DELPHI, t) ? DELPHI[t] : null;
}

/**
 * A stem colour key's new value when its control is set to `hex`: an OD
 * ramp `S=A..B` keeps its far end (`hex..B`), anything else becomes `hex`.
 *
 * @param {string} old the key's value ('' when absent)
 * @param {string} hex
 * @returns {string}
 */
export function stemValue(old, hex) {
  const ramp = /^[^.]+\.\.(.+)$/.exec(old);
  return ramp ? `${hex}..${ramp[1]}` : hex;
}

/**
 * The colour a stem colour key shows: a ramp's near end, else the value.
 *
 * @param {string} value
 * @returns {string}
 */
export function stemShown(value) {
  return value.split('..')[0];
}

/**
 * The `palette` line of an .lsys: its colours, each with its span in the
 * text (`start`, `end`) and its `#rrggbb`; `after`, where a colour added
 * goes (after the last colour, before a comment). Null without one. The
 * colours end at the first word that is none (a `#` that starts no
 * colour starts a comment).
 *
 * @param {string} text
 * @returns {{at: number, after: number, colours: Array<{start: number, end: number, value: string, hex: string}>}|null}
 */
export function palette(text) {
  const m = /^([ \t]*palette)(?=[ \t]|$)(.*)$/m.exec(text);
  if (!m) return null;
  const colours = [];
  let after = m.index + m[1].length;
  const word = /\S+/g;
  let w;
  while ((w = word.exec(m[2]))) {
    const hex = hexOf(w[0]);
    if (!hex) break;
    const start = m.index + m[1].length + w.index;
    colours.push({ start, end: start + w[0].length, value: w[0], hex });
    after = start + w[0].length;
  }
  return { at: m.index, after, colours };
}

/**
 * `text` with colour `i` of its palette set to `hex`; `i` one past the
 * last adds it; `hex` null removes colour `i`. Only that colour's word
 * changes (the line's spaces and comment stay); without a palette line,
 * one is added at the end of the text for a colour added.
 *
 * @param {string} text
 * @param {number} i
 * @param {string|null} hex
 * @returns {string}
 */
export function withPaletteColour(text, i, hex) {
  const p = palette(text);
  if (!p) {
    if (hex === null || i !== 0) return text;
    return `${text}${text.endsWith('\n') || text === '' ? '' : '\n'}palette ${hex}\n`;
  }
  const c = p.colours[i];
  if (hex === null) {
    if (!c) return text;
    // The word and the space before it.
    let from = c.start;
    while (from > 0 && (text[from - 1] === ' ' || text[from - 1] === '\t')) from--;
    return text.slice(0, from) + text.slice(c.end);
  }
  if (c) return text.slice(0, c.start) + hex + text.slice(c.end);
  if (i !== p.colours.length) return text;
  return `${text.slice(0, p.after)} ${hex}${text.slice(p.after)}`;
}
