// The editor's underline layer (underlined in src/serve/page/diagnostics.js),
// tested in Node without a browser: `node --test tests/page`. The
// expected HTML is written out by hand from the texts below.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { underlined, spanOf } from '../../src/serve/page/diagnostics.js';

test('a diagnostic underlines its span: the expression, not the line', () => {
  const text = 'rule A(l) -> F(l)A(l*r2)\n';
  // `r2` is columns 22-23 of line 1: the server's span, 1-based, end past it.
  const [start, end] = spanOf(text, { line: 1, column: 22, end_line: 1, end_column: 24 });
  assert.deepEqual([start, end], [21, 23]);
  assert.equal(
    underlined(text, [{ start, end, cls: 'error' }]),
    'rule A(l) -&gt; F(l)A(l*<mark class="error">r2</mark>)\n',
  );
});

test('spans in order, overlaps cut, empty and outside spans left out', () => {
  const text = 'a<b&c';
  assert.equal(
    underlined(text, [
      { start: 3, end: 5, cls: 'warning' },
      { start: 0, end: 2, cls: 'error' },
      { start: 1, end: 4, cls: 'error' },
      { start: 5, end: 9, cls: 'error' },
      { start: 2, end: 2, cls: 'error' },
    ]),
    '<mark class="error">a&lt;</mark><mark class="error">b&amp;</mark><mark class="warning">c</mark>',
  );
  assert.equal(underlined('x', []), 'x');
});
