// Files: Open… (a file from disk into the editor), the Save button (the
// saving itself is document.js's), and the PNG, SVG, BED and (a 3D
// input's mesh) GLB exports.

import { byId } from './dom.js';

export function createFiles(app) {
  const { state } = app;
  const input = byId('open-file');

  function download(blob, name) {
    // What was offered last, for scripts and tests.
    state.lastDownload = { name, size: blob.size, type: blob.type };
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = name;
    document.body.appendChild(a);
    a.click();
    setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
  }

  const baseName = () => state.doc.name.replace(/\.[^.]*$/, '');

  // The width and height of the picture at the default size: the shown
  // answer's SVG when it is this text's 2D picture, else (a 3D view at
  // the view's angles, a text not drawn yet) an export at the default
  // size, remembered per request. Null when there is none (errors).
  const defaultSizes = new Map();
  async function defaultSize(request) {
    const header = (svg) => {
      const m = /<svg[^>]* width="(\d+)" height="(\d+)"/.exec(svg.slice(0, 400));
      return m ? [Number(m[1]), Number(m[2])] : null;
    };
    const a = state.answer;
    if (a && a.ok && !a.space && !request.view && state.answerText === request.source) return header(a.svg);
    const key = JSON.stringify(request);
    if (!defaultSizes.has(key)) {
      defaultSizes.clear();
      defaultSizes.set(key, app.engine.export(request, 'svg').then(async (e) => (e.ok ? header(await e.blob.text()) : null)));
    }
    return defaultSizes.get(key);
  }

  // The size asked for, `[w, h]`, or undefined for the default. With one
  // side only ("4000 x auto"), the other comes from the default picture's
  // aspect, rounded, so the picture keeps its shape and the command shown
  // writes the same bytes.
  async function exportSize(request) {
    const side = (id) => {
      const v = byId(id).value.trim();
      return v === '' ? null : Math.floor(Number(v));
    };
    const w = side('export-w');
    const h = side('export-h');
    if (w !== null && h !== null) return [w, h];
    if (w === null && h === null) return undefined;
    const d = await defaultSize(request);
    if (!d) return undefined;
    const other = (n) => Math.min(16384, Math.max(1, Math.round(n)));
    return w !== null ? [w, other((w * d[1]) / d[0])] : [other((h * d[0]) / d[1]), h];
  }

  // The export options (size, layout, background) as request fields.
  async function exportOptions() {
    const o = { show_layout: byId('export-layout').checked };
    if (byId('export-transparent').checked) o.background = 'none';
    else if (byId('export-coloured').checked) o.background = byId('export-colour').value;
    // A 3D input's picture from the angles the 3D view shows.
    if (state.answer && state.answer.ok && state.answer.space) o.view = app.view3d.angles();
    const size = await exportSize({ ...app.session.request(), ...o });
    if (size) o.size = size;
    return o;
  }

  // The mesh's `--unit` as typed (the engine refuses one that is not a
  // positive number, with its reason).
  const meshUnit = () => Number(byId('mesh-unit').value.trim() || '0.01');

  // The command line that writes the same bytes as an export.
  function command(format, o) {
    const r = app.session.request();
    const name = state.doc.name;
    const args = format === 'bed' ? ['stlc', 'compile', name] : ['stlc', 'render', name];
    if (format === 'glb') args.push('--mesh', 'glb', '--unit', String(meshUnit()));
    if (r.growth && r.growth !== 'bfs') args.push('--growth', r.growth);
    if (r.seed !== undefined) args.push('--seed', r.seed);
    if (r.depth !== undefined) args.push('--depth', String(r.depth));
    if (r.clearance !== undefined) args.push('--clearance', String(r.clearance));
    if (r.max_stems !== undefined) args.push('--max-stems', String(r.max_stems));
    if (format !== 'bed' && format !== 'glb') {
      if (o.size) args.push('--size', `${o.size[0]}x${o.size[1]}`);
      if (o.view) args.push('--view', o.view.join(','));
      if (o.show_layout && r.kind !== 'lsys') args.push('--show-layout');
      if (o.background) args.push('--background', o.background === 'none' ? 'none' : `'${o.background}'`);
    }
    args.push('-o', `${baseName()}.${format}`);
    return args.join(' ');
  }

  let shown = 0;
  async function showCommand() {
    if (!byId('export-options').open) return;
    const asked = ++shown;
    const o = await exportOptions();
    // A later call (a newer keystroke) writes instead.
    if (asked !== shown) return;
    // The side left empty shows what it will be.
    for (const [id, i] of [['export-w', 0], ['export-h', 1]]) {
      const e = byId(id);
      e.placeholder = e.value.trim() === '' && o.size ? `auto: ${o.size[i]}` : 'auto';
    }
    const formats = ['png', 'svg'];
    if (byId('kind').value === 'od') formats.push('bed');
    if (document.body.classList.contains('space')) formats.push('glb');
    byId('export-cli').textContent = formats.map((f) => command(f, o)).join('\n');
  }
  byId('export-options').addEventListener('toggle', showCommand);
  for (const id of ['export-w', 'export-h', 'export-layout', 'export-transparent', 'export-coloured', 'export-colour', 'mesh-unit']) {
    byId(id).addEventListener('input', showCommand);
  }

  // The 3D view's angles beside the mesh export (3D view: view3d.js).
  function showView([az, el]) {
    byId('mesh-view').textContent = `view ${az}°, ${el}° (PNG, SVG); the mesh: y up, root at the origin`;
  }

  // What an export asks: a BED the text's growth alone, a mesh its unit
  // too (a mesh has no view, size or background), a picture the panel's
  // options.
  async function exportRequest(format) {
    if (format === 'bed') return app.session.request();
    if (format === 'glb') return { ...app.session.request(), unit: meshUnit() };
    return { ...app.session.request(), ...(await exportOptions()) };
  }

  async function exportAs(format) {
    const request = await exportRequest(format);
    const a = await app.engine.export(request, format);
    if (a.ok) download(a.blob, `${baseName()}.${format}`);
    else if (a.diagnostics) app.diagnostics.show(a.diagnostics);
    else app.diagnostics.showError(a.error);
  }

  byId('open').addEventListener('click', () => input.click());
  input.addEventListener('change', async () => {
    const f = input.files[0];
    if (!f) return;
    const text = await f.text();
    // Cleared, so that opening the same file again reads it again.
    input.value = '';
    const ext = (f.name.split('.').pop() || '').toLowerCase();
    const kind = ext === 'bed' ? 'bed' : ext === 'lsys' || ext === 'ls' ? 'lsys' : 'od';
    state.selected = -1;
    app.tools.cancelPolygon();
    // A new file starts a new history; its unsaved edits are kept by name.
    app.document.opened({ name: f.name, kind, text, can_save: false, path: null, version: null }, ' (Save downloads)');
  });
  // New: a template or an example as a new document (Save downloads it).
  const menu = byId('new');
  let examples = [];
  app.engine.examples().then((list) => {
    examples = list;
    for (const [i, e] of list.entries()) {
      const o = document.createElement('option');
      o.value = String(i);
      o.textContent = i < 2 ? `${e.name} (template)` : e.name;
      menu.append(o);
    }
  }).catch(() => { menu.disabled = true; });
  menu.addEventListener('change', () => {
    const e = examples[Number(menu.value)];
    menu.value = '';
    openExample(e);
  });
  // An example or template as a new document (the New menu, a thumbnail).
  function openExample(e) {
    if (!e) return;
    state.selected = -1;
    app.tools.cancelPolygon();
    app.document.opened({ name: e.name, kind: e.kind, text: e.text, can_save: false, path: null, version: null }, ' (new; Save downloads)');
  }
  byId('save').addEventListener('click', () => app.document.save());
  byId('export-png').addEventListener('click', () => exportAs('png'));
  byId('export-svg').addEventListener('click', () => exportAs('svg'));
  byId('export-bed').addEventListener('click', () => exportAs('bed'));
  byId('export-glb').addEventListener('click', () => exportAs('glb'));

  return { download, showCommand, showView, openExample };
}
