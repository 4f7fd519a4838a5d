// The render loop: the options in the header, one render at a time
// through the engine, and each answer applied to the state, the view and
// the diagnostics. The text is the source of truth: every change of it
// ends here, and the answer redraws everything.

import { byId, grouped } from './dom.js';

export function createSession(app) {
  const { state } = app;

  // The engine's RenderRequest for the editor's text. An OD's and an
  // .lsys's settings are keys in the text (settings.js), so the request is
  // the text and its kind; the controls only show and edit those keys. A
  // BED grows nothing and chooses nothing: it has no settings.
  function request() {
    app.settings.sync();
    return { source: app.editor.text(), kind: byId('kind').value };
  }

  // The request in flight, if any. A newer edit ends it: its fetch is
  // aborted, which closes its connection, and the server stops its work
  // (docs/serve.md); the newer request goes at once.
  let current = null;
  let busyTimer = null;

  // Long work shows itself after 300 ms, with a way out.
  function busy(on) {
    clearTimeout(busyTimer);
    if (on) busyTimer = setTimeout(() => { byId('busy').hidden = false; }, 300);
    else byId('busy').hidden = true;
  }

  function settle(mine) {
    if (current !== mine) return;
    current = null;
    state.inFlight = false;
    busy(false);
  }

  async function refresh() {
    if (current) current.abort();
    const mine = new AbortController();
    current = mine;
    state.inFlight = true;
    busy(true);
    const req = request();
    const started = state.editedAt || performance.now();
    try {
      const answer = await app.engine.render(req, { signal: mine.signal });
      if (current !== mine) return;
      if (answer.error !== undefined) {
        // Refused: no answer to this text, the last one stays.
        app.diagnostics.showError(answer.error);
      } else {
        apply(answer, req.source);
        const ms = performance.now() - started;
        state.timings.push(ms);
        status(answer, ms);
      }
    } catch (e) {
      if (e.name === 'AbortError') return;
      byId('status').textContent = 'The server does not answer: is stlc serve still running? (' + e + ')';
    } finally {
      settle(mine);
    }
  }

  // The busy indicator's Cancel: the work stops; the last picture stays.
  function cancel() {
    if (!current) return;
    const mine = current;
    mine.abort();
    settle(mine);
    byId('status').textContent = 'Cancelled: the picture shown is of an earlier text (edit to try again)';
  }
  byId('cancel').addEventListener('click', cancel);

  function status(answer, ms) {
    const parts = [];
    if (answer.ok) {
      // Digits, exact at any depth (a JS number is exact only to 2^53).
      parts.push(`${answer.stems_exact ? '' : 'at least '}${grouped(answer.stems)} stems`);
      const decisions = answer.space ? answer.space.decisions : answer.growth && answer.growth.decisions;
      if (decisions) parts.push(`${grouped(decisions)} growth decisions`);
    } else {
      parts.push(state.otherFile ? 'errors: no picture of this file yet' : 'errors: the last good picture is shown');
    }
    parts.push(`${Math.round(ms)} ms from edit to picture`);
    byId('status').textContent = parts.join(' · ');
  }

  function apply(answer, text) {
    state.answer = answer;
    state.answerText = text;
    // The stem colour field shows the colour drawn where the text names none.
    if (answer.ok) app.settings.sync();
    if (!answer.ok) {
      app.diagnostics.show(answer.diagnostics);
      // The last good picture stays, faded, while you fix this file; a
      // file just opened that fails shows no picture of another file.
      if (state.otherFile) app.view.forget();
      else app.view.stale();
      return;
    }
    state.otherFile = false;
    app.diagnostics.show(answer.warnings);
    app.words.refresh();
    app.scrub.refresh();
    app.files.showCommand();
    if (answer.root) {
      state.root = [answer.root.x, answer.root.y];
      state.rootSpan = [answer.root.start, answer.root.end];
      state.others = (answer.root.others || []).map((r) => [r.x, r.y]);
      state.layoutSpan = answer.layout ? [answer.layout.start, answer.layout.end] : null;
      state.shapes = answer.layout ? answer.layout.shapes.map((s) => Object.assign({}, s)) : [];
    } else {
      state.root = null;
      state.others = [];
      state.shapes = [];
      state.layoutSpan = null;
    }
    if (state.selected >= state.shapes.length) state.selected = -1;
    app.replay.reset(answer.space ? answer.space.decisions : answer.growth ? answer.growth.decisions : 0);
    app.view.draw();
  }

  // The answer's spans are valid only while the text is the one answered.
  const inSync = () => app.editor.text() === state.answerText;

  function setKind(kind) {
    byId('kind').value = kind;
    document.body.classList.toggle('renderer', kind !== 'od');
    document.body.classList.toggle('lsys', kind === 'lsys');
    document.body.classList.toggle('bed', kind === 'bed');
    byId('mode-name').textContent = kind === 'od' ? 'Tree Maker' : 'Tree Renderer';
    state.refit = true;
  }

  const edited = () => { state.editedAt = performance.now(); app.editor.schedule(); };
  byId('kind').addEventListener('change', () => { setKind(byId('kind').value); app.editor.schedule(); });
  byId('reseed').addEventListener('click', () => {
    const now = byId('seed').value.trim();
    let next = 1n;
    try { if (now !== '') next = BigInt(now) + 1n; } catch { next = 1n; }
    byId('seed').value = String(next);
    if (!app.settings.changed('seed')) edited();
  });
  // A control edits its key in the text (which renders), else just renders.
  const control = (id) => () => { if (!app.settings.changed(id)) edited(); };
  ['clearance', 'max-stems', 'depth', 'seed', 'stem-colour'].forEach((id) => byId(id).addEventListener('input', control(id)));
  byId('growth').addEventListener('change', control('growth'));
  byId('leaf').addEventListener('change', control('leaf'));

  return { request, refresh, cancel, setKind, inSync };
}
