// Files: Open… (a file from disk into the editor), Save (through the
// engine, or a download when there is no file to write back), and the
// PNG, SVG and BED exports.

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

  const baseName = () => state.name.replace(/\.[^.]*$/, '');

  async function exportAs(format) {
    const a = await app.engine.export(app.session.request(), format);
    if (a.ok) download(a.blob, `${baseName()}.${format}`);
    else if (a.diagnostics) app.diagnostics.show(a.diagnostics);
    else app.diagnostics.showError(a.error);
  }

  async function save() {
    const text = app.editor.text();
    if (!state.canSave) {
      download(new Blob([text], { type: 'text/plain' }), state.name);
      return;
    }
    const a = await app.engine.save(text);
    if (a.ok) {
      byId('saved').textContent = `Saved ${state.name} at ${new Date().toLocaleTimeString()}.`;
      document.title = `${state.name} - stlc`;
    } else {
      byId('saved').textContent = 'Not saved: ' + (a.error || a.diagnostics.map((d) => d.message).join('; '));
    }
  }

  // The file being edited: its name, whether Save writes it, its text.
  function opened(name, kind, canSave, note) {
    state.name = name;
    state.canSave = canSave;
    byId('file-name').textContent = name + note;
    document.title = `${name} - stlc`;
    app.session.setKind(kind);
  }

  // The engine's file (the one named on the command line, or the example).
  async function openServed() {
    const f = await app.engine.open();
    opened(f.name, f.kind, f.can_save, f.can_save ? '' : ' (example; Save downloads)');
    app.editor.load(f.text);
  }

  byId('open').addEventListener('click', () => input.click());
  input.addEventListener('change', async () => {
    const f = input.files[0];
    if (!f) return;
    const text = await f.text();
    // Cleared, so that opening the same file again reads it again.
    input.value = '';
    const ext = (f.name.split('.').pop() || '').toLowerCase();
    opened(f.name, ext === 'bed' ? 'bed' : ext === 'lsys' || ext === 'ls' ? 'lsys' : 'od', false, ' (Save downloads)');
    state.selected = -1;
    app.tools.cancelPolygon();
    // A new file starts a new history.
    app.editor.load(text);
  });
  byId('save').addEventListener('click', save);
  byId('export-png').addEventListener('click', () => exportAs('png'));
  byId('export-svg').addEventListener('click', () => exportAs('svg'));
  byId('export-bed').addEventListener('click', () => exportAs('bed'));

  return { save, openServed };
}
