// The reciprocating rig: the form's rig sends test.reciprocating, a stroke shorter than the
// contact is refused at its field, and a short run shows its wear map (a canvas that drew),
// its axial profile and its cycle traces; the same scene on the disc shows none of them.
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";

import { FORM, RIG, RUN, STROKE_PLOT, fieldId } from "../../../static/js/ids.js";
import { openPage, points, sel, shots, step, waitForStatus } from "../lib.mjs";

const STROKE_PATH = "test.reciprocating.stroke_mm";
// Six cycles of a 0.6 mm stroke on 32 cells, cycle 3 recorded: traced at cycles 1, 3 and 6.
const CYCLES = "6", GRID = "32", RECORDED = [3];

// Submits what the form holds and waits until the page shows the new job, succeeded.
async function submitAndWait(page) {
  const before = await page.evaluate(() => e2e.run.selectedId());
  await page.click(sel(FORM.submit));
  await page.waitForFunction((id) => e2e.run.selectedId() !== id, before);
  await waitForStatus(page, RUN.status, "succeeded");
  await page.waitForFunction(() => e2e.run.currentResult());
}

async function refusedStroke(page) {
  step("the rig's fields: a stroke shorter than the contact is refused at the stroke field");
  await openPage(page);
  assert.equal(await page.isHidden(sel(RIG.fields)), true, "the stroke's fields show on the disc");
  await page.selectOption(sel(RIG.kind), "reciprocating");
  await page.fill(sel(fieldId(STROKE_PATH)), "0.05");
  await page.fill(sel(fieldId("test.reciprocating.frequency_hz")), "1");
  await page.fill(sel(fieldId("test.cycles")), CYCLES);
  await page.fill(sel(fieldId("numerics.grid")), GRID);
  assert.match(await page.inputValue(sel(FORM.name)), /reciprocating, stroke 0\.05 mm, frequency 1 Hz$/);
  await page.click(sel(FORM.submit));
  const error = page.locator(`.field[data-path="${STROKE_PATH}"] .error`);
  await error.filter({ hasText: /\S/ }).waitFor();
  console.log(`   stroke error: ${await error.textContent()}`);
  assert.match(await error.textContent(), /longer than the contact/);
  assert.equal(await page.getAttribute(sel(fieldId(STROKE_PATH)), "aria-invalid"), "true");
  await page.screenshot({ path: path.join(shots, "stroke-refused.png"), clip: { x: 0, y: 0, width: 720, height: 900 } });
}

async function strokeRun(page) {
  step("a reciprocating run from the form: test.reciprocating as given, an empty field not sent");
  await page.fill(sel(fieldId(STROKE_PATH)), "0.6");
  await page.click(sel(FORM.fieldsToJson));
  const sent = JSON.parse(await page.inputValue(sel(FORM.sceneJson)));
  assert.deepEqual(sent.overrides.test.reciprocating, { stroke_mm: 0.6, frequency_hz: 1 });
  // The traced cycles need numerics.record_cycles, which has no field: the JSON gives it.
  sent.overrides.numerics.record_cycles = RECORDED;
  await page.check(sel(FORM.useJson));
  await page.fill(sel(FORM.sceneJson), JSON.stringify(sent));
  await submitAndWait(page);
  await page.uncheck(sel(FORM.useJson));
  await page.waitForFunction((id) => Number(document.getElementById(id).dataset.points) > 0, STROKE_PLOT.map);
}

// The map's canvas, as drawn: its size, the coloured pixels (viridis is saturated, the
// white ground and the black ink are not) and how many colours they take.
const mapPixels = (page) => page.$eval(`${sel(STROKE_PLOT.map)} canvas`, (c) => {
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let coloured = 0;
  const colours = new Set();
  for (let i = 0; i < d.length; i += 4) {
    if (Math.max(d[i], d[i + 1], d[i + 2]) - Math.min(d[i], d[i + 1], d[i + 2]) < 40) continue;
    coloured++;
    colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
  }
  return { width: c.width, height: c.height, coloured, colours: colours.size };
});

// Each stroke chart's series labels and x range; null where there is no chart.
const charts = (page) => page.evaluate((ids) => Object.fromEntries(ids.map((id) => {
  const u = e2e.plots.chart(id);
  return [id, u ? { labels: u.series.slice(1).map((s) => s.label), x: [u.data[0][0], u.data[0][u.data[0].length - 1]] } : null];
})), Object.values(STROKE_PLOT));

async function strokeFigures(page) {
  step("the stroke's figures: the wear map drew, the profile and a trace per traced cycle");
  const stroke = await page.evaluate(() => e2e.run.currentResult().stroke);
  assert.ok(stroke, "the result has no stroke");
  const map = await mapPixels(page);
  console.log(`   map: ${JSON.stringify(map)}`);
  assert.ok(map.coloured > 0.3 * map.width * 0.3 * map.height, "the wear map's canvas is (nearly) blank");
  assert.ok(map.colours > 8, `the wear map takes ${map.colours} colours: no depth shows`);
  assert.equal(await points(page, STROKE_PLOT.map), stroke.map.x_um.length * stroke.map.y_um.length);
  const drawn = await charts(page);
  console.log(`   charts: ${JSON.stringify(drawn)}`);
  assert.deepEqual(drawn[STROKE_PLOT.profile].labels, ["depth on the centre line"]);
  assert.equal(await points(page, STROKE_PLOT.profile), stroke.axial_profile.x_um.length);
  const cycles = stroke.traces.map((t) => `cycle ${t.cycle}`);
  assert.deepEqual(cycles, ["cycle 1", "cycle 3", "cycle 6"]);
  for (const id of [STROKE_PLOT.potential, STROKE_PLOT.current]) {
    assert.deepEqual(drawn[id].labels, cycles, `${id}: a series per traced cycle`);
    // One cycle at 1 Hz: the times within it, from the first sample's middle to the last's.
    assert.ok(drawn[id].x[0] > 0 && drawn[id].x[1] < 1, `${id}: x ${drawn[id].x} is not within one cycle`);
  }
  // The run's printable report carries the rig's three figures, the map among them.
  const report = await page.evaluate(async () => (await fetch(`/api/v1/jobs/${e2e.run.selectedId()}/report`)).text());
  for (const caption of ["Wear map along and across the stroke", "Wear depth along the stroke", "Potential over a cycle"]) {
    assert.ok(report.includes(`<figcaption>${caption}`), `the report has no figure "${caption}"`);
  }
  const [download] = await Promise.all([page.waitForEvent("download"), page.click(`${sel(STROKE_PLOT.map)} .export-svg`)]);
  assert.match(fs.readFileSync(await download.path(), "utf8"), /^<svg[^>]*>.*<image [^>]*href="data:image\/png;base64,/s);
  // The four boxes together, in the page's coordinates.
  const boxes = await page.evaluate((ids) => ids.map((id) => {
    const r = document.getElementById(id).getBoundingClientRect();
    return { top: r.top + scrollY, bottom: r.bottom + scrollY, left: r.left + scrollX, right: r.right + scrollX };
  }), Object.values(STROKE_PLOT));
  const top = Math.min(...boxes.map((b) => b.top)), bottom = Math.max(...boxes.map((b) => b.bottom));
  const left = Math.min(...boxes.map((b) => b.left)), right = Math.max(...boxes.map((b) => b.right));
  await page.screenshot({ path: path.join(shots, "stroke-figures.png"), fullPage: true, clip: { x: left, y: top, width: right - left, height: bottom - top } });
}

async function phoneWidth(page) {
  step("at phone width the wear map fits the page, and the rig's fields are not cut");
  await page.setViewportSize({ width: 390, height: 844 });
  await page.waitForTimeout(400);
  const fit = await page.evaluate(([map, rig]) => ({
    right: document.querySelector(`#${map} canvas`).getBoundingClientRect().right,
    page: document.documentElement.clientWidth,
    narrowest: Math.min(...[...document.querySelectorAll(`#${rig} input, #${rig} select`)].map((el) => el.getBoundingClientRect().width)),
  }), [STROKE_PLOT.map, RIG.fields]);
  console.log(`   phone: ${JSON.stringify(fit)}`);
  assert.ok(fit.right <= fit.page, `the map reaches ${fit.right} px of ${fit.page}`);
  assert.ok(fit.narrowest >= 60, `a rig field is ${fit.narrowest} px wide`);
  await page.setViewportSize({ width: 1440, height: 1000 });
}

async function discRun(page) {
  step("the same scene on the disc: none of the stroke's figures");
  await page.selectOption(sel(RIG.kind), "disc");
  await page.click(sel(FORM.fieldsToJson));
  const sent = JSON.parse(await page.inputValue(sel(FORM.sceneJson)));
  assert.equal(sent.overrides.test.reciprocating, undefined);
  await submitAndWait(page);
  const result = await page.evaluate(() => e2e.run.currentResult());
  assert.equal(result.stroke, undefined, "a disc's result with a stroke");
  const hidden = await page.evaluate((ids) => ids.filter((id) => !document.getElementById(id).hidden), Object.values(STROKE_PLOT));
  assert.deepEqual(hidden, [], "stroke figures shown for a disc's run");
  assert.deepEqual(Object.values(await charts(page)), [null, null, null, null]);
  assert.equal(await page.locator(`${sel(STROKE_PLOT.map)} canvas`).count(), 0);
}

export async function stroke(page) {
  await refusedStroke(page);
  await strokeRun(page);
  await strokeFigures(page);
  await phoneWidth(page);
  await discRun(page);
}
