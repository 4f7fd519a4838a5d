// Which lines of two texts differ: a line diff for Compare (the longest
// common subsequence of lines, after the common first and last lines are
// set aside). No state.

// Most cells of the table the common subsequence is found with (lines of
// one middle times the other's): past it the whole middle is marked.
const MAX_CELLS = 4_000_000;

/**
 * For each line of `a` and of `b` (split at '\n'), whether it is not in
 * their longest common subsequence of lines: the lines that differ.
 *
 * @param {string[]} a
 * @param {string[]} b
 * @returns {[boolean[], boolean[]]}
 */
export function differing(a, b) {
  let start = 0;
  while (start < a.length && start < b.length && a[start] === b[start]) start++;
  let end = 0;
  while (end < a.length - start && end < b.length - start && a[a.length - 1 - end] === b[b.length - 1 - end]) end++;
  const ma = a.slice(start, a.length - end);
  const mb = b.slice(start, b.length - end);
  const da = a.map((_, i) => i >= start && i < a.length - end);
  const db = b.map((_, i) => i >= start && i < b.length - end);
  if (ma.length === 0 || mb.length === 0 || ma.length * mb.length > MAX_CELLS) return [da, db];
  // lcs[i][j]: the common subsequence's length of ma[i..] and mb[j..].
  const w = mb.length + 1;
  const lcs = new Uint32Array((ma.length + 1) * w);
  for (let i = ma.length - 1; i >= 0; i--) {
    for (let j = mb.length - 1; j >= 0; j--) {
      lcs[i * w + j] = ma[i] === mb[j] ? lcs[(i + 1) * w + j + 1] + 1 : Math.max(lcs[(i + 1) * w + j], lcs[i * w + j + 1]);
    }
  }
  let i = 0;
  let j = 0;
  while (i < ma.length && j < mb.length) {
    if (ma[i] === mb[j]) {
      da[start + i++] = false;
      db[start + j++] = false;
    } else if (lcs[(i + 1) * w + j] >= lcs[i * w + j + 1]) {
      i++;
    } else {
      j++;
    }
  }
  return [da, db];
}
