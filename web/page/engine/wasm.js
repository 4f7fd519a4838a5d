// The engine in the browser: the pipeline compiled to WebAssembly
// (web/, docs/web.md), run in a Web Worker (worker.js), for the static
// Tree Maker. Same interface and answers as the HTTP engine (index.js):
// the module reads and writes `stlc serve`'s request and answer JSON with
// the server's own code.
//
// One call runs at a time; the others wait their turn. A render whose
// signal is aborted (a newer edit, Cancel) ends at once: its worker is
// ended mid-work and a fresh one takes the next call (it instantiates the
// module compiled once, here).
//
// There is no file on a server: the document is an example, a file
// opened from disk or a share link's text (share.js), and Save downloads.

import { parse } from '../stlc-wasm.js';
import { fromFragment } from '../share.js';

/**
 * The document this tab shows, kept in `sessionStorage` (this tab's
 * only; it outlives a reload) by entry.js each time one is opened:
 * `{name, kind, text, hash}`, its text as opened (its unsaved edits are
 * the draft, kept apart) and the address's fragment then.
 */
const SHOWN_KEY = 'stlc-shown';

/** Remembers `f` as the document this tab shows. */
export function remember(f) {
  try {
    sessionStorage.setItem(SHOWN_KEY, JSON.stringify({ name: f.name, kind: f.kind, text: f.text, hash: location.hash }));
  } catch {
    // Storage refused or full: a reload starts from the 2DTree.
  }
}

function shown() {
  try {
    return JSON.parse(sessionStorage.getItem(SHOWN_KEY) || 'null');
  } catch {
    return null;
  }
}

const MEDIA = { png: 'image/png', svg: 'image/svg+xml', bed: 'text/plain;charset=utf-8', glb: 'model/gltf-binary' };

/**
 * @returns {import('./index.js').Engine}
 */
export function createWasmEngine() {
  const compiled = WebAssembly.compileStreaming(fetch(new URL('../stlc.wasm', import.meta.url)));
  let worker = null;
  let running = null;
  const queue = [];
  let nextId = 1;

  function spawn() {
    worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    worker.onmessage = (e) => {
      const job = running;
      if (!job || e.data.id !== job.id) return;
      running = null;
      if (e.data.crash !== undefined) {
        // A trapped module may be in any state: the next call gets a
        // fresh one. A panic's message comes as its failed answer.
        stop();
        if (e.data.bytes) job.resolve({ status: 1, bytes: e.data.bytes });
        else job.resolve({ status: 1, crash: e.data.crash });
      } else {
        job.resolve({ status: e.data.status, bytes: e.data.bytes });
      }
      pump();
    };
    worker.onerror = (e) => {
      const job = running;
      running = null;
      stop();
      if (job) job.reject(new Error('the WebAssembly worker failed: ' + (e.message || 'unknown error')));
      pump();
    };
  }

  function stop() {
    if (worker) worker.terminate();
    worker = null;
  }

  async function pump() {
    if (running || queue.length === 0) return;
    const job = queue.shift();
    running = job;
    let module;
    try {
      module = await compiled;
    } catch (e) {
      running = null;
      job.reject(new Error('the WebAssembly module could not be loaded: ' + e));
      pump();
      return;
    }
    if (running !== job) return;
    if (!worker) spawn();
    worker.postMessage({ module, id: job.id, op: job.op, json: job.json, format: job.format });
  }

  function aborted() {
    return new DOMException('the render was superseded', 'AbortError');
  }

  // One call through the worker: {status, bytes} or {status: 1, crash}.
  function run(op, request, format, signal) {
    return new Promise((resolve, reject) => {
      if (signal && signal.aborted) { reject(aborted()); return; }
      const job = { id: nextId++, op, json: JSON.stringify(request), format, resolve, reject };
      if (signal) {
        signal.addEventListener('abort', () => {
          if (running === job) {
            // Mid-work: the worker is ended, the work with it.
            running = null;
            stop();
            pump();
          } else {
            const i = queue.indexOf(job);
            if (i < 0) return;
            queue.splice(i, 1);
          }
          reject(aborted());
        }, { once: true });
      }
      queue.push(job);
      pump();
    });
  }

  // A JSON answer, or the failure of a module that trapped.
  function json(a) {
    if (a.crash !== undefined) return { ok: false, error: 'the work stopped in the WebAssembly module: ' + a.crash };
    return parse(a.bytes);
  }

  let listed = null;
  async function text(path) {
    const res = await fetch(new URL('../' + path, import.meta.url));
    if (!res.ok) throw new Error(`${path}: ${res.status} ${res.statusText}`);
    return res.text();
  }
  const kindOf = (name) => (name.endsWith('.bed') ? 'bed' : name.endsWith('.lsys') ? 'lsys' : 'od');

  return {
    async render(request, { signal } = {}) {
      return json(await run('render', request, undefined, signal));
    },

    async export(request, format) {
      const a = await run('export', request, format);
      if (a.status === 0 && a.crash === undefined) return { ok: true, blob: new Blob([a.bytes], { type: MEDIA[format] }) };
      return json(a);
    },

    async words(request) {
      return json(await run('words', request));
    },

    // The templates, then every example (examples/index.json, written by
    // web/build.sh).
    examples() {
      if (!listed) {
        listed = text('examples/index.json').then(async (index) => {
          const { templates, examples } = JSON.parse(index);
          const files = [
            ...templates.map((n) => ['templates/' + n, n]),
            ...examples.map((n) => ['examples/' + n, n]),
          ];
          return Promise.all(files.map(async ([path, name]) => ({ name, kind: kindOf(name), text: await text(path) })));
        });
      }
      return listed;
    },

    // The document the page starts with: the one this tab showed before
    // a reload (its draft is then offered as after any reload), else a
    // share link's text, else the paper's 2DTree. A share link newer than
    // that document (pasted into the address) wins. Nothing to watch:
    // `known` is always current.
    async open(known) {
      if (known !== undefined) return { unchanged: true, version: known };
      const before = shown();
      const f = before && (before.hash === location.hash || !location.hash.includes('s='))
        ? before
        : await fromFragment(location.hash) || { name: '2dtree.od', kind: 'od', text: await text('examples/2dtree.od') };
      remember(f);
      return { name: f.name, kind: f.kind, text: f.text, version: null, path: null, can_save: false };
    },

    async save() {
      return { ok: false, error: 'there is no file here to save to: Save downloads' };
    },
  };
}
