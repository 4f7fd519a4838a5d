// Replay: the stems in the order the grower decided them, from the
// answer's `growth.stems` (six numbers a stem: from, to, width, decision).
// The slider picks a decision, ◀ and ▶ step one decision, and Replay plays
// them at the chosen speed: one decision a frame (30 a second), or all of
// them in 30, 4 or 1 seconds.

import { byId, el, grouped } from './dom.js';
import { stemsUpTo } from './bigtree.js';

export function createReplay(app) {
  const { state } = app;
  const preview = app.view.element;
  const step = byId('step');
  const play = byId('play');

  // The stroke colour of the library's tree, for the stems drawn here.
  function strokeColour() {
    if (state.answer.stroke) return state.answer.stroke;
    const p = preview.querySelector('.lib path[fill="none"]');
    return p ? p.getAttribute('stroke') : '#4a2c12';
  }

  // Draws the stems of decisions 0..k from the growth order.
  function showStems(k) {
    const layer = preview.querySelector('.replay-layer');
    layer.innerHTML = '';
    const g = state.answer.growth.stems;
    const byWidth = new Map();
    for (let i = 0; i < g.length; i += 6) {
      if (g[i + 5] > k) continue;
      const w = g[i + 4];
      const d = byWidth.get(w) || [];
      d.push(`M${g[i]} ${g[i + 1]}L${g[i + 2]} ${g[i + 3]}`);
      byWidth.set(w, d);
    }
    const colour = strokeColour();
    for (const [w, d] of byWidth) {
      el('path', {
        d: d.join(''), fill: 'none', stroke: colour, 'stroke-width': Math.max(w, 0.3),
        'stroke-linecap': 'round', 'stroke-linejoin': 'round',
      }, layer);
    }
  }

  function countStems(k) {
    const g = state.answer.growth.stems;
    let n = 0;
    for (let i = 5; i < g.length; i += 6) if (g[i] <= k) n++;
    return n;
  }

  // A 3D input's stems of decisions up to `k`, on the 3D view.
  function replay3d(a, k) {
    const max = a.space.decisions;
    app.view3d.upTo(k < max ? k : Infinity);
    const g = a.space.stems;
    let n = 0;
    for (let i = 7; i < g.length; i += 8) if (g[i] <= k) n++;
    byId('step-label').textContent = max ? `decision ${grouped(k)} of ${grouped(max)} · ${grouped(n)} stems` : '';
  }

  function replayTo(k, fromUser) {
    const a = state.answer;
    if (a && a.ok && a.space) {
      replay3d(a, k);
      if (fromUser) stopReplay(true);
      return;
    }
    if (!a || !a.ok || !a.growth) return;
    const max = a.growth.decisions;
    const partial = k < max;
    const grownNoLayout = !a.view && a.root;
    // A big tree is on its canvas (bigtree.js), which replays it itself.
    const big = a.tree_in_svg === false;
    preview.classList.toggle('replaying', partial && !grownNoLayout && !big);
    if (big) app.view.tree.show(k);
    else if (partial || grownNoLayout) showStems(k);
    else preview.querySelector('.replay-layer').innerHTML = '';
    const stems = big ? stemsUpTo(a.growth.stems, k) : countStems(k);
    byId('step-label').textContent = max ? `decision ${grouped(k)} of ${grouped(max)} · ${grouped(stems)} stems` : '';
    if (fromUser) stopReplay(true);
  }

  function stopReplay(keep) {
    if (state.replayTimer) clearInterval(state.replayTimer);
    state.replayTimer = null;
    play.textContent = '▶ Replay';
    if (!keep) preview.classList.remove('replaying');
  }

  // A new answer with `decisions` decisions: the slider at its end.
  function reset(decisions) {
    step.max = decisions;
    step.value = decisions;
    stopReplay();
  }

  step.addEventListener('input', () => replayTo(Number(step.value), true));
  // One decision back or on.
  function nudge(by) {
    const v = Math.max(0, Math.min(Number(step.max), Number(step.value) + by));
    step.value = v;
    replayTo(v, true);
  }
  byId('step-back').addEventListener('click', () => nudge(-1));
  byId('step-next').addEventListener('click', () => nudge(1));

  // Decisions a frame (33 ms) for the chosen speed.
  function perFrame(max) {
    const speed = byId('replay-speed').value;
    if (speed === '1') return 1;
    const seconds = speed === '1s' ? 1 : Number(speed);
    return Math.max(1, Math.ceil(max / (seconds * 30)));
  }
  play.addEventListener('click', () => {
    if (state.replayTimer) { stopReplay(true); return; }
    const max = Number(step.max);
    if (!max) return;
    if (Number(step.value) >= max) step.value = 0;
    const per = perFrame(max);
    play.textContent = '❚❚ Pause';
    state.replayTimer = setInterval(() => {
      const v = Math.min(max, Number(step.value) + per);
      step.value = v;
      replayTo(v, false);
      if (v >= max) stopReplay(false);
    }, 33);
  });

  return {
    showStems,
    reset,
    nudge,
    // The slider's decision, after a redraw.
    show: () => replayTo(Number(step.value), false),
  };
}
