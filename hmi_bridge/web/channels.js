// One column per channel: its state, what it waits for, its program with the current line, its
// toolpath and the operator's controls.

import { el, setText, setData, asNumber, asString, stringsOf, isObject } from './dom.js';
import { ToolpathPlot } from './toolpath.js';

const CHANNEL_STATES = new Set(['reset', 'idle', 'running', 'hold', 'waiting', 'alarm']);

const OVERRIDES = [
  { action: 'feed_override', label: 'Feed', min: 0, max: 200 },
  { action: 'rapid_override', label: 'Rapid', min: 0, max: 100 },
  { action: 'spindle_override', label: 'Spindle', min: 50, max: 120 },
];

// After a slider is let go the channel reports the new value a few frames later; until then the
// frames still carry the old one and must not pull the slider back.
const SLIDER_SETTLE_MS = 1000;

function waitText(wait) {
  if (!isObject(wait)) return '';
  if (wait.kind === 'mark') {
    const names = stringsOf(wait.waiting_for);
    const p = asNumber(wait.p);
    return `G04.1 P${p ?? '?'}: waiting${names.length ? ` for ${names.join(', ')}` : ''}`;
  }
  if (wait.kind === 'call') {
    const target = asString(wait.target);
    return `G144: waiting${target ? ` for ${target}` : ''}`;
  }
  if (wait.kind === 'fin') {
    return `FIN: waiting for the PLC to finish ${asString(wait.code) || 'an M code'}`;
  }
  if (wait.kind === 'exchange') {
    const g = asNumber(wait.g);
    const axis = asString(wait.axis);
    return `G${g ?? '?'}: waiting for ${axis || 'the axes'}`;
  }
  return 'waiting';
}

// The modal G codes as the control's modal screen lists them, and the modal F with its unit.
function modalText(channel) {
  return stringsOf(channel.modal).join(' ');
}

function feedText(channel) {
  const feed = asNumber(channel.feed);
  if (feed === null) return '—';
  const modal = stringsOf(channel.modal);
  const perRev = modal.includes('G99') || modal.includes('G95');  // system A, system B
  return `F${Number(feed.toFixed(3))} ${perRev ? 'mm/rev' : 'mm/min'}`;
}

function callText(call) {
  const caller = isObject(call) ? asString(call.caller) : '';
  return caller ? `called by ${caller}` : '';
}

function endText(channel) {
  if (channel.ended !== true) return '';
  const code = asNumber(channel.end_code);
  return code === null || code < 0 ? 'end' : `end M${String(code).padStart(2, '0')}`;
}

function statusItem(label, value) {
  return el('div', {}, el('dt', {}, label), el('dd', {}, value));
}

class OverrideSlider {
  constructor(spec, onSet) {
    this.settleUntil = 0;
    this.input = el('input', {
      type: 'range', class: 'command', 'data-action': spec.action,
      min: spec.min, max: spec.max, step: 1, value: 100, 'aria-label': `${spec.label} override`,
    });
    this.output = el('output', { class: `ch-${spec.action.replace('_', '-')}` }, '—');
    this.root = el('label', { class: 'override' }, el('span', {}, spec.label), this.input, this.output);

    this.input.addEventListener('input', () => setText(this.output, `${this.input.value} %`));
    this.input.addEventListener('change', () => {
      this.settleUntil = performance.now() + SLIDER_SETTLE_MS;
      onSet(Number(this.input.value));
    });
  }

  show(value) {
    const percent = asNumber(value);
    // Not while the operator holds the slider, nor before the channel has taken the new value.
    if (percent === null || this.input.matches(':active') || performance.now() < this.settleUntil) return;
    setText(this.output, `${percent} %`);
    if (Number(this.input.value) !== percent) this.input.value = percent;
  }
}

export class ChannelView {
  constructor(name, sendCommand) {
    this.name = name;
    this.lineEls = [];
    this.currentLine = 0;
    this.currentLineEl = null;
    this.scrollPending = false;
    this.singleBlock = false;
    const send = (action, extra) => sendCommand(action, name, extra);

    this.stateEl = el('span', { class: 'ch-state', 'data-state': 'none' }, '—');
    this.waitEl = el('div', { class: 'ch-wait' });
    this.callEl = el('div', { class: 'ch-call' });
    this.endEl = el('span', { class: 'ch-end' });

    this.blockEl = el('span', { class: 'ch-block' }, '—');
    this.lineEl = el('span', { class: 'ch-line' }, '—');
    this.rpmEl = el('span', { class: 'ch-rpm' }, '—');
    this.feedEl = el('span', { class: 'ch-feed' }, '—');
    this.modalEl = el('div', { class: 'ch-modal', title: 'modal G codes of the executing block' });
    this.singleBlockEl = el('span', { class: 'ch-single-block' }, '—');
    this.alarmCountEl = el('span', { class: 'ch-alarms' }, '—');

    this.programNameEl = el('div', { class: 'program-name' }, 'no program');
    this.listing = el('div', { class: 'program-lines' });

    this.canvas = el('canvas', { class: 'toolpath', 'data-toolpath': name });
    this.toolpath = new ToolpathPlot(this.canvas);

    const button = (action, label) => {
      const b = el('button', { type: 'button', class: `command ${action.replace('_', '-')}`, 'data-action': action }, label);
      b.addEventListener('click', () => send(action));
      return b;
    };
    this.singleBlockButton = el('button', {
      type: 'button', class: 'command single-block', 'data-action': 'single_block', 'aria-pressed': 'false',
    }, 'Single block');
    this.singleBlockButton.addEventListener('click', () => send('single_block', { value: this.singleBlock ? 0 : 1 }));

    this.sliders = new Map(OVERRIDES.map((spec) => [
      spec.action, new OverrideSlider(spec, (value) => send(spec.action, { value })),
    ]));

    this.root = el('section', { class: 'channel', 'data-channel': name, 'data-state': 'none' },
      el('header', { class: 'ch-head' }, el('h2', {}, name), this.endEl, this.stateEl),
      el('div', { class: 'ch-coordination' }, this.waitEl, this.callEl),
      el('dl', { class: 'ch-status' },
        statusItem('block', this.blockEl),
        statusItem('line', this.lineEl),
        statusItem('feed', this.feedEl),
        statusItem('spindle', this.rpmEl),
        statusItem('single block', this.singleBlockEl),
        statusItem('alarms', this.alarmCountEl)),
      this.modalEl,
      el('div', { class: 'ch-program' }, this.programNameEl, this.listing),
      this.canvas,
      el('div', { class: 'ch-controls' },
        el('div', { class: 'buttons' },
          button('cycle_start', 'Cycle start'),
          button('feed_hold', 'Feed hold'),
          button('reset', 'Reset'),
          this.singleBlockButton),
        ...[...this.sliders.values()].map((slider) => slider.root),
        this.textCommand('select_program', 'Select', 'program file, e.g. O1100.nc', send),
        this.textCommand('mdi', 'MDI', 'one block, e.g. G00 X100', send)));
  }

  textCommand(action, label, placeholder, send) {
    const input = el('input', {
      type: 'text', class: 'command', placeholder, spellcheck: 'false', autocomplete: 'off',
      'aria-label': `${label} ${this.name}`,
    });
    const form = el('form', { class: `text-command ${action.replace('_', '-')}` },
      input, el('button', { type: 'submit', class: 'command', 'data-action': action }, label));
    form.addEventListener('submit', (event) => {
      event.preventDefault();
      const text = input.value.trim();
      if (text) send(action, { text });
    });
    return form;
  }

  update(channel) {
    const state = CHANNEL_STATES.has(channel.state) ? channel.state : null;
    setText(this.stateEl, state ?? '—');
    setData(this.stateEl, 'state', state ?? 'none');
    setData(this.root, 'state', state ?? 'none');
    setText(this.waitEl, waitText(channel.wait));
    setText(this.callEl, callText(channel.call));
    setText(this.endEl, endText(channel));

    const block = asNumber(channel.block);
    const total = asNumber(channel.block_total);
    setText(this.blockEl, block === null ? '—' : `${block}/${total ?? '?'}`);
    const line = asNumber(channel.line);
    setText(this.lineEl, line ? String(line) : '—');
    const rpm = asNumber(channel.spindle_rpm);
    setText(this.rpmEl, rpm === null ? '—' : `${Math.round(rpm)} rpm`);
    setText(this.feedEl, feedText(channel));
    setText(this.modalEl, modalText(channel));
    const alarms = asNumber(channel.alarms);
    setText(this.alarmCountEl, alarms === null ? '—' : String(alarms));
    setData(this.alarmCountEl, 'count', alarms ? 'some' : 'none');

    if (typeof channel.single_block === 'boolean') {
      this.singleBlock = channel.single_block;
      setText(this.singleBlockEl, this.singleBlock ? 'on' : 'off');
      this.singleBlockButton.setAttribute('aria-pressed', String(this.singleBlock));
    }
    for (const [action, slider] of this.sliders) slider.show(channel[action]);

    // The listing's own name wins: the heading must name the lines shown under it.
    const program = asString(channel.program);
    if (program && !this.lineEls.length) setText(this.programNameEl, program);
    this.showLine(line ?? 0);
  }

  setProgram(name, lines) {
    if (name) setText(this.programNameEl, name);
    this.lineEls = lines.map((text, index) => el('div', { class: 'line', 'data-line': index + 1 }, text));
    this.listing.replaceChildren(...this.lineEls);
    const line = this.currentLine;
    this.currentLine = 0;
    this.currentLineEl = null;
    this.showLine(line);
  }

  // Scrolls only when the line changes, and only the listing, never the page.
  showLine(line) {
    if (line === this.currentLine) return;
    this.currentLineEl?.classList.remove('current');
    this.currentLine = line;
    this.currentLineEl = this.lineEls[line - 1] ?? null;
    if (!this.currentLineEl) return;
    this.currentLineEl.classList.add('current');
    // Measured in the next animation frame: measuring now would lay the page out once per
    // channel per message.
    if (!this.scrollPending) {
      this.scrollPending = true;
      requestAnimationFrame(() => this.scrollToCurrentLine());
    }
  }

  scrollToCurrentLine() {
    this.scrollPending = false;
    const lineEl = this.currentLineEl;
    if (!lineEl) return;
    const box = this.listing;
    const top = lineEl.offsetTop;
    const bottom = top + lineEl.offsetHeight;
    if (top < box.scrollTop || bottom > box.scrollTop + box.clientHeight) {
      box.scrollTop = top - box.clientHeight / 3;
    }
  }
}
