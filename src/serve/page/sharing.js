// Share, in `stlc serve`'s page and in the static site alike: the whole
// document in a link (share.js), copied and put in the address bar; a
// share link pasted into the tab's address opens its document (Save
// downloads it). A link holds the text and never a token: only the
// fragment `#k=...&n=...&s=...` after the page's own address.

import { byId } from './dom.js';
import { toFragment, fromFragment } from './share.js';

export function addShare(app) {
  /** The address that opens this document as it is now. */
  async function shareLink() {
    // The file's name only: never the folders it is in on this machine.
    const name = app.state.doc.name.split(/[/\\]/).pop();
    const doc = { name, kind: app.session.request().kind, text: app.editor.text() };
    // Never the query: `stlc serve`'s printed link may carry its token there.
    return location.origin + location.pathname + await toFragment(doc);
  }
  app.shareLink = shareLink;

  const button = document.createElement('button');
  button.id = 'share';
  button.dataset.testid = 'share';
  button.textContent = 'Share';
  button.title = 'Put the whole text in a link (nothing is uploaded) and copy it';
  byId('save').after(button);
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
    byId('saved').textContent = `Share link: ${link.length} characters, ${copied ? 'copied; ' : ''}in the address bar`;
  });

  // A share link pasted into this tab's address opens its document.
  window.addEventListener('hashchange', async () => {
    const shared = await fromFragment(location.hash);
    if (!shared) return;
    app.document.opened({ ...shared, version: null, path: null, can_save: false }, ' (shared; Save downloads)');
  });
}
