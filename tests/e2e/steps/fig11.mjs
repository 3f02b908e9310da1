// The paper's Fig. 11 view of the preset's run: a refused companion said so; its own EPP
// records and an elastic companion run over the first 300 cycles with Table 3's points
// there; the companion re-used when the view is asked again; the view refused, with the
// reason, beside the 10 N run; beside an elastic run, an EPP companion; the page opened
// without an address shows a run, not a companion.
import assert from "node:assert/strict";
import path from "node:path";

import { RUN, RUN_PLOT } from "../../../static/js/ids.js";
import { RUN_LIMIT, openPage, points, sel, shots, step } from "../lib.mjs";

const EPP = "EPP (elastic-perfectly-plastic)";
const ELASTIC = "elastic (perfectly elastic)";
const MEASURED = "Table 3, measured";

// The companion runs on the server: the jobs tagged fig11.
const companions = (page) => page.evaluate(async () => (await e2e.api.api("/api/v1/jobs?tag=fig11")).body);

// Opens run `id` and turns the view on once the run's scene allows it; waits for the
// view's `state` (ready: both curves drawn).
async function viewOn(page, id, state = "ready") {
  await openPage(page, `#run=${id}`);
  await page.waitForFunction((run) => e2e.run.selectedId() === run && e2e.run.currentResult(), id);
  await page.waitForFunction((box) => !document.getElementById(box).disabled, RUN.showFig11);
  // Every frame's note, to see that the page said what it was computing.
  await page.evaluate((note) => {
    window.fig11Notes = [];
    const sample = () => {
      const text = document.getElementById(note).textContent;
      if (!window.fig11Notes.includes(text)) window.fig11Notes.push(text);
      requestAnimationFrame(sample);
    };
    requestAnimationFrame(sample);
  }, RUN.fig11Note);
  await page.check(sel(RUN.showFig11));
  await waitForView(page, state);
}

const waitForView = (page, state) =>
  page.waitForFunction(([box, s]) => document.getElementById(box).dataset.fig11 === s, [RUN_PLOT.volume, state], { timeout: RUN_LIMIT });

// The companion's submission answered as a full queue would: the view says why, the rest
// of the run's figures stay; ticked again, it is asked for anew.
async function refusedCompanion(page, found) {
  step("the companion refused (a full queue, played by the browser): the view says why, the rest stays");
  const companionPost = (url) => url.pathname === "/api/v1/jobs" && url.searchParams.get("tags") === "fig11";
  await page.route(companionPost, (route) => (route.request().method() === "POST"
    ? route.fulfill({ status: 429, contentType: "application/json", body: JSON.stringify({ error: "the queue is full" }) })
    : route.continue()));
  await viewOn(page, found.presetRun, "failed");
  await page.unroute(companionPost);
  const note = await page.textContent(sel(RUN.fig11Note));
  console.log(`   ${note}`);
  assert.match(note, /the elastic companion failed: the server refused it: the queue is full; tick the view again to retry/);
  assert.deepEqual((await drawnSeries(page)).slice(0, 2).map((s) => s.label), [EPP, MEASURED]);
  for (const id of [RUN_PLOT.depth, RUN_PLOT.potential, RUN_PLOT.profile]) assert.ok(await points(page, id) > 0, `${id} is empty`);
  assert.deepEqual(await companions(page), [], "a refused companion left a job");
  await page.uncheck(sel(RUN.showFig11));
  assert.equal(await page.textContent(sel(RUN.fig11Note)), "");
}

// The volume chart's series: each one's label and its (cycle, value) points.
const drawnSeries = (page) => page.evaluate((volume) => {
  const u = e2e.plots.chart(volume);
  return u.series.slice(1).map((s, k) => ({
    label: s.label,
    points: u.data[0].map((x, i) => [x, u.data[k + 1][i]]).filter(([, y]) => y != null),
  }));
}, RUN_PLOT.volume);

async function view(page, found) {
  step("the Fig. 11 view of the preset's run: EPP (its records), elastic (a companion run), Table 3 to 300 cycles");
  await page.check(sel(RUN.showFig11));
  await waitForView(page, "ready");
  const notes = await page.evaluate(() => window.fig11Notes);
  console.log(`   notes: ${JSON.stringify(notes.filter(Boolean).slice(0, 3))}`);
  assert.ok(notes.some((n) => /computing the elastic companion/.test(n)), "the view never said it was computing the companion");
  const series = await drawnSeries(page);
  console.log(`   series: ${JSON.stringify(series.map((s) => [s.label, s.points.length, s.points[s.points.length - 1]]))}`);
  assert.deepEqual(series.slice(0, 3).map((s) => s.label), [EPP, ELASTIC, MEASURED]);
  // The wear volumes the measurements step attached to this run, those within the view.
  for (const s of series.slice(3)) {
    assert.equal(s.label, "attached measurement");
    assert.ok(s.points.every(([x]) => x <= 300), `attached points past the view: ${JSON.stringify(s.points)}`);
  }
  const [epp, elastic, measured] = series.map((s) => s.points);
  assert.deepEqual(measured.map((p) => p[0]), [10, 60, 300], "Table 3's points within 300 cycles");
  for (const curve of [epp, elastic]) {
    assert.ok(curve.length > 2 && curve[0][0] >= 1 && curve[curve.length - 1][0] === 300, `a curve does not span cycles 1 to 300: ${JSON.stringify(curve.slice(0, 3))}`);
  }
  // The EPP curve is the run's own records to cycle 300.
  const own = await page.evaluate(() => e2e.run.currentResult().cycles.filter((r) => r.cycle <= 300).map((r) => [r.cycle, r.wear_volume_mm3 * 1e3]));
  assert.deepEqual(epp, own);
  // The yield groove is EPP's alone: at cycle 300 its volume lies over the elastic one
  // (docs/paper.md, Fig. 11: 1.23 against 1.05e-3 mm^3 on the paper's mesh).
  assert.ok(epp[epp.length - 1][1] > elastic[elastic.length - 1][1], "the EPP curve is not over the elastic one at cycle 300");

  step("the companion: an ordinary job, labelled, of the run's scene with the cap off and 300 cycles");
  const [job] = await companions(page);
  assert.equal(job.status, "succeeded");
  assert.equal(job.note, `Fig. 11 elastic companion of ${found.presetRun}`);
  const [ownScene, companionScene, companionResult] = await page.evaluate(async ([run, companion]) => [
    (await e2e.api.api(`/api/v1/jobs/${run}/scene`)).body,
    (await e2e.api.api(`/api/v1/jobs/${companion}/scene`)).body,
    (await e2e.api.api(`/api/v1/jobs/${companion}/result?compact=true`)).body,
  ], [found.presetRun, job.id]);
  assert.equal(companionScene.wear.plasticity, "off");
  assert.equal(companionScene.test.cycles, 300);
  assert.deepEqual({ ...companionScene, name: "", wear: null, test: { ...companionScene.test, cycles: 0 } },
    { ...ownScene, name: "", wear: null, test: { ...ownScene.test, cycles: 0 } }, "the companion's scene differs in more than the cap and the cycles");
  assert.deepEqual(elastic, companionResult.cycles.map((r) => [r.cycle, r.wear_volume_mm3 * 1e3]));
  await page.locator(sel(RUN_PLOT.volume)).screenshot({ path: path.join(shots, "fig11-view.png") });
  found.fig11Companion = job.id;
}

async function reused(page, found) {
  step("asked again, on the page reopened, the view re-uses the companion: no second job");
  await viewOn(page, found.presetRun);
  const jobs = await companions(page);
  assert.deepEqual(jobs.map((j) => j.id), [found.fig11Companion]);
  assert.match(await page.textContent(sel(RUN.fig11Note)), new RegExp(`elastic: the companion run ${found.fig11Companion}`));
  assert.deepEqual((await drawnSeries(page)).slice(0, 3).map((s) => s.label), [EPP, ELASTIC, MEASURED]);
}

async function refused(page, found) {
  step("the 10 N run: the Fig. 11 view is disabled, and the page says why");
  await openPage(page, `#run=${found.tenRun}`);
  await page.waitForFunction((note) => /differ/.test(document.getElementById(note).textContent), RUN.table3Note);
  assert.equal(await page.isDisabled(sel(RUN.showFig11)), true);
  const reason = await page.textContent(sel(RUN.table3Note));
  console.log(`   ${reason}`);
  assert.match(reason, /Fig\. 11 view are not shown: this run's load differs/);
}

// The view beside an elastic run: the elastic companion itself, whose own records are the
// elastic curve and whose EPP curve is a companion of its own.
async function besideElastic(page, found) {
  step("beside an elastic run (the elastic companion itself): its records, and an EPP companion of its own");
  await viewOn(page, found.fig11Companion);
  const series = await drawnSeries(page);
  assert.deepEqual(series.slice(0, 3).map((s) => s.label), [EPP, ELASTIC, MEASURED]);
  const own = await page.evaluate(() => e2e.run.currentResult().cycles.map((r) => [r.cycle, r.wear_volume_mm3 * 1e3]));
  assert.deepEqual(series[1].points, own, "the elastic curve is not the run's own records");
  const epp = (await companions(page)).find((job) => job.id !== found.fig11Companion);
  assert.equal(epp.note, `Fig. 11 EPP companion of ${found.fig11Companion}`);
  const scene = await page.evaluate(async (id) => (await e2e.api.api(`/api/v1/jobs/${id}/scene`)).body, epp.id);
  assert.deepEqual([scene.wear.plasticity, scene.test.cycles], ["on", 300]);
  const [eppCurve, elastic] = series.map((s) => s.points);
  assert.ok(eppCurve[eppCurve.length - 1][1] > elastic[elastic.length - 1][1], "the EPP curve is not over the elastic one at cycle 300");
  found.fig11Newest = epp.id;
}

// The companions are the newest jobs now; the page opened without an address shows the
// newest run the user submitted.
async function openedWithoutAddress(page, found) {
  step("opened without an address, the page shows the newest run, not the newer companions");
  await page.goto("about:blank");
  await openPage(page);
  const listed = await page.evaluate(async () => (await e2e.api.api("/api/v1/jobs?limit=50")).body);
  assert.equal(listed[0].id, found.fig11Newest, "a companion is not the newest job");
  const newestRun = listed.find((job) => !(job.tags || []).includes("fig11"));
  await page.waitForFunction((id) => e2e.run.selectedId() === id, newestRun.id);
  assert.ok(page.url().endsWith(`#run=${newestRun.id}`), page.url());
}

export async function fig11(page, found) {
  await refusedCompanion(page, found);
  await view(page, found);
  await reused(page, found);
  await refused(page, found);
  await besideElastic(page, found);
  await openedWithoutAddress(page, found);
}
