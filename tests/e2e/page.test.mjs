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
  // In JSON mode the fields show the JSON's values and cannot be edited.
  assert.equal(await page.inputValue("#f-test-speed_rpm"), "-5");
  assert.equal(await page.$eval("#f-test-speed_rpm", (el) => el.readOnly), true);
  await page.uncheck("#use-json");
  assert.equal(await page.$eval("#f-test-speed_rpm", (el) => el.readOnly), false);
  await page.fill("#f-test-speed_rpm", "60");

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
  const inked = await page.$$eval("#plot-volume canvas, #plot-depth canvas", (canvases) => canvases.map((c) => {
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 3; i < d.length; i += 4) if (d[i] > 0) n++;
    return n;
  }));
  assert.ok(inked.length >= 2 && inked.every((n) => n > 100), `blank canvas: ${inked}`);
  // The job list shows it finished, with a full progress bar and a Delete button.
  const row = page.locator("#jobs tbody tr.selected");
  assert.match(await row.textContent(), /succeeded/);
  assert.equal(await row.locator("progress").evaluate((p) => p.value === p.max), true);
  await row.locator("button.delete").waitFor();
  await page.screenshot({ path: path.join(shots, "after-run.png"), fullPage: true });

  step("the preset's run: Table 3 beside it, within the run's cycles; E_corr on the potential plot");
  const table3Cycles = [10, 60, 300, 1800, 3600];
  const volumePlot = await page.evaluate(() => ({
    measured: Number(document.getElementById("plot-volume").dataset.measured),
    enabled: !document.getElementById("show-table3").disabled,
    xMax: state.plots["plot-volume"].scales.x.max,
  }));
  console.log(`   volume plot: ${JSON.stringify(volumePlot)}`);
  assert.equal(volumePlot.measured, table3Cycles.filter((c) => c <= cyclesTotal).length);
  assert.ok(volumePlot.enabled, "the Table 3 choice is disabled for the preset's scene");
  assert.ok(volumePlot.xMax <= cyclesTotal, `the x axis runs to ${volumePlot.xMax}, past the run's ${cyclesTotal} cycles`);
  // The cursor on Table 3's 60 s point: every series reads that one row (cycle 60).
  const hover = await page.evaluate(() => {
    const u = state.plots["plot-volume"];
    u.setCursor({ left: u.valToPos(60, "x"), top: 10 });
    return { x: u.data[0][u.cursor.idx], rows: u.cursor.idxs.slice(1), legend: document.querySelector("#plot-volume .u-legend").textContent };
  });
  console.log(`   hover: ${JSON.stringify(hover)}`);
  assert.equal(hover.x, 60);
  assert.ok(hover.rows.every((i) => i === hover.rows[0]), `the legend reads rows ${hover.rows}`);
  assert.match(hover.legend, /simulated\s*\d/, "no simulated value at cycle 60");
  const potential = await page.evaluate(() => {
    const u = state.plots["plot-potential"];
    return { axis: u.axes[1].label, ecorr: u.data[2][0], series: u.series.map((s) => s.label) };
  });
  console.log(`   potential plot: ${JSON.stringify(potential)}`);
  assert.equal(potential.axis, "potential (V vs Ag/AgCl)");
  assert.equal(potential.ecorr, -0.1, "the dashed line is not the preset's E_corr (-0.1 V)");
  assert.ok(potential.series.some((l) => /E_corr/.test(l)));
  assert.doesNotMatch(await page.textContent("#run-panel"), /\bum\b/, "the run panel says um, not µm");

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

  step("a 10 N run: no Table 3 beside it, and the page says why");
  await page.fill("#f-test-load_n", "10");
  await page.fill("#f-test-cycles", "20");
  const presetRun = await page.$eval("#jobs tbody tr.selected", (tr) => tr.dataset.id);
  await page.click("#submit");
  await page.waitForFunction((id) => {
    const tr = document.querySelector("#jobs tbody tr.selected");
    return tr && tr.dataset.id !== id;
  }, presetRun);
  await page.waitForFunction(() => document.getElementById("run-status").textContent.startsWith("succeeded"), null, { timeout: 600_000 });
  await page.waitForFunction(() => Number(document.getElementById("plot-pressure").dataset.points) > 0);
  assert.equal(await page.$eval("#plot-volume", (el) => el.dataset.measured), "0");
  assert.equal(await page.isDisabled("#show-table3"), true);
  assert.match(await page.textContent("#table3-note"), /differ/);

  step("cancel a running job (after a confirmation), see why it stopped, then delete it");
  await page.fill("#f-test-cycles", "100000");
  await page.click("#submit");
  const newest = page.locator("#jobs tbody tr").first();
  let question = "";
  page.once("dialog", (d) => { question = d.message(); d.accept(); });
  await newest.locator("button.cancel").click();
  await newest.locator("td", { hasText: "cancelled" }).waitFor();
  assert.match(question, /^Cancel the run/);
  await newest.locator(".reason", { hasText: /Cancelled on request after \d+ of 100000 cycles/ }).waitFor();
  page.once("dialog", (d) => d.accept());
  const before = await page.locator("#jobs tbody tr").count();
  await newest.locator("button.delete").click();
  await page.waitForFunction((n) => document.querySelectorAll("#jobs tbody tr").length === n - 1, before);

  step("failed, damaged and re-run jobs show their reasons in the page's text");
  const fakes = [
    { status: "failed", error: "internal error: the simulation panicked: test", rerun_reason: null },
    { status: "damaged", error: "stored scene damaged: bad CRC", rerun_reason: null },
    { status: "queued", error: null, rerun_reason: "the stored result was damaged: bad CRC" },
  ].map((f, i) => ({
    id: `00000000-0000-4000-8000-00000000000${i}`, name: `fake ${f.status}`, cycles_done: 3, cycles_total: 10,
    eta_s: null, created_at: new Date().toISOString(), started_at: null, finished_at: null, ...f,
  }));
  // The service cannot be made to fail or damage a job from outside; the page's rendering
  // of such records is what is tested, so the job list is answered with them added.
  const jobList = (url) => url.pathname === "/api/v1/jobs";
  await page.route(jobList, async (route) => {
    if (route.request().method() !== "GET") return route.continue();
    const response = await route.fetch();
    route.fulfill({ response, json: [...fakes, ...(await response.json())] });
  });
  await page.evaluate(() => refreshJobs());
  for (const [name, text] of [["fake failed", "Failed: internal error"], ["fake damaged", "Damaged: stored scene damaged"], ["fake queued", "Run again: the stored result was damaged"]]) {
    const reason = page.locator("#jobs tbody tr", { hasText: name }).locator(".reason");
    await reason.filter({ hasText: text }).waitFor();
    assert.ok(await reason.isVisible(), `${name}: the reason is not visible`);
  }
  await page.unroute(jobList);

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
