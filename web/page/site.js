// The static Tree Maker's entry module (target/site/index.html, built by
// web/build.sh): the page of `stlc serve` (its own modules, unchanged)
// with the WebAssembly engine instead of the HTTP one, and a Share button.

import { useEngine } from './engine/index.js';
import { createWasmEngine, remember } from './engine/wasm.js';
import { toFragment, fromFragment } from './share.js';

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

/** The address that opens this document as it is now. */
async function shareLink() {
  const doc = { name: app.state.doc.name, kind: app.session.request().kind, text: app.editor.text() };
  const url = new URL(location.href);
  url.hash = await toFragment(doc);
  return url.href;
}
app.shareLink = shareLink;

const button = document.createElement('button');
button.id = 'share';
button.dataset.testid = 'share';
button.textContent = 'Share';
button.title = 'Put the whole text in the page\'s address (nothing is uploaded) and copy that link';
document.getElementById('save').after(button);
button.addEventListener('click', async () => {
  const link = await shareLink();
  history.replaceState(null, '', link);
  let copied = false;
  try {
    await navigator.clipboard.writeText(link);
    copied = true;
  } catch {
    // No clipboard here (an insecure origin, a refusal): the address bar has it.
  }
  document.getElementById('saved').textContent =
    `Share link: ${link.length} characters, ${copied ? 'copied; ' : ''}in the address bar`;
});

// A share link pasted into this tab's address opens its document.
window.addEventListener('hashchange', async () => {
  const shared = await fromFragment(location.hash);
  if (!shared) return;
  app.document.opened({ ...shared, version: null, path: null, can_save: false }, ' (shared; Save downloads)');
});

// When the first picture was drawn, in ms from the start of the page's
// navigation (benches/web.sh measures it; docs/web.md).
(function firstPicture() {
  if (app.state.answer && app.state.answer.ok) app.firstPicture = performance.now();
  else requestAnimationFrame(firstPicture);
})();
