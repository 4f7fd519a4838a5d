// Numbers you can scrub: a slider for each number of the header that
// shapes the picture (an OD's L, B, A and C; an .lsys's angle and length)
// and for each `define` of a parametric .lsys whose value is a number
// (defines.js). Dragging one rewrites that number in the text (only it: a
// decrement `(d)` stays, a define's line keeps its spacing and comment),
// and the tree regrows as you drag (a newer edit ends the older work).
// The text stays the one source of truth.

import { byId } from './dom.js';
import { defines, withDefine, range as defineRange } from './defines.js';

// Key, label, [min, max, step] for a value v.
const OD = [
  ['A', 'angle A', () => [0, 180, 0.5]],
  ['C', 'clearance C', (v) => [0, Math.max(10, 3 * v), 0.1]],
  ['L', 'length L', (v) => [0.5, Math.max(50, 3 * v), 0.5]],
  ['B', 'width B', (v) => [0.1, Math.max(10, 3 * v), 0.1]],
];
const LSYS = [
  ['angle', 'angle', () => [0, 180, 0.1]],
  ['length', 'length', (v) => [0.5, Math.max(50, 3 * v), 0.5]],
];

export function createScrub(app) {
  const panel = byId('scrub');
  const list = byId('scrub-list');
  let shown = '';

  // The sliders for the text's numbers (rebuilt when the set changes).
  function refresh() {
    if (!panel.open) return;
    const kind = byId('kind').value;
    const text = app.editor.text();
    const rows = (kind === 'od' ? OD : kind === 'lsys' ? LSYS : [])
      .map(([key, label, range]) => {
        const k = kind === 'od' ? app.settings.odKey(text, key) : app.settings.lsysKey(text, key);
        const v = k ? Number(k.value) : NaN;
        const set = (t, value) => app.settings.withKey(t, kind, key, value);
        return Number.isFinite(v) ? { key, label, v, range: range(v), set } : null;
      })
      .filter(Boolean);
    if (kind === 'lsys') {
      for (const d of defines(text)) {
        const set = (t, value) => withDefine(t, d.key, value);
        rows.push({ key: `define-${d.key}`, label: `define ${d.name}`, v: Number(d.value), range: defineRange(d.value), set });
      }
    }
    const signature = kind + rows.map((r) => r.key).join();
    if (signature === shown) {
      for (const r of rows) {
        const input = list.querySelector(`input[data-key="${r.key}"]`);
        if (input && input !== document.activeElement) {
          // A value typed past the slider's ends moves them.
          if (r.v < Number(input.min) || r.v > Number(input.max)) Object.assign(input, { min: r.range[0], max: r.range[1] });
          input.value = r.v;
          input.nextElementSibling.textContent = r.v;
        }
      }
      return;
    }
    shown = signature;
    list.replaceChildren();
    for (const r of rows) {
      const label = document.createElement('label');
      label.textContent = r.label + ' ';
      const input = document.createElement('input');
      Object.assign(input, { type: 'range', min: r.range[0], max: r.range[1], step: r.range[2], value: r.v });
      input.dataset.key = r.key;
      input.dataset.testid = `scrub-${r.key}`;
      const out = document.createElement('output');
      out.textContent = r.v;
      input.addEventListener('input', () => {
        out.textContent = input.value;
        const t = r.set(app.editor.text(), input.value);
        if (t !== app.editor.text()) app.editor.rewrite(t);
      });
      label.append(input, out);
      list.append(label);
    }
  }

  panel.addEventListener('toggle', refresh);
  return { refresh };
}
