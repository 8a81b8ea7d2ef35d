// The operator HMI of mcnc: one WebSocket to mcnc-hmi (docs/hmi.md), one screen.

import { setText, setData, asArray, asNumber, asString, stringsOf, isObject } from './dom.js';
import { ChannelView } from './channels.js';
import { AxisPanel } from './axes.js';
import { AlarmList } from './alarms.js';
import { Timeline } from './timeline.js';
import { ownedXZ } from './toolpath.js';

const RETRY_FIRST_MS = 1000;
const RETRY_MAX_MS = 5000;
const STALE_MS = 2000;
const ROLES = new Set(['operator', 'viewer', 'none']);

const ui = {
  machineName: document.getElementById('machine-name'),
  connection: document.getElementById('connection'),
  run: document.getElementById('run'),
  role: document.getElementById('role'),
  cycle: document.getElementById('cycle'),
  time: document.getElementById('time'),
  lastReply: document.getElementById('last-reply'),
  authForm: document.getElementById('auth-form'),
  token: document.getElementById('token'),
  overview: document.getElementById('overview'),
};

let socket = null;
let connected = false;
let retryMs = RETRY_FIRST_MS;
let typedToken = '';
let role = 'none';
let nextCommandId = 1;
const pendingCommands = new Map();   // id -> what it was, for the reply line

let layoutKey = '';
let channels = [];                   // from `machine`: {name, axes}
const addressOf = new Map();         // axis name -> its address (X, Z, A, S …)
const channelViews = new Map();
const programs = new Map();          // channel -> {name, lines}; may arrive before `machine`
let lastStateAt = 0;

const axisPanel = new AxisPanel(document.querySelector('#axes tbody'), document.getElementById('spindles'));
const alarmList = new AlarmList(document.getElementById('alarms'), document.getElementById('alarm-count'), {
  sendCommand,
  canCommand: () => connected && role === 'operator',
});
const timeline = new Timeline(document.getElementById('timeline'), document.getElementById('timeline-window'));

// Not URLSearchParams: it would read a '+' in the token as a space.
function tokenFromHash() {
  const part = location.hash.slice(1).split('&').find((item) => item.startsWith('token='));
  if (!part) return '';
  try {
    return decodeURIComponent(part.slice('token='.length));
  } catch {
    return part.slice('token='.length);
  }
}

function sendMessage(message) {
  if (!socket || socket.readyState !== WebSocket.OPEN) return false;
  socket.send(JSON.stringify(message));
  return true;
}

function authenticate(token) {
  if (token) sendMessage({ type: 'auth', token });
}

function showReply(text, ok) {
  setText(ui.lastReply, text);
  setData(ui.lastReply, 'ok', String(ok));
}

function sendCommand(action, channel, extra = {}) {
  const id = nextCommandId++;
  const command = { type: 'command', id, action, ...(channel ? { channel } : {}), ...extra };
  const what = [channel, action].filter(Boolean).join(' ');
  if (!sendMessage(command)) {
    showReply(`${what}: not sent, not connected`, false);
    return;
  }
  pendingCommands.set(id, what);
  showReply(`${what}: sent`, true);
}

function applyRole() {
  const operator = connected && role === 'operator';
  setText(ui.role, role);
  setData(ui.role, 'role', role);
  for (const control of document.querySelectorAll('.command')) control.disabled = !operator;
}

function setConnected(value) {
  connected = value;
  setText(ui.connection, value ? 'connected' : 'disconnected');
  setData(ui.connection, 'connected', String(value));
  if (!value) {
    role = 'none';
    pendingCommands.clear();
    timeline.interrupt();
  }
  applyRole();
}

function connect() {
  const scheme = location.protocol === 'https:' ? 'wss:' : 'ws:';
  let ws;
  try {
    ws = new WebSocket(`${scheme}//${location.host}/ws`);
  } catch {
    scheduleReconnect();
    return;
  }
  socket = ws;
  ws.addEventListener('open', () => {
    retryMs = RETRY_FIRST_MS;
    setConnected(true);
    authenticate(typedToken || tokenFromHash());
  });
  ws.addEventListener('message', (event) => {
    if (typeof event.data === 'string') handleMessage(event.data);
  });
  ws.addEventListener('close', () => {
    if (socket !== ws) return;
    socket = null;
    setConnected(false);
    scheduleReconnect();
  });
}

function scheduleReconnect() {
  setTimeout(connect, retryMs);
  retryMs = Math.min(retryMs * 2, RETRY_MAX_MS);
}

const handlers = new Map([
  ['machine', onMachine],
  ['role', onRole],
  ['state', onState],
  ['meeting', (message) => timeline.meeting(message.time_s, message.p, message.channels)],
  ['program', onProgram],
  ['alarms', (message) => alarmList.replaceAll(asArray(message.list))],
  ['alarm', (message) => alarmList.upsert(message)],
  ['reply', onReply],
  ['error', (message) => showReply(`error: ${asString(message.reason) || 'message refused'}`, false)],
]);

function handleMessage(text) {
  let message;
  try {
    message = JSON.parse(text);
  } catch {
    return;
  }
  if (isObject(message)) handlers.get(message.type)?.(message);
}

function onMachine(message) {
  const name = asString(message.name);
  setText(ui.machineName, name || '—');
  document.title = name ? `mcnc — ${name}` : 'mcnc';

  const axes = asArray(message.axes).filter((axis) => isObject(axis) && asString(axis.name)).map((axis) => ({
    name: axis.name,
    address: asString(axis.address),
    type: asString(axis.type),
    diameter: axis.diameter === true,
    home: asString(axis.home),
  }));
  const layout = asArray(message.channels).filter((ch) => isObject(ch) && asString(ch.name)).map((ch) => ({
    name: ch.name,
    axes: stringsOf(ch.axes),
  }));
  // The same machine again (a reconnect): keep the screen and its history.
  const key = JSON.stringify([layout, axes]);
  if (key === layoutKey) return;
  layoutKey = key;

  channels = layout;
  addressOf.clear();
  for (const axis of axes) addressOf.set(axis.name, axis.address);

  channelViews.clear();
  for (const channel of channels) {
    const view = new ChannelView(channel.name, sendCommand);
    const program = programs.get(channel.name);
    if (program) view.setProgram(program.name, program.lines);
    channelViews.set(channel.name, view);
  }
  ui.overview.replaceChildren(...[...channelViews.values()].map((view) => view.root));
  ui.overview.style.setProperty('--channels', String(Math.max(1, channels.length)));
  axisPanel.build(axes);
  timeline.setChannels(channels.map((channel) => channel.name));
  applyRole();
}

function onRole(message) {
  role = ROLES.has(message.role) ? message.role : 'none';
  applyRole();
}

function onProgram(message) {
  const channel = asString(message.channel);
  if (!channel || !Array.isArray(message.lines)) return;
  // A line that is not text stays as an empty line: the numbers after it must not shift.
  const program = { name: asString(message.name), lines: message.lines.map(asString) };
  programs.set(channel, program);
  channelViews.get(channel)?.setProgram(program.name, program.lines);
}

function onReply(message) {
  const id = asNumber(message.id);
  const what = pendingCommands.get(id) ?? `command ${id ?? '?'}`;
  pendingCommands.delete(id);
  if (message.ok === true) showReply(`${what}: ok`, true);
  else showReply(`${what}: refused: ${asString(message.reason) || 'no reason given'}`, false);
}

// The machine-wide run as the launcher commands it: an E-stop names its cause.
const RUN_PHASES = new Map([
  ['starting', 'starting'], ['running', 'running'], ['stopped', 'stopped'], ['estop', 'E-STOP'],
]);

function showRun(run) {
  const phase = isObject(run) && RUN_PHASES.has(run.phase) ? run.phase : 'starting';
  const reason = isObject(run) ? asString(run.reason) : '';
  setText(ui.run, phase === 'estop' && reason ? `E-STOP: ${reason}` : RUN_PHASES.get(phase));
  setData(ui.run, 'run', phase);
}

function onState(message) {
  lastStateAt = performance.now();
  const cycle = asNumber(message.cycle);
  setText(ui.cycle, cycle === null ? '—' : String(cycle));
  const timeS = asNumber(message.time_s);
  setText(ui.time, timeS === null ? '—' : `${timeS.toFixed(3)} s`);
  ui.time.classList.remove('stale');
  showRun(message.run);

  const channelStates = new Map();
  for (const channel of asArray(message.channels)) {
    if (isObject(channel) && asString(channel.name)) channelStates.set(channel.name, channel);
  }
  const axisStates = asArray(message.axes).filter(isObject);

  for (const channel of channels) {
    const state = channelStates.get(channel.name);
    const view = channelViews.get(channel.name);
    if (!state || !view) continue;
    view.update(state);
    view.toolpath.update(state, ownedXZ(channel, axisStates, addressOf));
  }
  axisPanel.update(axisStates);
  timeline.update(timeS, channelStates);
}

// Numbers that stop changing must not pass for a machine standing still.
setInterval(() => {
  const stale = connected && lastStateAt > 0 && performance.now() - lastStateAt > STALE_MS;
  ui.time.classList.toggle('stale', stale);
}, 1000);

ui.authForm.addEventListener('submit', (event) => {
  event.preventDefault();
  typedToken = ui.token.value.trim();
  ui.token.value = '';
  authenticate(typedToken);
});

window.addEventListener('hashchange', () => authenticate(tokenFromHash()));

setConnected(false);
connect();
