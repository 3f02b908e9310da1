// A study of the form's scene at two loads, and two of its members compared.
import assert from "node:assert/strict";

import { COMPARE, COMPARE_PLOT, STUDY, STUDY_PLOT, fieldId } from "../../../static/js/ids.js";
import { sel, step, waitForStatus } from "../lib.mjs";

export async function study(page) {
  step("a study: the form's scene at 2 and 5 N; its members' results against the load; two members compared");
  await page.fill(sel(fieldId("test.cycles")), "20");
  await page.fill(sel(fieldId("numerics.grid")), "32");
  await page.click(`${sel(STUDY.new)} summary`);
  await page.fill(sel(STUDY.axes), JSON.stringify({ "test.load_n": [2, 5] }));
  await page.click(sel(STUDY.submit));
  await page.waitForSelector(`${sel(STUDY.panel)}:not([hidden])`);
  await waitForStatus(page, STUDY.status, "succeeded");
  await page.waitForFunction((id) => Number(document.getElementById(id).dataset.points) === 2, STUDY_PLOT.volume);
  const members = await page.evaluate(([table, volume]) => ({
    rows: [...document.querySelectorAll(`#${table} tbody tr`)].map((tr) => tr.innerText.replace(/\s+/g, " ").trim()),
    xLabel: e2e.plots.spec(volume).xLabel,
    volumes: e2e.plots.chart(volume).data[1],
  }), [STUDY.members, STUDY_PLOT.volume]);
  console.log(`   study: ${JSON.stringify(members)}`);
  assert.equal(members.rows.length, 2);
  assert.equal(members.xLabel, "load (N)");
  assert.ok(members.volumes[1] > members.volumes[0], "the 5 N member did not wear more than the 2 N one");
  for (const box of await page.$$(`${sel(STUDY.members)} tbody input[type=checkbox]`)) await box.check();
  await page.click(sel(STUDY.compare));
  await page.waitForFunction((volume) => document.getElementById(volume).dataset.curves === "2" && e2e.compare.comparedRuns().length === 2, COMPARE_PLOT.volume);
  assert.deepEqual(await page.evaluate(() => e2e.compare.comparedRuns().map((r) => r.label)), ["load 2 N", "load 5 N"]);
  await page.click(sel(COMPARE.close));
}
