// The engine over HTTP: the pipeline runs in `stlc serve`, the server that
// served this page (the interface: index.js). Nothing leaves 127.0.0.1.

// The compact render answer of a big grown tree (docs/serve.md, "Big
// trees"): a JSON head, then `growth.stems` as 32-bit integers
// (thousandths of a unit, then the decision), put back into the answer as
// the numbers its JSON would hold (a Float64Array): no text to parse.
const COMPACT = 'application/x-stlc-render';

// `count` integers from byte `at`, `per` a stem, the last the decision.
function numbers(buf, at, count, per) {
  const ints = new Int32Array(buf, at, count);
  const g = new Float64Array(count);
  for (let i = 0; i < g.length; i += per) {
    for (let j = i; j < i + per - 1; j++) g[j] = ints[j] / 1000;
    g[i + per - 1] = ints[i + per - 1];
  }
  return g;
}

function unpack(buf) {
  const n = new DataView(buf).getUint32(0, true);
  const head = JSON.parse(new TextDecoder().decode(new Uint8Array(buf, 4, n)));
  const answer = head.answer;
  answer.growth.stems = numbers(buf, 4 + n, head.stems, 6);
  // A 3D input's stems follow, eight numbers a stem.
  if (head.space !== undefined) answer.space.stems = numbers(buf, 4 + n + 4 * head.stems, head.space, 8);
  return answer;
}

/**
 * @param {{token: string}} options the page's token, sent as X-Stlc-Token
 * @returns {import('./index.js').Engine}
 */
export function createHttpEngine({ token }) {
  function post(path, body, signal, accept = 'application/json') {
    return fetch(path, {
      method: 'POST',
      headers: { 'Content-Type': 'application/json', 'X-Stlc-Token': token, Accept: accept },
      body: JSON.stringify(body),
      signal,
    });
  }

  // The JSON of a refused request (400, 403, 413...): `{ok: false, error}`.
  async function refused(res) {
    const a = await res.json().catch(() => null);
    return { ok: false, error: (a && a.error) || res.statusText || `HTTP ${res.status}` };
  }

  return {
    async render(request, { signal } = {}) {
      // A big grown tree may come compact, anything else as JSON.
      const res = await post('/api/render', request, signal, `${COMPACT}, application/json`);
      if (!res.ok) return refused(res);
      if ((res.headers.get('Content-Type') || '').startsWith(COMPACT)) return unpack(await res.arrayBuffer());
      return res.json();
    },

    async export(request, format) {
      const res = await post('/api/export?format=' + encodeURIComponent(format), request);
      if (!res.ok) return refused(res);
      const type = res.headers.get('Content-Type') || '';
      // An input error comes as the render's diagnostics JSON.
      if (type.startsWith('application/json')) return res.json();
      return { ok: true, blob: await res.blob() };
    },

    async words(request) {
      const res = await post('/api/words', request);
      if (!res.ok) return refused(res);
      return res.json();
    },

    async examples() {
      const res = await fetch('/api/examples');
      if (!res.ok) throw new Error(`/api/examples: ${res.status} ${res.statusText}`);
      return res.json();
    },

    async open(known) {
      const res = await fetch('/api/file' + (known ? '?known=' + encodeURIComponent(known) : ''));
      if (!res.ok) throw new Error(`/api/file: ${res.status} ${res.statusText}`);
      return res.json();
    },

    async save(source, version) {
      const res = await post('/api/save', { source, version });
      const a = await res.json().catch(() => ({}));
      if (res.ok && a.ok) return { ok: true, version: a.version };
      if (res.status === 412) return { ok: false, conflict: true, version: a.version };
      if (a.diagnostics) return { ok: false, diagnostics: a.diagnostics };
      return { ok: false, error: a.error || res.statusText || `HTTP ${res.status}` };
    },
  };
}
