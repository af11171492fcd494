// Opens every page of a built site from file:// in headless Chromium and checks that
//   1. the browser logs no console error, page error or failed request;
//   2. every <math> element is rendered as MathML (a MathMLElement) with a non-zero box, at
//      1280 px and at 390 px (a formula wider than a phone is set twice, and each screen shows
//      one of the two: render/html/math.rs);
//   3. every <img> (the SVG plots) has loaded with a non-zero natural size;
//   4. no number in math is in e-notation (4.68750e−6 reads as 4.6875·e − 6): 4.6875 × 10⁻⁶;
//   5. no sine, cosine or tangent of a rational multiple of π is left unevaluated (cos(π/2)).
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
  let r = null;
  for (const width of [1280, 390]) {
    await page.setViewportSize({ width, height: 900 });
    const seen = await page.evaluate(() => {
      const all = [...document.querySelectorAll("math")];
      const math = all.filter((m) => m.checkVisibility());
      const badMath = math.filter((m) => {
        const b = m.getBoundingClientRect();
        return !(m instanceof MathMLElement) || b.width <= 0 || b.height <= 0;
      }).length;
      // The hidden ones are the other screen's: each must be shown on one of the two.
      const hidden = all.filter((m) => !m.checkVisibility() && !m.closest(".wide, .narrow")).length;
      const img = [...document.querySelectorAll("img")];
      const badImg = img.filter((i) => !i.complete || i.naturalWidth <= 0 || i.naturalHeight <= 0)
        .map((i) => i.getAttribute("src"));
      const eNotation = all.map((m) => m.textContent).filter((t) => /\d[eE][−+-]?\d/.test(t));
      // cos(π/2) is <mi>cos</mi><mo>⁡</mo><mrow>(<mfrac>π 2</mfrac>)</mrow>: the function's
      // name and the text of what follows it.
      const trigOfPi = all.flatMap((m) => [...m.querySelectorAll("mi")]
        .filter((mi) => /^(sin|cos|tan)$/.test(mi.textContent))
        .map((mi) => {
          // cos²(π/2) is the <msup> of cos and 2, then the bracket: start after the power.
          let at = mi;
          while (at.parentElement && ["mrow", "msup"].includes(at.parentElement.localName)
            && at.parentElement.firstElementChild === at) at = at.parentElement;
          let t = mi.textContent;
          for (let n = at.nextElementSibling, k = 0; n && k < 3; n = n.nextElementSibling, k++) t += n.textContent;
          return t;
        }))
        .filter((t) => /^(sin|cos|tan)[\u2061\s]*\(\s*\d*π\d*\s*\)/.test(t));
      return { math: math.length, badMath, hidden, img: img.length, badImg, eNotation, trigOfPi };
    });
    if (seen.hidden > 0) problems.push(`${seen.hidden} <math> elements hidden at ${width} px`);
    if (r === null) {
      r = seen;
    } else {
      r.math += seen.math;
      r.badMath += seen.badMath;
    }
  }
  maths += r.math;
  images += r.img;
  if (r.badMath > 0) problems.push(`${r.badMath} of ${r.math} <math> elements not rendered as MathML with a size`);
  for (const src of r.badImg) problems.push(`plot did not load: ${src}`);
  for (const t of r.eNotation.slice(0, 3)) problems.push(`a number in e-notation: ${t.slice(0, 80)}`);
  for (const t of r.trigOfPi.slice(0, 3)) problems.push(`a trigonometric function of a multiple of π left unevaluated: ${t.slice(0, 40)}`);
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
