// The Numbers panel's `define` sliders (src/serve/page/defines.js), a pure
// module, tested in Node without a browser: `node --test tests/page`.
// Spans and expected texts are counted by hand from the texts below.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { defines, withDefine, range } from '../../src/serve/page/defines.js';

const TEXT = [
  'define r1 0.9   # trunk', // the value at 10..13
  'define b 2*r1', // an expression: no slider
  '  define  wr\t0.707', // after 24 + 14 = 38 characters: 38 + 13 = 51..56
  '# define x 3', // a comment
  'define r1 1e-3', // r1 again: 57 + 13 = 70, + 10 = 80..84
  'axiom A(1)',
  '',
].join('\n');

test('a slider for each define whose value is a number, at its value', () => {
  assert.deepEqual(defines(TEXT), [
    { key: 'r1', name: 'r1', value: '0.9', start: 10, end: 13 },
    { key: 'wr', name: 'wr', value: '0.707', start: 51, end: 56 },
    { key: 'r1#2', name: 'r1', value: '1e-3', start: 80, end: 84 },
  ]);
  assert.deepEqual(defines('rule A(l) -> F(l)\ndefined 3\n'), []);
});

test('moving a slider rewrites its number only', () => {
  assert.equal(withDefine(TEXT, 'wr', '0.8'), TEXT.replace('wr\t0.707', 'wr\t0.8'));
  assert.equal(withDefine(TEXT, 'r1', '0.95'), TEXT.replace('r1 0.9   # trunk', 'r1 0.95   # trunk'));
  // The second r1, not the first.
  assert.equal(withDefine(TEXT, 'r1#2', '0.5'), TEXT.replace('r1 1e-3', 'r1 0.5'));
  assert.equal(withDefine(TEXT, 'b', '3'), TEXT);
});

test('ranges: 0 to three times the value, steps that hold it', () => {
  assert.deepEqual(range('0.9'), [0, 2.7, 0.001]);
  assert.deepEqual(range('0.707'), [0, 2.121, 0.001]);
  assert.deepEqual(range('137.5'), [0, 412.5, 0.1]);
  assert.deepEqual(range('45'), [0, 135, 0.1]);
  assert.deepEqual(range('-2'), [-6, 0, 0.01]);
  assert.deepEqual(range('0'), [-1, 1, 0.01]);
  assert.deepEqual(range('5000'), [0, 15000, 1]);
});
