// One student's variant, printed: each student sheet (and its key) opened at #variant-N must
// show and print that variant alone, one page per problem, and the whole sheet one page per
// problem of every variant (no blank page, no problem split). Printed as a teacher would: A4 and US Letter, with
// the sheet's own @page rules. A key printed at #variant-N takes no more pages than variant N
// takes in the whole key (its pages there are those headed "Variant N"; poppler's pdftotext
// reads them). Run by .ci/run. Usage, with playwright-core resolvable as there:
//   node one-variant.mjs SITE_DIR [SITE_DIR ...]   (PDF_DIR=dir keeps the PDFs to look at)
import { launch } from "./chromium.mjs";
import { execFileSync } from "node:child_process";
import { mkdtempSync, readdirSync, rmSync, writeFileSync } from "node:fs";
import { join, basename } from "node:path";
import { tmpdir } from "node:os";
import { pathToFileURL } from "node:url";

const sheets = process.argv.slice(2).flatMap(site => {
  const dir = join(site, "handouts");
  return readdirSync(dir).filter(n => n.endsWith("-problems-student.html")).sort().map(n => join(dir, n));
});
if (!sheets.length) { console.log("one variant: no student sheet found"); process.exit(1); }
const browser = await launch();
const page = await browser.newPage();
const pages = pdf => (pdf.toString("latin1").match(/\/Type\s*\/Page[^s]/g) || []).length;
let failing = 0, printed = 0, sharedChecked = 0, keysChecked = 0;
const scratch = mkdtempSync(join(tmpdir(), "mechbook-one-variant-"));
// The text of each page of a PDF, from poppler.
const pageTexts = (pdf) => {
  const file = join(scratch, "key.pdf");
  writeFileSync(file, pdf);
  return execFileSync("pdftotext", ["-layout", file, "-"], { encoding: "utf8" }).split("\f").slice(0, pages(pdf));
};
const fail = (...m) => { console.log("FAIL", ...m); failing++; };
for (const f of sheets) {
  const url = pathToFileURL(f).href;
  await page.goto(url);
  await page.emulateMedia({ media: "print" });
  const layout = await page.evaluate(() => [...document.querySelectorAll("section.variant")].map(s => s.querySelectorAll(".sheet-problem").length));
  const variants = layout.length, problems = layout[0];
  for (const format of ["A4", "Letter"]) {
    const all = pages(await page.pdf({ format, preferCSSPageSize: false }));
    printed++;
    if (all !== variants * problems) fail(f, format, `whole sheet: ${all} pages for ${variants} variants of ${problems} problem(s)`);
  }
  for (const k of [...new Set([1, 2, variants])].filter(k => k <= variants)) {
    await page.goto(`${url}#variant-${k}`);
    const shown = await page.evaluate(() => [...document.querySelectorAll("section.variant")].filter(s => getComputedStyle(s).display !== "none").map(s => s.classList[1]));
    if (shown.length !== 1 || shown[0] !== `variant-${k}`) fail(f, `#variant-${k} shows ${shown.join(", ")}`);
    for (const format of ["A4", "Letter"]) {
      const pdf = await page.pdf({ format });
      printed++;
      if (pages(pdf) !== problems) fail(f, format, `#variant-${k}: ${pages(pdf)} pages for ${problems} problem(s)`);
      if (process.env.PDF_DIR && k === 2) writeFileSync(join(process.env.PDF_DIR, `${basename(f, ".html")}-variant-${k}-${format}.pdf`), pdf);
    }
  }
  // The key prints one variant's answers the same way.
  const key = url.replace("-problems-student.html", "-problems-key.html");
  await page.goto(`${key}#variant-2`);
  const keyShown = await page.evaluate(() => [...document.querySelectorAll("section.variant")].filter(s => getComputedStyle(s).display !== "none").map(s => s.classList[1]));
  if (variants >= 2 && keyShown.join() !== "variant-2") fail(key, `#variant-2 shows ${keyShown.join(", ")}`);
  // A problem with fewer variants is answered once, in the shared section: picked at variant 2,
  // the key shows of each such problem just the variant that sheet variant 2 uses.
  const shared = await page.evaluate(() => [...document.querySelectorAll("section.shared .key-problem")].map(a => [a.classList.contains("s-2"), getComputedStyle(a).display !== "none"]));
  if (variants >= 2 && shared.some(([uses, shown]) => uses !== shown)) fail(key, `#variant-2 shows shared answers it does not use, or hides one it uses`);
  sharedChecked += shared.length;
  // Each variant's key alone takes no more pages than it does in the whole key, and than the
  // answers it shares with other variants take printed alone: in the whole key those are
  // printed once for all, on pages headed by no variant.
  await page.goto(key);
  const whole = await page.pdf({ preferCSSPageSize: true });
  const heads = pageTexts(whole).map((t) => (t.split("\n")[0].match(/Variant (\d+)\s*$/) || [])[1]);
  for (let k = 1; k <= variants; k++) {
    await page.goto(`${key}#variant-${k}`);
    const alone = pages(await page.pdf({ preferCSSPageSize: true }));
    const within = heads.filter((h) => h === `${k}`).length;
    // The shared answers variant k shows, printed without its own section.
    const ownSection = await page.evaluate((k) => {
      const own = document.querySelector(`section.variant.variant-${k}`);
      if (!own) return false;
      own.dataset.display = own.style.display;
      own.style.display = "none";
      return true;
    }, k);
    const sharedAlone = ownSection && await page.evaluate(() => document.querySelectorAll("section.shared .key-problem").length) > 0
      ? pages(await page.pdf({ preferCSSPageSize: true }))
      : 0;
    printed += 2;
    keysChecked += 1;
    if (alone > within + sharedAlone) fail(key, `#variant-${k} prints on ${alone} pages, ${within} in the whole key and ${sharedAlone} for its shared answers alone`);
  }
  // Back to every variant ("Show all variants" is a link to #sheet).
  await page.goto(`${url}#sheet`);
  const back = await page.evaluate(() => [...document.querySelectorAll("section.variant")].filter(s => getComputedStyle(s).display !== "none").length);
  if (back !== variants) fail(f, `#sheet shows ${back} of ${variants} variants`);
}
await browser.close();
rmSync(scratch, { recursive: true, force: true });
console.log(`one variant: ${sheets.length} student sheets, ${printed} PDFs printed (A4 and Letter), ${sharedChecked} shared answers checked, ${keysChecked} variants' keys no longer than in the whole key, ${failing} failing`);
process.exit(failing ? 1 : 0);
