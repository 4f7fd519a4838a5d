// Small DOM helpers shared by the modules. No state.

export const SVGNS = 'http://www.w3.org/2000/svg';

export const byId = (id) => document.getElementById(id);

// An SVG element with attributes, appended to `parent` if given.
export function el(name, attrs, parent) {
  const e = document.createElementNS(SVGNS, name);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (parent) parent.appendChild(e);
  return e;
}

export function escapeHtml(s) {
  return String(s).replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c]));
}

// A count with its digits grouped by threes ("1,131,266,948"): from its
// decimal digits (a string, exact at any size) or a number.
export function grouped(n) {
  const s = String(n);
  const m = /^(\D*)(\d+)(.*)$/.exec(s);
  if (!m) return s;
  return m[1] + m[2].replace(/\B(?=(\d{3})+$)/g, ',') + m[3];
}
