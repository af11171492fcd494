// Every handout of a built site printed as a teacher would (Chromium, the page's own @page
// size): each page is on the course's paper, and no page is blank or holds only the running
// head and the page number. The PDF's text comes from poppler's pdftotext, page by page.
// Usage: node handout-pages.mjs a4|letter SITE_DIR [SITE_DIR ...]   (PDF_DIR=dir keeps the PDFs)
import { launch } from "./chromium.mjs";
import { execFileSync } from "node:child_process";
import { mkdtempSync, readdirSync, rmSync, writeFileSync } from "node:fs";
import { basename, join } from "node:path";
import { tmpdir } from "node:os";
import { pathToFileURL } from "node:url";

// Points: A4 is 210 × 297 mm, Letter 8.5 × 11 in (Chromium rounds to within a point).
const sizes = { a4: [595.28, 841.89], letter: [612, 792] };
const [paper, ...sites] = process.argv.slice(2);
if (!sizes[paper] || !sites.length) {
  console.log("usage: node handout-pages.mjs a4|letter SITE_DIR [SITE_DIR ...]");
  process.exit(2);
}
const handouts = sites.flatMap((site) => {
  const dir = join(site, "handouts");
  return readdirSync(dir).filter((n) => n.endsWith(".html")).sort().map((n) => join(dir, n));
});
const scratch = mkdtempSync(join(tmpdir(), "mechbook-handouts-"));
const browser = await launch();
const page = await browser.newPage();
let failing = 0, printed = 0;
const fail = (...m) => { console.log("FAIL", ...m); failing++; };
for (const file of handouts) {
  await page.goto(pathToFileURL(file).href, { waitUntil: "load" });
  const pdf = await page.pdf({ preferCSSPageSize: true });
  const out = join(scratch, `${basename(file, ".html")}.pdf`);
  writeFileSync(out, pdf);
  if (process.env.PDF_DIR) writeFileSync(join(process.env.PDF_DIR, basename(out)), pdf);
  const info = execFileSync("pdfinfo", ["-l", "9999", out], { encoding: "utf8" });
  const boxes = [...info.matchAll(/Page\s+\d+ size:\s+([\d.]+) x ([\d.]+) pts/g)].map((m) => [+m[1], +m[2]]);
  const [w, h] = sizes[paper];
  const wrong = boxes.filter(([x, y]) => Math.abs(x - w) > 1.5 || Math.abs(y - h) > 1.5);
  if (!boxes.length) fail(file, "pdfinfo gave no page sizes");
  if (wrong.length) fail(file, `${wrong.length} of ${boxes.length} pages are ${wrong[0].join(" × ")} pt, not ${paper}`);
  // A page's text less its running head (what every page's first line starts with, such as
  // the course and the sheet, whatever follows it: "Variant 3") and a bare page number.
  const texts = boxes.map((_, k) => execFileSync("pdftotext", ["-layout", "-f", `${k + 1}`, "-l", `${k + 1}`, out, "-"], { encoding: "utf8" }));
  const lines = texts.map((t) => t.split("\n").map((l) => l.replace(/\s+/g, " ").trim()).filter((l) => l));
  const firsts = lines.map((ls) => ls[0] ?? "");
  let head = boxes.length > 1 ? firsts[0] : "";
  for (const f of firsts) while (!f.startsWith(head)) head = head.slice(0, -1);
  lines.forEach((ls, k) => {
    const body = ls.filter((l) => !(head.length >= 12 && l.startsWith(head))
      && !/^(page\s*)?\d+(\s*(of|\/)\s*\d+)?$/i.test(l));
    if (!body.length) fail(file, `page ${k + 1} of ${boxes.length} has no content`);
  });
  printed += boxes.length;
}
await browser.close();
rmSync(scratch, { recursive: true, force: true });
console.log(`handout pages: ${handouts.length} handouts, ${printed} pages printed on ${paper}, ${failing} failing`);
process.exit(failing ? 1 : 0);
