// A big grown tree, drawn on a canvas from the answer's stems. Past
// 20,000 stems the server leaves the tree out of the answer's SVG
// (`tree_in_svg: false`; docs/serve.md, "Big trees"): an SVG of 200,000
// stems is megabytes of text that the page would parse, import and
// rasterise in one go, stalling it for a third of a second. Instead the
// stems in growth order (`growth.stems`, six numbers a stem: from x, y, to
// x, y, width, decision) are stroked onto a <canvas> inside the preview
// (a <foreignObject> over the picture's box, so zoom and pan move it with
// the rest), a slice at a time: the page gets the thread back every few
// milliseconds, and a newer answer or replay step stops an older drawing.
//
// Replay draws the stems up to a decision: growth order puts them first,
// so a replay that moves on adds only the new stems.

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

export function createTreeCanvas() {
  let canvas = null;
  let ctx = null;
  // The stems, their colour, the canvas box (canvas units) and pixels a unit.
  let g = [];
  let colour = '#000';
  let box = [0, 0, 1, 1];
  let k = 1;
  // Stems on the canvas (a prefix of `g`), and the drawing under way.
  let drawn = 0;
  let job = 0;
  let finished = Promise.resolve(true);

  // A canvas over `pictureBox` in `layer`, for `answer`'s stems, at
  // `pxPerUnit` device pixels a canvas unit (at most MAX_SIDE a side).
  function place(layer, answer, pictureBox, pxPerUnit) {
    job++;
    g = answer.growth.stems;
    colour = answer.stroke || '#000';
    box = pictureBox;
    const [w, h] = [box[2] - box[0], box[3] - box[1]];
    k = Math.min(pxPerUnit, MAX_SIDE / Math.max(w, h, 1e-9));
    const fo = el('foreignObject', { x: box[0], y: box[1], width: w, height: h, 'pointer-events': 'none', class: 'tree' }, layer);
    canvas = document.createElementNS(XHTML, 'canvas');
    canvas.width = Math.max(1, Math.round(w * k));
    canvas.height = Math.max(1, Math.round(h * k));
    canvas.style.cssText = 'display:block;width:100%;height:100%';
    canvas.dataset.testid = 'tree-canvas';
    fo.appendChild(canvas);
    ctx = canvas.getContext('2d');
    ctx.lineJoin = 'round';
    drawn = 0;
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
    drawn = 0;
  }

  // Shows the stems of decisions up to `decision` (Infinity: all): only
  // the new ones when the canvas holds a prefix of them. Resolves true
  // once they are drawn, false if a newer call took over.
  function show(decision) {
    if (!ctx) return Promise.resolve(false);
    const my = ++job;
    const to = stemsUpTo(g, decision);
    if (to < drawn || drawn === 0) clear();
    finished = new Promise((resolve) => {
      const step = () => {
        if (my !== job) { resolve(false); return; }
        const t0 = performance.now();
        while (drawn < to && performance.now() - t0 < SLICE_MS) {
          const end = Math.min(to, drawn + BATCH);
          stroke(drawn, end);
          drawn = end;
        }
        if (drawn < to) later(step);
        else resolve(true);
      };
      step();
    });
    return finished;
  }

  return {
    place,
    show,
    // Resolves once the drawing under way (if any) has ended.
    settled: () => finished,
    // Stems on the canvas now.
    drawn: () => drawn,
  };
}
