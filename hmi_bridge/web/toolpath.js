// The live toolpath of one channel: Z to the right, X (radius) up, one scale for both so the
// picture keeps the part's proportions, as a lathe drawing.

import { asNumber, throttled } from './dom.js';

const MAX_POINTS = 20000;
const REDRAW_MS = 100;
const MIN_STEP = 0.0005;   // mm: a channel standing still adds no points
const MIN_SPAN = 1;        // mm: a single point is not zoomed to infinity
const MARGIN = 14;
const ACTIVE_STATES = new Set(['running', 'waiting', 'hold']);

// The X and Z the channel moves now: the axes it owns with those addresses, its own configured
// ones first (an X it borrowed only counts when it has none of its own).
export function ownedXZ(channel, axisStates, addressOf) {
  const owned = axisStates
    .filter((axis) => axis.owner === channel.name && asNumber(axis.act) !== null)
    .sort((a, b) => Number(!channel.axes.includes(a.name)) - Number(!channel.axes.includes(b.name)));
  const x = owned.find((axis) => addressOf.get(axis.name) === 'X');
  const z = owned.find((axis) => addressOf.get(axis.name) === 'Z');
  return x && z ? { xName: x.name, zName: z.name, x: x.act, z: z.act } : null;
}

export class ToolpathPlot {
  constructor(canvas) {
    this.canvas = canvas;
    this.zs = [];
    this.xs = [];        // NaN in both marks a gap: the channel lost one of its axes
    this.axesLabel = '';
    this.newRunPending = false;
    this.requestDraw = throttled(() => this.draw(), REDRAW_MS);
    this.resetBounds();
    new ResizeObserver(() => this.resize()).observe(canvas);
  }

  // channelState: the channel's entry of `state`; xz: from ownedXZ, or null.
  update(channelState, xz) {
    // A run ends at M30/M02 or a reset; its path stays until the next one starts.
    const active = ACTIVE_STATES.has(channelState.state);
    if (!active && (channelState.state === 'reset' || channelState.ended === true)) {
      this.newRunPending = true;
    } else if (active && this.newRunPending) {
      this.newRunPending = false;
      this.clear();
    }
    if (!xz) {
      this.addGap();
      return;
    }
    const label = `${xz.zName}/${xz.xName}`;
    if (label !== this.axesLabel) {
      this.addGap();
      this.axesLabel = label;
    }
    this.addPoint(xz.z, xz.x);
  }

  clear() {
    this.zs = [];
    this.xs = [];
    this.resetBounds();
    this.requestDraw();
  }

  resetBounds() {
    this.bounds = { zMin: Infinity, zMax: -Infinity, xMin: Infinity, xMax: -Infinity };
  }

  addGap() {
    const n = this.zs.length;
    if (n > 0 && !Number.isNaN(this.zs[n - 1])) {
      this.zs.push(NaN);
      this.xs.push(NaN);
    }
  }

  addPoint(z, x) {
    const n = this.zs.length;
    if (n > 0 && Math.abs(this.zs[n - 1] - z) < MIN_STEP && Math.abs(this.xs[n - 1] - x) < MIN_STEP) return;
    this.zs.push(z);
    this.xs.push(x);
    this.extendBounds(z, x);
    if (this.zs.length > MAX_POINTS) this.decimate();
    this.requestDraw();
  }

  extendBounds(z, x) {
    const b = this.bounds;
    b.zMin = Math.min(b.zMin, z);
    b.zMax = Math.max(b.zMax, z);
    b.xMin = Math.min(b.xMin, x);
    b.xMax = Math.max(b.xMax, x);
  }

  // Keeps every other point, every gap and the last point (where the tool is).
  decimate() {
    const zs = [];
    const xs = [];
    const last = this.zs.length - 1;
    let keep = true;
    for (let i = 0; i <= last; i++) {
      const gap = Number.isNaN(this.zs[i]);
      if (gap || keep || i === last) {
        zs.push(this.zs[i]);
        xs.push(this.xs[i]);
      }
      keep = gap || !keep;
    }
    this.zs = zs;
    this.xs = xs;
  }

  resize() {
    const ratio = window.devicePixelRatio || 1;
    const width = Math.round(this.canvas.clientWidth * ratio);
    const height = Math.round(this.canvas.clientHeight * ratio);
    if (width !== this.canvas.width || height !== this.canvas.height) {
      this.canvas.width = width;
      this.canvas.height = height;
      this.draw();
    }
  }

  draw() {
    const ratio = window.devicePixelRatio || 1;
    const width = this.canvas.width / ratio;
    const height = this.canvas.height / ratio;
    const ctx = this.canvas.getContext('2d');
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, width, height);
    ctx.font = '11px ui-monospace, monospace';
    const b = this.bounds;
    if (!(b.zMax >= b.zMin)) {
      ctx.fillStyle = '#6f7c8c';
      ctx.textBaseline = 'middle';
      ctx.fillText('no X/Z motion yet', MARGIN, height / 2);
      return;
    }

    const zSpan = Math.max(b.zMax - b.zMin, MIN_SPAN);
    const xSpan = Math.max(b.xMax - b.xMin, MIN_SPAN);
    const scale = Math.min((width - 2 * MARGIN) / zSpan, (height - 2 * MARGIN - 12) / xSpan);
    const zMid = (b.zMin + b.zMax) / 2;
    const xMid = (b.xMin + b.xMax) / 2;
    const px = (z) => width / 2 + (z - zMid) * scale;
    const py = (x) => (height - 12) / 2 + 6 - (x - xMid) * scale;

    // The spindle centreline, when the view reaches it.
    const centre = py(0);
    if (centre >= 0 && centre <= height) {
      ctx.strokeStyle = '#3a4656';
      ctx.setLineDash([6, 4]);
      ctx.beginPath();
      ctx.moveTo(0, centre);
      ctx.lineTo(width, centre);
      ctx.stroke();
      ctx.setLineDash([]);
    }

    ctx.strokeStyle = '#4fc3f7';
    ctx.lineWidth = 1.5;
    ctx.lineJoin = 'round';
    ctx.beginPath();
    let penDown = false;
    for (let i = 0; i < this.zs.length; i++) {
      const z = this.zs[i];
      if (Number.isNaN(z)) {
        penDown = false;
      } else if (penDown) {
        ctx.lineTo(px(z), py(this.xs[i]));
      } else {
        ctx.moveTo(px(z), py(this.xs[i]));
        penDown = true;
      }
    }
    ctx.stroke();

    const tool = this.lastPoint();
    if (tool) {
      ctx.fillStyle = '#ffb74d';
      ctx.beginPath();
      ctx.arc(px(tool.z), py(tool.x), 3.5, 0, 2 * Math.PI);
      ctx.fill();
    }

    const [zName, xName] = this.axesLabel.split('/');
    ctx.fillStyle = '#8b97a6';
    ctx.textBaseline = 'bottom';
    ctx.fillText(`${zName} ${b.zMin.toFixed(3)} … ${b.zMax.toFixed(3)} →`, 4, height - 2);
    ctx.textBaseline = 'top';
    ctx.fillText(`${xName} ↑ ${b.xMin.toFixed(3)} … ${b.xMax.toFixed(3)}`, 4, 2);
  }

  lastPoint() {
    for (let i = this.zs.length - 1; i >= 0; i--) {
      if (!Number.isNaN(this.zs[i])) return { z: this.zs[i], x: this.xs[i] };
    }
    return null;
  }
}
