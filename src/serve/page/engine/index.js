// The engine: the one thing the page asks to render, export, open and
// save. The editor, the view and the tools call only the methods below;
// which engine runs is chosen here, so another one (a WebAssembly build of
// the pipeline in a Web Worker) is added in this folder without touching
// the other modules.
//
// Every answer is the HTTP API's JSON (docs/serve.md, "HTTP API"),
// whichever engine gives it.

/**
 * What to render or export: the body of `POST /api/render`.
 *
 * @typedef {object} RenderRequest
 * @property {string} source the text
 * @property {'od'|'bed'|'lsys'} [kind] guessed from the text when absent
 * @property {'bfs'|'dfs'|'space'} [growth] the growth order of an `.od` (bfs; `strategy`, its old name, is still read)
 * @property {number} [depth] `--depth` of an `.lsys`
 * @property {number} [clearance] `--clearance`
 * @property {number} [max_stems] `--max-stems`
 * @property {string} [seed] `--seed`, a string of digits (64 bits)
 * @property {[number, number]} [size] `--size WxH` of the picture, each 1 to 16384 pixels
 * @property {boolean} [show_layout] `--show-layout`; absent: wherever there is a layout (the editor's view)
 * @property {string} [background] `--background`: `none`, `#rrggbb` or a Delphi colour name
 * @property {[number, number]} [view] `--view AZ,EL` of a 3D input's picture, degrees
 * @property {number} [unit] `--unit` of a mesh export: metres per canvas unit (0.01)
 */

/**
 * A diagnostic. `line`, `column`, `end_line`, `end_column` are 1-based;
 * columns count Unicode characters (code points), not UTF-16 units (see
 * `textIndex` in diagnostics.js); the end is just past the span. `line` is
 * null for a diagnostic with no place in the text.
 *
 * @typedef {object} Diagnostic
 * @property {string} message
 * @property {'error'|'warning'} severity
 * @property {number|null} line
 * @property {number|null} [column]
 * @property {number|null} [end_line]
 * @property {number|null} [end_column]
 * @property {string|null} [label]
 * @property {string|null} [help]
 */

/**
 * The answer to a render:
 * - `{ok: true, svg, bed, stems, warnings, growth: {stems, decisions},
 *   view, root: {x, y, start, end, others}, layout: {start, end, shapes}}`
 *   (`start`, `end`: UTF-16 offsets into `source`, JavaScript indices);
 * - `{ok: false, diagnostics: Diagnostic[]}` for an input error;
 * - `{ok: false, error: string}` when the request itself was refused
 *   (malformed, too large): there is no answer to the text.
 *
 * @typedef {object} RenderAnswer
 */

/**
 * The answer to an export: `{ok: true, blob}` with the bytes (a Blob typed
 * `image/png`, `image/svg+xml` or `text/plain`), else a failed
 * RenderAnswer (`diagnostics` or `error`).
 *
 * @typedef {object} ExportAnswer
 */

/**
 * The engine's interface. Every method returns a Promise, which rejects
 * only when the engine cannot answer at all (the server is gone).
 *
 * @typedef {object} Engine
 * @property {(request: RenderRequest, options?: {signal?: AbortSignal}) => Promise<RenderAnswer>} render
 *   the picture, growth order, root and layout of `request.source`; an
 *   aborted `signal` ends the work (the promise rejects with an
 *   `AbortError`), as a newer edit or the busy indicator's Cancel does
 * @property {(request: RenderRequest, format: 'png'|'svg'|'bed'|'glb') => Promise<ExportAnswer>} export
 *   the bytes `stlc render -f png|svg --show-layout` or `stlc compile`
 *   would write
 * @property {(request: RenderRequest) => Promise<{ok: true, words: Array<{depth: number, word: string, length: string, stats: string, cut: boolean}>}|{ok: false, diagnostics?: Diagnostic[], error?: string}>} words
 *   an `.lsys`'s word at each generation from 0 (at most 8, each cut at
 *   2,000 characters, with its exact length)
 * @property {() => Promise<Array<{name: string, kind: 'od'|'bed'|'lsys', text: string}>>} examples
 *   the templates a new file starts from (`new.od`, `new.lsys`), then
 *   every example: the New menu
 * @property {() => Promise<{text: string, version: string|null, kind: 'od'|'bed'|'lsys', name: string, path: string, can_save: boolean}>} open
 *   the file being edited (or the example) as it is now; `version` names
 *   its contents (`null`: the file does not exist yet; Save creates it).
 *   `open(known)` answers `{version, unchanged: true}` instead while the
 *   file is still at version `known` (a cheap check for watching)
 * @property {(source: string, version: string|null) => Promise<{ok: true, version: string}|{ok: false, conflict: true, version: string|null}|{ok: false, error?: string, diagnostics?: Diagnostic[]}>} save
 *   writes `source` to that file (when `can_save`) if it is still at
 *   `version`, the version the edit is based on; `conflict` when another
 *   tab or program changed it since (with the version there now)
 */

import { createHttpEngine } from './http.js';

let chosen = createHttpEngine;

/**
 * Chooses another engine for this page, before app.js creates it: the
 * static site's entry module (web/page/entry.js) chooses the WebAssembly
 * one (web/page/engine/wasm.js). `stlc serve` chooses none: HTTP.
 *
 * @param {(options: object) => Engine} create
 */
export function useEngine(create) {
  chosen = create;
}

/**
 * The engine this page uses: the HTTP one unless another was chosen.
 *
 * @param {object} options the engine's options (none today)
 * @returns {Engine}
 */
export function createEngine(options) {
  return chosen(options);
}
