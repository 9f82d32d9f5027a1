// The click half of the browser test of `gcs navigate` (tests/navigate_browser.sh runs it):
// headless Chromium, driven by playwright-core, opens a navigator page, clicks a candidate's
// button as a user would, and writes what the page then shows for the shell script to check:
// the state before and after, the picture (the SVG shown) before and after, and the RON of the
// realization shown after (which `gcs analyze` then checks against every constraint, apart from
// the residual the page was given). Takes a screenshot.
//
//   node navigate_click.mjs PAGE.html STEP CANDIDATE OUT_PREFIX
//
// PLAYWRIGHT_CORE: where playwright-core is installed (its directory); CHROMIUM: the browser
// (default /usr/bin/chromium).
import { createRequire } from 'node:module';
import { writeFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

const [page, step, candidate, out] = process.argv.slice(2);
const require = createRequire(import.meta.url);
const { chromium } = require(process.env.PLAYWRIGHT_CORE || 'playwright-core');

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu'],
});
try {
  const tab = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  await tab.goto(pathToFileURL(page).href);
  const shown = () => tab.evaluate(() => ({
    state: JSON.parse(document.getElementById('state').textContent),
    svg: document.getElementById('picture').innerHTML,
  }));
  const before = await shown();
  // The step's candidates as small drawings (a click on the step), then its button.
  await tab.click(`#plan li:nth-child(${Number(step) + 1}) span.node`);
  await tab.click(`button[data-step="${step}"][data-candidate="${candidate}"]`);
  const after = await shown();
  const ron = await tab.evaluate(() => {
    const data = JSON.parse(document.getElementById('data').textContent);
    const k = JSON.parse(document.getElementById('state').textContent).realization;
    return data.realizations[k].ron;
  });
  await tab.screenshot({ path: `${out}.png`, fullPage: true });
  writeFileSync(`${out}.json`, JSON.stringify({ before, after }));
  writeFileSync(`${out}.ron`, ron);
} finally {
  await browser.close();
}
