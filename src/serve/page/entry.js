// The page's entry module, the one `index.html` names: as `stlc serve`
// serves it, the page with its default engine, HTTP (engine/index.js).
// The static site (web/build.sh) ships web/page/entry.js in this file's
// place, which chooses the WebAssembly engine before loading the same
// page: the HTML names one entry and is never rewritten.
import './app.js';
