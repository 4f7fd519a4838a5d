// Every setting in the file (stl-language.md section 10): the header
// controls are views of keys in the text. An OD's growth order, seed, max
// stems and clearance are its `O=`, `V=`, `M=` and `C=`; an .lsys's depth
// and seed are its `generations` and `seed` lines. The stem colour is an
// OD's `S=` (a ramp's near end) and an .lsys's `color`; an .lsys's
// palette is its `palette` line, a colour field per colour (colours.js).
// Changing a control rewrites that key in the text (only that key, or
// that colour of the palette); typing a key moves the control. So a tree
// made here grows the same from the command line, after a reload, and on
// another machine.

import { byId } from './dom.js';
import { hexOf, palette, stemShown, stemValue, withPaletteColour } from './colours.js';

// Control id -> key, per kind.
const OD = { growth: 'O', seed: 'V', 'max-stems': 'M', clearance: 'C', 'stem-colour': 'S' };
const LSYS = { depth: 'generations', seed: 'seed', 'stem-colour': 'color' };

// Whether `at` is inside a comment: after a `#` on its line that is not a
// colour's (`S=#8b4513`, `G=#ffffff`).
function inComment(text, at) {
  const lineStart = text.lastIndexOf('\n', at - 1) + 1;
  return /(^|[^=])#/.test(text.slice(lineStart, at));
}

// Where an OD's header ends: its `RULE` keyword (outside comments).
function headerEnd(text) {
  const re = /(^|[^\w#])RULE\b/g;
  let m;
  while ((m = re.exec(text))) {
    const at = m.index + m[1].length;
    if (!inComment(text, at)) return at;
  }
  return -1;
}

// The `K=value` of an OD header: [start, end] of the value, and the value.
function odKey(text, key) {
  const end = headerEnd(text);
  if (end < 0) return null;
  const re = new RegExp(`(^|[\\s)>])${key}=([^\\s(]+)`, 'g');
  let m;
  while ((m = re.exec(text)) && m.index < end) {
    const at = m.index + m[1].length;
    if (inComment(text, at)) continue;
    const start = at + key.length + 1;
    return { at, start, end: start + m[2].length, value: m[2] };
  }
  return null;
}

// An .lsys `key value` line: the value's span and the value.
function lsysKey(text, key) {
  const m = new RegExp(`^([ \\t]*${key}[ \\t]+)(\\S+)`, 'm').exec(text);
  if (!m) return null;
  const start = m.index + m[1].length;
  return { at: m.index, start, end: start + m[2].length, value: m[2] };
}

// `text` with `key` set to `value` ('' removes it).
function withKey(text, kind, key, value) {
  if (kind === 'od') {
    const k = odKey(text, key);
    if (k) {
      if (value === '') {
        const from = text[k.at - 1] === ' ' ? k.at - 1 : k.at;
        return text.slice(0, from) + text.slice(k.end);
      }
      return text.slice(0, k.start) + value + text.slice(k.end);
    }
    if (value === '') return text;
    const end = headerEnd(text);
    if (end < 0) return text;
    let j = end;
    while (j > 0 && /\s/.test(text[j - 1])) j--;
    // A space after it too where the header runs straight into `RULE`
    // (the paper's one-line spelling: `B=1(0)RULE`).
    const after = /\s/.test(text[j] || ' ') ? '' : ' ';
    return `${text.slice(0, j)} ${key}=${value}${after}${text.slice(j)}`;
  }
  const k = lsysKey(text, key);
  if (k) {
    if (value !== '') return text.slice(0, k.start) + value + text.slice(k.end);
    const lineEnd = text.indexOf('\n', k.at);
    return text.slice(0, k.at) + (lineEnd < 0 ? '' : text.slice(lineEnd + 1));
  }
  if (value === '') return text;
  return `${text}${text.endsWith('\n') || text === '' ? '' : '\n'}${key} ${value}\n`;
}

export function createSettings(app) {
  const keys = (kind) => (kind === 'od' ? OD : kind === 'lsys' ? LSYS : {});

  // The colour drawn where the text names none: the last answer's stroke.
  const drawn = () => (app.state.answer && app.state.answer.stroke && hexOf(app.state.answer.stroke)) || '#000000';

  // The controls show the text's keys (none written: empty, bfs, the
  // colour drawn).
  function sync() {
    const kind = byId('kind').value;
    const text = app.editor.text();
    for (const [id, key] of Object.entries(keys(kind))) {
      const k = kind === 'od' ? odKey(text, key) : lsysKey(text, key);
      const v = k ? k.value : '';
      const control = byId(id);
      if (id === 'growth') control.value = v === 'dfs' || v === 'space' ? v : 'bfs';
      else if (id === 'stem-colour') control.value = hexOf(stemShown(v)) || drawn();
      else if (control !== document.activeElement || control.value !== v) control.value = v;
    }
    if (kind === 'lsys') syncPalette(text);
  }

  // The palette's fields, one per colour of the `palette` line, and `+`
  // to add one (a copy of the last). Fields are made again only when the
  // number of colours changes, so one being picked stays open.
  const fields = byId('palette-colours');
  function syncPalette(text) {
    const p = palette(text);
    const colours = p ? p.colours : [];
    if (fields.children.length !== colours.length) {
      fields.replaceChildren(...colours.map((_, i) => {
        const f = document.createElement('input');
        f.type = 'color';
        f.dataset.testid = `palette-${i}`;
        f.title = `palette colour ${i} (',' and ';' step through them; Alt-click removes it)`;
        f.addEventListener('input', () => setPalette(i, f.value));
        f.addEventListener('click', (e) => {
          if (!e.altKey) return;
          e.preventDefault();
          setPalette(i, null);
        });
        return f;
      }));
    }
    colours.forEach((c, i) => { fields.children[i].value = c.hex; });
  }
  function setPalette(i, hex) {
    const text = withPaletteColour(app.editor.text(), i, hex);
    if (text !== app.editor.text()) app.editor.rewrite(text);
  }
  byId('palette-add').addEventListener('click', () => {
    const p = palette(app.editor.text());
    const n = p ? p.colours.length : 0;
    setPalette(n, n ? p.colours[n - 1].hex : drawn());
  });

  // A control changed: its key in the text changes, and only that.
  function changed(id) {
    const kind = byId('kind').value;
    const key = keys(kind)[id];
    if (!key) return false;
    let value = byId(id).value.trim();
    if (id === 'growth' && value === 'bfs' && !odKey(app.editor.text(), 'O')) value = '';
    if (id === 'stem-colour') {
      const k = kind === 'od' ? odKey(app.editor.text(), key) : lsysKey(app.editor.text(), key);
      value = stemValue(k ? k.value : '', value);
    }
    const text = withKey(app.editor.text(), kind, key, value);
    if (text !== app.editor.text()) app.editor.rewrite(text);
    return true;
  }

  return { sync, changed, withKey, odKey, lsysKey, setPalette };
}
