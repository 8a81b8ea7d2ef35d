// Small helpers shared by the panels: building elements, updating text in place, and reading
// fields of server messages that may be missing or of the wrong type.

const SVG_NS = 'http://www.w3.org/2000/svg';

function fill(node, attrs, children) {
  for (const [name, value] of Object.entries(attrs)) {
    if (value !== null && value !== undefined && value !== false) node.setAttribute(name, value);
  }
  node.append(...children);
  return node;
}

export function el(tag, attrs = {}, ...children) {
  return fill(document.createElement(tag), attrs, children);
}

export function svg(tag, attrs = {}, ...children) {
  return fill(document.createElementNS(SVG_NS, tag), attrs, children);
}

// Frames arrive 25 times a second and mostly repeat: touch the DOM only when the text changes.
export function setText(node, text) {
  if (node.textContent !== text) node.textContent = text;
}

export function setData(node, key, value) {
  if (node.dataset[key] !== value) node.dataset[key] = value;
}

export function isObject(value) {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}

export function asArray(value) {
  return Array.isArray(value) ? value : [];
}

export function asNumber(value) {
  return typeof value === 'number' && Number.isFinite(value) ? value : null;
}

export function asString(value) {
  return typeof value === 'string' ? value : '';
}

export function stringsOf(value) {
  return asArray(value).filter((item) => typeof item === 'string');
}

export function fixed(value, digits) {
  const n = asNumber(value);
  return n === null ? '—' : n.toFixed(digits);
}

// A redraw at most every `ms`: requests in between are served by one call at the end of it.
export function throttled(fn, ms) {
  let timer = 0;
  let last = -Infinity;
  return () => {
    if (timer) return;
    timer = setTimeout(() => {
      timer = 0;
      last = performance.now();
      fn();
    }, Math.max(0, last + ms - performance.now()));
  };
}
