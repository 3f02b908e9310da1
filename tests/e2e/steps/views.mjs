// The page's views by address: the newest run opened on load, a run, a comparison and a
// study reopened from their hash and scrolled into place; a run's labels edited and found.
import assert from "node:assert/strict";

import { COMPARE, FORM, JOBS, LABELS, RUN, STUDY, fieldId } from "../../../static/js/ids.js";
import { GRID, openPage, sel, step } from "../lib.mjs";

// The top of the panel `id` in the viewport: in place when it is near the top.
const topOf = (page, id) => page.$eval(sel(id), (el) => el.getBoundingClientRect().top);
const inPlace = async (page, id) => {
  const top = await topOf(page, id);
  assert.ok(top >= -1 && top < 200, `${id} is at ${top} px`);
};

export async function views(page, found) {
  step("on load, the newest run is open and the address names it");
  await openPage(page);
  const newest = await page.evaluate(async () => (await e2e.api.api("/api/v1/jobs?limit=1")).body[0].id);
  await page.waitForFunction((id) => e2e.run.selectedId() === id, newest);
  assert.ok(page.url().endsWith(`#run=${newest}`), page.url());

  step("a run's address reopens it, scrolled into place");
  await openPage(page, `#run=${found.presetRun}`);
  await page.waitForFunction((id) => e2e.run.selectedId() === id, found.presetRun);
  await inPlace(page, RUN.panel);

  step("a comparison's address reopens it, scrolled into place");
  await openPage(page, `#compare=${found.presetRun},${found.tenRun}`);
  await page.waitForSelector(`${sel(COMPARE.panel)}:not([hidden])`);
  const compared = await page.evaluate(() => e2e.compare.comparedRuns().length);
  assert.equal(compared, 2);
  await inPlace(page, COMPARE.panel);

  step("a study's address reopens it, scrolled into place");
  const studyId = await page.evaluate(async () => (await e2e.api.api("/api/v1/studies?limit=1")).body[0].id);
  await openPage(page, `#study=${studyId}`);
  await page.waitForSelector(`${sel(STUDY.panel)}:not([hidden])`);
  await inPlace(page, STUDY.panel);
  assert.ok(page.url().endsWith(`#study=${studyId}`));

  step("a run's sample, tags and note: saved, shown in the list, found by the search");
  await openPage(page, `#run=${found.tenRun}`);
  await page.waitForFunction((id) => e2e.run.selectedId() === id, found.tenRun);
  await page.click("#run-labels summary");
  await page.fill(sel(LABELS.sample), "S-e2e-10N");
  await page.fill(sel(LABELS.tags), "ten, e2e");
  await page.fill(sel(LABELS.note), "the 10 N run");
  await page.click(sel(LABELS.save));
  await page.locator(sel(LABELS.status), { hasText: "Saved." }).waitFor();
  const stored = await page.evaluate(async (id) => (await e2e.api.api(`/api/v1/jobs/${id}`)).body, found.tenRun);
  assert.deepEqual([stored.sample, stored.tags, stored.note], ["S-e2e-10N", ["ten", "e2e"], "the 10 N run"]);
  await page.fill(sel(JOBS.name), "s-E2E-10n");
  await page.waitForFunction((table) => document.querySelectorAll(`#${table} tbody tr`).length === 1, JOBS.table);
  const row = await page.$eval(`${sel(JOBS.table)} tbody tr`, (tr) => [tr.dataset.id, tr.querySelector("td .muted").textContent]);
  assert.equal(row[0], found.tenRun);
  assert.match(row[1], /S-e2e-10N #ten #e2e/);
  await page.fill(sel(JOBS.name), "");
  await page.waitForFunction((table) => document.querySelectorAll(`#${table} tbody tr`).length > 1, JOBS.table);

  step("a sample and tags given with a new run reach its record");
  await page.fill(sel(fieldId("numerics.grid")), GRID);
  await page.fill(sel(fieldId("test.cycles")), "3");
  await page.fill(sel(FORM.sample), "S-form");
  await page.fill(sel(FORM.tags), "from-form, e2e");
  await page.click(sel(FORM.submit));
  await page.waitForFunction((id) => e2e.run.selectedId() && e2e.run.selectedId() !== id, found.tenRun);
  const submitted = await page.evaluate(async () => (await e2e.api.api(`/api/v1/jobs/${e2e.run.selectedId()}`)).body);
  assert.deepEqual([submitted.sample, submitted.tags], ["S-form", ["from-form", "e2e"]]);
  await page.waitForFunction((id) => document.getElementById(id).value === "S-form", LABELS.sample);

  step("the icon is inline: the page asks for no /favicon.ico");
  const icon = await page.$eval('link[rel="icon"]', (link) => link.getAttribute("href"));
  assert.ok(icon.startsWith("data:image/svg+xml,"), icon);
}
