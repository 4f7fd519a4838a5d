// The New menu's thumbnails: each template and example as a small picture,
// drawn by the page's engine (the server's or the WebAssembly module's:
// the same call, so the same pixels as `stlc render --size 96x96
// --show-layout -f png`) when the panel is first opened, one at a time,
// and kept for the session in `state.thumbnails` (name -> object URL).
// Closing the panel stops the drawing; opening it again goes on. A click
// opens that file as New does.

import { byId } from './dom.js';

/** The thumbnails' size in pixels, `--size 96x96`. */
export const THUMB = 96;

export function createThumbs(app) {
  const { state } = app;
  const panel = byId('new-gallery');
  const grid = byId('new-grid');
  let listed = null;

  function tile(e, i) {
    const b = document.createElement('button');
    b.className = 'thumb';
    b.dataset.testid = `thumb-${e.name}`;
    b.title = `New from ${e.name}${i < 2 ? ' (template)' : ''}`;
    const img = document.createElement('img');
    img.width = THUMB;
    img.height = THUMB;
    // The name is written under it: no alt text while it is drawn.
    img.alt = '';
    const label = document.createElement('span');
    label.textContent = e.name;
    b.append(img, label);
    b.addEventListener('click', () => { panel.open = false; app.files.openExample(e); });
    return b;
  }

  // Draws the thumbnails not drawn yet, in order, while the panel is open.
  let drawing = false;
  async function draw() {
    if (drawing) return;
    drawing = true;
    try {
      for (const [i, e] of listed.entries()) {
        if (!panel.open) break;
        const img = grid.children[i].querySelector('img');
        if (!state.thumbnails.has(e.name)) {
          const a = await app.engine.export({ source: e.text, kind: e.kind, size: [THUMB, THUMB] }, 'png')
            .catch(() => ({ ok: false }));
          state.thumbnails.set(e.name, a.ok ? URL.createObjectURL(a.blob) : '');
        }
        const url = state.thumbnails.get(e.name);
        if (url) img.src = url;
        else grid.children[i].classList.add('failed');
      }
    } finally {
      drawing = false;
    }
  }

  panel.addEventListener('toggle', async () => {
    if (!panel.open) return;
    if (!listed) {
      listed = await app.engine.examples().catch(() => []);
      grid.replaceChildren(...listed.map(tile));
    }
    draw();
  });
  return {};
}
