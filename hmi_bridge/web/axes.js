// The axis table and the spindle panel, built from `machine` and filled from `state.axes`.

import { el, setText, setData, fixed, asNumber, asString, isObject } from './dom.js';

function ownerText(owner) {
  return typeof owner === 'string' && owner ? owner : 'released';
}

function syncText(axis) {
  const master = asString(axis.coupled_to);
  if (!master) return '';
  return `sync: follows ${master} (${axis.locked === true ? 'locked' : 'not locked'})`;
}

// Restarts the row's flash even when the previous one has not finished.
function flash(node) {
  node.classList.remove('owner-changed');
  void node.offsetWidth;
  node.classList.add('owner-changed');
}

class AxisRow {
  constructor(axis) {
    this.owner = undefined;   // not heard yet: the first owner is no change
    const cell = (cls, text = '') => el('td', { class: cls }, text);
    this.ownerEl = cell('owner', '—');
    this.cmdEl = cell('cmd num', '—');
    this.actEl = cell('act num', '—');
    this.ferrEl = cell('ferr num', '—');
    this.velEl = cell('vel num', '—');
    this.driveEl = cell('drive', '—');
    this.syncEl = cell('sync');
    const address = axis.diameter ? `${axis.address} (radius)` : axis.address;
    this.root = el('tr', { 'data-axis': axis.name },
      el('th', { scope: 'row' }, axis.name),
      cell('address', address),
      cell('home', axis.home || '—'),
      this.ownerEl, this.cmdEl, this.actEl, this.ferrEl, this.velEl, this.driveEl, this.syncEl);
    this.root.addEventListener('animationend', () => this.root.classList.remove('owner-changed'));
  }

  update(axis) {
    if (axis.owner !== undefined) {
      const owner = asString(axis.owner) || null;
      if (this.owner !== undefined && owner !== this.owner) flash(this.root);
      this.owner = owner;
      setText(this.ownerEl, ownerText(owner));
      setData(this.ownerEl, 'released', String(owner === null));
    }
    setText(this.cmdEl, fixed(axis.cmd, 3));
    setText(this.actEl, fixed(axis.act, 3));
    setText(this.ferrEl, fixed(axis.following_error, 3));
    setText(this.velEl, fixed(axis.vel, 3));
    setText(this.driveEl, asString(axis.drive) || '—');
    setData(this.driveEl, 'drive', asString(axis.drive));
    setText(this.syncEl, syncText(axis));
    setData(this.root, 'alarm', String(axis.alarm === true));
  }
}

class SpindleCard {
  constructor(spindle) {
    const field = (cls, label) => {
      const value = el('dd', { class: cls }, '—');
      return [value, el('div', {}, el('dt', {}, label), value)];
    };
    const [speedEl, speedItem] = field('speed', 'speed');
    const [loadEl, loadItem] = field('load', 'load');
    const [driveEl, driveItem] = field('drive', 'drive');
    const [ownerEl, ownerItem] = field('owner', 'owner');
    this.speedEl = speedEl;
    this.loadEl = loadEl;
    this.driveEl = driveEl;
    this.ownerEl = ownerEl;
    this.syncEl = el('div', { class: 'sync' });
    this.root = el('article', { class: 'spindle', 'data-spindle': spindle.name },
      el('h3', {}, spindle.name),
      el('dl', {}, speedItem, loadItem, driveItem, ownerItem),
      this.syncEl);
  }

  update(axis) {
    const vel = asNumber(axis.vel);   // deg/s; 360 deg/rev, 60 s/min
    setText(this.speedEl, vel === null ? '—' : `${Math.round(vel / 6)} rpm`);
    // The drive's torque in percent of the motor's rated torque, when it sends it.
    const load = asNumber(axis.load);
    setText(this.loadEl, load === null ? '—' : `${Math.round(load)} %`);
    setText(this.driveEl, asString(axis.drive) || '—');
    setData(this.driveEl, 'drive', asString(axis.drive));
    setText(this.ownerEl, ownerText(axis.owner));
    setText(this.syncEl, syncText(axis));
    setData(this.root, 'alarm', String(axis.alarm === true));
  }
}

export class AxisPanel {
  constructor(tableBody, spindleRoot) {
    this.tableBody = tableBody;
    this.spindleRoot = spindleRoot;
    this.views = new Map();   // axis name -> AxisRow or SpindleCard
  }

  build(axes) {
    this.views.clear();
    const rows = [];
    const cards = [];
    for (const axis of axes) {
      if (axis.type === 'spindle') {
        const card = new SpindleCard(axis);
        cards.push(card.root);
        this.views.set(axis.name, card);
      } else {
        const row = new AxisRow(axis);
        rows.push(row.root);
        this.views.set(axis.name, row);
      }
    }
    this.tableBody.replaceChildren(...rows);
    this.spindleRoot.replaceChildren(...cards);
  }

  update(axisStates) {
    for (const axis of axisStates) {
      if (isObject(axis)) this.views.get(axis.name)?.update(axis);
    }
  }
}
