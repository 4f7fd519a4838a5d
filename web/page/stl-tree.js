// <stl-tree>: a tree drawn live from its STL text in any page.
//
//   <script type="module" src="stl-tree.js"></script>
//   <stl-tree growth="dfs" seed="7"><script type="text/stl">...</script></stl-tree>
//   <stl-tree src="examples/grove.od"></stl-tree>
//
// The text is a `<script type="text/stl">` child (STL is not HTML: `<` and
// `&` stay as written there) or the file at `src=`. The element draws the
// SVG `stlc render -f svg` writes (its default size, no layout underneath)
// as an inline <svg> child in the light DOM, so a page can inspect and
// style it. Attributes override the file's keys as the CLI's flags do:
// growth (bfs|dfs|space), seed, depth, clearance, max-stems, kind (od|bed|lsys;
// else from src's extension, else guessed), size ("WxH"), show-layout,
// time-budget (seconds). A text with errors shows its diagnostics as text
// (a <pre>) instead.
//
// One script to include: the element needs only stlc.wasm beside this
// file, found by this file's own URL (wherever the page is); when it is
// missing, each element says so, naming the address it tried.
//
// The module runs in a Web Worker (made here, from this file's own code:
// no second script), so a tree that takes seconds never freezes the
// page; elements draw one after another. Each draw has a time budget
// (`time-budget`, seconds, default 30 as `stlc serve`'s): past it the
// worker is ended, the element shows why, and a fresh worker draws the
// next. `element.svg` is the SVG drawn; `data-state` is drawing, drawn
// or error, and a `stl-tree-drawn` event says when.

/** Where the module is looked for: beside this file. */
const WASM_URL = new URL('stlc.wasm', import.meta.url);

/** Seconds a draw may take unless the element's `time-budget` says. */
const TIME_BUDGET = 30;

// The worker's code (run from a blob: URL, so it is this file's text):
// instantiates the compiled module once, then answers {id, json} with
// {id, status, bytes} as stlc-wasm.js's call() does, or {id, crash}.
function workerMain() {
  const encoder = new TextEncoder();
  let exports = null;
  const output = () => new Uint8Array(exports.memory.buffer, exports.stlc_output(), exports.stlc_output_len()).slice();
  self.onmessage = async (e) => {
    const { module, id, json } = e.data;
    try {
      if (!exports) exports = (await WebAssembly.instantiate(module, {})).exports;
      const input = encoder.encode(json);
      const at = exports.stlc_input(input.length);
      new Uint8Array(exports.memory.buffer, at, input.length).set(input);
      const status = exports.stlc_export(1);
      const bytes = output();
      self.postMessage({ id, status, bytes }, [bytes.buffer]);
    } catch (err) {
      let left = null;
      try { left = exports && output(); } catch { left = null; }
      self.postMessage({ id, crash: String(err && err.message ? err.message : err), left });
    }
  };
}
const WORKER_URL = URL.createObjectURL(new Blob([`(${workerMain.toString()})();`], { type: 'text/javascript' }));

let compiled = null;
// The module, compiled once; a missing one is an error naming it.
function module() {
  compiled ||= (async () => {
    let res;
    try {
      res = await fetch(WASM_URL);
    } catch (e) {
      throw new Error(`<stl-tree> needs stlc.wasm beside stl-tree.js, at ${WASM_URL}: it could not be fetched (${e.message})`);
    }
    if (!res.ok) {
      throw new Error(`<stl-tree> needs stlc.wasm beside stl-tree.js, at ${WASM_URL}: it answered ${res.status} ${res.statusText}. Copy stlc.wasm (target/site/stlc.wasm) next to stl-tree.js.`);
    }
    return WebAssembly.compile(await res.arrayBuffer());
  })();
  compiled.catch(() => { compiled = null; });
  return compiled;
}

// One worker; draws wait their turn. A draw past its budget ends it.
let worker = null;
let nextId = 1;
let turn = Promise.resolve();
function run(json, seconds) {
  const job = turn.then(async () => {
    const m = await module();
    worker ||= new Worker(WORKER_URL);
    const w = worker;
    const id = nextId++;
    return new Promise((resolve) => {
      const timer = setTimeout(() => {
        w.terminate();
        if (worker === w) worker = null;
        resolve({ late: true });
      }, seconds * 1000);
      w.onmessage = (e) => {
        if (e.data.id !== id) return;
        clearTimeout(timer);
        // A trapped module may be in any state: the next draw gets a fresh one.
        if (e.data.crash !== undefined) {
          w.terminate();
          if (worker === w) worker = null;
        }
        resolve(e.data);
      };
      w.onerror = (e) => {
        clearTimeout(timer);
        w.terminate();
        if (worker === w) worker = null;
        resolve({ crash: e.message || 'the worker failed' });
      };
      w.postMessage({ module: m, id, json });
    });
  });
  turn = job.catch(() => {});
  return job;
}

const decoder = new TextDecoder();
const parse = (bytes) => JSON.parse(decoder.decode(bytes));

const NUMBERS = { depth: 'depth', clearance: 'clearance', 'max-stems': 'max_stems' };

/** A diagnostic as one line of text (and its help). */
function describe(d) {
  const at = d.line ? `line ${d.line}, column ${d.column}: ` : '';
  return `${at}${d.severity}: ${d.message}${d.label ? ` (${d.label})` : ''}${d.help ? `\n  help: ${d.help}` : ''}`;
}

class StlTree extends HTMLElement {
  static observedAttributes = ['src', 'growth', 'seed', 'depth', 'clearance', 'max-stems', 'kind', 'size', 'show-layout', 'time-budget'];

  constructor() {
    super();
    this.svg = null;
    this.ticket = 0;
  }

  connectedCallback() {
    // A parser still reading the children: wait for the whole document.
    if (document.readyState === 'loading') {
      document.addEventListener('DOMContentLoaded', () => this.draw(), { once: true });
    } else {
      this.draw();
    }
  }

  attributeChangedCallback() {
    if (this.isConnected && document.readyState !== 'loading') this.draw();
  }

  // The element's text: its script child's, else src's file.
  async text() {
    const script = this.querySelector(':scope > script[type="text/stl"]');
    if (script) return script.textContent.replace(/^\n/, '');
    const src = this.getAttribute('src');
    if (!src) throw new Error('no STL text: give a <script type="text/stl"> child or src=');
    const res = await fetch(src);
    if (!res.ok) throw new Error(`${src}: ${res.status} ${res.statusText}`);
    return res.text();
  }

  request(source) {
    const r = { source, show_layout: this.hasAttribute('show-layout') };
    const src = this.getAttribute('src') || '';
    const ext = src.split(/[?#]/)[0].split('.').pop().toLowerCase();
    const kind = this.getAttribute('kind') || (['od', 'bed', 'lsys'].includes(ext) ? ext : null);
    if (kind) r.kind = kind;
    if (this.hasAttribute('growth')) r.growth = this.getAttribute('growth');
    if (this.hasAttribute('seed')) r.seed = this.getAttribute('seed');
    for (const [attr, field] of Object.entries(NUMBERS)) {
      if (this.hasAttribute(attr)) r[field] = Number(this.getAttribute(attr));
    }
    const size = /^(\d+)x(\d+)$/.exec(this.getAttribute('size') || '');
    if (size) r.size = [Number(size[1]), Number(size[2])];
    return r;
  }

  // Everything but the text's script: what the element drew before.
  clear() {
    for (const n of [...this.childNodes]) {
      if (!(n instanceof HTMLScriptElement)) n.remove();
    }
  }

  show(node, state) {
    this.clear();
    this.append(node);
    this.dataset.state = state;
    this.dispatchEvent(new CustomEvent('stl-tree-drawn', { detail: { state } }));
  }

  error(text) {
    this.svg = null;
    const pre = document.createElement('pre');
    pre.className = 'stl-tree-error';
    pre.textContent = text;
    this.show(pre, 'error');
  }

  // The element's time budget, seconds.
  budget() {
    const b = Number(this.getAttribute('time-budget'));
    return this.hasAttribute('time-budget') && b > 0 ? b : TIME_BUDGET;
  }

  async draw() {
    const mine = ++this.ticket;
    this.dataset.state = 'drawing';
    let a;
    try {
      const source = await this.text();
      if (mine !== this.ticket) return;
      a = await run(JSON.stringify(this.request(source)), this.budget());
    } catch (e) {
      if (mine === this.ticket) this.error(String(e.message || e));
      return;
    }
    if (mine !== this.ticket) return;
    if (a.late) {
      this.error(`stopped after ${this.budget()} s, the time budget of this element: draw less (a smaller depth or max-stems), or give it more time (time-budget="60", in seconds)`);
      return;
    }
    if (a.crash !== undefined) {
      this.error(a.left && a.left.length ? parse(a.left).error : `the work stopped in the WebAssembly module: ${a.crash}`);
      return;
    }
    if (a.status !== 0) {
      const f = parse(a.bytes);
      this.error(f.diagnostics ? f.diagnostics.map(describe).join('\n') : f.error);
      return;
    }
    this.svg = decoder.decode(a.bytes);
    const doc = new DOMParser().parseFromString(this.svg, 'image/svg+xml');
    this.show(document.importNode(doc.documentElement, true), 'drawn');
  }
}

customElements.define('stl-tree', StlTree);
