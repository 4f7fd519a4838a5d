// The WebAssembly engine's worker: runs the pipeline off the page's
// thread, one call at a time, so the page never freezes. The engine
// (wasm.js) ends a render that a newer edit replaced by ending this
// worker, and starts another.
//
// A message is {module, id, op, json, format}: the compiled module (the
// same for every message; instantiated once), and one call
// (stlc-wasm.js). The answer is {id, status, bytes} (bytes transferred),
// or {id, crash} when the module trapped (a panic, memory exhausted):
// `crash` is the panic's failed answer (JSON) when the module left one.

import { instantiate, call, output } from '../stlc-wasm.js';

let exports = null;

self.onmessage = async (e) => {
  const { module, id, op, json, format } = e.data;
  try {
    if (!exports) exports = await instantiate(module);
    const { status, bytes } = call(exports, op, json, format);
    self.postMessage({ id, status, bytes }, [bytes.buffer]);
  } catch (err) {
    let left = null;
    try { left = exports && output(exports); } catch { left = null; }
    if (left && left.length) {
      self.postMessage({ id, status: 1, bytes: left, crash: true }, [left.buffer]);
    } else {
      self.postMessage({ id, crash: String(err && err.message ? err.message : err) });
    }
  }
};
