// The alarm history, newest first; an alarm not yet acknowledged is highlighted and has its
// acknowledge button.

import { el, setText, asNumber, asString, isObject } from './dom.js';

const MAX_ALARMS = 500;

export class AlarmList {
  constructor(listEl, unacknowledgedEl, { sendCommand, canCommand }) {
    this.listEl = listEl;
    this.unacknowledgedEl = unacknowledgedEl;
    this.sendCommand = sendCommand;
    this.canCommand = canCommand;
    this.items = new Map();   // "src#seq" -> li, oldest first
    this.showCount();
  }

  // The server's history, oldest first.
  replaceAll(alarms) {
    this.items.clear();
    this.listEl.replaceChildren();
    for (const alarm of alarms) this.upsert(alarm);
  }

  // An alarm is known by its process and that process's own sequence number: a new one goes on
  // top, a known one (now acknowledged) is replaced where it stands.
  upsert(alarm) {
    if (!isObject(alarm)) return;
    const seq = asNumber(alarm.seq);
    if (seq === null) return;
    const key = `${asString(alarm.src)}#${seq}`;
    const item = this.render(seq, alarm);
    const old = this.items.get(key);
    if (old) {
      old.replaceWith(item);
    } else {
      this.listEl.prepend(item);
    }
    this.items.set(key, item);
    while (this.items.size > MAX_ALARMS) {
      const [oldest, oldestItem] = this.items.entries().next().value;
      oldestItem.remove();
      this.items.delete(oldest);
    }
    this.showCount();
  }

  render(seq, alarm) {
    const acknowledged = alarm.acknowledged === true;
    const number = asNumber(alarm.number);
    const line = asNumber(alarm.line);
    const column = asNumber(alarm.column);
    const program = asString(alarm.program);
    const cycle = asNumber(alarm.cycle);
    // As `mcnc run` says it: FILE:LINE:COL when the alarm names its file.
    const place = !line ? '' : program ? [program, line, column || null].filter(Boolean).join(':') : `line ${line}`;
    const where = [place, cycle === null ? '' : `cycle ${cycle}`].filter(Boolean).join(' · ');
    const item = el('li', { class: acknowledged ? 'alarm' : 'alarm unacknowledged', 'data-seq': seq },
      el('span', { class: 'alarm-src' }, asString(alarm.src) || '—'),
      el('span', { class: 'alarm-number' }, number === null ? '—' : String(number)),
      el('span', { class: 'alarm-text' }, asString(alarm.text)),
      el('span', { class: 'alarm-where' }, where));
    if (!acknowledged) {
      const button = el('button', { type: 'button', class: 'command', 'data-action': 'alarm_ack' }, 'Acknowledge');
      button.disabled = !this.canCommand();
      button.addEventListener('click', () => this.sendCommand('alarm_ack', null, { value: seq, text: asString(alarm.src) }));
      item.append(button);
    }
    return item;
  }

  showCount() {
    const count = [...this.items.values()].filter((item) => item.classList.contains('unacknowledged')).length;
    setText(this.unacknowledgedEl, String(count));
    this.unacknowledgedEl.dataset.count = count ? 'some' : 'none';
  }
}
