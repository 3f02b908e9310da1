// Cancelling: a queued and a running job cancelled and deleted, the cancelled run's partial
// result; jobs that failed, were damaged or run again say why; the phone width again.
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";

import { CALIB, FORM, JOBS, RUN, RUN_PLOT, STUDY, fieldId } from "../../../static/js/ids.js";
import { sel, shots, step } from "../lib.mjs";

const rows = `${sel(JOBS.table)} tbody tr`;

// Deletes the row's job (after accepting the confirmation) and waits for its row to go.
async function deleteRow(page, row) {
  page.once("dialog", (d) => d.accept());
  const before = await page.locator(rows).count();
  await row.locator("button.delete").click();
  await page.waitForFunction(([r, n]) => document.querySelectorAll(r).length === n - 1, [rows, before]);
}

async function cancelRunning(page) {
  step("cancel a running job (after a confirmation), see why it stopped, then delete it; a job queued behind it shows its place");
  await page.fill(sel(fieldId("test.cycles")), "1000000");
  await page.click(sel(FORM.submit));
  await page.waitForFunction((r) => (document.querySelector(`${r} .status`) || {}).textContent === "running", rows);
  await page.click(sel(FORM.submit));
  const queued = page.locator(rows).first();
  await queued.locator(".progress", { hasText: "number 1 in the queue" }).waitFor();
  console.log(`   queued: ${(await queued.locator(".progress").innerText()).replace(/\s+/g, " ")}`);
  page.once("dialog", (d) => d.accept());
  await queued.locator("button.cancel").click();
  await queued.locator("td", { hasText: "cancelled" }).waitFor();
  await deleteRow(page, queued);
  // Some cycles done before the cancel, so that there is a partial result to see; the
  // long run is also the one the screenshot of a run in progress shows.
  await page.waitForFunction((r) => document.querySelector(`${r} progress`).value > 0, rows);
  await page.locator(rows).first().locator("button.view").click();
  await page.waitForFunction(([status, volume]) => document.getElementById(status).textContent.startsWith("running") && Number(document.getElementById(volume).dataset.points) > 20, [RUN.status, RUN_PLOT.volume]);
  console.log(`   during the run: ${await page.$eval(sel(RUN.status), (el) => el.textContent)}`);
  await page.screenshot({ path: path.join(shots, "during-run.png"), fullPage: true });
  const newest = page.locator(rows).first();
  let question = "";
  page.once("dialog", (d) => { question = d.message(); d.accept(); });
  await newest.locator("button.cancel").click();
  await newest.locator("td", { hasText: "cancelled" }).waitFor();
  assert.match(question, /^Cancel the run/);
  await newest.locator(".reason", { hasText: /Cancelled on request after \d+ of 1000000 cycles/ }).waitFor();
  return newest;
}

async function partial(page, newest) {
  step("the cancelled run keeps what it computed: drawn, and downloadable as CSV");
  await newest.locator("button.view").click();
  await page.locator(sel(RUN.partial), { hasText: "Partial result" }).waitFor();
  await page.waitForFunction(([depth, csv]) => Number(document.getElementById(depth).dataset.points) > 0 && !document.getElementById(csv).disabled, [RUN_PLOT.depth, RUN.downloadCsv]);
  const [partialCsv] = await Promise.all([page.waitForEvent("download"), page.click(sel(RUN.downloadCsv))]);
  const partialRows = fs.readFileSync(await partialCsv.path(), "utf8").trim().split("\n");
  console.log(`   ${await page.textContent(sel(RUN.partial))} (${partialRows.length - 1} CSV rows)`);
  assert.ok(partialRows.length > 1, "the partial CSV has no rows");
  assert.ok(partialRows[0].trim().split(",").includes("cycles_stepped_over"), `the CSV does not say which cycles were stepped over: ${partialRows[0]}`);
  await deleteRow(page, newest);
}

async function reasons(page) {
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
  await page.evaluate(() => e2e.jobs.refresh());
  for (const [name, text] of [["fake failed", "Failed: internal error"], ["fake damaged", "Damaged: stored scene damaged"], ["fake queued", "Run again: the stored result was damaged"]]) {
    const reason = page.locator(rows, { hasText: name }).locator(".reason");
    await reason.filter({ hasText: text }).waitFor();
    assert.ok(await reason.isVisible(), `${name}: the reason is not visible`);
  }
  await page.unroute(jobList);
}

async function phoneAgain(page) {
  step("phone width again, with the study and calibration panels open: no sideways scroll");
  await page.setViewportSize({ width: 390, height: 844 });
  await page.waitForTimeout(400);
  const widths = await page.evaluate((panels) => ({
    open: panels.filter((id) => !document.getElementById(id).hidden),
    scrollWidth: document.documentElement.scrollWidth, clientWidth: document.documentElement.clientWidth,
  }), [STUDY.panel, CALIB.panel]);
  console.log(`   ${JSON.stringify(widths)}`);
  assert.deepEqual(widths.open, [STUDY.panel, CALIB.panel]);
  assert.ok(widths.scrollWidth <= widths.clientWidth, `the page scrolls sideways: ${widths.scrollWidth} > ${widths.clientWidth}`);
}

export async function cancel(page) {
  const newest = await cancelRunning(page);
  await partial(page, newest);
  await reasons(page);
  await phoneAgain(page);
}
