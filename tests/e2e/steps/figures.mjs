// The run's figures as a reader sees them, on the preset's run: each legend entry's sample
// drawn as its series is (a solid line, a dashed line, a dot), Table 3's error bars on the
// chart's pixels, and the pressure maps' colour bar in MPa.
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";

import { RUN, RUN_PLOT } from "../../../static/js/ids.js";
import { openPage, sel, shots, step } from "../lib.mjs";

const TABLE3 = "Table 3, measured";

// Each legend entry of the chart `plotId`: the sample it should show (the page's own
// `sampleKind` of its series) and the one its rendered style shows, with its colour.
const legendOf = (page, plotId) => page.evaluate((id) => {
  const u = e2e.plots.chart(id);
  return [...u.root.querySelectorAll(".u-legend .u-series")].slice(1).map((row, k) => {
    const m = getComputedStyle(row.querySelector(".u-marker"));
    const drawn = m.borderRadius === "50%" && m.borderTopStyle === "none" ? "marker"
      : m.borderBottomStyle !== "none" ? "square" : m.borderTopStyle;
    return {
      label: u.series[k + 1].label,
      expected: e2e.plots.sampleKind(u.series[k + 1]),
      drawn: drawn === "solid" ? "line" : drawn,
      colour: drawn === "marker" ? m.backgroundColor : m.borderTopColor,
    };
  });
}, plotId);

async function legends(page) {
  step("each legend entry is drawn as its series is: solid line, dashed line, dot");
  for (const id of [RUN_PLOT.volume, RUN_PLOT.potential, RUN_PLOT.profile]) {
    const entries = await legendOf(page, id);
    console.log(`   ${id}: ${JSON.stringify(entries.map((e) => [e.label, e.drawn]))}`);
    for (const e of entries) assert.equal(e.drawn, e.expected, `${id}: the sample of ${e.label}`);
    const looks = entries.map((e) => `${e.drawn} ${e.colour}`);
    assert.equal(new Set(looks).size, looks.length, `${id}: two entries look alike: ${looks}`);
  }
  const kinds = new Set((await legendOf(page, RUN_PLOT.potential)).map((e) => e.drawn));
  assert.ok(kinds.has("dashed") && kinds.has("line"), "the potential's E_corr is not shown dashed beside the solid potential");
}

// Table 3's error bars as pixels of the volume chart: red along each bar that reaches past
// its dot (6 px), at three quarters of its length above and below the point, and white
// 12 px to its right; every bar inside the y range.
async function errorBars(page) {
  step("Table 3's spreads are error bars on the volume chart, inside its range");
  const bars = await page.evaluate(([id, label]) => {
    const u = e2e.plots.chart(id);
    const k = u.series.findIndex((s) => s.label === label);
    const dpr = devicePixelRatio || 1;
    const pixel = (x, y) => [...u.ctx.getImageData(Math.round(x), Math.round(y), 1, 1).data].slice(0, 3);
    // The reddest of the three pixels across the 1.5 px stroke.
    const across = (x, y) => [-1, 0, 1].map((d) => pixel(x + d, y)).sort((a, b) => (b[0] - b[2]) - (a[0] - a[2]))[0];
    return u.data[0].flatMap((x, i) => {
      const y = u.data[k][i];
      if (y == null) return [];
      const e = u.series[k].yErrors.get(x) || 0;
      const cx = u.valToPos(x, "x", true), at = (v) => u.valToPos(v, "y", true);
      return [{
        x, y, e, reachPx: Math.abs(at(y + 0.75 * e) - at(y)) / dpr,
        inRange: u.scales.y.min <= y - e && y + e <= u.scales.y.max,
        above: across(cx, at(y + 0.75 * e)), below: across(cx, at(y - 0.75 * e)), off: pixel(cx + 12 * dpr, at(y + 0.75 * e)),
      }];
    });
  }, [RUN_PLOT.volume, TABLE3]);
  console.log(`   bars: ${JSON.stringify(bars.map((b) => [b.x, b.e, +b.reachPx.toFixed(1), b.above, b.off]))}`);
  assert.equal(bars.length, 5, "Table 3's five points");
  // MEASURED_COLOR is #b42318: red well over green and blue; white and the grey grid are not.
  const red = ([r, g, b]) => r - g > 60 && r - b > 60;
  const checked = bars.filter((b) => b.reachPx > 6);
  assert.ok(checked.length >= 1, "no bar reaches past its dot: nothing to see");
  for (const b of bars) assert.ok(b.inRange, `the bar at ${b.x} is cut by the y range`);
  for (const b of checked) {
    assert.ok(red(b.above) && red(b.below), `no bar drawn at cycle ${b.x}: ${b.above} ${b.below}`);
    assert.ok(!red(b.off), `red beside the bar at cycle ${b.x}: ${b.off}`);
  }

  step("the volume figure's SVG export draws the same error bars");
  const [download] = await Promise.all([page.waitForEvent("download"), page.click(`${sel(RUN_PLOT.volume)} .export-svg`)]);
  const exported = await page.evaluate(([text, label]) => {
    const doc = new DOMParser().parseFromString(text, "image/svg+xml");
    const d = doc.querySelector(`g[data-series="${label}"] path.error-bars`)?.getAttribute("d") || "";
    // Each bar is "M x top V bottom" and two caps "M x y h8".
    return d.match(/V/g)?.length || 0;
  }, [fs.readFileSync(await download.path(), "utf8"), TABLE3]);
  const spread = bars.filter((b) => b.e > 0).length;
  assert.equal(exported, spread, `the export draws ${exported} bars for ${spread} spreads`);
}

async function colourBar(page) {
  step("the pressure maps have a colour bar with ticks in MPa");
  const bar = await page.evaluate((id) => {
    const svg = document.querySelector(`#${id} svg`);
    const rect = svg.querySelector('rect[fill^="url(#"]');
    const right = Number(rect.getAttribute("x")) + Number(rect.getAttribute("width"));
    const texts = [...svg.querySelectorAll("text")];
    const beside = texts.filter((t) => Number(t.getAttribute("x")) > right);
    return {
      height: Number(rect.getAttribute("height")),
      gradientStops: svg.querySelectorAll(`${rect.getAttribute("fill").slice(4, -1)} stop`).length,
      ticks: beside.map((t) => t.textContent).filter((t) => /^\d+$/.test(t)).map(Number),
      unit: texts.some((t) => t.textContent === "MPa"),
    };
  }, RUN_PLOT.pressure);
  console.log(`   colour bar: ${JSON.stringify(bar)}`);
  assert.ok(bar.height > 100 && bar.gradientStops >= 2, "no colour bar beside the maps");
  assert.ok(bar.unit, "the colour bar has no unit");
  assert.ok(bar.ticks.length >= 3 && bar.ticks.includes(0), `the colour bar's ticks: ${bar.ticks}`);
  await page.locator(sel(RUN_PLOT.pressure)).screenshot({ path: path.join(shots, "pressure-maps.png") });
}

export async function figures(page, found) {
  await openPage(page, `#run=${found.presetRun}`);
  await page.waitForFunction((run) => e2e.run.selectedId() === run && e2e.run.currentResult(), found.presetRun);
  await page.waitForFunction((id) => Number(document.getElementById(id).dataset.points) > 0, RUN_PLOT.pressure);
  assert.ok(await page.isChecked(sel(RUN.showTable3)), "Table 3 is not shown beside the preset's run");
  await page.waitForFunction((id) => Number(document.getElementById(id).dataset.measured) === 5, RUN_PLOT.volume);
  await legends(page);
  await errorBars(page);
  await colourBar(page);
}
