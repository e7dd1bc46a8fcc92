// Opens one of shatter's HTML pages from file:// in headless Chromium (Debian's /usr/bin/chromium,
// driven by the npm package puppeteer-core) and says what a person would see.
//
// usage: node check_page.js NODE_MODULES_DIR PAGE OUT_DIR [--viewer]
//
// Writes OUT_DIR/page.png (the page, full length) and, with --viewer, OUT_DIR/viewer_start.png and
// OUT_DIR/viewer_end.png (the 3D view at the start and the end of the animation), and prints one
// JSON object:
//   {"console_errors": [...], "page_errors": [...], "requests": [every URL the page asked for],
//    "failed_requests": [...], "values": {data-key: data-value, ...} (outside rows with data-run),
//    "runs": {RUN: {data-key: data-value, ...}} (in them), "broken_images": [src of every image that did not load or shows at no size],
//    "title": ..., "viewer": {"loaded", "error", "pieces",
//    "duration", "cameras": {"start", "end", "dragged", "back"}} (with --viewer: the view's
//    camera (position, direction, fov, following) at the start and the end of the animation, after
//    a drag across the view at the end, and after the Movie camera button)}
// Exits 0 when the page was opened (whatever it showed), 2 when Chromium could not be driven.
'use strict';

const fs = require('fs');
const os = require('os');
const path = require('path');

const [modules, page, outDir, flag] = process.argv.slice(2);
if (!modules || !page || !outDir) {
  console.error('usage: node check_page.js NODE_MODULES_DIR PAGE OUT_DIR [--viewer]');
  process.exit(2);
}
const puppeteer = require(path.join(path.resolve(modules), 'puppeteer-core'));

async function main() {
  // A new, empty profile each time; the flags keep Chromium off the network (the closed network
  // refuses its background connections) and make it run as root in a container.
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'shatter-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: '/usr/bin/chromium',
    headless: true,
    userDataDir: profile,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync',
           '--window-size=1280,900'],
  });
  const result = { console_errors: [], page_errors: [], requests: [], failed_requests: [], values: {}, runs: {} };
  try {
    const tab = await browser.newPage();
    await tab.setViewport({ width: 1280, height: 900 });
    tab.on('console', (m) => { if (m.type() === 'error') result.console_errors.push(m.text()); });
    tab.on('pageerror', (e) => result.page_errors.push(String(e && e.message ? e.message : e)));
    tab.on('request', (r) => result.requests.push(r.url().slice(0, 200)));
    tab.on('requestfailed', (r) => result.failed_requests.push(`${r.url().slice(0, 200)}: ${r.failure() && r.failure().errorText}`));
    const url = 'file://' + path.resolve(page);
    await tab.goto(url, { waitUntil: 'load', timeout: 60000 });
    result.title = await tab.title();
    const read = await tab.evaluate(() => {
      const values = {}, runs = {};
      document.querySelectorAll('[data-key]').forEach((e) => {
        const row = e.closest('[data-run]');
        const into = row ? (runs[row.getAttribute('data-run')] = runs[row.getAttribute('data-run')] || {}) : values;
        into[e.getAttribute('data-key')] = e.getAttribute('data-value');
      });
      const broken = [];
      // An image that did not load, or that the page's layout shows at no size (a thumbnail whose
      // max-width is a percentage of an auto-sized table cell comes out 0 pixels wide).
      document.querySelectorAll('img').forEach((i) => {
        const box = i.getBoundingClientRect();
        if (!i.complete || i.naturalWidth === 0 || box.width < 1 || box.height < 1) broken.push(i.getAttribute('src'));
      });
      return { values, runs, broken };
    });
    result.values = read.values;
    result.runs = read.runs;
    result.broken_images = read.broken;
    if (flag === '--viewer') {
      try {
        await tab.waitForFunction(() => window.shatterViewer && (window.shatterViewer.loaded || window.shatterViewer.error),
                                  { timeout: 60000 });
      } catch (e) {
        result.viewer_timeout = String(e.message);
      }
      result.viewer = await tab.evaluate(() => {
        const v = window.shatterViewer || {};
        return { loaded: !!v.loaded, error: v.error || null, pieces: v.pieces || 0, duration: v.duration || 0 };
      });
      if (result.viewer.loaded) {
        const box = await tab.$('#viewer');
        await box.scrollIntoView();
        const shoot = async (t, file) => {
          await tab.evaluate((time) => window.shatterViewer.setTime(time), t);
          // two animation frames: the canvas is composited before the screenshot
          await tab.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
          await box.screenshot({ path: path.join(outDir, file) });
        };
        const camera = () => tab.evaluate(() => window.shatterViewer.camera());
        result.viewer.cameras = {};
        await shoot(0, 'viewer_start.png');
        result.viewer.cameras.start = await camera();
        await shoot(result.viewer.duration, 'viewer_end.png');
        result.viewer.cameras.end = await camera();
        // A person's drag across the middle of the view, then the button back.
        const b = await box.boundingBox();
        await tab.mouse.move(b.x + b.width / 2, b.y + b.height / 2);
        await tab.mouse.down();
        await tab.mouse.move(b.x + b.width / 2 + 120, b.y + b.height / 2 + 30, { steps: 8 });
        await tab.mouse.up();
        result.viewer.cameras.dragged = await camera();
        await tab.click('#movie-camera');
        result.viewer.cameras.back = await camera();
      }
    }
    await tab.evaluate(() => window.scrollTo(0, 0));
    await tab.screenshot({ path: path.join(outDir, 'page.png'), fullPage: true });
    await tab.close();
  } finally {
    await browser.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
  console.log(JSON.stringify(result));
}

main().catch((e) => {
  console.error(`check_page: ${e && e.stack ? e.stack : e}`);
  process.exit(2);
});
