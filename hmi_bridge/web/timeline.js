// The timeline: one lane per channel over the last minutes of machine time (`state.time_s`).
// Each lane's shapes are placed in seconds inside a group scaled to pixels, so moving on means
// moving the group and stretching the open segment, not laying the lane out again. Every frame
// is recorded; the SVG is touched at most a few times a second, as repainting it is what costs.

import { svg, setText, asNumber, throttled } from './dom.js';

const LANE_HEIGHT = 26;
const LANE_GAP = 6;
const LABEL_WIDTH = 48;
const RIGHT_PAD = 8;
const AXIS_HEIGHT = 18;
const KEEP_SECONDS = 300;          // the longest window offered
const MIN_TICK_SPACING = 0.1;      // s: short blocks would otherwise pile up thousands of ticks
const TICK_CHUNK_SECONDS = 10;     // ticks are drawn as one path per chunk: fewer shapes to paint
const REDRAW_MS = 200;
const SEGMENT_STATES = new Set(['reset', 'idle', 'running', 'hold', 'waiting', 'alarm']);
const CLIP_ID = 'timeline-clip';

function timeStep(windowSeconds) {
  if (windowSeconds <= 60) return 10;
  if (windowSeconds <= 120) return 20;
  return 60;
}

// The track is scaled in x; its text is scaled back so it reads normally.
function unscale(label, pixelsPerSecond) {
  label.setAttribute('transform', `scale(${1 / pixelsPerSecond} 1)`);
}

class Lane {
  constructor(name, index) {
    this.name = name;
    this.segments = [];   // {el, state, t0, t1}; t1 null while open
    this.tickChunks = []; // {el, t0, t1, d, changed}
    this.syncs = [];      // {el, label, t}
    this.unplaced = [];   // [layer, el] recorded since the last redraw
    this.open = null;
    this.lastBlock = null;
    this.lastTick = -Infinity;
    this.pixelsPerSecond = 1;

    this.segmentLayer = svg('g', { class: 'segments' });
    this.tickLayer = svg('g', { class: 'ticks' });
    this.syncLayer = svg('g', { class: 'syncs' });
    this.track = svg('g', { class: 'track' }, this.segmentLayer, this.tickLayer, this.syncLayer);
    this.background = svg('rect', { class: 'lane-bg', x: 0, y: 0, height: LANE_HEIGHT });
    this.root = svg('g', {
      class: 'lane',
      'data-lane': name,
      transform: `translate(0 ${index * (LANE_HEIGHT + LANE_GAP)})`,
    },
    svg('text', { class: 'lane-label', x: 4, y: LANE_HEIGHT / 2 + 4 }, name),
    svg('g', { transform: `translate(${LABEL_WIDTH} 0)`, 'clip-path': `url(#${CLIP_ID})` },
      this.background, this.track));
  }

  close(t) {
    if (!this.open) return;
    this.open.t1 = t;
    this.open.el.setAttribute('width', Math.max(0, t - this.open.t0));
    this.open = null;
  }

  // Forgets what was seen last: the next frame starts new segments rather than stretching old
  // ones over a time nobody watched.
  interrupt(t) {
    this.close(t);
    this.lastBlock = null;
  }

  record(t, channel) {
    const state = SEGMENT_STATES.has(channel.state) ? channel.state : null;
    if (this.open && this.open.state !== state) this.close(t);
    if (!this.open && state) {
      const el = svg('rect', { class: `seg ${state}`, x: t, y: 3, width: 0, height: LANE_HEIGHT - 6 });
      this.open = { el, state, t0: t, t1: null };
      this.segments.push(this.open);
      this.unplaced.push([this.segmentLayer, el]);
    }

    const block = asNumber(channel.block);
    if (block !== null && block > 0 && this.lastBlock !== null && block !== this.lastBlock
        && t - this.lastTick >= MIN_TICK_SPACING) {
      this.addTick(t);
      this.lastTick = t;
    }
    if (block !== null) this.lastBlock = block;
  }

  addTick(t) {
    let chunk = this.tickChunks.at(-1);
    if (!chunk || t - chunk.t0 >= TICK_CHUNK_SECONDS) {
      const el = svg('path', { class: 'tick', 'vector-effect': 'non-scaling-stroke' });
      chunk = { el, t0: t, t1: t, d: '', changed: true };
      this.tickChunks.push(chunk);
      this.unplaced.push([this.tickLayer, el]);
    }
    chunk.t1 = t;
    chunk.d += `M${t} 0V7`;
    chunk.changed = true;
  }

  addSync(t, p) {
    const label = svg('text', { x: 0, y: LANE_HEIGHT - 3 }, ` P${p}`);
    const el = svg('g', { class: 'sync', 'data-p': p, transform: `translate(${t} 0)` },
      svg('line', { x1: 0, x2: 0, y1: 0, y2: LANE_HEIGHT, 'vector-effect': 'non-scaling-stroke' }),
      label);
    unscale(label, this.pixelsPerSecond);
    this.syncs.push({ el, label, t });
    this.unplaced.push([this.syncLayer, el]);
  }

  // Drops what has scrolled out of the longest window; each list is in time order.
  prune(oldest) {
    while (this.segments.length && this.segments[0].t1 !== null && this.segments[0].t1 < oldest) {
      this.segments.shift().el.remove();
    }
    while (this.tickChunks.length && this.tickChunks[0].t1 < oldest) this.tickChunks.shift().el.remove();
    while (this.syncs.length && this.syncs[0].t < oldest) this.syncs.shift().el.remove();
  }

  resize(plotWidth, pixelsPerSecond) {
    this.pixelsPerSecond = pixelsPerSecond;
    this.background.setAttribute('width', plotWidth);
    for (const sync of this.syncs) unscale(sync.label, pixelsPerSecond);
  }

  draw(now, left, pixelsPerSecond) {
    for (const [layer, el] of this.unplaced) layer.append(el);
    this.unplaced = [];
    for (const chunk of this.tickChunks) {
      if (chunk.changed) chunk.el.setAttribute('d', chunk.d);
      chunk.changed = false;
    }
    this.prune(now - KEEP_SECONDS);
    if (this.open) this.open.el.setAttribute('width', Math.max(0, now - this.open.t0));
    this.track.setAttribute('transform', `translate(${-left * pixelsPerSecond} 0) scale(${pixelsPerSecond} 1)`);
  }
}

export class Timeline {
  constructor(root, windowSelect) {
    this.root = root;
    this.windowSeconds = Number(windowSelect.value) || 120;
    this.width = 0;
    this.now = null;
    this.lanes = [];
    this.requestDraw = throttled(() => this.draw(), REDRAW_MS);
    this.clipRect = svg('rect', { x: 0, y: 0, height: LANE_HEIGHT });
    this.laneLayer = svg('g', { class: 'lanes' });
    this.axisLayer = svg('g', { class: 'time-axis' });
    this.axisLabels = [];
    root.append(svg('defs', {}, svg('clipPath', { id: CLIP_ID }, this.clipRect)), this.laneLayer, this.axisLayer);

    windowSelect.addEventListener('change', () => {
      this.windowSeconds = Number(windowSelect.value) || 120;
      this.resize();
    });
    new ResizeObserver(() => {
      const width = Math.floor(root.parentElement.clientWidth);
      if (width !== this.width) {
        this.width = width;
        this.resize();
      }
    }).observe(root.parentElement);
  }

  get plotWidth() {
    return Math.max(1, this.width - LABEL_WIDTH - RIGHT_PAD);
  }

  get pixelsPerSecond() {
    return this.plotWidth / this.windowSeconds;
  }

  setChannels(names) {
    this.laneLayer.replaceChildren();
    this.lanes = names.map((name, index) => new Lane(name, index));
    this.laneLayer.append(...this.lanes.map((lane) => lane.root));
    this.now = null;
    this.resize();
  }

  // A gap in what the page heard (the connection dropped).
  interrupt() {
    if (this.now === null) return;
    for (const lane of this.lanes) lane.interrupt(this.now);
    this.requestDraw();
  }

  update(timeS, channelsByName) {
    const t = asNumber(timeS);
    if (t === null) return;
    // Machine time going back means the machine was started again: its old history is not ours.
    if (this.now !== null && t < this.now - 1) this.setChannels(this.lanes.map((lane) => lane.name));
    this.now = t;
    for (const lane of this.lanes) {
      const channel = channelsByName.get(lane.name);
      if (channel) lane.record(t, channel);
    }
    this.requestDraw();
  }

  // A G04.1 meeting (from the server, taken from the channels' arrivals): a marker on each
  // participant's lane at the time the last of them arrived.
  meeting(timeS, p, channels) {
    const t = asNumber(timeS);
    const mark = asNumber(p);
    if (t === null || mark === null || !Array.isArray(channels)) return;
    for (const lane of this.lanes) {
      if (channels.includes(lane.name)) lane.addSync(t, mark);
    }
    this.requestDraw();
  }

  resize() {
    const lanesHeight = Math.max(1, this.lanes.length * (LANE_HEIGHT + LANE_GAP));
    this.root.setAttribute('width', this.width);
    this.root.setAttribute('height', lanesHeight + AXIS_HEIGHT);
    this.clipRect.setAttribute('width', this.plotWidth);
    this.axisLayer.setAttribute('transform', `translate(${LABEL_WIDTH} ${lanesHeight})`);
    for (const lane of this.lanes) lane.resize(this.plotWidth, this.pixelsPerSecond);
    this.draw();
  }

  draw() {
    if (this.now === null) return;
    const left = this.now - this.windowSeconds;
    const pixelsPerSecond = this.pixelsPerSecond;
    for (const lane of this.lanes) lane.draw(this.now, left, pixelsPerSecond);
    this.drawAxis(left, pixelsPerSecond);
  }

  drawAxis(left, pixelsPerSecond) {
    const step = timeStep(this.windowSeconds);
    const first = Math.max(0, Math.ceil(left / step) * step);
    let used = 0;
    for (let t = first; t <= this.now; t += step, used++) {
      if (used === this.axisLabels.length) {
        const label = svg('g', {}, svg('line', { y1: -4, y2: 2 }), svg('text', { y: 14 }));
        this.axisLayer.append(label);
        this.axisLabels.push(label);
      }
      const label = this.axisLabels[used];
      label.setAttribute('transform', `translate(${(t - left) * pixelsPerSecond} 0)`);
      setText(label.lastChild, `${t} s`);
      label.style.display = '';
    }
    for (let i = used; i < this.axisLabels.length; i++) this.axisLabels[i].style.display = 'none';
  }
}
