// Opens a `conicloc report` page in headless Chromium (Debian's, driven by playwright-core) and
// checks what a user would see: no console or page error, a slider that changes the drawn
// particles, and a screenshot that is not blank.
// Usage: node report_page.mjs PAGE.html SCREENSHOT.png [FRAME]  (the screenshot's frame; default
// the middle one)
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';
import path from 'node:path';

const require = createRequire(path.join(path.dirname(new URL(import.meta.url).pathname), '../js/'));
const { chromium } = require('playwright-core');

const [pagePath, screenshotPath, shotFrame] = process.argv.slice(2);
const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); };

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-gl=swiftshader', '--disable-gpu'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1320, height: 1100 } });
  const errors = [];
  const requests = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push('console: ' + m.text()); });
  page.on('pageerror', (e) => errors.push('page error: ' + e.message));
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) requests.push(r.url()); });
  await page.goto(pathToFileURL(path.resolve(pagePath)).href, { waitUntil: 'load' });
  await page.waitForFunction(() => document.body.dataset.frame === '0');

  const frames = Number(await page.getAttribute('#slider', 'max')) + 1;
  check(frames >= 3, `the slider has ${frames} frames (>= 3)`);
  const sampling = await page.textContent('#sampling');
  check(/sampled: every \d+(st|nd|rd|th) scan, \d+ of \d+ scans/.test(sampling) && /page size [0-9.]+ MB/.test(sampling),
        `the page states its sampling and size: "${sampling}"`);
  const stated = Number(await page.evaluate(() => document.body.dataset.pageBytes));
  const fs = await import('node:fs');
  check(stated === fs.statSync(pagePath).size, `stated size ${stated} = file size`);

  const before = {
    hash: await page.getAttribute('#plan', 'data-particle-hash'),
    drawn: Number(await page.getAttribute('#plan', 'data-particles-drawn')),
    pixels: await page.locator('#plan').screenshot(),
  };
  check(before.drawn > 0, `particles drawn at the first frame: ${before.drawn}`);
  // Move the slider as a user does: focus it and step to the last frame with the keyboard.
  await page.focus('#slider');
  await page.keyboard.press('End');
  await page.waitForFunction((n) => document.body.dataset.frame === String(n - 1), frames);
  const after = {
    hash: await page.getAttribute('#plan', 'data-particle-hash'),
    pixels: await page.locator('#plan').screenshot(),
  };
  check(after.hash !== before.hash, `moving the slider changes the drawn particles (${before.hash} -> ${after.hash})`);
  check(!after.pixels.equals(before.pixels), 'moving the slider changes the plan view\'s pixels');

  // Play advances the frame; then back to the middle for the screenshot.
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.frame !== String(Number(document.getElementById('slider').max)));
  await page.click('#play');
  check(true, 'play advances the frame');
  await page.evaluate((n) => { const s = document.getElementById('slider'); s.value = String(n); s.dispatchEvent(new Event('input')); }, shotFrame === undefined ? Math.floor(frames / 2) : Number(shotFrame));

  const shot = await page.screenshot({ path: screenshotPath, fullPage: true });
  // Not blank: the screenshot's decoded pixels vary (measured on the plan canvas's RGBA data).
  const variance = await page.evaluate(() => {
    const c = document.getElementById('plan');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let sum = 0, sum2 = 0, n = 0;
    for (let i = 0; i < d.length; i += 4) {
      const v = d[i + 3] === 0 ? 255 : (d[i] + d[i + 1] + d[i + 2]) / 3;
      sum += v; sum2 += v * v; ++n;
    }
    return sum2 / n - (sum / n) ** 2;
  });
  check(shot.length > 20000 && variance > 100,
        `screenshot ${shot.length} bytes, plan pixel variance ${variance.toFixed(0)} (not blank)`);
  check(errors.length === 0, `no console or page errors${errors.length ? ': ' + errors.join('; ') : ''}`);
  check(requests.length === 0, `no network request${requests.length ? ': ' + requests.join(', ') : ''}`);
} finally {
  await browser.close();
}
if (failures.length) {
  console.error(`${failures.length} check(s) failed`);
  process.exit(1);
}
