// The source editor: the textarea, its line-number gutter, and the one
// undo history of the text (typing and drawing edits alike). Every change
// of the text schedules a render (app.session.refresh), debounced.

import { byId, escapeHtml } from './dom.js';
import { underlined } from './diagnostics.js';

const DEBOUNCE_MS = 40;
const HISTORY = 100;

export function createEditor(app) {
  const { state } = app;
  const src = byId('source');
  const gutter = byId('gutter');
  const under = byId('underlines');
  let timer = null;

  function updateGutter() {
    const marks = state.marks;
    const lines = src.value.split('\n').length;
    const parts = [];
    for (let i = 1; i <= lines; i++) {
      const m = marks.get(i);
      parts.push(m ? `<span class="${m.cls}" title="${escapeHtml(m.title)}">${i}</span>` : `<span>${i}</span>`);
    }
    gutter.innerHTML = parts.join('');
    // Two more lines: room to scroll as far as the textarea, whose
    // scroll bar takes some of its height.
    under.innerHTML = underlined(src.value, state.underlines) + '\n\n';
    scrolled();
  }

  // The gutter and the underlines follow the text's scrolling.
  function scrolled() {
    gutter.scrollTop = src.scrollTop;
    under.scrollTop = src.scrollTop;
    under.scrollLeft = src.scrollLeft;
  }

  function schedule() {
    clearTimeout(timer);
    timer = setTimeout(() => app.session.refresh(), DEBOUNCE_MS);
  }

  // Keeps the text for Ctrl-Z before an edit replaces it.
  function remember() {
    const u = state.undo;
    if (u.length && u[u.length - 1] === src.value) return;
    u.push(src.value);
    if (u.length > HISTORY) u.shift();
    state.redo = [];
  }

  function travel(from, to) {
    if (!from.length) return;
    to.push(src.value);
    const text = from.pop();
    state.selected = -1;
    state.typedAt = -Infinity;
    app.tools.cancelPolygon();
    setText(text);
  }
  const undo = () => travel(state.undo, state.redo);
  const redo = () => travel(state.redo, state.undo);

  function setText(text) {
    // Keep the caret where it was, as far as possible.
    const pos = src.selectionStart;
    src.value = text;
    src.selectionStart = src.selectionEnd = Math.min(pos, text.length);
    state.editedAt = performance.now();
    updateGutter();
    schedule();
    app.document.edited();
  }

  // A drawing edit: one undo step, then the new text.
  function rewrite(text) {
    remember();
    state.typedAt = -Infinity;
    setText(text);
  }

  // A new file's text: a new history, the caret at the start.
  function load(text) {
    state.undo = [];
    state.redo = [];
    state.typedAt = -Infinity;
    src.selectionStart = src.selectionEnd = 0;
    setText(text);
  }

  // Ctrl-Z, Ctrl-Shift-Z and Ctrl-Y, in the editor and out of it: one
  // history for typing and drawing (the browser's own is lost whenever a
  // drawing edit rewrites the text). True if `e` was one of them.
  function undoKey(e) {
    if (!(e.ctrlKey || e.metaKey) || e.altKey) return false;
    const k = e.key.toLowerCase();
    if (k === 'z' && !e.shiftKey) undo();
    else if ((k === 'z' && e.shiftKey) || k === 'y') redo();
    else return false;
    e.preventDefault();
    return true;
  }

  // Selects [a, b) of the text (JavaScript indices) and focuses it.
  function select(a, b) {
    src.focus();
    src.setSelectionRange(a, b);
  }

  src.addEventListener('scroll', scrolled);
  src.addEventListener('beforeinput', (e) => {
    if (e.inputType === 'historyUndo' || e.inputType === 'historyRedo') {
      e.preventDefault();
      if (e.inputType === 'historyUndo') undo(); else redo();
      return;
    }
    // A burst of typing is one undo step: the text before it is kept.
    const now = performance.now();
    if (now - state.typedAt > 1000) remember();
    state.typedAt = now;
    // Pasting over most of the text is a new description: fit it.
    if (e.inputType === 'insertFromPaste' || e.inputType === 'insertFromDrop') {
      const replaced = src.selectionEnd - src.selectionStart;
      if (replaced >= src.value.trim().length / 2) state.refit = true;
    }
  });
  src.addEventListener('input', () => {
    state.editedAt = performance.now();
    updateGutter();
    schedule();
    app.document.edited();
  });
  src.addEventListener('keydown', (e) => {
    if (e.key === 'Tab') {
      e.preventDefault();
      src.setRangeText('    ', src.selectionStart, src.selectionEnd, 'end');
      src.dispatchEvent(new Event('input'));
    }
  });

  return {
    element: src,
    text: () => src.value,
    setText,
    rewrite,
    load,
    schedule,
    updateGutter,
    undoKey,
    select,
  };
}
