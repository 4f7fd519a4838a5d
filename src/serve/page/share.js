// Share links: the whole document in the page's address, after the `#`
// (a fragment is never sent to any server). `#k=od&n=2dtree.od&s=...`:
// the kind, the file name and the text, deflated (deflate-raw, the
// browser's own CompressionStream) and written in base64url. Every
// setting of a tree (growth order, seed, clearance, depth) is a key in
// its text (docs/serve.md), so the text alone restores it exactly.

const KINDS = ['od', 'bed', 'lsys'];

/**
 * The engine's input limit in bytes (`--max-input`'s default, 64 MiB;
 * src/limits.rs): a link's text inflates to at most this much, or is
 * refused. A few hundred KB of link can inflate to gigabytes.
 */
export const MAX_INPUT_BYTES = 64 * 1024 * 1024;

async function through(stream, bytes) {
  const out = new Blob([bytes]).stream().pipeThrough(stream);
  return new Uint8Array(await new Response(out).arrayBuffer());
}

// Inflates deflate-raw `bytes`, reading at most `limit` bytes of output:
// past that the stream is cancelled (nothing more is inflated) and null
// is returned.
async function inflate(bytes, limit) {
  const reader = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate-raw')).getReader();
  const chunks = [];
  let total = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    total += value.length;
    if (total > limit) {
      await reader.cancel();
      return null;
    }
    chunks.push(value);
  }
  const out = new Uint8Array(total);
  let at = 0;
  for (const c of chunks) {
    out.set(c, at);
    at += c.length;
  }
  return out;
}

function base64url(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(s).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function unbase64url(text) {
  const s = atob(text.replace(/-/g, '+').replace(/_/g, '/'));
  const bytes = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) bytes[i] = s.charCodeAt(i);
  return bytes;
}

/**
 * The fragment (with its `#`) that carries a document.
 *
 * @param {{name: string, kind: string, text: string}} doc
 * @returns {Promise<string>}
 */
export async function toFragment({ name, kind, text }) {
  const packed = await through(new CompressionStream('deflate-raw'), new TextEncoder().encode(text));
  return `#k=${kind}&n=${encodeURIComponent(name)}&s=${base64url(packed)}`;
}

/**
 * The document a fragment carries, or null when it carries none (or a
 * damaged one: then `error` says why).
 *
 * @param {string} hash `location.hash`
 * @returns {Promise<{name: string, kind: string, text: string}|null>}
 */
export async function fromFragment(hash) {
  const p = new URLSearchParams(hash.replace(/^#/, ''));
  const s = p.get('s');
  if (!s) return null;
  const kind = KINDS.includes(p.get('k')) ? p.get('k') : 'od';
  const name = p.get('n') || `shared.${kind}`;
  try {
    const bytes = await inflate(unbase64url(s), MAX_INPUT_BYTES);
    if (!bytes) {
      return {
        name, kind,
        text: '# This share link\'s text is too large: it inflates to more\n'
          + `# than the input limit of ${MAX_INPUT_BYTES} bytes (64 MiB),\n`
          + '# so it was not read. Share a smaller text, or open\n'
          + '# the file itself with Open... or New.\n',
      };
    }
    return { name, kind, text: new TextDecoder('utf-8', { fatal: true }).decode(bytes) };
  } catch (e) {
    return { name, kind, text: `# This share link is damaged (${e.message}): its text could not be read.\n` };
  }
}
