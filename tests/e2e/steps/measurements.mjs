// Measurements attached to the run: a bad table refused, three kinds drawn and stored.
import assert from "node:assert/strict";

import { MEASURE, RUN_PLOT } from "../../../static/js/ids.js";
import { sel, step } from "../lib.mjs";

// Waits until the figure `id` says it draws `n` attached points.
const attachedOn = (page, id, n) =>
  page.waitForFunction(([plot, count]) => document.getElementById(plot).dataset.attached === count, [id, String(n)]);

export async function measurements(page) {
  step("measurements attached to the run: a bad table refused with its column named, then three kinds drawn");
  await page.click(`${sel(MEASURE.box)} summary`);
  const attach = async (kind, csv, asFile) => {
    await page.selectOption(sel(MEASURE.kind), kind);
    if (asFile) await page.setInputFiles(sel(MEASURE.file), { name: `${kind}.csv`, mimeType: "text/csv", buffer: Buffer.from(csv) });
    else await page.fill(sel(MEASURE.text), csv);
    await page.click(sel(MEASURE.attach));
  };
  await attach("wear_volume", "cycles,volume_mm3\n10,-0.001\n", false);
  await page.locator(sel(MEASURE.errors), { hasText: "volume_mm3" }).waitFor();
  console.log(`   refused: ${await page.textContent(sel(MEASURE.errors))}`);
  await attach("wear_volume", "cycles,volume_mm3\n10,0.00097\n60,0.00109\n300,0.00118\n", true);
  await attachedOn(page, RUN_PLOT.volume, 3);
  await attach("profile", "y_mm,depth_um\n-0.1,0.4\n0,3.1\n0.1,0.4\n", false);
  await attachedOn(page, RUN_PLOT.profile, 3);
  assert.equal(await page.textContent(sel(MEASURE.read)), "", "documented names need no note");
  // A potentiostat's export: its headers with units in brackets, read under the documented
  // names, and the page says how.
  await attach("ocp", "Time (s)\tEwe [V]\n100\t-0.30\n1000\t-0.35\n", false);
  await attachedOn(page, RUN_PLOT.potential, 2);
  assert.equal(await page.textContent(sel(MEASURE.errors)), "");
  const read = await page.textContent(sel(MEASURE.read));
  console.log(`   ${read}`);
  assert.match(read, /“Time \(s\)” as time_s/);
  assert.match(read, /as potential_v/);
  const figures = [RUN_PLOT.volume, RUN_PLOT.profile, RUN_PLOT.potential];
  const drawn = await page.evaluate((ids) => ids.map((id) => {
    const u = e2e.plots.chart(id);
    const k = u.series.findIndex((s) => s.label === "attached measurement");
    return [id, k > 0 ? u.data[k].filter((v) => v != null).length : 0];
  }), figures);
  console.log(`   attached points drawn: ${JSON.stringify(drawn)}`);
  assert.deepEqual(drawn, [[RUN_PLOT.volume, 3], [RUN_PLOT.profile, 3], [RUN_PLOT.potential, 2]]);
  // Stored with the job: the API returns them.
  const stored = await page.evaluate(async () => (await e2e.api.api(`/api/v1/jobs/${e2e.run.selectedId()}/measurements`)).body);
  assert.deepEqual(stored.wear_volume.cycles, [10, 60, 300]);

  step("each kind scored under its figure: the model at the measured points, the residual, the z-score");
  const scoreRows = (id) => page.$$eval(`#${id} .scores tbody tr`, (rows) => rows.map((tr) => [...tr.cells].map((td) => td.textContent)));
  await page.waitForFunction((id) => document.querySelectorAll(`#${id} .scores tbody tr`).length === 3, RUN_PLOT.volume);
  const volumeRows = await scoreRows(RUN_PLOT.volume);
  console.log(`   volume scores: ${JSON.stringify(volumeRows)}`);
  const scores = await page.evaluate(async () => (await e2e.api.api(`/api/v1/jobs/${e2e.run.selectedId()}/scores`)).body);
  scores.wear_volume.points.forEach((p, i) => {
    assert.equal(volumeRows[i][1], p.measured.toPrecision(4));
    assert.equal(volumeRows[i][2], p.model.toPrecision(4));
    // The residual is the difference of what the rows show, to their 4 digits.
    assert.ok(Math.abs(p.residual - (p.measured - p.model)) <= 1e-12 * Math.abs(p.measured));
  });
  assert.equal((await scoreRows(RUN_PLOT.profile)).length, 3);
  assert.equal((await scoreRows(RUN_PLOT.potential)).length, 2);
}
