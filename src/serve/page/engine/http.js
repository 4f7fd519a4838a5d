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

// Where this tab keeps the server's per-run key (docs/serve.md, "Security
// model"). sessionStorage belongs to this origin, port included, and to
// this tab: a reload keeps it, a new tab needs the printed link.
const KEY = 'stlc-token';

/**
 * The per-run key: the printed link carries it in its fragment
 * (`#token=T`), which the browser never sends to a server; it is kept in
 * sessionStorage and taken out of the address bar (and so out of the
 * history, bookmarks and Share links). No cookie carries it: a browser
 * sends the cookies of 127.0.0.1 to every port.
 *
 * @returns {string} the key, or '' (this tab was not opened from the link)
 */
export function pageToken() {
  const fragment = new URLSearchParams(location.hash.slice(1));
  const given = fragment.get('token');
  if (given) {
    sessionStorage.setItem(KEY, given);
    fragment.delete('token');
    const rest = fragment.toString();
    history.replaceState(history.state, '', location.pathname + location.search + (rest ? '#' + rest : ''));
  }
  return sessionStorage.getItem(KEY) || '';
}

/**
 * @param {{token?: string}} [options] the key to send as X-Stlc-Token on
 *   every call; by default the page's own (pageToken)
 * @returns {import('./index.js').Engine}
 */
export function createHttpEngine({ token = pageToken() } = {}) {
  const key = { 'X-Stlc-Token': token };

  function post(path, body, signal, accept = 'application/json') {
    return fetch(path, {
      method: 'POST',
      headers: { ...key, 'Content-Type': 'application/json', Accept: accept },
      body: JSON.stringify(body),
      signal,
    });
  }

  // Reads carry the key too: the file is the owner's.
  function get(path) {
    return fetch(path, { headers: key });
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
      const res = await get('/api/examples');
      if (!res.ok) throw new Error(`/api/examples: ${(await refused(res)).error}`);
      return res.json();
    },

    async open(known) {
      const res = await get('/api/file' + (known ? '?known=' + encodeURIComponent(known) : ''));
      // Without the key (a tab not opened from the printed link), the
      // server's 401 says to open that link.
      if (!res.ok) throw new Error(`/api/file: ${(await refused(res)).error}`);
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
