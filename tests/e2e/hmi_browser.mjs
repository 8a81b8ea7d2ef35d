// The browser half of the HMI end-to-end test (tests/integration/hmi_test.cpp starts the
// machine with its HMI and runs this): Debian's Chromium driven by playwright-core opens the
// HMI, starts the part-transfer programs from the page and watches them run. Exits 0 when every
// check held, 1 with the failed check on stderr.
//
//   node hmi_browser.mjs URL OUT_DIR
//
// URL carries the operator token in its fragment (#token=...); screenshots go to OUT_DIR.
import { chromium } from 'playwright-core';
import { mkdirSync } from 'node:fs';
import { join } from 'node:path';

const [url, outDir] = process.argv.slice(2);
if (!url || !outDir) {
  console.error('usage: node hmi_browser.mjs URL OUT_DIR');
  process.exit(2);
}
mkdirSync(outDir, { recursive: true });

const browser = await chromium.launch({
  // The harness stops a run that overstays with SIGINT: our handler below says where it stood.
  handleSIGINT: false,
  executablePath: process.env.MCNC_CHROMIUM || '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
const errors = [];
page.on('pageerror', (e) => errors.push(String(e)));

let shot = 0;
async function screenshot(name) {
  shot += 1;
  await page.screenshot({ path: join(outDir, `${String(shot).padStart(2, '0')}-${name}.png`), fullPage: true });
}

// What the page shows, for a failure's message: the connection, the machine's time, and each
// channel's state, current line and wait.
function pageSummary() {
  const text = (el, sel) => el.querySelector(sel)?.textContent.trim().replace(/\s+/g, ' ') || '-';
  const channels = [...document.querySelectorAll('[data-channel]')].map((ch) =>
    `${ch.dataset.channel} ${text(ch, '.ch-state')} line ${ch.querySelector('.line.current')?.dataset.line || '-'}` +
    ` wait "${text(ch, '.ch-wait')}" end "${text(ch, '.ch-end')}"`);
  return `${text(document, '#connection')} as ${text(document, '#role')}, machine time ` +
    `${text(document, '#time')}; ${channels.join('; ')}`;
}

// Each check passed is printed with the wall time since the start and the machine's time, so a
// run that is stopped from outside still tells which step took long.
const started = Date.now();
let step = 'opening the page';
const elapsed = () => `${((Date.now() - started) / 1000).toFixed(1)} s`;
async function passed(what) {
  const machineTime = await page.locator('#time').first().innerText().catch(() => '-');
  console.log(`[${elapsed()}, machine ${machineTime}] ${what}`);
}

// Polls `probe` (run in the page) until it returns true; fails with `what` after `ms`. The
// machine runs in paced lockstep, which a loaded host slows down (two cores run it at a fifth
// of real time or less), so the time allowed is a backstop, not a measure.
async function until(what, probe, arg, ms = 90000) {
  step = what;
  try {
    await page.waitForFunction(probe, arg, { timeout: ms, polling: 20 });
    await passed(what);
  } catch (e) {
    const seen = await page.evaluate(pageSummary).catch((err) => `page not readable: ${err}`);
    await screenshot('failed');
    throw new Error(`${what}: not seen within ${ms} ms; the page shows: ${seen}`);
  }
}

const text = (sel) => page.locator(sel).first().innerText();

// The harness kills 5 s after its SIGINT: say where we stood first, then what the page shows
// if a starved renderer answers within 2 s.
let stopping = false;
process.on('SIGINT', async () => {
  stopping = true;
  console.error(`FAILED: stopped from outside ${elapsed()} after the start, at or after "${step}"`);
  const seen = await Promise.race([
    page.evaluate(pageSummary).catch((err) => `not readable: ${err}`),
    new Promise((resolve) => setTimeout(() => resolve('no answer within 2 s'), 2000)),
  ]);
  console.error(`the page shows: ${seen}`);
  process.exit(1);
});
const stateOf = (ch) => `[data-channel="${ch}"] .ch-state`;
const FEED_OVERRIDE_CH1 = '[data-channel="CH1"] input[data-action="feed_override"]';
// The slider's value went out and the HMI answered it.
const feedOverrideTaken = (percent) => until(`CH1 takes ${percent} % feed override`, (p) =>
  document.querySelector('#last-reply')?.textContent.trim() === 'CH1 feed_override: ok' &&
  document.querySelector('[data-channel="CH1"] .ch-feed-override')?.textContent.trim() === `${p} %`, percent);

try {
  await page.goto(url);
  await until('connected as operator', () =>
    document.querySelector('#role')?.textContent.trim() === 'operator' &&
    document.querySelector('#connection')?.textContent.trim() === 'connected');
  // Manual start: every channel idle with its program loaded.
  for (const ch of ['CH1', 'CH2', 'CH3']) {
    await until(`${ch} idle`, (sel) => document.querySelector(sel)?.textContent.trim() === 'idle', stateOf(ch));
  }
  await until('A1 owned by CH1', () =>
    document.querySelector('#axes tr[data-axis="A1"] .owner')?.textContent.trim() === 'CH1');
  await until('CH1 program shown', () =>
    document.querySelectorAll('[data-channel="CH1"] .ch-program .line').length >= 10);
  await screenshot('ready');

  // As an operator proving out a program: CH1's feed override down to 10 % before the start, so
  // the turning block lasts 32 s of machine time and the feed hold below lands in it however
  // slowly a loaded host lets the page poll (at 100 % it lasted 3.2 s and a starved browser
  // could see CH1 past it).
  await page.locator(FEED_OVERRIDE_CH1).fill('10');
  await feedOverrideTaken(10);

  // Start both turrets from the page; CH2 waits at P1 for CH1.
  await page.click('[data-channel="CH1"] button[data-action="cycle_start"]');
  await page.click('[data-channel="CH2"] button[data-action="cycle_start"]');
  await until('CH2 waits at G04.1 P1 for CH1', () => {
    const ch = document.querySelector('[data-channel="CH2"]');
    const wait = ch?.querySelector('.ch-wait')?.textContent || '';
    return ch?.querySelector('.ch-state')?.textContent.trim() === 'waiting' &&
      wait.includes('P1') && wait.includes('CH1');
  });
  await screenshot('barrier-wait');
  if ((await text('#run')) !== 'running') {
    throw new Error(`the run shows "${await text('#run')}", not running`);
  }

  // Feed hold while CH1 turns the left end (line 9: G01 Z-30): Z1 stands still.
  await until('CH1 turning the left end', () =>
    document.querySelector('[data-channel="CH1"] .line.current')?.dataset.line === '9' &&
    document.querySelector('[data-channel="CH1"] .ch-state')?.textContent.trim() === 'running');
  // The turning block shows its modal state and feed, and the main spindle its drive's load.
  const modal = await text('[data-channel="CH1"] .ch-modal');
  if (!modal.startsWith('G01 ') || !modal.includes('G18')) {
    throw new Error(`CH1's modal codes in G01 Z-30: "${modal}"`);
  }
  if (!(await text('[data-channel="CH1"] .ch-feed')).startsWith('F600 ')) {
    throw new Error(`CH1's feed: ${await text('[data-channel="CH1"] .ch-feed')}`);
  }
  await until('S1 shows its load', () =>
    /^-?[0-9]+ %$/.test(document.querySelector('[data-spindle="S1"] .load')?.textContent.trim() || ''));
  await page.click('[data-channel="CH1"] button[data-action="feed_hold"]');
  await until('CH1 in feed hold', (sel) => document.querySelector(sel)?.textContent.trim() === 'hold', stateOf('CH1'));
  // The path ramps down to rest; wait until Z1's command has stood for 0.3 s of machine time (a
  // loaded host runs the machine far slower than the page's clock), then it must stand while
  // machine time runs on. (The command, not the actual position: a servo settles by microns
  // after the ramp.)
  await until('Z1 at rest in feed hold', () => {
    const now = document.querySelector('#axes tr[data-axis="Z1"] .cmd')?.textContent;
    const t = parseFloat(document.querySelector('#time')?.textContent);
    if (window.z1Seen !== now || !(t >= window.z1Since)) {
      window.z1Seen = now;
      window.z1Since = t;
      return false;
    }
    return t - window.z1Since > 0.3;
  });
  const z1Before = await text('#axes tr[data-axis="Z1"] .cmd');
  const timeBefore = await text('#time');
  await page.waitForTimeout(700);
  const z1After = await text('#axes tr[data-axis="Z1"] .cmd');
  if (z1Before !== z1After) {
    throw new Error(`Z1 moved in feed hold: ${z1Before} -> ${z1After}`);
  }
  if (timeBefore === await text('#time')) {
    throw new Error(`machine time stood still in feed hold (${timeBefore}): nothing was checked`);
  }
  if (!(await text('#last-reply')).includes('ok')) {
    throw new Error(`feed hold reply: ${await text('#last-reply')}`);
  }
  await screenshot('feed-hold');
  await page.click('[data-channel="CH1"] button[data-action="cycle_start"]');
  await until('CH1 running again', (sel) => document.querySelector(sel)?.textContent.trim() === 'running', stateOf('CH1'));
  await page.locator(FEED_OVERRIDE_CH1).fill('100');
  await feedOverrideTaken(100);

  // A1 goes to CH2 (G140 in CH1, G141 in CH2) and back (G142).
  await until('A1 owned by CH2', () =>
    document.querySelector('#axes tr[data-axis="A1"] .owner')?.textContent.trim() === 'CH2', undefined, 120000);
  await screenshot('a1-with-ch2');
  await until('A1 back with CH1', () =>
    document.querySelector('#axes tr[data-axis="A1"] .owner')?.textContent.trim() === 'CH1', undefined, 120000);
  await until('both programs ended', () =>
    ['CH1', 'CH2'].every((ch) =>
      document.querySelector(`[data-channel="${ch}"] .ch-end`)?.textContent.trim() === 'end M30'),
    undefined, 120000);
  await screenshot('ended');
  // The timeline has a lane per channel and the sync point.
  const lanes = await page.locator('#timeline [data-lane]').count();
  if (lanes !== 3) {
    throw new Error(`timeline lanes: ${lanes}, not one per channel`);
  }
  // The turrets met at P1 and P2: a marker on both lanes, also where a channel came last and
  // never waited (the meetings come from the channels' arrivals, not from sampled states).
  for (const ch of ['CH1', 'CH2']) {
    for (const p of ['1', '2']) {
      if ((await page.locator(`#timeline [data-lane="${ch}"] [data-p="${p}"]`).count()) !== 1) {
        throw new Error(`not one P${p} marker on ${ch}'s timeline lane`);
      }
    }
  }
  if ((await page.locator('#timeline [data-lane="CH3"] [data-p]').count()) !== 0) {
    throw new Error('a marker on the loader\'s lane, which met nobody');
  }
  if (errors.length > 0) {
    throw new Error(`page errors: ${errors.join('; ')}`);
  }
  console.log(`ok: ${shot} screenshots in ${outDir}`);
  await browser.close();
  process.exit(0);
} catch (e) {
  if (stopping) {
    await new Promise(() => {});  // the SIGINT handler reports and exits
  }
  console.error(`FAILED: ${e.message}`);
  await browser.close();
  process.exit(1);
}
