// The static Tree Maker's entry module: web/build.sh copies it over the
// page's own entry.js (src/serve/page/entry.js), so the same index.html
// loads the page of `stlc serve` (its own modules, unchanged) with the
// WebAssembly engine instead of the HTTP one (Share is the page's own,
// sharing.js).

import { useEngine } from './engine/index.js';
import { createWasmEngine, remember } from './engine/wasm.js';

useEngine(createWasmEngine);
await import('./app.js');
const app = window.stlc;

// Each document opened (New, Open..., a share link) is remembered for
// this tab, so a reload comes back to it and offers its draft
// (engine/wasm.js's open, which remembers the one shown first).
const opened = app.document.opened;
app.document.opened = (f, note) => {
  remember(f);
  opened(f, note);
};

// When the first picture was drawn, in ms from the start of the page's
// navigation (benches/web.sh measures it; docs/web.md).
(function firstPicture() {
  if (app.state.answer && app.state.answer.ok) app.firstPicture = performance.now();
  else requestAnimationFrame(firstPicture);
})();
