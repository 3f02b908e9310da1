// End-to-end test of the results page in headless Chromium (Debian's package), driven by
// playwright-core. Needs TRIBOSIM_URL (a running `tribosim serve`); SCREENSHOT_DIR (default
// docs/screenshots) receives the screenshots. Every wait is for a condition, with generous
// time limits: the machine may be a loaded 2-core box.
import { chromium } from "playwright-core";
import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";

const base = process.env.TRIBOSIM_URL;
assert.ok(base, "TRIBOSIM_URL is not set");
const shots = path.resolve(process.env.SCREENSHOT_DIR || "../../docs/screenshots");
fs.mkdirSync(shots, { recursive: true });
const LONG = 120_000;

const profile = fs.mkdtempSync(path.join(os.tmpdir(), "tribosim-chromium-"));
// A fresh, empty profile directory (Playwright's way of passing --user-data-dir).
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  headless: true,
  args: [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
  ],
  viewport: { width: 1440, height: 1000 },
  acceptDownloads: true,
});

let failed = false;
const step = (name) => console.log(`-- ${name}`);
const points = (page, id) => page.$eval(`#${id}`, (el) => Number(el.dataset.points));

try {
  const page = context.pages()[0] || await context.newPage();
  page.setDefaultTimeout(LONG);
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));

  step("open the page; the presets load");
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]");
  assert.equal(await page.inputValue("#preset"), "dalmau2018-316l");

  step("a bad field: load -1 is refused, and the message sits next to the load field");
  await page.fill("#f-test-load_n", "-1");
  await page.click("#submit");
  const loadError = page.locator('.field[data-path="test.load_n"] .error');
  await loadError.filter({ hasText: /\S/ }).waitFor();
  console.log(`   load error: ${await loadError.textContent()}`);
  assert.equal(await page.getAttribute("#f-test-load_n", "aria-invalid"), "true");
  await page.screenshot({ path: path.join(shots, "validation-error.png"), clip: { x: 0, y: 0, width: 720, height: 760 } });

  step("a pasted scene with a bad field: the error is listed under the JSON box");
  await page.check("#use-json");
  await page.fill("#scene-json", JSON.stringify({ preset: "dalmau2018-316l", overrides: { test: { speed_rpm: -5 } } }));
  await page.click("#submit");
  await page.locator("#json-errors", { hasText: "test.speed_rpm" }).waitFor();
  console.log(`   json error: ${await page.textContent("#json-errors")}`);
  await page.uncheck("#use-json");

  step("start the preset on a small grid, driven by the keyboard-usable form");
  await page.fill("#f-test-load_n", "5");
  await page.fill("#f-numerics-grid", process.env.E2E_GRID || "64");
  await page.fill("#f-test-cycles", process.env.E2E_CYCLES || "3600");
  // Samples, every frame, the run's progress bar and the live volume plot's point count,
  // to show that both moved while the job was running (not only at its end).
  await page.evaluate(() => {
    window.samples = [];
    const sample = () => {
      const p = document.getElementById("run-progress");
      window.samples.push([p.value, p.max, Number(document.getElementById("plot-volume").dataset.points),
        document.getElementById("run-status").textContent]);
      if (!document.getElementById("run-status").textContent.startsWith("succeeded")) requestAnimationFrame(sample);
    };
    requestAnimationFrame(sample);
  });
  await page.focus("#submit");
  await page.keyboard.press("Enter");
  await page.waitForSelector("#run-panel:not([hidden])");
  assert.equal(await loadError.textContent(), "", "the load error stayed after a good submit");

  step("the progress moves and the live plots fill");
  await page.waitForFunction(() => {
    const p = document.getElementById("run-progress");
    return p.value > 0 && p.value < p.max && Number(document.getElementById("plot-volume").dataset.points) > 0;
  }, null, { polling: "raf" });
  // For the screenshot only: a third of the way in, if the run has not ended by then.
  await page.waitForFunction(() => {
    const p = document.getElementById("run-progress");
    return p.value >= p.max / 3 || !document.getElementById("run-status").textContent.startsWith("running");
  }, null, { polling: "raf" });
  console.log(`   during the run: ${await page.$eval("#run-status", (el) => el.textContent)}`);
  await page.screenshot({ path: path.join(shots, "during-run.png"), fullPage: true });

  step("the run ends; the final plots hold data");
  await page.waitForFunction(() => document.getElementById("run-status").textContent.startsWith("succeeded"), null, { timeout: 600_000 });
  await page.waitForFunction(() => Number(document.getElementById("plot-pressure").dataset.points) > 0);
  const cyclesTotal = await page.$eval("#run-progress", (p) => p.max);
  const samples = await page.evaluate(() => window.samples);
  const mid = samples.filter(([v, max, n]) => v > 0 && v < max && n > 0);
  const distinct = new Set(mid.map(([v]) => v));
  console.log(`   ${samples.length} frames sampled; ${mid.length} mid-run, at ${distinct.size} distinct progress values`);
  assert.ok(distinct.size >= 2, "the progress did not move during the run");
  const counts = {};
  for (const id of ["plot-volume", "plot-depth", "plot-potential", "plot-wac", "plot-profile", "plot-pressure"]) {
    counts[id] = await points(page, id);
  }
  console.log(`   data points: ${JSON.stringify(counts)}`);
  for (const [id, n] of Object.entries(counts)) assert.ok(n > 0, `${id} holds no data`);
  // The charts really drew: uPlot's canvases exist and are not blank.
  const inked = await page.$$eval("#plot-volume canvas, #plot-pressure canvas", (canvases) => canvases.map((c) => {
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 3; i < d.length; i += 4) if (d[i] > 0) n++;
    return n;
  }));
  assert.ok(inked.length >= 3 && inked.every((n) => n > 100), `blank canvas: ${inked}`);
  // The job list shows it finished, with a full progress bar and a Delete button.
  const row = page.locator("#jobs tbody tr.selected");
  assert.match(await row.textContent(), /succeeded/);
  assert.equal(await row.locator("progress").evaluate((p) => p.value === p.max), true);
  await row.locator("button.delete").waitFor();
  await page.screenshot({ path: path.join(shots, "after-run.png"), fullPage: true });

  step("download the JSON and the CSV");
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#download-json")]);
  const file = await download.path();
  const result = JSON.parse(fs.readFileSync(file, "utf8"));
  assert.equal(result.cycles.length, counts["plot-depth"]);
  assert.equal(result.cycles[result.cycles.length - 1].cycle, cyclesTotal);
  assert.ok(result.pressure_maps.length >= 1 && result.profiles.length >= 1);
  console.log(`   ${download.suggestedFilename()}: ${result.cycles.length} cycles, ${result.profiles.length} profiles`);
  const [csvDownload] = await Promise.all([page.waitForEvent("download"), page.click("#download-csv")]);
  const csv = fs.readFileSync(await csvDownload.path(), "utf8").trim().split("\n");
  assert.equal(csv.length, result.cycles.length + 1);
  console.log(`   ${csvDownload.suggestedFilename()}: ${csv.length - 1} rows`);

  step("cancel a running job, then delete it");
  await page.fill("#f-test-cycles", "100000");
  await page.click("#submit");
  const newest = page.locator("#jobs tbody tr").first();
  await newest.locator("button.cancel").click();
  await newest.locator("td", { hasText: "cancelled" }).waitFor();
  page.once("dialog", (d) => d.accept());
  const before = await page.locator("#jobs tbody tr").count();
  await newest.locator("button.delete").click();
  await page.waitForFunction((n) => document.querySelectorAll("#jobs tbody tr").length === n - 1, before);

  assert.deepEqual(errors, [], "errors in the page");
  console.log("e2e: all checks passed");
} catch (e) {
  failed = true;
  console.error("e2e FAILED:", e);
} finally {
  await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
