// Shared helpers of the browser tests: the platoonsim binary, runs made for the tests, and
// headless Chromium from Debian's package driven by playwright-core (which never downloads a
// browser of its own here).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { inflateSync } from 'node:zlib';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
export const ROOT = resolve(here, '..', '..');
export const BIN = process.env.PLATOONSIM_BIN || join(ROOT, 'target', 'release', 'platoonsim');
export const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';

// Under CI a missing browser or binary fails the tests; elsewhere they are skipped with the
// reason.
export function missing() {
  const why = [];
  if (!existsSync(CHROMIUM)) why.push(`no Chromium at ${CHROMIUM} (apt-get install chromium)`);
  if (!existsSync(BIN)) why.push(`no platoonsim binary at ${BIN} (cargo build --release -p platoonsim)`);
  if (why.length && process.env.CI === 'true') throw new Error(why.join('; '));
  return why.length ? why.join('; ') : null;
}

export function platoonsim(args) {
  return execFileSync(BIN, ['--quiet', ...args], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

// A run directory with trajectories (and trips) and its view.html.
export function makeRun(name, runArgs) {
  const dir = join(mkdtempSync(join(tmpdir(), 'platoonsim-view-')), name);
  platoonsim(['run', ...runArgs, '--out', dir]);
  platoonsim(['view', dir]);
  return dir;
}

// trajectories.csv as objects (numbers converted), by header name.
export function readTrajectories(dir) {
  const [head, ...lines] = readFileSync(join(dir, 'trajectories.csv'), 'utf8').trim().split('\n');
  const cols = head.split(',');
  const num = new Set(['t_s', 'id', 'lane', 'x_m', 'v_mps', 'a_mps2', 'platoon_pos']);
  return lines.map((l) => {
    const cells = l.split(',');
    const o = {};
    cols.forEach((c, i) => { o[c] = num.has(c) && cells[i] !== '' ? Number(cells[i]) : cells[i]; });
    return o;
  });
}

export const CHROME_ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic',
  '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// Opens `file` in a fresh browser profile; records console errors, page errors and every
// request other than the page itself (and refuses those requests).
export async function openView(file, viewport = { width: 1400, height: 800 }) {
  const profile = mkdtempSync(join(tmpdir(), 'platoonsim-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    args: CHROME_ARGS,
    viewport,
    deviceScaleFactor: 1,
    offline: true,
  });
  const url = pathToFileURL(file).href;
  const errors = [];
  const requests = [];
  await context.route('**/*', (route) => {
    if (route.request().url() === url) return route.continue();
    requests.push(route.request().url());
    return route.abort();
  });
  const page = context.pages()[0] || (await context.newPage());
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(url);
  await page.waitForFunction(() => window.__platoonsimView && window.__platoonsimView.ready, null, { timeout: 60_000 });
  return { context, page, errors, requests };
}

// The colour of one screen pixel, from a 1 x 1 PNG screenshot (what the browser composited).
export async function pixel(page, x, y) {
  const png = await page.screenshot({ clip: { x: Math.floor(x), y: Math.floor(y), width: 1, height: 1 } });
  return decodeOnePixel(png);
}

// A 1 x 1 8-bit RGB(A) PNG: the IDAT data inflate to one filter byte and the pixel (with no
// neighbours every PNG filter leaves the bytes as they are).
export function decodeOnePixel(png) {
  let at = 8;
  const idat = [];
  let colourType = 0;
  while (at < png.length) {
    const len = png.readUInt32BE(at);
    const type = png.toString('latin1', at + 4, at + 8);
    const data = png.subarray(at + 8, at + 8 + len);
    if (type === 'IHDR') {
      if (data.readUInt32BE(0) !== 1 || data.readUInt32BE(4) !== 1 || data[8] !== 8) throw new Error('not a 1x1 8-bit PNG');
      colourType = data[9];
    }
    if (type === 'IDAT') idat.push(data);
    at += 12 + len;
  }
  if (colourType !== 2 && colourType !== 6) throw new Error(`PNG colour type ${colourType}`);
  const raw = inflateSync(Buffer.concat(idat));
  return [raw[1], raw[2], raw[3]];
}

// The project's speed scale (crates/plot): 24 bins of 5 km/h, the colour at the bin's centre.
export function speedColour(kmh) {
  const b = Math.max(0, Math.min(23, Math.floor(kmh / 5)));
  const t = (b + 0.5) / 24;
  const stops = [[0, [200, 30, 35]], [0.5, [250, 215, 70]], [1, [30, 145, 70]]];
  const [a, c] = t <= 0.5 ? [stops[0], stops[1]] : [stops[1], stops[2]];
  const f = (t - a[0]) / (c[0] - a[0]);
  return [0, 1, 2].map((k) => Math.round(a[1][k] + (c[1][k] - a[1][k]) * f));
}
