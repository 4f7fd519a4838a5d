// A big grown tree, drawn on a canvas from the answer's stems. Past
// 10,000 stems the server leaves the tree out of the answer's SVG
// (`tree_in_svg: false`; docs/serve.md, "Big trees"): an SVG of 200,000
// stems is megabytes of text that the page would parse, import and
// rasterise in one go, stalling it for a third of a second. Instead the
// stems in growth order (`growth.stems`, six numbers a stem: from x, y, to
// x, y, width, decision) are stroked onto a <canvas> inside the preview
// (a <foreignObject> over the picture's box, so zoom and pan move it with
// the rest), a slice at a time: the page gets the thread back every few
// milliseconds, and a newer answer or replay step stops an older drawing.
// A stem shorter and thinner than a pixel is not stroked (a stroke costs
// the canvas far more than the pixel it touches): its area, the coverage
// an anti-aliased stroke would give it, is added to the pixel under its
// middle on a second canvas over the first (a dot), as the library's PNG
// renderer paints sub-pixel blots.
//
// Replay draws the stems up to a decision: growth order puts them first,
// so a replay that moves on adds only the new stems.
//
// The canvas covers the part of the picture in view, at the screen's
// resolution: zoomed in (or panned to a part it does not cover), a new
// one is drawn for the new view once the view rests, and replaces the old
// when it is done. So a zoomed tree is as sharp as the screen.

import { el } from './dom.js';

const XHTML = 'http://www.w3.org/1999/xhtml';

// Most pixels a side of the canvas (16 M pixels, 64 MB).
const MAX_SIDE = 4096;
// The thinnest stroke, in pixels of the canvas: the library's hairline.
const HAIRLINE = 0.5;
// How long one slice of drawing runs before the page gets the thread back.
const SLICE_MS = 6;
// Stems stroked as one path at most (a path is stroked when its width
// changes or it holds this many).
const BATCH = 2048;

// Runs `f` soon, after what the page has waiting (input, a frame).
function later(f) {
  const s = globalThis.scheduler;
  if (s && s.postTask) s.postTask(f);
  else setTimeout(f, 0);
}

// The number of stems of decisions up to `k`: decisions never decrease
// along the growth order, so they are a prefix.
export function stemsUpTo(g, k) {
  let [lo, hi] = [0, g.length / 6];
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (g[mid * 6 + 5] <= k) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

// A canvas filling its parent, in `parent`.
function canvasIn(parent, w, h, testid) {
  const c = document.createElementNS(XHTML, 'canvas');
  c.width = w;
  c.height = h;
  c.style.cssText = 'position:absolute;left:0;top:0;width:100%;height:100%';
  c.dataset.testid = testid;
  parent.appendChild(c);
  return c;
}

export function createTreeCanvas() {
  let canvas = null;
  let ctx = null;
  // The dots' canvas, and per pixel what its dots leave uncovered (1 - alpha).
  let dots = null;
  let keep = null;
  let rgb = [0, 0, 0];
  // The box of the dots' pixels changed since they were last painted
  // (empty: x0 > x1).
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  // The stems, their colour, the canvas box (canvas units) and pixels a unit.
  let g = [];
  let colour = '#000';
  let box = [0, 0, 1, 1];
  let k = 1;
  // Where canvases go, the whole picture's box, the decision shown, the
  // canvas's <foreignObject> and those it replaces.
  let layer = null;
  let full = [0, 0, 1, 1];
  let shown = Infinity;
  let fo = null;
  let old = [];
  let resting = null;
  // Stems on the canvas (a prefix of `g`), and the drawing under way.
  let drawn = 0;
  let job = 0;
  let finished = Promise.resolve(true);

  // The part of the picture in `view` (all of it without a view), and
  // pixels a unit there: `pxPerUnit`, at most MAX_SIDE a side.
  function region(view, pxPerUnit) {
    let r = full;
    if (view) {
      r = [Math.max(full[0], view[0]), Math.max(full[1], view[1]), Math.min(full[2], view[2]), Math.min(full[3], view[3])];
      if (r[2] <= r[0] || r[3] <= r[1]) r = full;
    }
    return [r, Math.min(pxPerUnit, MAX_SIDE / Math.max(r[2] - r[0], r[3] - r[1], 1e-9))];
  }

  // A canvas over the picture's box `pictureBox` in `where`, for
  // `answer`'s stems, covering `view` at `pxPerUnit` device pixels a unit.
  function place(where, answer, pictureBox, view, pxPerUnit) {
    layer = where;
    g = answer.growth.stems;
    colour = answer.stroke || '#000';
    const c = /^#([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})$/i.exec(colour);
    rgb = c ? [1, 2, 3].map((i) => parseInt(c[i], 16)) : [0, 0, 0];
    full = pictureBox;
    shown = Infinity;
    fo = null;
    old = [];
    focus(...region(view, pxPerUnit));
  }

  // A new canvas over `r` at `scale` pixels a unit (the old one stays
  // until the new one is drawn).
  function focus(r, scale) {
    job++;
    if (fo) old.push(fo);
    box = r;
    k = scale;
    const [w, h] = [box[2] - box[0], box[3] - box[1]];
    fo = el('foreignObject', { x: box[0], y: box[1], width: w, height: h, 'pointer-events': 'none', class: 'tree' }, layer);
    const div = document.createElementNS(XHTML, 'div');
    div.style.cssText = 'position:relative;width:100%;height:100%';
    fo.appendChild(div);
    const [pw, ph] = [Math.max(1, Math.round(w * k)), Math.max(1, Math.round(h * k))];
    canvas = canvasIn(div, pw, ph, 'tree-canvas');
    dots = canvasIn(div, pw, ph, 'tree-dots');
    ctx = canvas.getContext('2d');
    ctx.lineJoin = 'round';
    keep = new Float32Array(pw * ph);
    drawn = 0;
  }

  // The view changed: once it rests, a canvas for it if the one shown
  // does not cover it or is too coarse for it.
  function viewChanged(view, pxPerUnit) {
    clearTimeout(resting);
    if (!ctx) return;
    resting = setTimeout(() => {
      if (!fo || !fo.isConnected) return;
      const [r, scale] = region(view, pxPerUnit);
      const covers = r[0] >= box[0] - 1e-9 && r[1] >= box[1] - 1e-9 && r[2] <= box[2] + 1e-9 && r[3] <= box[3] + 1e-9;
      if (covers && k >= 0.8 * scale) return;
      focus(r, scale);
      show(shown);
    }, 150);
  }

  // A dot for stem `o` (its offset in the stems) if it is under a pixel
  // long and wide: true if it was one.
  // (Called for every stem: no allocation in it.)
  function dot(o) {
    const dx = g[o + 2] - g[o];
    const dy = g[o + 3] - g[o + 1];
    const len = Math.sqrt(dx * dx + dy * dy) * k;
    if (len >= 1) return false;
    const wide = Math.max(g[o + 4] * k, HAIRLINE);
    if (wide > 1) return false;
    const x = Math.floor(((g[o] + g[o + 2]) * 0.5 - box[0]) * k);
    const y = Math.floor(((g[o + 1] + g[o + 3]) * 0.5 - box[1]) * k);
    if (x < 0 || y < 0 || x >= dots.width || y >= dots.height) return true;
    keep[y * dots.width + x] *= 1 - len * wide;
    if (x < x0) x0 = x;
    if (x >= x1) x1 = x + 1;
    if (y < y0) y0 = y;
    if (y >= y1) y1 = y + 1;
    return true;
  }

  // Paints the dots' changed pixels.
  function paintDots() {
    if (x0 >= x1) return;
    const img = new ImageData(x1 - x0, y1 - y0);
    const d = img.data;
    for (let y = y0, i = 0; y < y1; y++) {
      for (let x = x0, p = y * dots.width + x0; x < x1; x++, p++, i += 4) {
        d[i] = rgb[0];
        d[i + 1] = rgb[1];
        d[i + 2] = rgb[2];
        d[i + 3] = Math.round(255 * (1 - keep[p]));
      }
    }
    dots.getContext('2d').putImageData(img, x0, y0);
    [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  }

  // Strokes the path of stems `w` wide: round ends where a stroke is
  // wider than a pixel (below, they cannot be seen, and cost the most).
  function strokeAt(w) {
    ctx.lineWidth = Math.max(w, HAIRLINE / k);
    ctx.lineCap = w * k > 1 ? 'round' : 'butt';
    ctx.stroke();
  }

  // Strokes stems `from` to `to` (indices into the stems).
  function stroke(from, to) {
    let w = g[from * 6 + 4];
    ctx.beginPath();
    for (let s = from; s < to; s++) {
      const o = s * 6;
      if (dot(o)) continue;
      if (g[o + 4] !== w) {
        strokeAt(w);
        ctx.beginPath();
        w = g[o + 4];
      }
      ctx.moveTo(g[o], g[o + 1]);
      ctx.lineTo(g[o + 2], g[o + 3]);
    }
    strokeAt(w);
  }

  function clear() {
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.setTransform(k, 0, 0, k, -box[0] * k, -box[1] * k);
    ctx.strokeStyle = colour;
    dots.getContext('2d').clearRect(0, 0, dots.width, dots.height);
    keep.fill(1);
    [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
    drawn = 0;
  }

  // Shows the stems of decisions up to `decision` (Infinity: all): only
  // the new ones when the canvas holds a prefix of them. Resolves true
  // once they are drawn, false if a newer call took over.
  function show(decision) {
    if (!ctx) return Promise.resolve(false);
    shown = decision;
    const my = ++job;
    const to = stemsUpTo(g, decision);
    if (to < drawn || drawn === 0) clear();
    let painted = performance.now();
    finished = new Promise((resolve) => {
      const step = () => {
        if (my !== job) { resolve(false); return; }
        const t0 = performance.now();
        while (drawn < to && performance.now() - t0 < SLICE_MS) {
          const end = Math.min(to, drawn + BATCH);
          stroke(drawn, end);
          drawn = end;
        }
        // The dots show every few slices, and at the end.
        if (drawn >= to || performance.now() - painted > 4 * SLICE_MS) {
          paintDots();
          painted = performance.now();
        }
        if (drawn < to) { later(step); return; }
        old.forEach((f) => f.remove());
        old = [];
        resolve(true);
      };
      // Not in the caller's task: that one applies a whole answer.
      later(step);
    });
    return finished;
  }

  return {
    place,
    show,
    viewChanged,
    // Resolves once the drawing under way (if any) has ended.
    settled: () => finished,
    // Stems on the canvas now.
    drawn: () => drawn,
  };
}
