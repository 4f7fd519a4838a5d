// A parametric .lsys's `define NAME VALUE` lines (docs/lsys.md), read and
// rewritten for the Numbers panel's sliders (scrub.js): each constant
// whose value is a plain number is a slider, and moving it rewrites that
// number and nothing else (not its line's spacing, not its comment, not
// another line). A pure module, tested in Node (tests/page).

// `define`, a name, a plain number, then spaces or a comment to the end.
const LINE = /^([ \t]*define[ \t]+)([A-Za-z][A-Za-z0-9_]*)([ \t]+)(-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)(?=[ \t]*(?:#|$))/gm;

/**
 * Every `define` whose value is a plain number, in file order: its name,
 * its value as written, and the value's span [start, end) in `text`
 * (JavaScript indices). A name defined twice has two entries; `key`
 * tells them apart (`r1`, then `r1#2`). A `define` whose value is an
 * expression (`define b 2*a`) is not listed: a slider would overwrite
 * the expression.
 *
 * @param {string} text
 * @returns {Array<{key: string, name: string, value: string, start: number, end: number}>}
 */
export function defines(text) {
  const out = [];
  const seen = new Map();
  for (const m of text.matchAll(LINE)) {
    const name = m[2];
    const n = (seen.get(name) || 0) + 1;
    seen.set(name, n);
    const start = m.index + m[1].length + name.length + m[3].length;
    out.push({ key: n === 1 ? name : `${name}#${n}`, name, value: m[4], start, end: start + m[4].length });
  }
  return out;
}

/**
 * `text` with the value of the define `key` (as `defines` names it) set to
 * `value`; the text unchanged when there is no such define.
 *
 * @param {string} text
 * @param {string} key
 * @param {string} value
 * @returns {string}
 */
export function withDefine(text, key, value) {
  const d = defines(text).find((x) => x.key === key);
  if (!d) return text;
  return text.slice(0, d.start) + value + text.slice(d.end);
}

/**
 * A slider's [min, max, step] for a constant written `written`: from 0 to
 * three times the value (a negative one mirrored; 0 gets -1 to 1), in
 * steps fine enough to hold the value as written and a hundredth of its
 * order of magnitude (0.707: steps of 0.001; 137.5: 0.1; 45: 0.1).
 *
 * @param {string} written
 * @returns {[number, number, number]}
 */
export function range(written) {
  const v = Number(written);
  if (!Number.isFinite(v) || v === 0) return [-1, 1, 0.01];
  const mantissa = written.split(/[eE]/)[0];
  const dot = mantissa.indexOf('.');
  const decimals = Math.max(0, (dot < 0 ? 0 : mantissa.length - dot - 1) - exponent(written));
  const magnitude = Math.floor(Math.log10(Math.abs(v))) - 2;
  const k = Math.max(decimals, -magnitude);
  const step = Number(`1e-${k}`);
  // Written to the step's decimals, so the slider's grid holds the value.
  const far = Number((3 * v).toFixed(Math.min(k, 20)));
  return [Math.min(0, far), Math.max(0, far), step];
}

// The exponent of a number written with one (`1e-3`: -3), else 0.
function exponent(written) {
  const e = written.split(/[eE]/)[1];
  return e === undefined ? 0 : Number(e);
}
