// The JavaScript side of the WebAssembly module (web/src/lib.rs): a
// request's JSON written into the module's input buffer, one exported
// call, the answer's bytes copied out. The module imports nothing and
// owns both buffers, so nothing here allocates or frees its memory.
//
// Used by the Tree Maker's worker (engine/worker.js). <stl-tree>
// (stl-tree.js) has the same few lines in its own worker, so that it is
// one script to include.

const encoder = new TextEncoder();
const decoder = new TextDecoder();

/** The module's URL, beside this file in the site. */
export const WASM_URL = new URL('stlc.wasm', import.meta.url);

/**
 * An instance of the module: `module` a compiled WebAssembly.Module, else
 * it is fetched and compiled from WASM_URL.
 *
 * @param {WebAssembly.Module} [module]
 * @returns {Promise<WebAssembly.Exports>}
 */
export async function instantiate(module) {
  const m = module || await WebAssembly.compileStreaming(fetch(WASM_URL));
  const instance = await WebAssembly.instantiate(m, {});
  return instance.exports;
}

const FORMATS = { png: 0, svg: 1, bed: 2, glb: 3 };

/**
 * One call: `op` is render, export, words, compile or check; `json` the
 * request (the body of POST /api/render); `format` (png, svg, bed, glb) for an
 * export. Status 0: the answer (JSON, or an export's bytes); 1: a failure
 * as JSON (`{ok: false, diagnostics}` or `{ok: false, error}`).
 *
 * @returns {{status: number, bytes: Uint8Array}}
 */
export function call(exports, op, json, format) {
  const input = encoder.encode(json);
  const at = exports.stlc_input(input.length);
  new Uint8Array(exports.memory.buffer, at, input.length).set(input);
  let status;
  if (op === 'export') {
    if (!(format in FORMATS)) return { status: 1, bytes: encoder.encode('{"ok":false,"error":"say format png, svg, bed or glb"}') };
    status = exports.stlc_export(FORMATS[format]);
  } else {
    status = exports['stlc_' + op]();
  }
  return { status, bytes: output(exports) };
}

/**
 * A copy of the module's output buffer: the last answer, or after a trap
 * the panic's failed answer (empty when it left none). Copied: the memory
 * may grow (and move) at the next call.
 */
export function output(exports) {
  return new Uint8Array(exports.memory.buffer, exports.stlc_output(), exports.stlc_output_len()).slice();
}

/** An answer's bytes as the JSON they are. */
export function parse(bytes) {
  return JSON.parse(decoder.decode(bytes));
}
