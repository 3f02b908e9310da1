// The reciprocating rig's figures, from the result's `stroke` (docs/result.md): the wear map
// of the flat on a canvas, the depth along the track's centre line, and the potential and
// the anodic current over one cycle at the traced cycles. A disc's result has no `stroke`:
// the boxes stay hidden.
import { $ } from "./dom.js";
import { STROKE_PLOT } from "./ids.js";
import { COLORS, dropChart, joinTables, linePlot, lineSeries, setSvgFigure } from "./plots.js";
import { cellCanvas, colour, extent } from "./pressure.js";
import { esc, niceTicks } from "./svg.js";
import { getPath, referenceShort } from "./words.js";

const WAITING = "Shown after the run ends.";
const NO_CORROSION = "This scene has no corrosion model: nothing to plot.";
const X_LABEL = "x along the stroke (µm)";
const LINE_PLOTS = [STROKE_PLOT.profile, STROKE_PLOT.potential, STROKE_PLOT.current];

// The map's margins around the plot (left, top, right with the colour bar, bottom) and the
// bar's width, in px. The plot is as wide as the box; its height is to scale between
// MIN_H and MAX_H: a stroke is 10 to 50 times longer than the track is wide, so to scale
// it would be a line of a few pixels.
const L = 60, T = 10, R = 100, B = 42, BAR = 12, MIN_H = 120, MAX_H = 240;
const INK = "#1b1f24";
const FONT = "12px system-ui, -apple-system, Segoe UI, sans-serif";
// The exported picture's resolution: the PNG export's (export.js's PNG_SCALE), so that the
// export's pixels are the painted ones.
const EXPORT_SCALE = 3;

let settled = false; // a result decided whether the figures show: the scene no longer does

const isReciprocating = (scene) => Boolean(getPath(scene, "test.reciprocating"));
const fmt = (v) => String(+v.toPrecision(3));

function show(on) {
  for (const id of Object.values(STROKE_PLOT)) $(id).hidden = !on;
}

/** Empties and hides the figures until a result (or a reciprocating scene) comes. */
export function resetStroke() {
  settled = false;
  show(false);
  for (const id of Object.values(STROKE_PLOT)) {
    $(id).dataset.points = "0";
    $(id).querySelector(".note").textContent = WAITING;
  }
  for (const id of LINE_PLOTS) dropChart(id);
  $(STROKE_PLOT.map).querySelector(".heatmaps").replaceChildren();
  setSvgFigure(STROKE_PLOT.map, null);
}

/** Shows the figures, empty, while a run of a reciprocating scene has no result yet. */
export function expectStroke(scene) {
  if (!settled) show(isReciprocating(scene));
}

/** Draws the result's stroke figures; a result without `stroke` (a disc's) hides them. */
export function drawStroke(result) {
  settled = true;
  const stroke = result && result.stroke;
  show(Boolean(stroke));
  if (!stroke) return;
  // Shown before drawn: the charts take their box's width.
  drawMap(stroke.map);
  drawAxialProfile(stroke.axial_profile);
  drawTraces(stroke.traces || [], result);
}

// The map's frame: the canvas's size in CSS px, the plot's, its µm edges, and how much
// taller y is drawn than to scale.
function mapLayout(map, width) {
  const e = extent(map);
  const W = Math.max(360, Math.floor(width));
  const pw = W - L - R;
  const toScale = (pw * (e.y1 - e.y0)) / (e.x1 - e.x0);
  const ph = Math.round(Math.min(MAX_H, Math.max(MIN_H, toScale)));
  return { e, W, H: T + ph + B, pw, ph, stretch: ph / toScale };
}

// The x and y axes' ticks and labels, in µm.
function paintAxes(ctx, { e, pw, ph }) {
  const X = (v) => L + ((v - e.x0) / (e.x1 - e.x0)) * pw, Y = (v) => T + ph - ((v - e.y0) / (e.y1 - e.y0)) * ph;
  ctx.beginPath();
  ctx.textAlign = "center"; ctx.textBaseline = "top";
  for (const v of niceTicks(e.x0, e.x1, Math.max(2, Math.floor(pw / 70)))) {
    ctx.moveTo(X(v), T + ph); ctx.lineTo(X(v), T + ph + 4);
    ctx.fillText(String(v), X(v), T + ph + 6);
  }
  ctx.fillText(X_LABEL, L + pw / 2, T + ph + 24);
  ctx.textAlign = "right"; ctx.textBaseline = "middle";
  // At least three ticks asked: a narrow track's round ticks may fall outside it.
  for (const v of niceTicks(e.y0, e.y1, Math.max(3, Math.floor(ph / 30)))) {
    ctx.moveTo(L - 4, Y(v)); ctx.lineTo(L, Y(v));
    ctx.fillText(String(v), L - 6, Y(v));
  }
  ctx.stroke();
  ctx.save();
  ctx.translate(14, T + ph / 2); ctx.rotate(-Math.PI / 2);
  ctx.textAlign = "center";
  ctx.fillText("y across (µm)", 0, 0);
  ctx.restore();
}

// The colour bar right of the map, as pressure.js draws its own: its maximum labelled, a
// round tick about every 40 px, none crowding the maximum's label.
function paintColourBar(ctx, { W, ph }, dMax) {
  const bx = W - R + 16;
  for (let k = 0; k < ph; k++) {
    ctx.fillStyle = colour(1 - k / Math.max(1, ph - 1));
    ctx.fillRect(bx, T + k, BAR, 1);
  }
  ctx.strokeRect(bx, T, BAR, ph);
  ctx.fillStyle = INK;
  ctx.textAlign = "left"; ctx.textBaseline = "middle";
  ctx.fillText(`${fmt(dMax)} max`, bx + BAR + 4, T + 4);
  for (const v of niceTicks(0, dMax, Math.max(2, Math.floor(ph / 40)))) {
    const y = T + ph - (v / (dMax || 1)) * ph;
    if (y - T >= 14) ctx.fillText(String(v), bx + BAR + 4, y);
  }
  // On the x label's row: the row of the x ticks reaches under the bar.
  ctx.textBaseline = "top";
  ctx.fillText("depth (µm)", bx - 8, T + ph + 24);
}

// The whole figure: the cells (one block each, not smoothed into one another), the frame,
// the axes and the colour bar.
function paintMap(ctx, lay, cells, dMax) {
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, lay.W, lay.H);
  ctx.imageSmoothingEnabled = false;
  ctx.drawImage(cells, L, T, lay.pw, lay.ph);
  ctx.font = FONT;
  ctx.strokeStyle = INK; ctx.fillStyle = INK; ctx.lineWidth = 1;
  ctx.strokeRect(L, T, lay.pw, lay.ph);
  paintAxes(ctx, lay);
  paintColourBar(ctx, lay, dMax);
}

// Sizes `canvas` for the layout at `scale` device pixels per CSS px, and paints it.
function paintAt(canvas, lay, paint, scale) {
  canvas.width = Math.round(lay.W * scale);
  canvas.height = Math.round(lay.H * scale);
  canvas.style.width = `${lay.W}px`;
  const ctx = canvas.getContext("2d");
  ctx.scale(scale, scale);
  paint(ctx);
}

// The map for the export: the same painting at the PNG export's resolution, in an SVG of
// the on-screen size. The map is cells, a picture either way; one painter serves the page
// and the file. Made only when exported (a data URL of a few hundred kB).
function exportSvg(lay, paint, label) {
  const canvas = document.createElement("canvas");
  paintAt(canvas, lay, paint, EXPORT_SCALE);
  return `<svg xmlns="http://www.w3.org/2000/svg" width="${lay.W}" height="${lay.H}" viewBox="0 0 ${lay.W} ${lay.H}" role="img" aria-label="${esc(label)}"><image x="0" y="0" width="${lay.W}" height="${lay.H}" href="${canvas.toDataURL("image/png")}"/></svg>`;
}

// The depth under the cursor, in words, under the map.
function readoutFor(canvas, map, lay) {
  const readout = document.createElement("p");
  readout.className = "muted";
  readout.setAttribute("aria-live", "polite");
  const nx = map.x_um.length, ny = map.y_um.length;
  canvas.addEventListener("mousemove", (ev) => {
    const r = canvas.getBoundingClientRect();
    const k = lay.W / r.width; // the canvas shrinks with a narrow box
    const i = Math.floor((((ev.clientX - r.left) * k - L) / lay.pw) * nx);
    const j = Math.floor((1 - ((ev.clientY - r.top) * k - T) / lay.ph) * ny);
    const inside = i >= 0 && j >= 0 && i < nx && j < ny;
    readout.textContent = inside ? `x ${map.x_um[i].toFixed(1)} µm, y ${map.y_um[j].toFixed(1)} µm: depth ${map.depth_um[j][i].toFixed(3)} µm` : "";
  });
  canvas.addEventListener("mouseleave", () => { readout.textContent = ""; });
  return readout;
}

function mapNote(dMax, lay) {
  const scale = lay.stretch > 1.05 ? `y drawn ${lay.stretch.toFixed(1)} times the x scale, the track being long and narrow`
    : "x and y at one scale";
  return `Colour: wear depth below the original flat at the end of the run, 0 to ${fmt(dMax)} µm; x along the stroke, 0 at its middle; y across the track; ${scale}.`;
}

// The wear map: depth_um[iy][ix] on a canvas, with its axes and colour scale.
function drawMap(map) {
  const box = $(STROKE_PLOT.map), holder = box.querySelector(".heatmaps");
  const nx = map.x_um.length, ny = map.y_um.length;
  const dMax = map.depth_um.reduce((m, row) => row.reduce((a, d) => Math.max(a, d), m), 0);
  const cells = cellCanvas(map.depth_um, nx, ny, dMax);
  const lay = mapLayout(map, holder.clientWidth || box.clientWidth - 16);
  const paint = (ctx) => paintMap(ctx, lay, cells, dMax);
  const canvas = document.createElement("canvas");
  paintAt(canvas, lay, paint, devicePixelRatio || 1);
  const label = `Wear map of the flat: depth up to ${fmt(dMax)} µm over ${nx} × ${ny} cells`;
  canvas.setAttribute("role", "img");
  canvas.setAttribute("aria-label", label);
  holder.replaceChildren(canvas, readoutFor(canvas, map, lay));
  setSvgFigure(STROKE_PLOT.map, () => exportSvg(lay, paint, label));
  box.querySelector(".note").textContent = mapNote(dMax, lay);
  box.dataset.points = String(nx * ny);
}

// D(x): the depth along the track's centre line.
function drawAxialProfile(profile) {
  $(STROKE_PLOT.profile).querySelector(".note").textContent =
    "At the end of the run, along the track's centre line: the ends of the stroke see less sliding.";
  linePlot(STROKE_PLOT.profile, [profile.x_um, profile.depth_um], [lineSeries("depth on the centre line", COLORS[2])],
    X_LABEL, "wear depth (µm)", profile.x_um.length);
}

// A trace's times from its cycle's start: its samples sit at the middles of even
// intervals. Rounded, so that the cycles' times are the same numbers and share one x column.
function withinCycle(t) {
  const start = t[0] - (t.length > 1 ? t[1] - t[0] : 0) / 2;
  return t.map((v) => +(v - start).toPrecision(9));
}

// One quantity of the traces against the time within the cycle, a line per traced cycle.
function drawTrace(plotId, traces, key, yLabel, note) {
  const box = $(plotId);
  if (!traces.length) {
    dropChart(plotId);
    box.dataset.points = "0";
    box.querySelector(".note").textContent = NO_CORROSION;
    return;
  }
  box.querySelector(".note").textContent = note;
  const tables = traces.map((tr) => [withinCycle(tr.time_s), tr[key]]);
  const series = traces.map((tr, i) => lineSeries(`cycle ${tr.cycle}`, COLORS[i % COLORS.length]));
  linePlot(plotId, joinTables(tables), series, "time within the cycle (s)", yLabel,
    traces.reduce((n, tr) => n + tr.time_s.length, 0), { rebuild: true });
}

// What the potential figure says: why it swings, or that it does not (a capped potential).
function potentialNote(traces) {
  const all = traces.flatMap((tr) => tr.potential_v);
  if (!all.length) return NO_CORROSION;
  const lo = Math.min(...all), hi = Math.max(...all);
  return hi - lo > 1e-9 ? "One cycle, forward and back: the ball uncovers the track twice a cycle, so the potential swings at twice the stroke's frequency."
    : `The potential holds at ${fmt(lo)} V over these cycles; the run's warnings say when it was capped at E_corr.`;
}

// The potential and the anodic current over one cycle (forward and back) at the first, the
// recorded and the last cycles.
function drawTraces(traces, result) {
  const reference = referenceShort((result.summary && result.summary.potential_reference) || getPath(result.scene, "corrosion.reference_electrode"));
  drawTrace(STROKE_PLOT.potential, traces, "potential_v", `potential (V vs ${reference})`, potentialNote(traces));
  drawTrace(STROKE_PLOT.current, traces, "anodic_current_ma", "anodic current (mA)",
    "One cycle, forward and back: the current the bare area passes as the ball strips and leaves the track.");
}
