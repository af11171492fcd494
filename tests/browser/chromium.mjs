// The headless Chromium every browser test drives: Debian's (or $CHROMIUM), with a throwaway
// profile that is removed when the browser is closed. `options` go to Playwright's
// launchPersistentContext (a viewport, say).
import { chromium } from "playwright-core";
import { mkdtempSync, readdirSync, rmSync, statSync } from "node:fs";
import { join } from "node:path";
import { tmpdir } from "node:os";

export async function launch(options = {}) {
  const profile = mkdtempSync(join(tmpdir(), "mechbook-chromium-"));
  const browser = await chromium.launchPersistentContext(profile, {
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    headless: true,
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
    ...options,
  });
  const close = browser.close.bind(browser);
  browser.close = async () => {
    await close();
    rmSync(profile, { recursive: true, force: true });
  };
  return browser;
}

// Every .html file under `dir`, in sorted order, for the checks that open each page.
export function pagesUnder(dir, pages = []) {
  for (const name of readdirSync(dir).sort()) {
    const p = join(dir, name);
    if (statSync(p).isDirectory()) pagesUnder(p, pages);
    else if (name.endsWith(".html")) pages.push(p);
  }
  return pages;
}
