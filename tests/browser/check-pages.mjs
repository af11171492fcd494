// Opens every page of a built site from file:// in headless Chromium and checks that
//   1. the browser logs no console error, page error or failed request;
//   2. every <math> element is rendered as MathML (a MathMLElement) with a non-zero box;
//   3. every <img> (the SVG plots) has loaded with a non-zero natural size;
//   4. no number in math is in e-notation (4.68750e−6 reads as 4.6875·e − 6): 4.6875 × 10⁻⁶.
// Usage: node check-pages.mjs SITE_DIR   (playwright-core must be resolvable; see .ci/run)
import { launch, pagesUnder } from "./chromium.mjs";
import { resolve } from "node:path";
import { pathToFileURL } from "node:url";

const site = resolve(process.argv[2] ?? "site");
const pages = pagesUnder(site);
if (pages.length === 0) {
  console.error(`no pages under ${site}`);
  process.exit(1);
}

const browser = await launch();
let failures = 0;
let maths = 0;
let images = 0;
for (const file of pages) {
  const page = await browser.newPage();
  const problems = [];
  page.on("console", (m) => { if (m.type() === "error") problems.push(`console: ${m.text()}`); });
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  page.on("requestfailed", (r) => problems.push(`failed request: ${r.url()}`));
  await page.goto(pathToFileURL(file).href, { waitUntil: "load" });
  const r = await page.evaluate(() => {
    const math = [...document.querySelectorAll("math")];
    const badMath = math.filter((m) => {
      const b = m.getBoundingClientRect();
      return !(m instanceof MathMLElement) || b.width <= 0 || b.height <= 0;
    }).length;
    const img = [...document.querySelectorAll("img")];
    const badImg = img.filter((i) => !i.complete || i.naturalWidth <= 0 || i.naturalHeight <= 0)
      .map((i) => i.getAttribute("src"));
    const eNotation = math.map((m) => m.textContent).filter((t) => /\d[eE][−+-]?\d/.test(t));
    return { math: math.length, badMath, img: img.length, badImg, eNotation };
  });
  maths += r.math;
  images += r.img;
  if (r.badMath > 0) problems.push(`${r.badMath} of ${r.math} <math> elements not rendered as MathML with a size`);
  for (const src of r.badImg) problems.push(`plot did not load: ${src}`);
  for (const t of r.eNotation.slice(0, 3)) problems.push(`a number in e-notation: ${t.slice(0, 80)}`);
  const rel = file.slice(site.length + 1);
  if (problems.length) {
    failures += 1;
    console.log(`FAIL ${rel}\n  ${problems.join("\n  ")}`);
  } else {
    console.log(`ok   ${rel}: ${r.math} math, ${r.img} plots`);
  }
  await page.close();
}
await browser.close();
console.log(`browser check: ${pages.length} pages, ${maths} math elements, ${images} plots, ${failures} failing`);
process.exit(failures ? 1 : 0);
