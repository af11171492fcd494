// Every page and handout of a built site through axe-core (WCAG 2.1 A and AA rules, and its
// best practices): no violation anywhere. Run by .ci/run on the lectures, tests/course and the
// `init` starter.
// Usage: node axe.mjs SITE_DIR   (playwright-core and axe-core must be resolvable; see .ci/run)
import { launch, pagesUnder } from "./chromium.mjs";
import { createRequire } from "node:module";
import { readFileSync } from "node:fs";
import { relative, resolve } from "node:path";
import { pathToFileURL } from "node:url";

const require = createRequire(import.meta.url);
const axeSource = readFileSync(require.resolve("axe-core/axe.min.js"), "utf8");
const site = resolve(process.argv[2] ?? "site");
const pages = pagesUnder(site);
const browser = await launch();
const tally = new Map();
let failing = 0;
for (const file of pages) {
  const page = await browser.newPage();
  await page.goto(pathToFileURL(file).href, { waitUntil: "load" });
  await page.addScriptTag({ content: axeSource });
  const violations = await page.evaluate(async () => {
    const r = await window.axe.run(document, { resultTypes: ["violations"] });
    return r.violations.map((v) => ({ id: v.id, impact: v.impact, help: v.help,
      nodes: v.nodes.map((n) => n.target.join(" ")).slice(0, 3), count: v.nodes.length }));
  });
  if (violations.length) {
    failing++;
    console.log(`${relative(site, file)}:`);
    for (const v of violations) {
      console.log(`  ${v.id} (${v.impact}, ${v.count}): ${v.help}: ${v.nodes.join(", ")}`);
      tally.set(v.id, (tally.get(v.id) ?? 0) + v.count);
    }
  }
  await page.close();
}
await browser.close();
console.log(`axe-core: ${pages.length - failing} of ${pages.length} pages of ${site} without a violation`
  + (tally.size ? `; ${[...tally].map(([k, n]) => `${k} ×${n}`).join(", ")}` : ""));
process.exit(failing ? 1 : 0);
