// Calibrations: a table refused, the hardness law fitted and its scene run, and an Archard
// fit with a change of regime.
import assert from "node:assert/strict";
import path from "node:path";

import { CALIB, JOBS, RUN } from "../../../static/js/ids.js";
import { sel, step, waitForStatus } from "../lib.mjs";

const FIT_LIMIT = 300_000;

async function hardness(page) {
  step("a calibration: a table the fit cannot use is refused; the hardness law fitted to Table 3's hardness; the fitted scene run");
  await page.click(`${sel(CALIB.new)} summary`);
  const hardnessCsv = path.resolve("../../docs/calibration/table3_hardness.csv");
  await page.selectOption(sel(CALIB.kind), "tafel");
  await page.setInputFiles(sel(CALIB.file), hardnessCsv);
  await page.click(sel(CALIB.submit));
  await page.locator(sel(CALIB.errors), { hasText: /potential_v|current_density/ }).waitFor();
  console.log(`   refused: ${await page.textContent(sel(CALIB.errors))}`);
  await page.selectOption(sel(CALIB.kind), "hardness");
  await page.setInputFiles(sel(CALIB.file), hardnessCsv);
  await page.click(sel(CALIB.submit));
  await page.waitForFunction((id) => document.getElementById(id).textContent === "succeeded", CALIB.status, { timeout: FIT_LIMIT });
  const calib = await page.evaluate((ids) => ({
    values: [...document.querySelectorAll(`#${ids.values} tbody tr`)].map((tr) => tr.innerText.replace(/\s+/g, " ").trim()),
    residuals: document.querySelectorAll(`#${ids.residuals} tbody tr`).length,
    plotted: Number(document.getElementById(ids.plot).dataset.points),
  }), CALIB);
  console.log(`   calibration: ${JSON.stringify(calib)}`);
  // docs/calibration.md: A = 2454.99 ± 26.98 MPa, B = 63.38 ± 4.96 MPa over the five points and the bulk value.
  assert.deepEqual(calib.values, ["a (MPa) 2455 26.98", "b (MPa) 63.38 4.955"]);
  assert.equal(calib.residuals, 6);
  assert.equal(calib.plotted, 6);
  const beforeFit = await page.$$eval(`${sel(JOBS.table)} tbody tr`, (trs) => trs.map((tr) => tr.dataset.id));
  await page.click(sel(CALIB.run));
  await page.waitForFunction((ids) => e2e.run.selectedId() && !ids.includes(e2e.run.selectedId()), beforeFit);
  await waitForStatus(page, RUN.status, "succeeded");
}

async function regimes(page) {
  step("an Archard fit with a change of regime at 300 cycles: both k's and the better model shown");
  await page.selectOption(sel(CALIB.kind), "archard");
  await page.fill(sel(CALIB.regime), "300");
  await page.setInputFiles(sel(CALIB.file), path.resolve("../../docs/calibration/table3_wear.csv"));
  const previous = await page.evaluate(() => e2e.calibration.current().id);
  await page.click(sel(CALIB.submit));
  await page.waitForFunction(([ids, id]) => document.getElementById(ids.errors).textContent
    || (e2e.calibration.current().id !== id && document.getElementById(ids.status).textContent !== "running"), [CALIB, previous], { timeout: FIT_LIMIT });
  assert.equal(await page.textContent(sel(CALIB.errors)), "");
  const fit = await page.evaluate((ids) => ({
    status: document.getElementById(ids.status).textContent,
    values: [...document.querySelectorAll(`#${ids.values} tbody tr`)].map((tr) => tr.cells[0].innerText.trim()),
    note: document.getElementById(ids.note).textContent,
    residuals: document.querySelectorAll(`#${ids.residuals} tbody tr`).length,
  }), CALIB);
  console.log(`   regimes: ${JSON.stringify(fit)}`);
  assert.equal(fit.status, "succeeded");
  assert.equal(fit.values.length, 3, "one k, k before and k after");
  assert.match(fit.note, /change cycle/i);
  assert.equal(fit.residuals, 5, "Table 3's five points");
}

export async function calibration(page) {
  await hardness(page);
  await regimes(page);
}
