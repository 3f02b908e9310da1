// A rough disc: a height map uploaded, and the run's contact cells drawn one per pixel.
import assert from "node:assert/strict";

import { FORM, RUN, RUN_PLOT, fieldId } from "../../../static/js/ids.js";
import { openPage, sel, step, waitForStatus } from "../lib.mjs";

// Each map's frame, contact image and cells, as drawn and as the result has them.
const drawnMaps = (page) => page.evaluate(async (id) => Promise.all([...document.querySelectorAll(`#${id} svg g[data-cycle]`)].map(async (g) => {
  const result = e2e.run.currentResult();
  const map = result.pressure_maps.find((m) => m.cycle === Number(g.dataset.cycle));
  const frame = g.querySelector("rect.frame"), image = g.querySelector("image.contact");
  const picture = new Image();
  picture.src = image.getAttribute("href");
  await picture.decode();
  const canvas = document.createElement("canvas");
  canvas.width = picture.naturalWidth; canvas.height = picture.naturalHeight;
  const ctx = canvas.getContext("2d");
  ctx.drawImage(picture, 0, 0);
  const alpha = ctx.getImageData(0, 0, canvas.width, canvas.height).data.filter((_, k) => k % 4 === 3);
  const span = (c) => c[c.length - 1] - c[0] + (c[1] - c[0]);
  return {
    cycle: map.cycle, cellUm: map.x_um[1] - map.x_um[0], umPerPx: Number(g.dataset.umPerPx),
    spanX: span(map.x_um), spanY: span(map.y_um), width: Number(frame.getAttribute("width")), height: Number(frame.getAttribute("height")),
    imageWidth: Number(image.getAttribute("width")), cells: [map.x_um.length, map.y_um.length], pixels: [picture.naturalWidth, picture.naturalHeight],
    contact: map.pressure_mpa.flat().filter((p) => p > 0).length, drawn: alpha.filter((a) => a > 0).length,
    surface: Boolean(result.surface),
  };
})), RUN_PLOT.pressure);

export async function rough(page) {
  step("a rough run on an uploaded height map: its contact cells drawn one cell per pixel, to scale");
  await page.setViewportSize({ width: 1440, height: 1000 });
  await openPage(page);
  // A 64 x 64 text matrix of heights in m, 1 µm pixels: ripples of about 0.1 µm.
  const side = 64;
  const rows = Array.from({ length: side }, (_, j) => Array.from({ length: side },
    (_, i) => (1e-7 * (Math.sin(0.9 * i) + Math.cos(0.7 * j + 0.3 * i))).toExponential(6)).join(" "));
  await page.fill(sel(FORM.surfacePixel), "1");
  await page.setInputFiles(sel(FORM.surfaceFile), { name: "ripples.txt", mimeType: "text/plain", buffer: Buffer.from(rows.join("\n") + "\n") });
  await page.locator(sel(FORM.surfaceStatus), { hasText: "64 × 64 pixels" }).waitFor();
  console.log(`   ${await page.textContent(sel(FORM.surfaceStatus))}`);
  await page.fill(sel(fieldId("numerics.grid")), "128");
  await page.fill(sel(fieldId("test.cycles")), "3");
  const surfaceInScene = JSON.parse(await page.inputValue(sel(FORM.sceneJson))).overrides.disc.surface;
  assert.equal(surfaceInScene.kind, "measured");
  // The page opened the newest run on load: its status and maps are the old run's until
  // the new one is shown.
  const before = await page.evaluate(() => e2e.run.selectedId());
  await page.click(sel(FORM.submit));
  await page.waitForFunction((id) => e2e.run.selectedId() !== id, before);
  await waitForStatus(page, RUN.status, "succeeded");
  await page.waitForFunction((id) => Number(document.getElementById(id).dataset.points) > 0, RUN_PLOT.pressure);
  const roughMaps = await drawnMaps(page);
  console.log(`   rough maps: ${JSON.stringify(roughMaps)}`);
  assert.ok(roughMaps.length >= 1 && roughMaps.every((m) => m.surface));
  for (const m of roughMaps) {
    // One cell per pixel, to the float error of x_um's differences; frames and images at
    // that one scale to the 0.005 px of their two written decimals.
    assert.ok(Math.abs(m.umPerPx / m.cellUm - 1) < 1e-9, `map ${m.cycle}: ${m.umPerPx} µm per px, cells of ${m.cellUm} µm`);
    assert.ok(Math.abs(m.spanX / m.umPerPx - m.width) <= 0.0051 && Math.abs(m.spanY / m.umPerPx - m.height) <= 0.0051, `map ${m.cycle}: not to scale`);
    assert.equal(m.imageWidth, m.width);
    assert.deepEqual(m.pixels, m.cells, `map ${m.cycle}: the image is not one pixel per cell`);
    assert.ok(m.contact > 0 && m.drawn === m.contact, `map ${m.cycle}: ${m.drawn} pixels drawn for ${m.contact} contact cells`);
  }

  step("every axis of the rough run's figures has distinct tick labels; Table 3's reason names the surface");
  const repeated = await page.evaluate((ids) => ids.flatMap((id) => {
    const u = e2e.plots.chart(id);
    if (!u) return [];
    return u.axes.map((axis, k) => [id, k, axis._values || []])
      .filter(([, , labels]) => new Set(labels.filter((l) => l !== "")).size !== labels.filter((l) => l !== "").length);
  }), [RUN_PLOT.volume, RUN_PLOT.depth, RUN_PLOT.potential, RUN_PLOT.wac]);
  const wac = await page.evaluate((id) => { const u = e2e.plots.chart(id); return u ? u.axes[1]._values : null; }, RUN_PLOT.wac);
  console.log(`   WAC axis: ${JSON.stringify(wac)}`);
  assert.ok(wac && wac.length > 1, "the WAC figure has y ticks");
  assert.deepEqual(repeated, [], "an axis repeats a tick label");
  const reason = await page.textContent(sel(RUN.table3Note));
  console.log(`   ${reason}`);
  assert.match(reason, /disc's surface differs/);
  assert.doesNotMatch(reason, /load|speed|material/);
}
