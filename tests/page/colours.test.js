// The colour controls' text edits (src/serve/page/colours.js), a pure
// module, tested in Node without a browser: `node --test tests/page`.
// Spans and expected texts are counted by hand from the texts below.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { hexOf, stemValue, stemShown, palette, withPaletteColour } from '../../src/serve/page/colours.js';

const TEXT = [
  'generations 3', // 0..13, newline at 13
  'palette #2f5d1e clGreen  #abc # bark, leaf, petal', // 14..: `#2f5d1e` at 22..29, `clGreen` 30..37, `#abc` 39..43
  'axiom A',
  '',
].join('\n');

test('a colour of the text is a colour field\'s #rrggbb', () => {
  assert.equal(hexOf('#1F4E79'), '#1f4e79');
  assert.equal(hexOf('#abc'), '#aabbcc');
  assert.equal(hexOf('clMaroon'), '#800000');
  assert.equal(hexOf('CLSKYBLUE'), '#a6caf0');
  assert.equal(hexOf('#12'), null);
  assert.equal(hexOf('clGren'), null);
  assert.equal(hexOf('#'), null);
});

test('every Delphi name of src/color.rs has its colour here', () => {
  const rust = readFileSync(new URL('../../src/color.rs', import.meta.url), 'utf8');
  const rows = [...rust.matchAll(/\("(cl\w+)", Rgb::new\(0x(\w\w), 0x(\w\w), 0x(\w\w)\)\)/g)];
  assert.ok(rows.length >= 19, `only ${rows.length} rows read`);
  for (const [, name, r, g, b] of rows) assert.equal(hexOf(name), `#${r}${g}${b}`.toLowerCase(), name);
});

test('a stem colour keeps a ramp\'s far end', () => {
  assert.equal(stemValue('clMaroon', '#112233'), '#112233');
  assert.equal(stemValue('', '#112233'), '#112233');
  assert.equal(stemValue('#5b3a1e..#3b5e2b', '#112233'), '#112233..#3b5e2b');
  assert.equal(stemShown('#5b3a1e..#3b5e2b'), '#5b3a1e');
  assert.equal(stemShown('clGreen'), 'clGreen');
});

test('the palette line\'s colours, where each is, and where a comment starts', () => {
  assert.deepEqual(palette(TEXT), {
    at: 14,
    after: 43,
    colours: [
      { start: 22, end: 29, value: '#2f5d1e', hex: '#2f5d1e' },
      { start: 30, end: 37, value: 'clGreen', hex: '#008000' },
      { start: 39, end: 43, value: '#abc', hex: '#aabbcc' },
    ],
  });
  assert.equal(palette('axiom A\npalettes #fff\n'), null);
  assert.deepEqual(palette('palette\n'), { at: 0, after: 7, colours: [] });
});

test('a palette colour set, added or removed changes that word only', () => {
  const line = (t) => t.split('\n')[1];
  const others = (a, b) => {
    const [x, y] = [a.split('\n'), b.split('\n')];
    assert.equal(x.length, y.length);
    return x.filter((l, i) => l !== y[i]).length;
  };
  const set = withPaletteColour(TEXT, 1, '#ff8800');
  assert.equal(line(set), 'palette #2f5d1e #ff8800  #abc # bark, leaf, petal');
  assert.equal(others(TEXT, set), 1);
  const added = withPaletteColour(TEXT, 3, '#010203');
  assert.equal(line(added), 'palette #2f5d1e clGreen  #abc #010203 # bark, leaf, petal');
  assert.equal(others(TEXT, added), 1);
  const removed = withPaletteColour(TEXT, 1, null);
  assert.equal(line(removed), 'palette #2f5d1e  #abc # bark, leaf, petal');
  // Past the end: nothing changes.
  assert.equal(withPaletteColour(TEXT, 5, '#010203'), TEXT);
  assert.equal(withPaletteColour(TEXT, 5, null), TEXT);
  // No palette yet: the first colour adds the line.
  assert.equal(withPaletteColour('axiom A', 0, '#010203'), 'axiom A\npalette #010203\n');
  assert.equal(withPaletteColour('axiom A\n', 1, '#010203'), 'axiom A\n');
});
