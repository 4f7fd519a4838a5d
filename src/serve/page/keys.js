// The header's keys in the text (pure; tested in Node): an OD's `K=value`
// before its `RULE`, an .lsys's `key value` line, where each value is and
// the text with one of them set or removed. Nothing else of the text
// changes (settings.js, leaves.js).

// Where the comment of the line holding `at` starts before `at`: its
// first `#` that is not a colour's (`S=#8b4513`, a ramp's far end
// `S=#5b3a1e..#3b5e2b`); -1 when none does.
function commentStart(text, at) {
  const lineStart = text.lastIndexOf('\n', at - 1) + 1;
  const m = /(?<!=|\.\.)#/.exec(text.slice(lineStart, at));
  return m ? lineStart + m.index : -1;
}

// Whether `at` is inside a comment.
export function inComment(text, at) {
  return commentStart(text, at) >= 0;
}

// Where an OD's header ends: its `RULE` keyword (outside comments).
export function headerEnd(text) {
  const re = /(^|[^\w#])RULE\b/g;
  let m;
  while ((m = re.exec(text))) {
    const at = m.index + m[1].length;
    if (!inComment(text, at)) return at;
  }
  return -1;
}

// The `K=value` of an OD header: [start, end] of the value, and the value.
export function odKey(text, key) {
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
export function lsysKey(text, key) {
  const m = new RegExp(`^([ \\t]*${key}[ \\t]+)(\\S+)`, 'm').exec(text);
  if (!m) return null;
  const start = m.index + m[1].length;
  return { at: m.index, start, end: start + m[2].length, value: m[2] };
}

// `text` with `key` set to `value` ('' removes it).
export function withKey(text, kind, key, value) {
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
    // Before the last header line's comment, not in it.
    const c = commentStart(text, j);
    if (c >= 0) {
      j = c;
      while (j > 0 && (text[j - 1] === ' ' || text[j - 1] === '\t')) j--;
    }
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
