// Every figure the page draws, by the id of its box: the uPlot charts with what each
// draws (for the SVG and PNG export), and the figures drawn as SVG (the pressure maps).
import uPlot from "./uplot.js";
import { $ } from "./dom.js";

/** Line colours, each at least 4.5:1 against white (WCAG asks 3:1 of graphics). */
export const COLORS = ["#0a58ca", "#c2255c", "#1a7f37", "#b35900", "#6f42c1", "#0b7285", "#b42318", "#495057"];
export const MEASURED_COLOR = "#b42318";
export const ATTACHED_COLOR = "#1b1f24";
/** The fill of a band of x (the rubbing on the potential figure). */
export const BAND_COLOR = "rgba(179, 89, 0, 0.12)";

// Tick steps of 1, 2 and 5 times a power of ten (uPlot's default also has 2.5).
const ROUND_STEPS = [];
for (let e = -9; e <= 9; e++) for (const m of [1, 2, 5]) ROUND_STEPS.push(+(m * 10 ** e).toPrecision(1));

const HEIGHT = 260;
const charts = new Map();
const specs = new Map();
const svgFigures = new Map();

/** The uPlot chart drawn in the box `plotId`, if any. */
export const chart = (plotId) => charts.get(plotId);

/** What the line chart `plotId` last drew: { data, series, xLabel, yLabel }. */
export const spec = (plotId) => specs.get(plotId);

/** Removes the chart of `plotId`, if any. */
export function dropChart(plotId) {
  const existing = charts.get(plotId);
  if (existing) { existing.destroy(); charts.delete(plotId); }
}

/**
 * Keeps (or with null, clears) the SVG text of a figure that is not a uPlot chart; or a
 * function that makes it, for a figure whose SVG is costly and wanted only on export.
 */
export const setSvgFigure = (plotId, svg) => { svgFigures.set(plotId, svg); };

/** A figure's SVG text: undefined for a line chart's box, null while it has none. */
export function svgFigure(plotId) {
  if (!svgFigures.has(plotId)) return undefined;
  const svg = svgFigures.get(plotId);
  return typeof svg === "function" ? svg() : svg;
}

// A value for the legend: four significant figures; words where the cursor's point has none.
function legendValue(u, v) {
  if (u.cursor.idx == null) return "";
  return v == null ? "none at this point" : String(+v.toPrecision(4));
}
// uPlot writes "--" in the legend while the cursor is off the chart: nothing is said instead.
function blankLegend(u) {
  for (const td of u.root.querySelectorAll(".u-legend .u-value")) if (td.textContent === "--") td.textContent = "";
}

function chartWidth(plotId) {
  const box = $(plotId);
  return Math.max(240, Math.min(box.querySelector(".chart").clientWidth || box.clientWidth - 16, box.clientWidth - 16));
}

/** Fits every chart to its box's width again (after the window was resized). */
export function resizeAll() {
  for (const [id, plot] of charts) plot.setSize({ width: chartWidth(id), height: HEIGHT });
}

/** A line series: 2 px, across gaps, no points. */
export const lineSeries = (label, stroke) => ({ label, stroke, width: 2, spanGaps: true, points: { show: false } });

/**
 * A series of measured points only (no line): drawn as dots, exported as dots. `yErrors`,
 * if given, maps a point's x to the half-length of its error bar (in y's unit).
 */
export function markerSeries(label, color, yErrors = null) {
  return { label, stroke: color, fill: color, marker: true, yErrors, width: 0, paths: () => null, points: { show: true, size: 8, fill: color } };
}

/** The colour a series is drawn in (uPlot keeps it as a function). */
const strokeOf = (u, i) => (typeof u.series[i].stroke === "function" ? u.series[i].stroke(u, i) : u.series[i].stroke);

/** How a series is drawn, as its legend sample shows it: "marker", "dashed" or "line". */
export const sampleKind = (series) => (series.marker ? "marker" : series.dash ? "dashed" : "line");

// uPlot's legend marks every series with a square: a line, a dashed line and a measured
// point look alike. Each sample is redrawn as its series is: a short line, solid or
// dashed, or a dot.
function legendSamples(u) {
  u.root.querySelectorAll(".u-legend .u-series").forEach((row, i) => {
    const series = u.series[i], marker = row.querySelector(".u-marker");
    if (i === 0 || !marker) return;
    const kind = sampleKind(series);
    marker.dataset.sample = kind;
    Object.assign(marker.style, kind === "marker"
      ? { width: "8px", height: "8px", border: "none", borderRadius: "50%", background: strokeOf(u, i) }
      : { width: "24px", height: "0", border: "none", borderTop: `${series.width || 2}px ${kind === "dashed" ? "dashed" : "solid"} ${strokeOf(u, i)}`, background: "none", verticalAlign: "middle" });
  });
}

// The error bars of the series that have them: a vertical stroke from y - e to y + e with
// 4 px caps, in the series' colour, over the plot.
function errorBars(u) {
  const px = devicePixelRatio || 1;
  u.ctx.save();
  u.series.forEach((series, i) => {
    if (!series.yErrors || !series.show) return;
    u.ctx.strokeStyle = strokeOf(u, i);
    u.ctx.lineWidth = 1.5 * px;
    u.ctx.beginPath();
    u.data[0].forEach((x, k) => {
      const y = u.data[i][k], e = series.yErrors.get(x);
      if (y == null || !e) return;
      const cx = u.valToPos(x, "x", true), top = u.valToPos(y + e, "y", true), bottom = u.valToPos(y - e, "y", true);
      u.ctx.moveTo(cx, top); u.ctx.lineTo(cx, bottom);
      for (const end of [top, bottom]) { u.ctx.moveTo(cx - 4 * px, end); u.ctx.lineTo(cx + 4 * px, end); }
    });
    u.ctx.stroke();
  });
  u.ctx.restore();
}

// The y range holding every point and its error bar, padded as uPlot pads its own.
function errorRange(series) {
  return (u, min, max) => {
    for (const [i, s] of series.entries()) {
      if (!s.yErrors) continue;
      u.data[0].forEach((x, k) => {
        const y = u.data[i + 1][k], e = s.yErrors.get(x) || 0;
        if (y != null) { min = Math.min(min, y - e); max = Math.max(max, y + e); }
      });
    }
    return uPlot.rangeNum(min, max, 0.1, true);
  };
}

/** Several [x, y] tables on one x column (uPlot's join wants each sorted by x). */
export function joinTables(tables) {
  return tables.length > 1 ? uPlot.join(tables) : tables[0];
}

// Shades `band` ({ from, to } in x) across the plot, under the series.
function shade(band) {
  return (u) => {
    const left = Math.max(u.bbox.left, u.valToPos(band.from, "x", true));
    const right = Math.min(u.bbox.left + u.bbox.width, u.valToPos(band.to, "x", true));
    if (right <= left) return;
    u.ctx.save();
    u.ctx.fillStyle = BAND_COLOR;
    u.ctx.fillRect(left, u.bbox.top, right - left, u.bbox.height);
    u.ctx.restore();
  };
}

/**
 * An axis's tick labels, each with the digits its step needs: uPlot's own keep at most
 * three decimals, so ticks 0.0001 apart (a rough run's WAC volume) all read "0". Steps
 * under 0.001 are written as powers of ten, with as many digits as tell them apart.
 */
export function tickLabels(_u, splits, _axis, _space, incr) {
  const step = Math.abs(incr) || 1;
  const biggest = Math.max(0, ...splits.map((v) => Math.abs(v || 0)));
  if (step >= 1e-3 && biggest < 1e6) {
    const decimals = Math.max(0, Math.ceil(-Math.log10(step) - 1e-9));
    return splits.map((v) => (v == null ? "" : v.toFixed(decimals)));
  }
  const digits = Math.max(0, Math.floor(Math.log10(biggest || step)) - Math.floor(Math.log10(step) + 1e-9));
  return splits.map((v) => (v == null ? "" : v === 0 ? "0" : v.toExponential(digits)));
}

function chartOptions(plotId, series, xLabel, yLabel, extra) {
  return {
    width: chartWidth(plotId),
    height: HEIGHT,
    scales: { x: { time: false }, ...(series.some((s) => s.yErrors) ? { y: { range: errorRange(series) } } : {}), ...(extra.scales || {}) },
    axes: [
      { label: xLabel, stroke: "#1b1f24", grid: { stroke: "#eee" }, incrs: ROUND_STEPS, space: 45, values: tickLabels },
      { label: yLabel, stroke: "#1b1f24", grid: { stroke: "#eee" }, size: 60, incrs: ROUND_STEPS, space: 20, values: tickLabels },
    ],
    series: [{ label: xLabel, value: legendValue }, ...series.map((s) => ({ value: legendValue, ...s }))],
    legend: { live: true },
    // Every series reads the cursor's own row, so the legend's values are of one x (one
    // cycle, one time, one y), never of neighbouring points.
    cursor: { dataIdx: (_u, _s, idx) => idx },
    hooks: { ready: [blankLegend, legendSamples], setLegend: [blankLegend], drawClear: extra.band ? [shade(extra.band)] : [], draw: [errorBars] },
  };
}

/**
 * Draws (or updates) a uPlot line chart in the plot box `plotId`; `data` is uPlot's column
 * table; `points` is recorded on the box as data-points for tests and tools. The chart is
 * made anew when its series change or `extra.rebuild` asks; `extra.scales` adds scales;
 * `extra.band` ({ from, to, label }) shades a band of x under the series.
 */
export function linePlot(plotId, data, series, xLabel, yLabel, points, extra = {}) {
  const box = $(plotId);
  box.dataset.points = String(points);
  specs.set(plotId, { data, series, xLabel, yLabel, band: extra.band });
  const chartBox = box.querySelector(".chart");
  chartBox.setAttribute("role", "img");
  chartBox.setAttribute("aria-label", `${box.querySelector("h3").textContent}: ${series.map((s) => s.label).join("; ")}; ${points} points; ${yLabel} against ${xLabel}. The values are in the summary table and the downloads.`);
  const existing = charts.get(plotId);
  const sameSeries = existing && existing.series.length === series.length + 1 && series.every((s, i) => existing.series[i + 1].label === s.label);
  const sameBand = JSON.stringify(existing && existing.band) === JSON.stringify(extra.band);
  if (sameSeries && sameBand && !extra.rebuild) {
    existing.setData(data);
    return;
  }
  if (existing) existing.destroy();
  const made = new uPlot(chartOptions(plotId, series, xLabel, yLabel, extra), data, chartBox);
  made.band = extra.band;
  charts.set(plotId, made);
}
