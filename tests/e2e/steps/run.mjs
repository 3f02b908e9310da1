// A run of the preset on a small grid: live progress and plots, then every final figure,
// Table 3 beside it, the pressure maps to scale, the scene as run, and the downloads.
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";

import { FORM, JOBS, RUN, RUN_PLOT, fieldId } from "../../../static/js/ids.js";
import { CYCLES, GRID, points, sel, shots, step, waitForStatus } from "../lib.mjs";

async function start(page) {
  step("start the preset on a small grid, driven by the keyboard-usable form");
  await page.fill(sel(fieldId("test.load_n")), "5");
  await page.fill(sel(fieldId("numerics.grid")), GRID);
  await page.fill(sel(fieldId("test.cycles")), CYCLES);
  // Samples, every frame, the run's progress bar and the live volume plot's point count,
  // to show that both moved while the job was running (not only at its end).
  await page.evaluate(([progress, volume, status]) => {
    window.samples = [];
    const sample = () => {
      const p = document.getElementById(progress);
      window.samples.push([p.value, p.max, Number(document.getElementById(volume).dataset.points),
        document.getElementById(status).textContent]);
      if (!document.getElementById(status).textContent.startsWith("succeeded")) requestAnimationFrame(sample);
    };
    requestAnimationFrame(sample);
  }, [RUN.progress, RUN_PLOT.volume, RUN.status]);
  await page.focus(sel(FORM.submit));
  await page.keyboard.press("Enter");
  await page.waitForSelector(`${sel(RUN.panel)}:not([hidden])`);
  const loadError = page.locator('.field[data-path="test.load_n"] .error');
  assert.equal(await loadError.textContent(), "", "the load error stayed after a good submit");

  step("the progress moves and the live plots fill");
  // A frame the sampler recorded since the submit: a short run can end before a wait that
  // started now would see one.
  await page.waitForFunction(() => window.samples.some(([v, max, n]) => v > 0 && v < max && n > 0), null, { polling: "raf" });
}

async function ends(page, found) {
  step("the run ends; the final plots hold data");
  await waitForStatus(page, RUN.status, "succeeded");
  await page.waitForFunction((id) => Number(document.getElementById(id).dataset.points) > 0, RUN_PLOT.pressure);
  found.cyclesTotal = await page.$eval(sel(RUN.progress), (p) => p.max);
  const samples = await page.evaluate(() => window.samples);
  const mid = samples.filter(([v, max, n]) => v > 0 && v < max && n > 0);
  const distinct = new Set(mid.map(([v]) => v));
  console.log(`   ${samples.length} frames sampled; ${mid.length} mid-run, at ${distinct.size} distinct progress values`);
  assert.ok(distinct.size >= 2, "the progress did not move during the run");
  const counts = {};
  for (const id of Object.values(RUN_PLOT)) counts[id] = await points(page, id);
  console.log(`   data points: ${JSON.stringify(counts)}`);
  for (const [id, n] of Object.entries(counts)) assert.ok(n > 0, `${id} holds no data`);
  found.cycleRecords = counts[RUN_PLOT.depth];
  // The charts really drew: uPlot's canvases exist and are not blank.
  const inked = await page.$$eval(`${sel(RUN_PLOT.volume)} canvas, ${sel(RUN_PLOT.depth)} canvas`, (canvases) => canvases.map((c) => {
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 3; i < d.length; i += 4) if (d[i] > 0) n++;
    return n;
  }));
  assert.ok(inked.length >= 2 && inked.every((n) => n > 100), `blank canvas: ${inked}`);
  // The job list shows it finished, with a full progress bar and a Delete button.
  const row = page.locator(`${sel(JOBS.table)} tbody tr.selected`);
  assert.match(await row.textContent(), /succeeded/);
  assert.equal(await row.locator("progress").evaluate((p) => p.value === p.max), true);
  await row.locator("button.delete").waitFor();
  await page.screenshot({ path: path.join(shots, "after-run.png"), fullPage: true });
}

async function table3(page, found) {
  step("the preset's run: Table 3 beside it, within the run's cycles; E_corr on the potential plot");
  const table3Cycles = [10, 60, 300, 1800, 3600];
  const volumePlot = await page.evaluate(([volume, choice]) => ({
    measured: Number(document.getElementById(volume).dataset.measured),
    enabled: !document.getElementById(choice).disabled,
    xMax: e2e.plots.chart(volume).scales.x.max,
  }), [RUN_PLOT.volume, RUN.showTable3]);
  console.log(`   volume plot: ${JSON.stringify(volumePlot)}`);
  assert.equal(volumePlot.measured, table3Cycles.filter((c) => c <= found.cyclesTotal).length);
  assert.ok(volumePlot.enabled, "the Table 3 choice is disabled for the preset's scene");
  assert.ok(volumePlot.xMax <= found.cyclesTotal, `the x axis runs to ${volumePlot.xMax}, past the run's ${found.cyclesTotal} cycles`);
  // The cursor on Table 3's 60 s point: every series reads that one row (cycle 60).
  const hover = await page.evaluate((volume) => {
    const u = e2e.plots.chart(volume);
    u.setCursor({ left: u.valToPos(60, "x"), top: 10 });
    return { x: u.data[0][u.cursor.idx], rows: u.cursor.idxs.slice(1), legend: document.querySelector(`#${volume} .u-legend`).textContent };
  }, RUN_PLOT.volume);
  console.log(`   hover: ${JSON.stringify(hover)}`);
  assert.equal(hover.x, 60);
  assert.ok(hover.rows.every((i) => i === hover.rows[0]), `the legend reads rows ${hover.rows}`);
  assert.match(hover.legend, /simulated\s*\d/, "no simulated value at cycle 60");
  const potential = await page.evaluate((id) => {
    const u = e2e.plots.chart(id);
    return { axis: u.axes[1].label, ecorr: u.data[2][0], series: u.series.map((s) => s.label) };
  }, RUN_PLOT.potential);
  console.log(`   potential plot: ${JSON.stringify(potential)}`);
  assert.equal(potential.axis, "potential (V vs Ag/AgCl)");
  assert.equal(potential.ecorr, -0.1, "the dashed line is not the preset's E_corr (-0.1 V)");
  assert.ok(potential.series.some((l) => /E_corr/.test(l)));
  assert.doesNotMatch(await page.textContent(sel(RUN.panel)), /\bum\b/, "the run panel says um, not µm");
  assert.doesNotMatch(await page.textContent(sel(RUN.panel)), /--|WearTrack/, "a legend or a reason says -- or WearTrack");
}

async function pressureMaps(page) {
  step("the pressure maps: both at one length scale, x and y alike");
  const maps = await page.evaluate((id) => [...document.querySelectorAll(`#${id} svg g[data-cycle]`)].map((g) => {
    const map = e2e.run.currentResult().pressure_maps.find((m) => m.cycle === Number(g.dataset.cycle));
    const frame = g.querySelector("rect.frame");
    const span = (c) => c[c.length - 1] - c[0] + (c[1] - c[0]);
    return { cycle: map.cycle, spanX: span(map.x_um), spanY: span(map.y_um), width: Number(frame.getAttribute("width")), height: Number(frame.getAttribute("height")), umPerPx: Number(g.dataset.umPerPx) };
  }), RUN_PLOT.pressure);
  console.log(`   maps: ${JSON.stringify(maps)}`);
  assert.equal(maps.length, 2);
  assert.equal(maps[0].umPerPx, maps[1].umPerPx);
  // Each frame is its span at the one scale, to the 0.005 px of its two written decimals.
  for (const m of maps) {
    assert.ok(Math.abs(m.spanX / maps[0].umPerPx - m.width) <= 0.0051, `map ${m.cycle}: x not at the common scale`);
    assert.ok(Math.abs(m.spanY / maps[0].umPerPx - m.height) <= 0.0051, `map ${m.cycle}: y not at the common scale`);
  }
}

async function downloads(page, found) {
  step("the run's parameters: the scene as run, and what differs from the preset");
  assert.match(await page.textContent(sel(RUN.paramsDiff)), new RegExp(`Differs from the preset dalmau2018-316l in \\d+ fields?:.*grid ${GRID}`));
  assert.match(await page.textContent(sel(RUN.paramsJson)), /"load_n": 5/);

  step("download the JSON and the CSV");
  const [download] = await Promise.all([page.waitForEvent("download"), page.click(sel(RUN.downloadJson))]);
  const result = JSON.parse(fs.readFileSync(await download.path(), "utf8"));
  assert.equal(result.cycles.length, found.cycleRecords);
  assert.equal(result.cycles[result.cycles.length - 1].cycle, found.cyclesTotal);
  assert.ok(result.pressure_maps.length >= 1 && result.profiles.length >= 1);
  console.log(`   ${download.suggestedFilename()}: ${result.cycles.length} cycles, ${result.profiles.length} profiles`);
  const [csvDownload] = await Promise.all([page.waitForEvent("download"), page.click(sel(RUN.downloadCsv))]);
  const csv = fs.readFileSync(await csvDownload.path(), "utf8").trim().split("\n");
  assert.equal(csv.length, result.cycles.length + 1);
  assert.ok(csv[0].trim().split(",").includes("cycles_stepped_over"), `the CSV does not say which cycles were stepped over: ${csv[0]}`);
  console.log(`   ${csvDownload.suggestedFilename()}: ${csv.length - 1} rows`);
  // Named after the run, not its id.
  for (const d of [download, csvDownload]) assert.doesNotMatch(d.suggestedFilename(), /^tribosim-[0-9a-f-]{36}/);
  assert.match(download.suggestedFilename(), /\.result\.json$/);

  step("the profiles, the pressure maps and the result without its maps");
  const fetched = async (button) => {
    const [d] = await Promise.all([page.waitForEvent("download"), page.click(sel(button))]);
    return [d.suggestedFilename(), fs.readFileSync(await d.path(), "utf8")];
  };
  const [profilesName, profiles] = await fetched(RUN.downloadProfiles);
  const profileRows = result.profiles.reduce((n, p) => n + p.y_um.length, 0);
  assert.equal(profiles.trim().split("\n").length, profileRows + 1, profilesName);
  const [pressureName, pressure] = await fetched(RUN.downloadPressure);
  const cells = result.pressure_maps.reduce((n, m) => n + m.x_um.length * m.y_um.length, 0);
  assert.equal(pressure.trim().split("\n").length, cells + 1, pressureName);
  const [compactName, compact] = await fetched(RUN.downloadCompact);
  assert.deepEqual(JSON.parse(compact).pressure_maps, []);
  console.log(`   ${profilesName}: ${profileRows} rows; ${pressureName}: ${cells} rows; ${compactName}: ${compact.length} of ${JSON.stringify(result).length} bytes`);
}

export async function run(page, found) {
  await start(page);
  await ends(page, found);
  await table3(page, found);
  await pressureMaps(page);
  await downloads(page, found);
}
