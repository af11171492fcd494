// `mechbook serve` in a real browser: a page open in headless Chromium reloads by itself when a
// scene is saved (before its PDFs, which it says are being typeset, and reloads again for),
// shows a broken scene's error at its top, and comes back when it is fixed.
// Prints the time from saving the scene to the reloaded page showing the change.
// Usage: node live-reload.mjs MECHBOOK WORK_DIR [SCREENSHOT_PREFIX]
//   (playwright-core must be resolvable; see .ci/run). Exits 1 on any failure.
import { launch } from "./chromium.mjs";
import { spawn, execFileSync } from "node:child_process";
import { readFileSync, writeFileSync, rmSync } from "node:fs";
import { join, resolve } from "node:path";

const mechbook = resolve(process.argv[2]);
const work = resolve(process.argv[3]);
const shots = process.argv[4];
const course = join(work, "live-reload-course");
rmSync(course, { recursive: true, force: true });
execFileSync(mechbook, ["init", course], { stdio: "inherit" });

const server = spawn(mechbook, ["serve"], { cwd: course, stdio: ["ignore", "ignore", "pipe"] });
let log = "";
const port = await new Promise((ok, fail) => {
  const timer = setTimeout(() => fail(new Error(`serve printed no address:\n${log}`)), 120000);
  server.stderr.on("data", (d) => {
    log += d;
    const m = log.match(/serving http:\/\/127\.0\.0\.1:(\d+)\//);
    if (m) { clearTimeout(timer); ok(Number(m[1])); }
  });
});

let failed = false;
const fail = (why) => { console.error(`live reload: FAILED: ${why}`); failed = true; };
const browser = await launch();
const scene = join(course, "lectures/lecture-1/01-book.toml");
const original = readFileSync(scene, "utf8");
const times = [];
// Each save reloads the page twice: first the page, then again when its PDFs are ready. The
// page has settled when it carries no note of PDFs being typeset: no reload is then due.
const settled = (page) =>
  page.waitForFunction(() => document.readyState === "complete" &&
                             !document.querySelector("#mechbook-serve-pdfs"),
                       null, { timeout: 60000, polling: 10 });
// Marks the page (a reload clears the mark); a reload that lands meanwhile is waited out.
const mark = async (page) => {
  for (let tries = 0; tries < 10; tries++) {
    try {
      await page.evaluate(() => { window.mechbookMarker = true; });
      return;
    } catch {
      await page.waitForLoadState("load");
      await settled(page);
    }
  }
  throw new Error("the page kept reloading: it could not be marked");
};
try {
  const page = await browser.newPage();
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  await page.goto(`http://127.0.0.1:${port}/book.html`);
  for (let trial = 1; trial <= 5; trial++) {
    const title = `A book, edit ${trial}`;
    // Set in this page only: a reload clears it, so its absence proves the page reloaded.
    await settled(page);
    await mark(page);
    const saved = performance.now();
    writeFileSync(scene, original.replace("A book as a uniform box", title));
    try {
      await page.waitForFunction((t) => document.title.startsWith(t) && !window.mechbookMarker,
                                 title, { timeout: 2000, polling: 10 });
      times.push(performance.now() - saved);
    } catch {
      fail(`trial ${trial}: the page did not reload with "${title}" within 2 s`);
    }
  }
  // The page comes before its PDFs: it says they are being typeset, and reloads again when
  // they are ready. The pages served are read as they pass: the starter's PDFs take about a
  // quarter of a second, so the page that carries the note may be replaced before the poll
  // below sees it in the browser (CI once missed it that way).
  const served = [];
  await page.route("**/book.html", async (route) => {
    const response = await route.fetch();
    const body = await response.text();
    served.push({ title: (body.match(/<title>([^<]*)<\/title>/) || [])[1] || "",
                  note: body.includes('id="mechbook-serve-pdfs"') });
    await route.fulfill({ response, body });
  });
  await settled(page);
  writeFileSync(scene, original.replace("A book as a uniform box", "A book and its PDFs"));
  const edited = (s) => s.title.startsWith("A book and its PDFs");
  try {
    await page.waitForFunction(() => document.title.startsWith("A book and its PDFs"), null,
                               { timeout: 5000, polling: 10 });
    if (shots && await page.$("#mechbook-serve-pdfs")) {
      await page.screenshot({ path: `${shots}-pdfs.png` });
    }
    await settled(page);
    const first = served.findIndex((s) => edited(s) && s.note);
    if (first < 0) {
      fail(`no page served after the save said that its PDFs were being typeset: ` +
           JSON.stringify(served));
    } else if (!served.slice(first + 1).some((s) => edited(s) && !s.note)) {
      fail(`the page did not reload once its PDFs were ready: ${JSON.stringify(served)}`);
    }
  } catch (e) {
    fail(`the page did not show the save, then settle once its PDFs were ready: ${e.message}`);
  }
  await page.unroute("**/book.html");
  // A broken scene: the error appears in the open page, over the last good site.
  writeFileSync(scene, original.replace('value = "m*(h^2 + d^2)/3"', 'value = "m*(h^2 + 2d^2)/3"'));
  try {
    await page.waitForSelector("#mechbook-serve-error", { state: "visible", timeout: 2000 });
    const text = await page.textContent("#mechbook-serve-error");
    if (!text.includes("01-book.toml:33:20")) fail(`the error does not locate the mistake: ${text}`);
    if (shots) await page.screenshot({ path: `${shots}-error.png` });
  } catch {
    fail("the error did not appear in the page within 2 s");
  }
  writeFileSync(scene, original);
  try {
    await page.waitForSelector("#mechbook-serve-error", { state: "detached", timeout: 2000 });
    if (shots) await page.screenshot({ path: `${shots}-fixed.png` });
  } catch {
    fail("the error did not go once the scene was fixed");
  }
  if (errors.length) fail(`page errors: ${errors.join("; ")}`);
} finally {
  await browser.close();
  server.kill("SIGINT");
}
const code = await new Promise((ok) => server.on("exit", (c) => ok(c)));
if (code !== 0) fail(`serve exited with ${code} on Ctrl-C`);
if (times.length) {
  times.sort((a, b) => a - b);
  const ms = (x) => `${x.toFixed(0)} ms`;
  console.log(`live reload: ${times.length} edits, from saving the scene to the reloaded page ` +
              `showing it: median ${ms(times[Math.floor(times.length / 2)])}, ` +
              `fastest ${ms(times[0])}, slowest ${ms(times[times.length - 1])}; ` +
              `a broken scene's error shown in the page and cleared when fixed`);
}
rmSync(course, { recursive: true, force: true });
process.exit(failed ? 1 : 0);
