// An OD's leaves in the text (pure; tested in Node): the surfaces its
// `SURFACES ... ENDSURFACES` block defines, and the header's `P=` set to
// one of them or removed (docs/language.md, *Leaves*). The leaf control
// (settings.js) lists `none` and those surfaces; choosing one rewrites
// only the `P=` key, and `none` removes only that key.

import { odKey, withKey } from './keys.js';

/**
 * The surfaces of an OD's `SURFACES` block, in the order written, each
 * with its name's span in the text (`start`, `end`); a name defined
 * twice is listed once, at its first line. Lines are `surface X { word }`
 * (a `#` starts a comment); the block runs to `ENDSURFACES` or, unclosed,
 * to `LAYOUT` or the end. Empty without a block.
 *
 * @param {string} text
 * @returns {Array<{name: string, start: number, end: number}>}
 */
export function surfaces(text) {
  const kw = /^[ \t]*SURFACES[ \t]*(?:#.*)?$/m.exec(text);
  if (!kw) return [];
  const found = [];
  let at = kw.index + kw[0].length + 1;
  while (at < text.length) {
    const nl = text.indexOf('\n', at);
    const lineEnd = nl < 0 ? text.length : nl;
    const body = text.slice(at, lineEnd).split('#')[0];
    const t = body.trim();
    if (t === 'ENDSURFACES' || t === 'LAYOUT') break;
    const m = /^([ \t]*surface[ \t]+)(\S)/.exec(body);
    if (m && m[2] !== '{' && !found.some((s) => s.name === m[2])) {
      const start = at + m[1].length;
      found.push({ name: m[2], start, end: start + 1 });
    }
    at = lineEnd + 1;
  }
  return found;
}

/**
 * The leaf the header names: its `P=` value, or 'none' without one.
 *
 * @param {string} text
 * @returns {string}
 */
export function leafShown(text) {
  const k = odKey(text, 'P');
  return k ? k.value : 'none';
}

/**
 * `text` with its header's `P=` set to `name`, or removed for 'none'.
 * Only that key changes; a header without one gets ` P=name` at its end.
 *
 * @param {string} text
 * @param {string} name
 * @returns {string}
 */
export function withLeaf(text, name) {
  return withKey(text, 'od', 'P', name === 'none' ? '' : name);
}
