// The diagnostics list under the editor and the marks in its gutter.
// Clicking a diagnostic selects its span in the text.

import { byId, escapeHtml } from './dom.js';

/**
 * The JavaScript string index (UTF-16 units) of a 1-based `line` and
 * `column` of `text`, where columns count Unicode characters (code points),
 * as the server's diagnostics do (`diag::line_column`): a character
 * outside the BMP (an emoji) is one column but two JavaScript units.
 * A column past the line's end gives the line's end.
 */
export function textIndex(text, line, column) {
  let p = 0;
  for (let l = 1; l < line; l++) {
    const nl = text.indexOf('\n', p);
    if (nl < 0) return text.length;
    p = nl + 1;
  }
  for (let c = 1; c < column && p < text.length && text[p] !== '\n'; c++) {
    p += text.codePointAt(p) > 0xffff ? 2 : 1;
  }
  return p;
}

// The span [start, end) of diagnostic `d` in `text`, as JavaScript indices;
// at least one character where the text has one.
export function spanOf(text, d) {
  const a = textIndex(text, d.line, d.column || 1);
  let b = d.end_line == null ? a : textIndex(text, d.end_line, d.end_column || 1);
  if (b <= a) b = a < text.length ? a + (text.codePointAt(a) > 0xffff ? 2 : 1) : a;
  return [a, b];
}

/**
 * The editor's underline layer for `text`: the text, HTML-escaped, with
 * each span [start, end) of `spans` wrapped in a `<mark>` of its class
 * (error, warning), drawn under the textarea with the text itself
 * transparent, so only the wavy underline shows, at the very characters a
 * diagnostic is about (an unknown name inside a rule's expression, not
 * the whole line). Spans are taken in order of their start; a span
 * overlapping an earlier one keeps only its part after it; empty spans
 * and spans past the text are left out.
 *
 * @param {string} text
 * @param {Array<{start: number, end: number, cls: string}>} spans
 * @returns {string}
 */
export function underlined(text, spans) {
  const sorted = [...spans].sort((a, b) => a.start - b.start);
  let html = '';
  let at = 0;
  for (const s of sorted) {
    const start = Math.max(s.start, at);
    const end = Math.min(s.end, text.length);
    if (end <= start) continue;
    html += escapeHtml(text.slice(at, start)) + `<mark class="${escapeHtml(s.cls)}">${escapeHtml(text.slice(start, end))}</mark>`;
    at = end;
  }
  return html + escapeHtml(text.slice(at));
}

export function createDiagnostics(app) {
  const { state } = app;
  const ul = byId('diagnostics');

  function goTo(d) {
    const [a, b] = spanOf(app.editor.text(), d);
    app.editor.select(a, b);
  }

  // Lists `list` and marks their lines, an error over a warning.
  function show(list) {
    ul.innerHTML = '';
    state.marks = new Map();
    const text = app.editor.text();
    state.underlines = list
      .filter((d) => d.line != null)
      .map((d) => {
        const [start, end] = spanOf(text, d);
        return { start, end, cls: d.severity };
      });
    for (const d of list) {
      const li = document.createElement('li');
      li.className = d.severity;
      li.dataset.line = d.line == null ? '' : d.line;
      const where = d.line == null ? '' : `line ${d.line}, column ${d.column}: `;
      li.innerHTML = `<b>${d.severity}</b> ${escapeHtml(where)}${escapeHtml(d.message)}` +
        (d.label && d.label !== d.message ? ` <i>(${escapeHtml(d.label)})</i>` : '') +
        (d.help ? `<span class="help">help: ${escapeHtml(d.help)}</span>` : '');
      if (d.line != null) {
        li.addEventListener('click', () => goTo(d));
        const prev = state.marks.get(d.line);
        if (!prev || d.severity === 'error') state.marks.set(d.line, { cls: d.severity, title: d.message });
      }
      ul.appendChild(li);
    }
    app.editor.updateGutter();
  }

  // One error with no place in the text (a refused request, a failed save).
  const showError = (message) => show([{ severity: 'error', message, line: null }]);

  return { show, showError };
}
