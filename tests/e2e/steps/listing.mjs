// The job list's filters and the calibrations list: a name no job has empties the list and
// says so, a status keeps only its jobs, clearing brings every job back; the fits run so far
// are listed newest first.
import assert from "node:assert/strict";

import { CALIB, JOBS } from "../../../static/js/ids.js";
import { sel, step } from "../lib.mjs";

const rows = `${sel(JOBS.table)} tbody tr`;

export async function listing(page) {
  step("the job list filtered by name and status, then cleared; the fits listed");
  const every = await page.$$eval(rows, (trs) => trs.length);
  await page.fill(sel(JOBS.name), "no job is called this");
  await page.locator(sel(JOBS.message), { hasText: "No job matches." }).waitFor();
  assert.equal(await page.isHidden(sel(JOBS.table)), true);
  await page.fill(sel(JOBS.name), "");
  await page.selectOption(sel(JOBS.status), "succeeded");
  await page.waitForFunction((r) => {
    const statuses = [...document.querySelectorAll(r)].map((tr) => tr.querySelector(".status").textContent);
    return statuses.length > 0 && statuses.every((s) => s === "succeeded");
  }, rows);
  const succeeded = await page.$$eval(rows, (trs) => trs.length);
  await page.selectOption(sel(JOBS.status), "");
  await page.waitForFunction(([r, n]) => document.querySelectorAll(r).length === n, [rows, every]);
  console.log(`   jobs: ${every} listed, ${succeeded} succeeded`);
  assert.ok(succeeded > 0 && succeeded <= every);
  await page.selectOption(sel(JOBS.status), "damaged");
  await page.locator(sel(JOBS.message), { hasText: "No job matches." }).waitFor();
  await page.selectOption(sel(JOBS.status), "");
  await page.waitForFunction(([r, n]) => document.querySelectorAll(r).length === n, [rows, every]);
  const fits = await page.$$eval(`${sel(CALIB.list)} tbody tr`, (trs) => trs.map((tr) => tr.cells[0].textContent));
  console.log(`   fits listed: ${JSON.stringify(fits)}`);
  assert.deepEqual(fits.slice(0, 2), ["archard", "hardness"]);
}
