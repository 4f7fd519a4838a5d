// The document: the file being edited, and the promise that no edit is
// ever lost.
//
// - Every Save names the version of the file the edit is based on; the
//   engine refuses it when another tab or program changed the file since,
//   and the page offers: load theirs, keep mine (overwrite), or both side
//   by side. Nothing is overwritten in silence.
// - The file is watched: a change on disk is loaded by itself when there
//   are no unsaved edits, and asked about when there are.
// - Unsaved edits are shown (title and status), kept in the browser's
//   storage per file path (not per port: the port changes between runs),
//   offered back on the next load (never applied silently), and a reload or
//   close with unsaved edits asks first.

import { byId } from './dom.js';
import { differing } from './diff.js';

const WATCH_MS = 1500;
const DRAFT_MS = 250;
const DRAFT_PREFIX = 'stlc-draft:';

export function createDocument(app) {
  const { state } = app;
  const notice = byId('notice');
  const saved = byId('saved');
  let draftTimer = null;
  // The disk version already asked about, so a change is asked once.
  let askedAbout = null;

  state.doc = {
    name: 'untitled.od', path: null, version: null, savedText: '', canSave: false, savedAt: null,
  };

  const dirty = () => app.editor.text() !== state.doc.savedText;
  const key = () => DRAFT_PREFIX + (state.doc.path || 'page:' + state.doc.name);

  const EARLIER = ':earlier';

  function read(k) {
    try {
      return JSON.parse(localStorage.getItem(k) || 'null');
    } catch {
      return null;
    }
  }

  function forget(k) {
    try { localStorage.removeItem(k); } catch { /* refused: nothing kept */ }
  }

  // The draft of an earlier visit, set aside (under its own key, so that
  // new edits do not replace it) until the user restores or discards it.
  function setAside(text) {
    const d = read(key());
    if (d && d.text !== text) {
      try { localStorage.setItem(key() + EARLIER, JSON.stringify(d)); } catch { /* kept where it was */ }
    }
    forget(key());
    return read(key() + EARLIER);
  }

  function writeDraft() {
    try {
      if (dirty()) {
        localStorage.setItem(key(), JSON.stringify({
          text: app.editor.text(), base: state.doc.version, at: Date.now(),
        }));
      } else {
        localStorage.removeItem(key());
      }
    } catch {
      // Storage full or refused: the unload guard still asks.
    }
  }

  // Title and status say whether there are unsaved edits.
  function show() {
    const d = dirty();
    document.title = `${d ? '• ' : ''}${state.doc.name} - stlc`;
    saved.classList.toggle('dirty', d);
    if (d) saved.textContent = 'Unsaved changes';
    else if (state.doc.savedAt) saved.textContent = `Saved ${state.doc.name} at ${state.doc.savedAt}.`;
    else saved.textContent = '';
  }

  // Every change of the text (typing, drawing, undo) comes here.
  function edited() {
    show();
    clearTimeout(draftTimer);
    draftTimer = setTimeout(writeDraft, DRAFT_MS);
  }

  // A notice above the editor with choices; each choice closes it.
  function ask(message, choices) {
    notice.replaceChildren();
    const text = document.createElement('span');
    text.textContent = message;
    notice.append(text);
    for (const [label, act, testid] of choices) {
      const b = document.createElement('button');
      b.textContent = label;
      b.dataset.testid = testid;
      b.addEventListener('click', () => { close(); act(); });
      notice.append(b);
    }
    notice.hidden = false;
  }
  function close() {
    notice.hidden = true;
    notice.replaceChildren();
  }

  // Theirs and mine side by side, with the same choices.
  // The lines that differ are marked (a line diff), on both sides.
  function compare(theirs, choices, mine = app.editor.text()) {
    const dialog = byId('compare');
    const sides = [theirs.split('\n'), mine.split('\n')];
    const marks = differing(...sides);
    for (const [k, id] of ['compare-theirs', 'compare-mine'].entries()) {
      const lines = sides[k];
      byId(id).replaceChildren(...lines.map((line, i) => {
        const span = document.createElement('span');
        span.textContent = i < lines.length - 1 ? line + '\n' : line;
        if (marks[k][i]) span.className = 'differs';
        return span;
      }));
      const n = marks[k].filter(Boolean).length;
      byId(id + '-count').textContent = n ? `: ${n} line${n === 1 ? '' : 's'} differ${n === 1 ? 's' : ''}` : ': the same';
    }
    const buttons = byId('compare-choices');
    buttons.replaceChildren();
    for (const [label, act, testid] of [...choices, ['Close', () => {}, 'compare-close']]) {
      const b = document.createElement('button');
      b.textContent = label;
      b.dataset.testid = testid;
      b.addEventListener('click', () => { dialog.close(); act(); });
      buttons.append(b);
    }
    dialog.showModal();
  }

  // The file's text as it is on disk becomes the editor's.
  function takeTheirs(f) {
    state.doc.version = f.version;
    state.doc.savedText = f.text;
    askedAbout = null;
    app.editor.load(f.text);
    edited();
  }

  // The other version is set aside: the next Save writes over it.
  function keepMine(version) {
    state.doc.version = version;
    askedAbout = null;
    edited();
  }

  function conflict(message, f) {
    const choices = [
      ['Load theirs', () => takeTheirs(f), 'load-theirs'],
      ['Keep mine', () => keepMine(f.version), 'keep-mine'],
    ];
    ask(message, [...choices, ['Compare', () => compare(f.text, choices), 'compare']]);
  }

  async function save() {
    const text = app.editor.text();
    if (!state.doc.canSave) {
      app.files.download(new Blob([text], { type: 'text/plain' }), state.doc.name);
      return;
    }
    const a = await app.engine.save(text, state.doc.version);
    if (a.ok) {
      state.doc.version = a.version;
      state.doc.savedText = text;
      state.doc.savedAt = new Date().toLocaleTimeString();
      askedAbout = null;
      close();
      edited();
    } else if (a.conflict) {
      const f = await app.engine.open();
      askedAbout = f.version;
      conflict('Not saved: the file changed since this edit began (another tab or program).', f);
    } else {
      saved.textContent = 'Not saved: ' + (a.error || a.diagnostics.map((d) => d.message).join('; '));
    }
  }

  // A file that is now the editor's: its name, path, version, text.
  function opened(f, note) {
    // The document left keeps its unsaved edits in storage, offered back
    // when it is opened again.
    clearTimeout(draftTimer);
    if (dirty()) writeDraft();
    Object.assign(state.doc, {
      name: f.name, path: f.path || null, version: f.version ?? null,
      savedText: f.text, canSave: !!f.can_save, savedAt: null,
    });
    askedAbout = null;
    close();
    // Every per-file control starts from this file (its own keys), never
    // from the last file's settings; the picture shown is the last file's
    // until this one's comes.
    for (const id of ['depth', 'seed', 'clearance', 'max-stems']) byId(id).value = '';
    byId('growth').value = 'bfs';
    state.otherFile = true;
    byId('file-name').textContent = f.name + note;
    app.session.setKind(f.kind);
    const earlier = setAside(f.text);
    app.editor.load(f.text);
    show();
    if (earlier && earlier.text !== f.text) offerDraft(f, earlier);
    else forget(key() + EARLIER);
  }

  // Unsaved edits kept from an earlier visit: offered, never applied.
  function offerDraft(f, d) {
    const when = new Date(d.at).toLocaleString();
    const base = d.base === f.version ? 'this version of the file' : 'an earlier version of the file';
    const restore = () => { forget(key() + EARLIER); app.editor.rewrite(d.text); edited(); };
    ask(`Unsaved edits from ${when} (made to ${base}) were kept.`, [
      ['Restore them', restore, 'restore-draft'],
      ['Compare', () => compare(f.text, [['Restore them', restore, 'restore-draft']], d.text), 'compare'],
      ['Discard them', () => forget(key() + EARLIER), 'discard-draft'],
    ]);
  }

  // The engine's file (the one named on the command line, or the example).
  async function openServed() {
    const f = await app.engine.open();
    const note = !f.can_save ? ' (example; Save downloads)' : f.version === null ? ' (new: Save creates it)' : '';
    opened(f, note);
  }

  // Watches the file: theirs by itself when nothing is unsaved, else ask.
  async function watch() {
    if (!state.doc.canSave || document.hidden) return;
    let f;
    try {
      f = await app.engine.open(state.doc.version);
    } catch {
      return;
    }
    if (f.unchanged) return;
    if (f.path !== state.doc.path || f.version === state.doc.version || f.version === askedAbout) return;
    if (f.text === app.editor.text()) {
      // Saved elsewhere with this very text: nothing to ask.
      keepMine(f.version);
      state.doc.savedText = f.text;
      show();
    } else if (!dirty()) {
      takeTheirs(f);
      saved.textContent = `Reloaded ${f.name}: it changed on disk.`;
    } else {
      askedAbout = f.version;
      conflict('The file changed on disk, and you have unsaved edits.', f);
    }
  }
  setInterval(watch, WATCH_MS);

  window.addEventListener('beforeunload', (e) => {
    if (!dirty()) return;
    writeDraft();
    e.preventDefault();
    e.returnValue = '';
  });

  return { save, openServed, opened, edited, dirty, watch };
}
