// What the steps of the page's test share: the server's address, the screenshots' folder,
// the time limit, a step's heading, and the page opened with its modules at hand.
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";

export const base = process.env.TRIBOSIM_URL;
assert.ok(base, "TRIBOSIM_URL is not set");
export const shots = path.resolve(process.env.SCREENSHOT_DIR || "../../docs/screenshots");
fs.mkdirSync(shots, { recursive: true });
/** Every wait is for a condition, with this generous limit: the machine may be a loaded 2-core box. */
export const LONG = 120_000;
/** The limit for waiting on a run to end. */
export const RUN_LIMIT = 600_000;
/**
 * The grid and cycles of the test's runs. 128 cells per side makes the preset's run last
 * about 3 s (`tribosim run` of `{"numerics": {"grid": N}}`: 0.40 s at 64, 1.26 s at 96,
 * 2.94 s at 128), long enough that the sampler sees the progress move mid-run on a loaded
 * machine; at 64 cells the 0.4 s run ended before a frame showed it in 2 of 5 runs.
 */
export const GRID = process.env.E2E_GRID || "128";
export const CYCLES = process.env.E2E_CYCLES || "3600";

/** Prints a step's heading. */
export const step = (name) => console.log(`-- ${name}`);

/** The data points a figure's box says it holds. */
export const points = (page, id) => page.$eval(`#${id}`, (el) => Number(el.dataset.points));

/** A CSS selector for the element of this id. */
export const sel = (id) => `#${id}`;

/**
 * Opens the page and waits for its presets. The page's modules are then put at
 * `window.e2e` (plots, run, jobs, compare, calibration, api): importing a module's URL
 * again in the page gives the instance the page runs, so the test reads the charts and the
 * records the page holds, through the functions each module exports.
 */
export async function openPage(page, hash = "") {
  // From another document, so that an address differing only in its hash loads the page anew.
  if (hash) await page.goto("about:blank");
  await page.goto(base + hash);
  await page.waitForSelector("body[data-ready=true]");
  await page.evaluate(async () => {
    const modules = {};
    for (const name of ["api", "plots", "run", "jobs", "compare", "calibration"]) modules[name] = await import(`/static/js/${name}.js`);
    window.e2e = modules;
  });
}

/** Waits until the run panel's status starts with `word` (the run may take minutes). */
export const waitForStatus = (page, statusId, word) =>
  page.waitForFunction(([id, w]) => document.getElementById(id).textContent.startsWith(w), [statusId, word], { timeout: RUN_LIMIT });
