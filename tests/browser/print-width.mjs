// Measures what would run off a printed A4 page: each page of the built sites is laid out at
// the printable width (718 px: A4 at 96 dpi less 1.9 cm margins) with print styles, and every
// element whose right edge passes the page is counted (outermost only). Any such element fails
// the run (exit 1): long formulas are cut into pieces that wrap (src/render/linebreak.rs).
// Run by .ci/run on the lectures and tests/course. Usage, with playwright-core resolvable as in
// .ci/run:  node print-width.mjs SITE_DIR [SITE_DIR ...]
import { launch, pagesUnder } from "./chromium.mjs";
import { pathToFileURL } from "node:url";
const pages = [];
for (const site of process.argv.slice(2)) pagesUnder(site, pages);
// A4 printable width at 96 dpi, 1.9 cm margins.
const browser = await launch({ viewport: { width: 718, height: 1000 } });
const page = await browser.newPage();
await page.emulateMedia({ media: "print" });
let failing = 0;
for (const f of pages) {
  await page.goto(pathToFileURL(f).href);
  const r = await page.evaluate(() => {
    const w = document.documentElement.clientWidth;
    const wide = [...document.querySelectorAll("body *")].filter(e => e.getBoundingClientRect().right > w + 1 && getComputedStyle(e).display !== "none");
    const top = wide.filter(e => !wide.includes(e.parentElement));
    return { w, n: top.length, worst: Math.max(0, ...top.map(e => e.getBoundingClientRect().right)), tags: top.slice(0, 3).map(e => e.tagName + ":" + (e.textContent || "").slice(0, 40)) };
  });
  if (r.n) { console.log(f, r.n, Math.round(r.worst), r.tags.join(" | ")); failing++; }
}
await browser.close();
console.log(`print width: ${pages.length} pages laid out at 718 px, ${failing} with an element wider than the page`);
process.exit(failing ? 1 : 0);
