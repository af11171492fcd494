// A built site on phone screens 390, 360 and 320 px wide: no formula's box, nor any other
// element's, reaches past the screen's edge, no display formula scrolls sideways or up and
// down inside its box, and no page scrolls sideways. Run by .ci/run on the lectures,
// tests/course and the `init` starter.
// Usage: node phone-width.mjs SITE_DIR   (playwright-core must be resolvable; see .ci/run)
import { launch, pagesUnder } from "./chromium.mjs";
import { resolve } from "node:path";
import { pathToFileURL } from "node:url";

const site = resolve(process.argv[2] ?? "site");
const pages = pagesUnder(site);
const browser = await launch();
let failing = 0;
const totals = { past: 0, scrolled: 0 };
const widths = [390, 360, 320];
for (const file of pages) {
  const page = await browser.newPage();
  await page.goto(pathToFileURL(file).href, { waitUntil: "load" });
  const faults = [];
  for (const width of widths) {
    await page.setViewportSize({ width, height: 800 });
    const r = await page.evaluate(() => {
      const w = document.documentElement.clientWidth;
      const past = [...document.querySelectorAll("math")]
        .filter((m) => m.checkVisibility() && m.getBoundingClientRect().right > w + 1).length;
      const scrolled = [...document.querySelectorAll('math[display="block"], .formula')]
        .filter((m) => m.checkVisibility()
          && (m.scrollWidth > m.clientWidth + 1 || m.scrollHeight > m.clientHeight + 1)).length;
      // Any other element (a table, a figure, a line of text) past the edge.
      const elements = [...document.querySelectorAll("body *")]
        .filter((e) => e.checkVisibility() && e.getBoundingClientRect().right > w + 1).length;
      return { past, scrolled, elements, sideways: document.documentElement.scrollWidth > w + 1 };
    });
    totals.past += r.past;
    totals.scrolled += r.scrolled;
    if (r.past || r.scrolled || r.elements || r.sideways) {
      faults.push(`${width} px: ${r.past} formulas past the edge, ${r.scrolled} scrolled inside, ${r.elements} elements past the edge${r.sideways ? ", the page scrolls sideways" : ""}`);
    }
  }
  if (faults.length) {
    failing += 1;
    console.log(`FAIL ${file.slice(site.length + 1)}: ${faults.join("; ")}`);
  }
  await page.close();
}
await browser.close();
console.log(`phones (${widths.join(", ")} px): ${pages.length} pages, ${failing} failing; ${totals.past} formulas past the edge, ${totals.scrolled} display formulas scrolling inside their box`);
process.exit(failing ? 1 : 0);
