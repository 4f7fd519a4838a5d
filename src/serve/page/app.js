// stlc serve: the Tree Maker and Tree Renderer page, its entry module. No
// framework, no request leaves 127.0.0.1. The text is the source of truth:
// every drawing edit rewrites the LAYOUT section (and the root) in the
// text (layout.js), and every text change is rendered by the engine
// (engine/), whose answer redraws everything.
//
// One object, `app`, holds the page: `app.state` (all mutable state),
// `app.engine`, and each module's functions (`app.editor`, `app.view`...).
// Modules reach each other only through it, so none keeps loose state of
// its own. It is the page's one global, `window.stlc`, for scripts and the
// browser test. Its shape is declared here, whole, and sealed: a module
// that sets a field this literal does not declare throws at once (ES
// modules are strict), so the state cannot grow fields in other files.

import { createEngine } from './engine/index.js';
import { createEditor } from './editor.js';
import { createDiagnostics } from './diagnostics.js';
import { createSession } from './session.js';
import { createView } from './view.js';
import { createView3d } from './view3d.js';
import { createReplay } from './replay.js';
import { createTools } from './tools.js';
import { createFiles } from './files.js';
import { createDocument } from './document.js';
import { createSettings } from './settings.js';
import { createWords } from './words.js';
import { createScrub } from './scrub.js';
import { addShare } from './sharing.js';
import { createThumbs } from './thumbs.js';

const app = {
  engine: createEngine({}),
  state: {
    tool: 'select',
    // The last answer and the text it answers.
    answer: null,
    answerText: null,
    // Shapes and root of the last good .od answer (page coordinates = canvas units).
    shapes: [],
    layoutSpan: null,
    root: null,
    rootSpan: null,
    // A forest's roots after the first (shown, not dragged).
    others: [],
    selected: -1,
    view: null, // [minx, miny, maxx, maxy] shown
    fitView: null,
    inFlight: false,
    editedAt: 0,
    timings: [],
    replayTimer: null,
    // Show the whole new picture when its answer comes (a file opened, the
    // kind changed, a description pasted over the old one); drawing never
    // moves the view.
    refit: true,
    // Earlier texts for Ctrl-Z, later ones for Ctrl-Shift-Z / Ctrl-Y.
    undo: [],
    redo: [],
    typedAt: -Infinity,
    // The gutter's marks: line -> {cls, title}.
    marks: new Map(),
    // The diagnostics' spans, underlined in the text: [{start, end, cls}]
    // (JavaScript indices into the text they were shown for).
    underlines: [],
    // What was offered for download last.
    lastDownload: null,
    // The document: its name, path, version and saved text (document.js).
    doc: null,
    // The shape being drawn with the mouse, if any (tools.js).
    drawn: null,
    // Whether another file was opened since the last good picture.
    otherFile: false,
    // The New menu's thumbnails drawn so far: example name -> object URL
    // of its PNG ('' when it has none) (thumbs.js).
    thumbnails: new Map(),
  },
  // Each module's functions, set below, in this order.
  editor: null,
  settings: null,
  diagnostics: null,
  session: null,
  view3d: null,
  view: null,
  replay: null,
  tools: null,
  files: null,
  document: null,
  words: null,
  scrub: null,
  thumbs: null,
  // The share link of the document shown (sharing.js).
  shareLink: null,
  // When the first picture was drawn, ms from navigation (the static site's
  // entry.js sets it for benches/web.sh).
  firstPicture: null,
};
Object.seal(app);
Object.seal(app.state);
window.stlc = app;

app.editor = createEditor(app);
app.settings = createSettings(app);
app.diagnostics = createDiagnostics(app);
app.session = createSession(app);
app.view3d = createView3d({ onView: (angles) => { if (app.files) app.files.showView(angles); } });
app.view = createView(app);
app.replay = createReplay(app);
app.tools = createTools(app);
app.files = createFiles(app);
app.document = createDocument(app);
app.words = createWords(app);
app.scrub = createScrub(app);
app.thumbs = createThumbs(app);

// Keys outside the editor's own: Ctrl-S everywhere, undo and redo out of
// the number fields (which keep their own), and the tools' letters.
window.addEventListener('keydown', (e) => {
  const save = (e.ctrlKey || e.metaKey) && e.key === 's';
  if (save) e.preventDefault();
  if (e.target === app.editor.element || e.target.tagName === 'INPUT') {
    if (save) app.document.save();
    else if (e.target === app.editor.element) app.editor.undoKey(e);
    return;
  }
  if (save) { app.document.save(); return; }
  if (app.editor.undoKey(e)) return;
  const tool = { s: 'select', r: 'Rectangle', o: 'RoundRect', e: 'Ellipse', p: 'Polygon' }[e.key];
  if (e.key === 'Escape') app.tools.cancelPolygon();
  else if (e.key === 'Delete' || e.key === 'Backspace') app.tools.deleteSelected();
  else if (e.key === 'f') app.view.fit();
  else if (e.key === ',') app.replay.nudge(-1);
  else if (e.key === '.') app.replay.nudge(1);
  else if (tool) app.tools.setTool(tool);
});

app.tools.setTool('select');
addShare(app);
app.document.openServed();
