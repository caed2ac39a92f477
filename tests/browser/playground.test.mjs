// Browser test of the playground (`immerse serve`) and of immerse's Lottie
// output, in Debian's Chromium driven by playwright-core. Run it with
// scripts/browser-test.sh, which installs what it needs.
//
// 1. At 1280x800: starts `immerse serve --port 0`, checks the example pair
//    loaded at start, clears it, draws two curves with mouse events, adds
//    curves from the reference list, a file and the paste box, runs the
//    morph and checks that the options and downloads are on screen without
//    scrolling, scrubs to a frame and compares the canvas with the PNG
//    that `immerse morph` renders for the same curves and frame. The page
//    draws the server's PNG, so the two must agree to the pixel (the
//    tolerance of 2 per channel only absorbs a browser's image decoding).
//    Then: download names, GIF progress, stale downloads, the fps rule of
//    GIFs, the frames message and cubic-bezier easing.
// 2. Click-to-pause: a click on the picture pauses and resumes playback
//    and never starts a drawing.
// 3. At 390x844 (a phone): no horizontal scroll, the canvas scales, the
//    controls stack; the example pair morphs and plays.
// 4. Loads the `--format lottie` file of the morph of (1) in lottie-web on
//    a test page and compares a rendered frame with immerse's PNG of it.
//    Two rasterisers (tiny-skia, Chromium's Skia) anti-alias edges
//    differently and keyframes may be interpolated (within 1 px), so this
//    comparison counts pixels that differ by more than 32 in a channel:
//    they must be edge pixels, at most 2% of the image, with a small mean.
// Also: no console errors on any page, the page's downloads equal the
// CLI's files byte for byte, and screenshots at both sizes go to
// docs/img/playground.png and docs/img/playground-phone.png.

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { spawn, execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, writeFileSync, rmSync, mkdirSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, dirname, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { createRequire } from "node:module";
import { chromium } from "playwright-core";

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, "../..");
const require = createRequire(import.meta.url);
const BIN = resolve(root, process.env.IMMERSE_BIN || "target/release/immerse");
const CHROMIUM = process.env.CHROMIUM || "/usr/bin/chromium";
const SCREENSHOT = resolve(root, process.env.SCREENSHOT || "docs/img/playground.png");
const SCREENSHOT_PHONE = resolve(root, process.env.SCREENSHOT_PHONE || "docs/img/playground-phone.png");
const DESKTOP = { width: 1280, height: 800 };
const PHONE = { width: 390, height: 844 };
const FRAMES = 24;
const SCRUB_TO = 20; // a frame where the strip overlaps itself
const SIZE = 600;
const started = Date.now();
const measured = {};

let server;
let url;
let context;
let work;

function startServer() {
  return new Promise((resolvePromise, reject) => {
    const child = spawn(BIN, ["serve", "--port", "0"], { stdio: ["ignore", "pipe", "pipe"] });
    let out = "";
    let err = "";
    const timer = setTimeout(() => reject(new Error(`immerse serve printed no URL in 20 s: ${err}`)), 20000);
    child.stdout.on("data", (d) => {
      out += d;
      const m = out.match(/^(http:\/\/127\.0\.0\.1:\d+\/)\s*$/m);
      if (m) {
        clearTimeout(timer);
        resolvePromise({ child, url: m[1] });
      }
    });
    child.stderr.on("data", (d) => { err += d; });
    child.on("exit", (code) => {
      clearTimeout(timer);
      reject(new Error(`immerse serve exited (${code}): ${err}`));
    });
  });
}

before(async () => {
  work = mkdtempSync(join(tmpdir(), "immerse-browser-"));
  ({ child: server, url } = await startServer());
  context = await chromium.launchPersistentContext(join(work, "profile"), {
    executablePath: CHROMIUM,
    headless: true,
    args: [
      "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync",
      "--force-color-profile=srgb",
    ],
    viewport: DESKTOP,
    acceptDownloads: true,
    deviceScaleFactor: 1,
    timeout: 60000,
  });
});

after(async () => {
  if (context) await context.close().catch(() => {});
  if (server && server.exitCode === null) {
    // Ctrl-C: the server must stop cleanly and promptly.
    const exited = new Promise((r) => server.once("exit", (code, signal) => r({ code, signal })));
    server.kill("SIGINT");
    const res = await Promise.race([exited, new Promise((r) => setTimeout(() => r(null), 10000))]);
    if (!res) server.kill("SIGKILL");
    measured.server_exit = res ? (res.code ?? res.signal) : "killed after 10 s";
  }
  if (work) rmSync(work, { recursive: true, force: true });
  measured.run_seconds = Math.round((Date.now() - started) / 100) / 10;
  console.log("browser test measurements: " + JSON.stringify(measured));
});

/** Console errors and uncaught exceptions of a page. */
function watchConsole(page) {
  const errors = [];
  page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", (e) => errors.push(String(e)));
  return errors;
}

/** Mouse path of a closed curve in canvas pixels (y down). */
function ellipse(cx, cy, rx, ry, n) {
  return Array.from({ length: n }, (_, i) => {
    const a = (2 * Math.PI * i) / n;
    return [cx + rx * Math.cos(a), cy + ry * Math.sin(a)];
  });
}

/** A strip winding 470° around a centre, overlapping itself where its
 * ends meet: self-overlapping but not simple. */
function curlStrip(cx, cy) {
  const out = [];
  const total = (470 * Math.PI) / 180;
  const steps = 70;
  const outer = (t) => 150 + 40 * (t / total);
  for (let i = 0; i <= steps; i++) {
    const t = (total * i) / steps;
    out.push([cx + outer(t) * Math.cos(t), cy + outer(t) * Math.sin(t)]);
  }
  for (let i = steps; i >= 0; i--) {
    const t = (total * i) / steps;
    const r = outer(t) - 60;
    out.push([cx + r * Math.cos(t), cy + r * Math.sin(t)]);
  }
  return out;
}

/** Presses, drags along `path` (canvas pixels) and releases. */
async function drawFreehand(page, path) {
  const box = await page.locator("#stage").boundingBox();
  // The canvas has SIZE pixels a side and may be drawn smaller.
  const at = ([x, y]) => [box.x + (x * box.width) / SIZE, box.y + (y * box.height) / SIZE];
  await page.mouse.move(...at(path[0]));
  await page.mouse.down();
  for (const p of path.slice(1)) await page.mouse.move(...at(p), { steps: 2 });
  await page.mouse.up();
}

/** Compares the canvas `selector` with a PNG given as base64; per-pixel
 * largest channel difference. */
async function compareWithPng(page, selector, pngBase64, threshold) {
  return page.evaluate(async ({ selector, pngBase64, threshold }) => {
    const canvas = document.querySelector(selector);
    const img = new Image();
    img.src = "data:image/png;base64," + pngBase64;
    await img.decode();
    const ref = document.createElement("canvas");
    ref.width = img.width; ref.height = img.height;
    const rctx = ref.getContext("2d");
    rctx.drawImage(img, 0, 0);
    const a = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
    const b = rctx.getImageData(0, 0, ref.width, ref.height).data;
    if (canvas.width !== ref.width || canvas.height !== ref.height) {
      return { error: `sizes differ: ${canvas.width}x${canvas.height} vs ${ref.width}x${ref.height}` };
    }
    // The shades of depth 1 and 2 (render/src/style.rs: fill #3d7cc9 at
    // 1-(1-0.45)^k over #fbfaf7).
    const shade = (k) => {
      const o = 1 - Math.pow(0.55, k);
      return [[0xfb, 0x3d], [0xfa, 0x7c], [0xf7, 0xc9]].map(([bg, f]) => Math.round(bg * (1 - o) + f * o));
    };
    const near = (d, i, c) => Math.abs(d[i] - c[0]) <= 3 && Math.abs(d[i + 1] - c[1]) <= 3 && Math.abs(d[i + 2] - c[2]) <= 3;
    const [one, two] = [shade(1), shade(2)];
    let max = 0, sum = 0, over = 0, depth1 = [0, 0], depth2 = [0, 0];
    for (let i = 0; i < a.length; i += 4) {
      const d = Math.max(Math.abs(a[i] - b[i]), Math.abs(a[i + 1] - b[i + 1]), Math.abs(a[i + 2] - b[i + 2]));
      max = Math.max(max, d);
      sum += d;
      if (d > threshold) over++;
      if (near(b, i, one)) { depth1[0]++; if (near(a, i, one)) depth1[1]++; }
      if (near(b, i, two)) { depth2[0]++; if (near(a, i, two)) depth2[1]++; }
    }
    const pixels = a.length / 4;
    return {
      pixels, max, mean: sum / pixels, over, overFraction: over / pixels,
      // [pixels of that shade in the PNG, of those, pixels of that shade on the canvas]
      depth1, depth2,
    };
  }, { selector, pngBase64, threshold });
}

/** Fails unless every element of `selectors` lies inside the viewport
 * (the page not scrolled) and nothing scrolls sideways. */
async function assertOnScreen(page, selectors, size) {
  const got = await page.evaluate((selectors) => ({
    scrollX: window.scrollX,
    scrollY: window.scrollY,
    scrollWidth: document.documentElement.scrollWidth,
    boxes: selectors.map((s) => {
      const r = document.querySelector(s).getBoundingClientRect();
      return { s, left: r.left, top: r.top, right: r.right, bottom: r.bottom };
    }),
  }), selectors);
  assert.equal(got.scrollY, 0);
  assert.ok(got.scrollWidth <= size.width, `the page is ${got.scrollWidth} px wide at ${size.width}`);
  for (const b of got.boxes) {
    assert.ok(b.left >= 0 && b.right <= size.width && b.top >= 0 && b.bottom <= size.height,
      `${b.s} is off screen at ${size.width}x${size.height}: ${JSON.stringify(b)}`);
  }
  return got;
}

/** Waits for the example pair loaded at start. */
async function exampleLoaded(page) {
  await page.waitForFunction(() => window.immerse && window.immerse.ready === true);
  await page.waitForSelector("#curves li:nth-child(2)[data-status=ok]", { timeout: 20000 });
  const names = await page.locator("#curves .name").allTextContents();
  assert.deepEqual(names, ["1. ribbon-curl", "2. tail-loop"]);
}

/** Clicks a download link and returns the file name it saves as. */
async function downloadName(page, selector) {
  const [download] = await Promise.all([page.waitForEvent("download"), page.click(selector)]);
  const name = download.suggestedFilename();
  await download.delete();
  return name;
}

/** The keys of the page's last morph, fetched from its JSON download. */
async function fetchKeys(page) {
  const u = await page.evaluate(() => window.immerse.lastMorph.urls.json);
  const res = await page.request.get(new URL(u, url).href);
  assert.equal(res.status(), 200);
  const morph = JSON.parse(await res.text());
  assert.equal(morph.key_count, morph.keyframes.length);
  return morph.keyframes;
}

/** The shape at t from `keys`, computed here independently of the page:
 * a linear scan for the last key at or before t, then (1-w)·a + w·b. */
function lerpKeys(keys, t) {
  let j = 0;
  for (let i = 0; i < keys.length - 1; i++) if (keys[i].t <= t) j = i;
  const [a, b] = [keys[j], keys[j + 1]];
  const w = (t - a.t) / (b.t - a.t);
  return a.points.map((p, i) => [(1 - w) * p[0] + w * b.points[i][0], (1 - w) * p[1] + w * b.points[i][1]]);
}

/** Sets the scrubber to several t (between keys, exactly at keys (the
 * page reads a key's time written with the slider's 15 digits as that
 * key's), the ends) and checks, with no request to the server meanwhile, that the
 * page's shape equals the linear interpolation of the keys of the JSON and
 * that the picture changes. Returns what it measured. */
async function checkKeyScrub(page) {
  const keys = await fetchKeys(page);
  assert.ok(keys.length >= 2);
  assert.equal(keys[0].t, 0);
  assert.equal(keys[keys.length - 1].t, 1);
  const inner = keys.slice(1, -1).map((k) => k.t);
  const between = [];
  for (let j = 0; j < keys.length - 1; j += Math.max(1, Math.floor((keys.length - 1) / 3))) {
    // A slider holds 15 significant digits.
    between.push(Number((keys[j].t + 0.37 * (keys[j + 1].t - keys[j].t)).toPrecision(15)));
  }
  const atKeys = [0, 1, ...inner.filter((_, i) => i % Math.max(1, Math.floor(inner.length / 3)) === 0)];
  const ts = [...between, ...atKeys, 0.5].sort((x, y) => x - y);
  const requests = [];
  const onRequest = (r) => requests.push(r.url());
  page.on("request", onRequest);
  let previous = null;
  let changed = 0;
  let worst = 0;
  for (const t of ts) {
    await page.locator("#scrub").fill(String(t));
    await page.waitForFunction((t) => window.immerse.state.t === t, t);
    const got = await page.evaluate((t) => {
      const c = document.getElementById("stage");
      const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
      const sample = [];
      for (let i = 0; i < d.length; i += 4 * 97) sample.push(d[i], d[i + 1], d[i + 2]);
      return { points: window.immerse.shapeAt(t), sample, label: document.getElementById("frame-label").textContent };
    }, t);
    const k = keys.findIndex((key) => key.t === t);
    if (k >= 0) {
      // Exactly at a key: the key itself, to the bit.
      assert.deepEqual(got.points, keys[k].points, `t = ${t} (key ${k + 1})`);
      assert.match(got.label, new RegExp(` · key ${k + 1} of ${keys.length}$`));
    } else {
      const want = lerpKeys(keys, t);
      assert.equal(got.points.length, want.length);
      let scale = 1;
      for (const p of want) scale = Math.max(scale, Math.abs(p[0]), Math.abs(p[1]));
      for (let i = 0; i < want.length; i++) {
        const e = Math.max(Math.abs(got.points[i][0] - want[i][0]), Math.abs(got.points[i][1] - want[i][1]));
        worst = Math.max(worst, e / scale);
      }
      assert.match(got.label, / · between keys \d+ and \d+ of \d+$/);
    }
    if (previous) {
      let differ = 0;
      for (let i = 0; i < got.sample.length; i++) if (got.sample[i] !== previous[i]) differ++;
      if (differ > 0) changed++;
    }
    previous = got.sample;
  }
  page.off("request", onRequest);
  assert.ok(worst <= 1e-12, `the page's shape differs from the keys' interpolation by ${worst} (relative)`);
  assert.equal(changed, ts.length - 1, `the picture changed ${changed} times in ${ts.length - 1} moves`);
  assert.deepEqual(requests, [], "scrubbing asked the server");
  return { keys: keys.length, times: ts.length, worst_relative_error: worst };
}

const CONTROLS = ["#run", "#opt-frames", "#opt-path", "#opt-loop", "#opt-onion", "#dl-png", "#dl-gif", "#dl-svg", "#dl-lottie", "#dl-json", "#play", "#scrub", "#status"];

test("playground: draw two curves, morph, scrub; the canvas is immerse morph's PNG", { timeout: 180000 }, async () => {
  const page = await context.newPage();
  const errors = watchConsole(page);
  await page.goto(url);
  // One example pair is loaded at start.
  await exampleLoaded(page);
  await page.click("#clear-all");
  assert.equal(await page.locator("#curves li").count(), 0);

  const c = SIZE / 2;
  await drawFreehand(page, ellipse(c, c, 170, 120, 48));
  await page.waitForSelector("#curves li:nth-child(1)[data-status=ok]", { timeout: 20000 });
  await drawFreehand(page, curlStrip(c, c));
  await page.waitForSelector("#curves li:nth-child(2)[data-status=ok]", { timeout: 20000 });
  const verdicts = await page.locator("#curves .verdict").allTextContents();
  assert.deepEqual(verdicts, ["✓ self-overlapping", "✓ self-overlapping"]);
  const facts = await page.locator("#curves .facts").allTextContents();
  assert.match(facts[1], /turning number -?1 · crosses itself/);
  // The buttons of a curve name it when read out.
  assert.match(await page.locator("#curves li:nth-child(2) button[title=remove]").getAttribute("aria-label"), /^Remove curve 2 \(drawn curve \d+\)$/);

  // The reference list tags every curve that is not self-overlapping,
  // as the server's check finds it.
  const tags = await page.evaluate(async () => {
    const r = await (await fetch("/api/curves")).json();
    const shown = [...document.querySelectorAll("#reference option")].slice(1).map((o) => o.textContent);
    return r.curves.map((c, i) => [shown[i], c.self_overlapping]);
  });
  for (const [text, ok] of tags) assert.equal(text.endsWith("(not self-overlapping)"), !ok, text);
  assert.ok(tags.length >= 8 && tags.some(([, ok]) => !ok), JSON.stringify(tags));
  // A reference curve that is not self-overlapping says why.
  const eight = await page.locator("#reference option", { hasText: "figure-eight" }).getAttribute("value");
  await page.selectOption("#reference", eight);
  await page.click("#add-reference");
  await page.waitForSelector("#curves li:nth-child(3)[data-status=bad]", { timeout: 20000 });
  const why = await page.locator("#curves li:nth-child(3) .verdict").textContent();
  assert.match(why, /^✗ not self-overlapping: turning number is 0, not 1$/);
  assert.equal(await page.isDisabled("#run"), true, "Morph is disabled while a curve cannot be morphed");
  await page.locator("#curves li:nth-child(3) button[title=remove]").click();

  // Loading a curve file (SVG here) works the same way; a bad file's
  // message names it once.
  await page.setInputFiles("#file", join(root, "curves/tail-loop.svg"));
  await page.waitForSelector("#curves li:nth-child(3)[data-status=ok]", { timeout: 20000 });
  assert.equal(await page.locator("#curves li:nth-child(3) .name").textContent(), "3. tail-loop");
  await page.locator("#curves li:nth-child(3) button[title=remove]").click();
  await page.setInputFiles("#file", { name: "broken.svg", mimeType: "image/svg+xml", buffer: Buffer.from("<svg") });
  await page.waitForFunction(() => document.getElementById("status").textContent.startsWith("broken.svg: "));
  const message = await page.locator("#status").textContent();
  assert.equal(message.split("broken.svg").length - 1, 1, message);

  // Pasted points: x y per line.
  await page.click("#paste-box summary");
  await page.fill("#paste", "0 0\n100 0\n100 80\n0 80\n");
  await page.click("#add-paste");
  await page.waitForSelector("#curves li:nth-child(3)[data-status=ok]", { timeout: 20000 });
  assert.match(await page.locator("#curves li:nth-child(3) .name").textContent(), /^3\. pasted curve \d+$/);
  assert.equal(await page.locator("#curves li:nth-child(3) .facts").textContent(), "4 points · turning number 1 · simple");
  await page.locator("#curves li:nth-child(3) button[title=remove]").click();
  assert.equal(await page.locator("#curves li").count(), 2);
  await page.click("#paste-box summary");

  // frames must be whole: the page says so in words, before any request.
  await page.fill("#opt-frames", "2.5");
  await page.click("#run");
  assert.equal(await page.locator("#status").textContent(), "frames: 2.5 is not a whole number from 2 to 240");

  await page.fill("#opt-frames", String(FRAMES));
  const t0 = Date.now();
  await page.click("#run");
  await page.waitForSelector("#stage[data-shown='0']", { timeout: 60000 });
  measured.morph_and_first_frame_ms = Date.now() - t0;
  const status = await page.locator("#status").textContent();
  assert.match(status, new RegExp(`^${FRAMES} frames, every one an immersed disk`));
  // The motion measures of the morph the server made.
  const motion = await page.evaluate(() => window.immerse.lastMorph.morph.motion);
  assert.ok(motion.detour >= 1 && motion.unwind > 0, JSON.stringify(motion));
  assert.ok(status.includes(`detour ${motion.detour.toFixed(2)}, unwind ${motion.unwind.toFixed(2)}`), status);
  // After a morph, with its long status line, every control and download
  // is on screen at 1280x800.
  measured.layout_1280 = (await assertOnScreen(page, CONTROLS, DESKTOP)).scrollWidth;

  // Scrub with the slider to the time of frame SCRUB_TO: the page draws
  // the shape there from the keys.
  const scrubT = await page.evaluate((k) => window.immerse.lastMorph.morph.frames[k].t, SCRUB_TO);
  await page.locator("#scrub").fill(String(scrubT));
  await page.waitForSelector(`#stage[data-shown='${scrubT}']`, { timeout: 20000 });
  assert.match(await page.locator("#frame-label").textContent(), new RegExp(`^t ${scrubT.toFixed(3)} · (key|between keys) `));
  assert.equal(await page.locator("#scrub").getAttribute("aria-valuetext"), await page.locator("#frame-label").textContent());
  // The keyboard moves it too.
  await page.locator("#scrub").focus();
  await page.keyboard.press("ArrowRight");
  await page.waitForFunction((t) => window.immerse.state.t > t, scrubT);
  await page.locator("#scrub").fill(String(scrubT));
  await page.waitForSelector(`#stage[data-shown='${scrubT}']`);

  // The same curves through the command line.
  const curves = await page.evaluate(() => window.immerse.state.curves.map((c) => c.points));
  const a = join(work, "a.json");
  const b = join(work, "b.json");
  writeFileSync(a, JSON.stringify({ name: "drawn-a", points: curves[0] }));
  writeFileSync(b, JSON.stringify({ name: "drawn-b", points: curves[1] }));
  const framesDir = join(work, "frames");
  const cliJson = join(work, "morph.json");
  const cliLottie = join(work, "morph.lottie.json");
  execFileSync(BIN, ["morph", a, b, "--frames", String(FRAMES), "--size", `${SIZE}x${SIZE}`, "-o", framesDir, "--format", "png", "--json", cliJson, "--quiet"]);
  execFileSync(BIN, ["morph", a, b, "--frames", String(FRAMES), "--size", `${SIZE}x${SIZE}`, "--format", "lottie", "-o", cliLottie, "--quiet"]);
  const png = readFileSync(join(framesDir, `frame_${String(SCRUB_TO).padStart(4, "0")}.png`)).toString("base64");

  // The page draws the keys itself (Chromium's rasteriser, not
  // tiny-skia): the same shape in the same view, up to anti-aliased edges.
  const diff = await compareWithPng(page, "#stage", png, 32);
  assert.equal(diff.error, undefined, diff.error);
  measured.canvas_vs_png = diff;
  assert.ok(diff.overFraction <= 0.01, `${(diff.overFraction * 100).toFixed(2)}% of the pixels differ from immerse morph's PNG by more than 32`);
  assert.ok(diff.mean <= 1, `mean difference ${diff.mean} from immerse morph's PNG`);
  assert.ok(diff.depth1[1] >= 0.97 * diff.depth1[0], `depth 1 shading: ${diff.depth1}`);
  assert.ok(diff.depth2[1] >= 0.97 * diff.depth2[0], `depth 2 shading: ${diff.depth2}`);

  // Downloads are the CLI's outputs, byte for byte (same options).
  const job = await page.evaluate(() => window.immerse.lastMorph.urls);
  const get = async (u) => Buffer.from(await (await page.request.get(new URL(u, url).href)).body());
  assert.deepEqual(JSON.parse(await get(job.json)), JSON.parse(readFileSync(cliJson)));
  assert.equal((await get(job.lottie)).toString(), readFileSync(cliLottie).toString());
  const gif = await get(job.gif);
  assert.equal(gif.subarray(0, 6).toString(), "GIF89a");
  const svg = (await get(job.svg)).toString();
  assert.match(svg, /<animate attributeName="d"/);
  const pngDownload = await get(job.frame.replace("{k}", String(SCRUB_TO)));
  assert.equal(pngDownload.toString("base64"), png);

  // The names the downloads save as; the GIF shows its progress.
  assert.equal(await downloadName(page, "#dl-png"), `immerse-frame-${String(SCRUB_TO).padStart(4, "0")}.png`);
  assert.equal(await downloadName(page, "#dl-json"), "immerse-morph.json");
  await page.evaluate(() => {
    window.sawGifProgress = false;
    const bar = document.getElementById("gif-progress");
    new MutationObserver(() => { if (!bar.hidden) window.sawGifProgress = true; }).observe(bar, { attributes: true });
  });
  assert.equal(await downloadName(page, "#dl-gif"), "immerse-morph.gif");
  assert.equal(await page.evaluate(() => window.sawGifProgress), true, "no GIF progress was shown");
  await page.waitForFunction(() => document.getElementById("download-info").textContent.startsWith("GIF saved"));

  // Play for a moment, stop at the scrubbed frame for the screenshot.
  await page.click("#play");
  await page.waitForTimeout(400);
  await page.click("#play");
  await page.locator("#scrub").fill(String(scrubT));
  await page.waitForSelector(`#stage[data-shown='${scrubT}']`);
  mkdirSync(dirname(SCREENSHOT), { recursive: true });
  await page.screenshot({ path: SCREENSHOT });

  // Changing the curves makes the downloads stale until the next morph.
  const eightAgain = await page.locator("#reference option", { hasText: "letter-S" }).getAttribute("value");
  await page.selectOption("#reference", eightAgain);
  await page.click("#add-reference");
  await page.waitForSelector("#curves li:nth-child(3)[data-status=ok]", { timeout: 20000 });
  for (const id of ["#dl-png", "#dl-gif", "#dl-svg", "#dl-lottie", "#dl-json"]) {
    assert.equal(await page.getAttribute(id, "aria-disabled"), "true", `${id} stays active after the curves changed`);
  }
  await page.locator("#curves li:nth-child(3) button[title=remove]").click();
  assert.equal(await page.getAttribute("#dl-json", "aria-disabled"), "true");

  // A GIF plays at most 50 fps: at 60 the page offers no GIF and says why,
  // as the command line refuses one.
  await page.fill("#opt-frames", "6");
  await page.fill("#opt-fps", "60");
  await page.click("#run");
  await page.waitForSelector("#stage[data-shown='0']", { timeout: 60000 });
  assert.equal(await page.getAttribute("#dl-gif", "aria-disabled"), "true");
  assert.equal(await page.getAttribute("#dl-svg", "aria-disabled"), "false");
  assert.match(await page.locator("#download-info").textContent(), /a GIF plays at most 50/);
  await page.fill("#opt-fps", "0.01");
  await page.click("#run");
  assert.equal(await page.locator("#status").textContent(), "frames / second: 0.01 is not a rate from 0.1 to 1000 frames per second");
  await page.fill("#opt-fps", "30");

  // cubic-bezier easing: the frame times are those of the command line;
  // one that overshoots is refused in the same words.
  await page.selectOption("#opt-easing", "cubic-bezier");
  assert.equal(await page.isVisible("#bezier"), true);
  for (const [id, v] of [["#bz-x1", "0.2"], ["#bz-y1", "0.8"], ["#bz-x2", "0.6"], ["#bz-y2", "1"]]) await page.fill(id, v);
  const previous = await page.evaluate(() => window.immerse.lastMorph.id);
  await page.click("#run");
  await page.waitForFunction((p) => window.immerse.lastMorph.id !== p && document.getElementById("stage").dataset.shown === "0", previous);
  const times = await page.evaluate(() => window.immerse.lastMorph.morph.frames.map((f) => f.t));
  const eased = join(work, "eased.json");
  execFileSync(BIN, ["morph", a, b, "--frames", "6", "--easing", "cubic-bezier(0.2,0.8,0.6,1)", "--json", eased, "--quiet"]);
  assert.deepEqual(times, JSON.parse(readFileSync(eased)).frames.map((f) => f.t));
  await page.fill("#bz-y2", "1.1");
  await page.click("#run");
  await page.waitForFunction(() => document.getElementById("status").className === "error");
  assert.match(await page.locator("#status").textContent(),
    /^The morph failed: "easing": cubic-bezier\(0\.2,0\.8,0\.6,1\.1\): frame fraction [0-9.]+ \(at position \d\) is not a number in \[0, 1\]$/);

  // The only failed requests are the two bad inputs sent on purpose (the
  // broken SVG, the easing that overshoots): Chromium logs each.
  const refused = "Failed to load resource: the server responded with a status of 400 (Bad Request)";
  assert.equal(errors.filter((e) => e === refused).length, 2, JSON.stringify(errors));
  assert.deepEqual(errors.filter((e) => e !== refused), [], "console errors on the playground");
  await page.close();
});

test("playground: a click on the picture pauses and resumes playback", { timeout: 120000 }, async () => {
  const page = await context.newPage();
  const errors = watchConsole(page);
  await page.goto(url);
  await exampleLoaded(page);
  await page.fill("#opt-frames", "40");
  await page.fill("#opt-fps", "10");
  await page.click("#run");
  await page.waitForSelector("#stage[data-shown='0']", { timeout: 60000 });
  const box = await page.locator("#stage").boundingBox();
  const middle = [box.x + box.width / 2, box.y + box.height / 2];
  // Play, then click the picture: paused on a frame, still showing the morph.
  await page.click("#play");
  await page.waitForFunction(() => window.immerse.state.frame >= 2, null, { timeout: 20000 });
  await page.mouse.click(...middle);
  const paused = await page.evaluate(() => ({ playing: window.immerse.state.playing, mode: window.immerse.state.mode, label: document.getElementById("play").textContent }));
  assert.deepEqual(paused, { playing: false, mode: "play", label: "Play" });
  const at = await page.getAttribute("#stage", "data-shown");
  await page.waitForTimeout(400);
  assert.equal(await page.getAttribute("#stage", "data-shown"), at, "the picture moved while paused");
  assert.equal(await page.locator("#status").getAttribute("class"), "", "a click while playing gave an error");
  assert.match(await page.locator("#status").textContent(), /^40 frames, every one an immersed disk/);
  assert.equal(await page.locator("#curves li").count(), 2, "the click drew a curve");
  // Another click plays on from there.
  await page.mouse.click(...middle);
  await page.waitForFunction((from) => document.getElementById("stage").dataset.shown !== from, at, { timeout: 5000 });
  assert.equal(await page.evaluate(() => window.immerse.state.playing), true);
  await page.mouse.click(...middle);
  assert.equal(await page.evaluate(() => window.immerse.state.playing), false);
  // Edit curves goes back to drawing.
  await page.click("#edit");
  assert.equal(await page.evaluate(() => window.immerse.state.mode), "edit");
  assert.deepEqual(errors, [], "console errors on the playground");
  await page.close();
});

test("playground: the scrubber draws the certified keys at any t, without the server", { timeout: 120000 }, async () => {
  const page = await context.newPage();
  const errors = watchConsole(page);
  await page.goto(url);
  await exampleLoaded(page);
  await page.fill("#opt-frames", "30");
  await page.click("#run");
  await page.waitForSelector("#stage[data-shown='0']", { timeout: 60000 });
  const r = await page.evaluate(() => window.immerse.lastMorph);
  assert.ok(r.key_count >= 2);
  assert.ok((await page.locator("#status").textContent()).includes(`${r.key_count} certified keys`));
  measured.key_scrub_1280 = await checkKeyScrub(page);
  assert.deepEqual(errors, [], "console errors on the playground");
  await page.close();
});

/** Pixels of the canvas within 2 per channel of each "#rrggbb" colour. */
async function countColours(page, colours) {
  return page.evaluate((colours) => {
    const c = document.getElementById("stage");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const rgb = colours.map((h) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16)));
    const counts = colours.map(() => 0);
    for (let i = 0; i < d.length; i += 4) {
      rgb.forEach(([r, g, b], k) => {
        if (Math.abs(d[i] - r) <= 2 && Math.abs(d[i + 1] - g) <= 2 && Math.abs(d[i + 2] - b) <= 2) counts[k]++;
      });
    }
    return Object.fromEntries(colours.map((h, k) => [h, counts[k]]));
  }, colours);
}

test("playground: two multi-shape drawings morph, matched automatically, each shape in its own colours", { timeout: 120000 }, async () => {
  const page = await context.newPage();
  const errors = watchConsole(page);
  await page.goto(url);
  await exampleLoaded(page);
  await page.click("#clear-all");
  // An SVG of several closed shapes is read as a drawing.
  for (const [i, file] of [[1, "creature-a.svg"], [2, "creature-b.svg"]]) {
    await page.setInputFiles("#file", join(root, "curves/drawings", file));
    await page.waitForSelector(`#curves li:nth-child(${i})[data-status=ok]`, { timeout: 20000 });
  }
  const verdicts = await page.locator("#curves .verdict").allTextContents();
  assert.deepEqual(verdicts, ["✓ drawing: 4 shapes, every one self-overlapping", "✓ drawing: 4 shapes, every one self-overlapping"]);
  assert.match(await page.locator("#curves li:nth-child(1) .facts").textContent(), /^4 shapes · \d+ points · body, shell, horn, eye$/);

  // The matching the page shows is the command line's (auto).
  assert.equal(await page.inputValue("#opt-match"), "auto");
  await page.fill("#opt-frames", "12");
  await page.click("#run");
  await page.waitForSelector("#stage[data-shown='0']", { timeout: 60000 });
  const r = await page.evaluate(() => window.immerse.lastMorph);
  assert.equal(r.kind, "drawings");
  const status = await page.locator("#status").textContent();
  assert.match(status, /^12 frames of 4 shapes, every shape of every frame an immersed disk/);
  assert.ok(status.includes(r.matching), status);
  assert.match(r.matching, /^matching \(auto\): 'body' → 'body', 'shell' → 'shell', /);
  const cliJson = join(work, "creature.json");
  const drawingA = join(work, "creature-a.json");
  const drawingB = join(work, "creature-b.json");
  // The same drawings as the page sent them (fitted into the canvas).
  const sent = await page.evaluate(() => window.immerse.state.curves.map((c) => ({ name: c.name, shapes: c.shapes.map((s) => ({ id: s.id, points: s.points, fill: s.fill, stroke: s.stroke, stroke_width: s.stroke_width, opacity: s.opacity, fill_rule: s.fill_rule })) })));
  writeFileSync(drawingA, JSON.stringify(sent[0]));
  writeFileSync(drawingB, JSON.stringify(sent[1]));
  execFileSync(BIN, ["morph", drawingA, drawingB, "--match", "auto", "--frames", "12", "--json", cliJson, "--quiet"]);
  const cli = JSON.parse(readFileSync(cliJson));
  assert.deepEqual(r.morph.matching.pairs.map((p) => [p.source, p.target]), cli.matching.pairs.map((p) => [p.source, p.target]));
  assert.equal(r.morph.frames.length, 12);

  // Every shape is painted with its own colours: at t = 0 the source's
  // fills, at t = 1 the target's.
  const start = await countColours(page, ["#f2cc8f", "#e07a5f", "#3d405b"]);
  measured.drawing_colours_t0 = start;
  for (const [c, n] of Object.entries(start)) assert.ok(n > 200, `${c}: ${n} pixels at t = 0`);
  await page.locator("#scrub").fill("1");
  await page.waitForSelector("#stage[data-shown='1']");
  const end = await countColours(page, ["#81b29a", "#3d405b", "#f4f1de", "#f2cc8f"]);
  measured.drawing_colours_t1 = end;
  for (const [c, n] of Object.entries(end)) assert.ok(n > 100, `${c}: ${n} pixels at t = 1`);
  assert.ok(end["#81b29a"] > 5000 && start["#e07a5f"] > 2000, JSON.stringify({ start, end }));

  // The downloads of a drawing morph: its JSON is the answer's, and the
  // Lottie has one shape group per shape.
  const get = async (u) => Buffer.from(await (await page.request.get(new URL(u, url).href)).body());
  assert.deepEqual(JSON.parse(await get(r.urls.json)), r.morph);
  const lottie = JSON.parse(await get(r.urls.lottie));
  assert.equal(lottie.op, 12);
  assert.match((await get(r.urls.svg)).toString(), /^<svg/);

  // A hole is refused with the library's message, on the page.
  await page.click("#paste-box summary");
  await page.fill("#paste", '<svg xmlns="http://www.w3.org/2000/svg"><path fill-rule="evenodd" d="M0 0 L100 0 L100 100 L0 100 Z M20 20 L80 20 L80 80 L20 80 Z"/></svg>');
  await page.click("#add-paste");
  await page.waitForFunction(() => document.getElementById("status").className === "error");
  assert.match(await page.locator("#status").textContent(), /^pasted curve \d+: shape 2 \(path 1 subpath 2\) is a hole in shape 1 \(path 1 subpath 1\) \(under the evenodd fill rule it cuts a region out of it\); holes are not supported yet: draw the parts as separate shapes$/);
  assert.equal(await page.locator("#curves li").count(), 2);
  const refused = "Failed to load resource: the server responded with a status of 400 (Bad Request)";
  assert.deepEqual(errors.filter((e) => e !== refused), [], "console errors on the playground");
  assert.equal(errors.length, 1, JSON.stringify(errors));
  await page.close();
});

test("playground: every option list is the server's (GET /api/options)", { timeout: 60000 }, async () => {
  const page = await context.newPage();
  const errors = watchConsole(page);
  await page.goto(url);
  await page.waitForFunction(() => window.immerse && window.immerse.ready === true);
  const got = await page.evaluate(async () => {
    const o = await (await fetch("/api/options")).json();
    return [...document.querySelectorAll("select[data-option]")].map((sel) => ({
      option: sel.dataset.option,
      shown: [...sel.options].map((x) => x.value),
      selected: sel.value,
      served: o[sel.dataset.option].values.map((v) => v.name),
      default: o[sel.dataset.option].default,
    }));
  });
  const options = got.map((g) => g.option).sort();
  assert.deepEqual(options, ["correspondence", "counts", "easing", "intermediate", "loop", "match", "path", "quality"]);
  for (const g of got) {
    assert.deepEqual(g.shown, g.served, `the ${g.option} list`);
    assert.equal(g.selected, g.default, `the ${g.option} default`);
  }
  // The match modes are the command line's --match values.
  const help = execFileSync(BIN, ["morph", "--help"]).toString();
  for (const m of got.find((g) => g.option === "match").served) assert.ok(help.includes(m), m);
  assert.deepEqual(errors, [], "console errors on the playground");
  await page.close();
});

test("playground: at 390x844 nothing scrolls sideways and the controls stack", { timeout: 120000 }, async () => {
  const page = await context.newPage();
  await page.setViewportSize(PHONE);
  const errors = watchConsole(page);
  await page.goto(url);
  await exampleLoaded(page);
  const before = await page.evaluate(() => document.documentElement.scrollWidth);
  assert.ok(before <= PHONE.width, `the page is ${before} px wide`);
  await page.fill("#opt-frames", "30");
  await page.click("#run");
  await page.waitForSelector("#stage[data-shown='0']", { timeout: 60000 });
  const layout = await page.evaluate(() => {
    const r = (s) => document.querySelector(s).getBoundingClientRect();
    const right = Math.max(...[...document.querySelectorAll("body *")].map((e) => e.getBoundingClientRect().right));
    return { scrollWidth: document.documentElement.scrollWidth, right, canvas: r("#stage").width, toolbar: r(".toolbar").right, options: r(".options-col").top, curves: r(".curves-col").top, stageBottom: r(".stage-col").bottom };
  });
  measured.layout_390 = layout;
  measured.key_scrub_390 = await checkKeyScrub(page);
  assert.ok(layout.scrollWidth <= PHONE.width, `the page is ${layout.scrollWidth} px wide after a morph`);
  assert.ok(layout.right <= PHONE.width + 0.5, `an element reaches x = ${layout.right}`);
  assert.ok(layout.canvas <= PHONE.width && layout.canvas >= 300, `the canvas is ${layout.canvas} px wide`);
  // The columns stack: the curves, then the options, below the picture.
  assert.ok(layout.curves >= layout.stageBottom - 1 && layout.options > layout.curves, JSON.stringify(layout));
  // The scaled picture still plays and pauses on a click.
  await page.click("#play");
  await page.waitForFunction(() => window.immerse.state.frame >= 2, null, { timeout: 20000 });
  await page.locator("#stage").scrollIntoViewIfNeeded();
  const box = await page.locator("#stage").boundingBox();
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  assert.equal(await page.evaluate(() => window.immerse.state.playing), false);
  await page.evaluate(() => window.scrollTo(0, 0));
  mkdirSync(dirname(SCREENSHOT_PHONE), { recursive: true });
  await page.screenshot({ path: SCREENSHOT_PHONE });
  assert.deepEqual(errors, [], "console errors on the playground");
  await page.close();
});

test("lottie: lottie-web renders immerse's Lottie like immerse's PNG", { timeout: 120000 }, async () => {
  const lottieFile = join(work, "morph.lottie.json");
  const framesDir = join(work, "frames");
  const animation = JSON.parse(readFileSync(lottieFile, "utf8"));
  assert.equal(animation.layers.length, 1);
  assert.equal(animation.layers[0].ty, 4);
  const keys = animation.layers[0].shapes[0].it[0].ks.k;
  measured.lottie_keyframes = `${keys.length} of ${FRAMES} frames`;
  const page = await context.newPage();
  const errors = watchConsole(page);
  await page.setContent(`<!doctype html><html><body style="margin:0;background:#fff">
    <canvas id="lottie" width="${SIZE}" height="${SIZE}"></canvas></body></html>`);
  await page.addScriptTag({ path: require.resolve("lottie-web/build/player/lottie.min.js") });
  await page.evaluate((data) => {
    const canvas = document.getElementById("lottie");
    window.anim = window.lottie.loadAnimation({
      renderer: "canvas",
      loop: false,
      autoplay: false,
      animationData: data,
      rendererSettings: { context: canvas.getContext("2d"), clearCanvas: true, dpr: 1 },
    });
    return new Promise((done) => {
      if (window.anim.isLoaded) done(); else window.anim.addEventListener("DOMLoaded", done);
    });
  }, animation);

  // The scrubbed frame, and the last frame (the strip, overlapping itself).
  for (const frame of [SCRUB_TO, FRAMES - 1]) {
    await page.evaluate((k) => window.anim.goToAndStop(k, true), frame);
    const png = readFileSync(join(framesDir, `frame_${String(frame).padStart(4, "0")}.png`)).toString("base64");
    const diff = await compareWithPng(page, "#lottie", png, 32);
    assert.equal(diff.error, undefined, diff.error);
    measured[`lottie_vs_png_frame_${frame}`] = diff;
    assert.ok(diff.overFraction <= 0.02, `frame ${frame}: ${(diff.overFraction * 100).toFixed(2)}% of the pixels differ by more than 32`);
    assert.ok(diff.mean <= 2, `frame ${frame}: mean difference ${diff.mean}`);
    // Overlap depth is shaded as in the PNG: nearly every pixel of the
    // PNG's depth-1 and depth-2 shades has that shade in lottie-web too.
    assert.ok(diff.depth1[1] >= 0.95 * diff.depth1[0], `frame ${frame}, depth 1 shading: ${diff.depth1}`);
    assert.ok(diff.depth2[1] >= 0.95 * diff.depth2[0], `frame ${frame}, depth 2 shading: ${diff.depth2}`);
    if (frame === FRAMES - 1) {
      assert.ok(diff.depth2[0] > 500, `the last frame overlaps itself: ${diff.depth2}`);
    }
  }
  assert.deepEqual(errors, [], "console errors on the Lottie page");
  await page.close();
});
