// Words, generation by generation: an .lsys's derived word at depth 0 (the
// axiom), 1, 2, ... (at most eight, each cut at 2,000 characters, with its
// exact length), for teaching how rewriting grows a word. A parametric
// system's modules show their parameters (`A(0.9,7.07)`, as `stlc expand`
// writes them), and its length counts modules. Asked of the engine when
// the panel is open and after each new picture.

import { byId } from './dom.js';

export function createWords(app) {
  const panel = byId('words');
  const list = byId('word-list');

  async function refresh() {
    if (!panel.open || byId('kind').value !== 'lsys') return;
    const a = await app.engine.words(app.session.request()).catch(() => null);
    list.replaceChildren();
    if (!a || !a.ok) return;
    for (const w of a.words) {
      const li = document.createElement('li');
      li.value = w.depth;
      // A parametric word's length counts modules (a symbol and its
      // parameters), not characters.
      const unit = w.word.includes('(') ? 'modules' : 'symbols';
      const cut = w.cut ? ` … (${w.length} ${unit})` : ` (${w.length})`;
      li.textContent = w.word + cut;
      list.append(li);
    }
  }

  panel.addEventListener('toggle', refresh);
  return { refresh };
}
