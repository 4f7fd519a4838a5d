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
// growth (bfs|dfs), seed, depth, clearance, max-stems, kind (od|bed|lsys;
// else from src's extension, else guessed), size ("WxH"), show-layout. A
// text with errors shows its diagnostics as text (a <pre>) instead.
//
// The element runs the WebAssembly module (stlc.wasm, beside this file) on
// the page's thread: each element draws once its text is known, one after
// another. `element.svg` is the SVG drawn; `data-state` is drawing, drawn
// or error, and a `stl-tree-drawn` event says when.

import { instantiate, call, parse, output } from './stlc-wasm.js';

let module = null;
const exports = () => (module ||= instantiate());

const NUMBERS = { depth: 'depth', clearance: 'clearance', 'max-stems': 'max_stems' };

/** A diagnostic as one line of text (and its help). */
function describe(d) {
  const at = d.line ? `line ${d.line}, column ${d.column}: ` : '';
  return `${at}${d.severity}: ${d.message}${d.label ? ` (${d.label})` : ''}${d.help ? `\n  help: ${d.help}` : ''}`;
}

class StlTree extends HTMLElement {
  static observedAttributes = ['src', 'growth', 'seed', 'depth', 'clearance', 'max-stems', 'kind', 'size', 'show-layout'];

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
    if (this.hasAttribute('growth')) r.strategy = this.getAttribute('growth');
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

  async draw() {
    const mine = ++this.ticket;
    this.dataset.state = 'drawing';
    let source;
    let wasm;
    try {
      [source, wasm] = await Promise.all([this.text(), exports()]);
    } catch (e) {
      if (mine === this.ticket) this.error(String(e.message || e));
      return;
    }
    if (mine !== this.ticket) return;
    let status;
    let bytes;
    try {
      ({ status, bytes } = call(wasm, 'export', JSON.stringify(this.request(source)), 'svg'));
    } catch (e) {
      // The module trapped (a bug, memory exhausted): the next element
      // gets a fresh instance; a panic left its message as JSON.
      module = null;
      const left = output(wasm);
      this.error(left.length ? parse(left).error : `the work stopped in the WebAssembly module: ${e.message || e}`);
      return;
    }
    if (status !== 0) {
      const a = parse(bytes);
      this.error(a.diagnostics ? a.diagnostics.map(describe).join('\n') : a.error);
      return;
    }
    this.svg = new TextDecoder().decode(bytes);
    const doc = new DOMParser().parseFromString(this.svg, 'image/svg+xml');
    this.show(document.importNode(doc.documentElement, true), 'drawn');
  }
}

customElements.define('stl-tree', StlTree);
