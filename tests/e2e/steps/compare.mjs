// A 10 N run beside the preset's: no Table 3 for it, "Edit and run again", the two runs
// compared, and the comparison's figure exported as SVG and PNG.
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";

import { COMPARE, COMPARE_PLOT, COMPARE_X, FORM, JOBS, RUN, RUN_PLOT, fieldId } from "../../../static/js/ids.js";
import { GRID, sel, shots, step, waitForStatus } from "../lib.mjs";

const selectedRow = `${sel(JOBS.table)} tbody tr.selected`;

async function tenNewtons(page, found) {
  step("a 10 N run: no Table 3 beside it, and the page says why");
  await page.fill(sel(fieldId("test.load_n")), "10");
  found.presetRun = await page.$eval(selectedRow, (tr) => tr.dataset.id);
  await page.click(sel(FORM.submit));
  await page.waitForFunction(([rows, id]) => {
    const tr = document.querySelector(rows);
    return tr && tr.dataset.id !== id;
  }, [selectedRow, found.presetRun]);
  await waitForStatus(page, RUN.status, "succeeded");
  await page.waitForFunction((id) => Number(document.getElementById(id).dataset.points) > 0, RUN_PLOT.pressure);
  assert.equal(await page.$eval(sel(RUN_PLOT.volume), (el) => el.dataset.measured), "0");
  assert.equal(await page.isDisabled(sel(RUN.showTable3)), true);
  assert.match(await page.textContent(sel(RUN.table3Note)), /differ/);
  found.tenRun = await page.$eval(selectedRow, (tr) => tr.dataset.id);
}

async function editAgain(page) {
  step("edit and run again: the form takes the run's values, and the name follows the fields");
  const load = sel(fieldId("test.load_n"));
  await page.click(sel(RUN.editAgain));
  assert.equal(await page.inputValue(load), "10");
  assert.equal(await page.inputValue(sel(fieldId("numerics.grid"))), GRID);
  assert.match(await page.inputValue(sel(FORM.name)), /load 10 N/);
  await page.fill(load, "7");
  assert.match(await page.inputValue(sel(FORM.name)), /load 7 N/);
  assert.doesNotMatch(await page.inputValue(sel(FORM.name)), /10 N/);
  await page.fill(load, "5");
}

async function comparison(page, found) {
  step("compare the 5 N and the 10 N runs: both curves, a legend from their scenes, summaries side by side");
  for (const id of [found.presetRun, found.tenRun]) await page.check(`${sel(JOBS.table)} tr[data-id="${id}"] .compare-pick`);
  await page.click(sel(JOBS.compare));
  await page.waitForSelector(`${sel(COMPARE.panel)}:not([hidden])`);
  for (const id of Object.values(COMPARE_PLOT)) {
    await page.waitForFunction((plotId) => document.getElementById(plotId).dataset.curves === "2", id);
  }
  const compared = await page.evaluate(([volume, table]) => {
    const u = e2e.plots.chart(volume);
    return {
      labels: u.series.slice(1).map((s) => s.label),
      points: u.data.slice(1).map((col) => col.filter((v) => v != null).length),
      colours: u.series.slice(1).map((s) => s._stroke || s.stroke),
      table: document.getElementById(table).innerText,
    };
  }, [COMPARE_PLOT.volume, COMPARE.table]);
  console.log(`   comparison: ${JSON.stringify({ labels: compared.labels, points: compared.points })}`);
  assert.deepEqual(compared.labels, ["load 5 N", "load 10 N"]);
  assert.ok(compared.points.every((n) => n > 10), `a curve is missing: ${compared.points}`);
  assert.notEqual(compared.colours[0], compared.colours[1]);
  assert.match(compared.table, /load \(N\)\s+5\s+10/);
  assert.match(compared.table, /wear volume \(10⁻³ mm³\)\s+[\d.]+\s+[\d.]+ \(\+[\d.]+ %\)/);
  await page.check(`input[name="${COMPARE_X}"][value="time"]`);
  assert.equal(await page.evaluate((id) => e2e.plots.spec(id).xLabel, COMPARE_PLOT.volume), "time (s)");
  await page.check(`input[name="${COMPARE_X}"][value="cycles"]`);
  await page.locator(sel(COMPARE.panel)).screenshot({ path: path.join(shots, "comparison.png") });
}

// A downloaded SVG as the browser reads it.
const readSvg = (page, text) => page.evaluate((svgText) => {
  const doc = new DOMParser().parseFromString(svgText, "image/svg+xml");
  const root = doc.documentElement;
  return {
    error: doc.querySelector("parsererror") ? doc.querySelector("parsererror").textContent : null,
    width: Number(root.getAttribute("width")), height: Number(root.getAttribute("height")),
    lines: [...doc.querySelectorAll("polyline")].map((l) => [l.getAttribute("data-series"), l.getAttribute("points").split(" ").length]),
    texts: [...doc.querySelectorAll("text")].map((t) => t.textContent),
  };
}, text);

async function exports(page) {
  step("export the comparison's volume figure as SVG and PNG, and open both");
  const [svgDownload] = await Promise.all([page.waitForEvent("download"), page.click(`${sel(COMPARE_PLOT.volume)} .export-svg`)]);
  const svg = await readSvg(page, fs.readFileSync(await svgDownload.path(), "utf8"));
  console.log(`   ${svgDownload.suggestedFilename()}: ${svg.width} x ${svg.height}, lines ${JSON.stringify(svg.lines)}`);
  assert.equal(svg.error, null);
  assert.deepEqual(svg.lines.map((l) => l[0]), ["load 5 N", "load 10 N"]);
  assert.ok(svg.lines.every((l) => l[1] > 10));
  for (const text of ["wear volume (10⁻³ mm³)", "cycles (passes of the ball)", "load 5 N", "load 10 N"]) assert.ok(svg.texts.includes(text), `the SVG lacks "${text}"`);
  const [pngDownload] = await Promise.all([page.waitForEvent("download"), page.click(`${sel(COMPARE_PLOT.volume)} .export-png`)]);
  const png = fs.readFileSync(await pngDownload.path());
  assert.equal(png.subarray(1, 4).toString("latin1"), "PNG");
  const pngSize = [png.readUInt32BE(16), png.readUInt32BE(20)];
  // Decoded as an image: the page's content policy lets it show data: images, not fetch them.
  const decoded = await page.evaluate(async (b64) => {
    const image = new Image();
    image.src = "data:image/png;base64," + b64;
    await image.decode();
    return [image.naturalWidth, image.naturalHeight];
  }, png.toString("base64"));
  console.log(`   ${pngDownload.suggestedFilename()}: ${pngSize.join(" x ")} px, ${png.length} bytes`);
  assert.deepEqual(pngSize, [svg.width * 3, svg.height * 3]);
  assert.deepEqual(decoded, pngSize);
  const [mapDownload] = await Promise.all([page.waitForEvent("download"), page.click(`${sel(RUN_PLOT.pressure)} .export-svg`)]);
  const mapRects = await page.evaluate((text) => new DOMParser().parseFromString(text, "image/svg+xml").querySelectorAll("g[data-cycle] rect").length, fs.readFileSync(await mapDownload.path(), "utf8"));
  assert.ok(mapRects > 100, `the pressure maps' SVG has ${mapRects} cells`);
}

export async function compare(page, found) {
  await tenNewtons(page, found);
  await editAgain(page);
  await comparison(page, found);
  await exports(page);
}
