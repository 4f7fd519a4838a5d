// Every setting in the file (stl-language.md section 10): the header
// controls are views of keys in the text. An OD's growth order, seed, max
// stems and clearance are its `O=`, `V=`, `M=` and `C=`; an .lsys's depth
// and seed are its `generations` and `seed` lines. The stem colour is an
// OD's `S=` (a ramp's near end) and an .lsys's `color`; an .lsys's
// palette is its `palette` line, a colour field per colour (colours.js);
// an OD's leaf is its `P=`, one of its SURFACES or none (leaves.js).
// Changing a control rewrites that key in the text (only that key, or
// that colour of the palette); typing a key moves the control. So a tree
// made here grows the same from the command line, after a reload, and on
// another machine.

import { byId } from './dom.js';
import { hexOf, palette, stemShown, stemValue, withPaletteColour } from './colours.js';
import { odKey, lsysKey, withKey } from './keys.js';
import { surfaces, leafShown, withLeaf } from './leaves.js';

// Control id -> key, per kind.
const OD = { growth: 'O', seed: 'V', 'max-stems': 'M', clearance: 'C', 'stem-colour': 'S' };
const LSYS = { depth: 'generations', seed: 'seed', 'stem-colour': 'color' };

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
    if (kind === 'od') syncLeaf(text);
  }

  // The leaf control: `none` and the surfaces of the SURFACES block (a
  // `P=` naming none of them is listed too, as written, so the control
  // shows the text). Options are made again only when the names change.
  const leaf = byId('leaf');
  function syncLeaf(text) {
    const shown = leafShown(text);
    const names = ['none', ...surfaces(text).map((s) => s.name)];
    if (!names.includes(shown)) names.push(shown);
    if ([...leaf.options].map((o) => o.value).join('\n') !== names.join('\n')) {
      leaf.replaceChildren(...names.map((n) => {
        const o = document.createElement('option');
        o.value = n;
        o.textContent = n;
        return o;
      }));
    }
    leaf.value = shown;
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
    if (id === 'leaf') {
      if (kind !== 'od') return false;
      const text = withLeaf(app.editor.text(), leaf.value);
      if (text !== app.editor.text()) app.editor.rewrite(text);
      return true;
    }
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
