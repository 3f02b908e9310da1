// The run's contact pressure maps at the first and last cycle, as one SVG: one colour scale
// (MPa) and one length scale (the same µm per pixel on x, on y and on both maps), so they
// compare by eye. Its colour scale, cell picture and map extents serve the reciprocating
// rig's wear map too (stroke.js).
import { $ } from "./dom.js";
import { RUN_PLOT } from "./ids.js";
import { setSvgFigure } from "./plots.js";
import { FONT, esc, niceTicks } from "./svg.js";

const BOX = RUN_PLOT.pressure;
const WAITING = "Shown after the run ends.";

// A perceptually ordered colour scale (viridis, sampled), interpolated.
const VIRIDIS = [[68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142], [31, 158, 137], [53, 183, 121], [109, 205, 89], [180, 222, 44], [253, 231, 37]];
/** The colour scale at `f` in [0, 1] (clamped), as [r, g, b]. */
function rgb(f) {
  f = Math.min(1, Math.max(0, f)) * (VIRIDIS.length - 1);
  const i = Math.min(VIRIDIS.length - 2, Math.floor(f));
  const a = VIRIDIS[i], b = VIRIDIS[i + 1], u = f - i;
  return [0, 1, 2].map((j) => Math.round(a[j] + (b[j] - a[j]) * u));
}
/** The colour scale at `f` in [0, 1] (clamped), as CSS: the pressure maps' and the wear map's. */
export const colour = (f) => `rgb(${rgb(f).join(",")})`;

// The SVG's margins (left, top, bottom) and the gap between maps, in px.
const L = 52, T = 24, B = 44, GAP = 16;

/** Empties the figure until a result comes. */
export function resetPressure() {
  $(BOX).querySelector(".heatmaps").replaceChildren();
  $(BOX).querySelector(".note").textContent = WAITING;
  $(BOX).dataset.points = "0";
  setSvgFigure(BOX, null);
}

/** Draws the result's first and last pressure maps, with a readout under the cursor. */
export function drawPressure(result) {
  const maps = result.pressure_maps || [];
  const box = $(BOX).querySelector(".heatmaps");
  const note = $(BOX).querySelector(".note");
  box.replaceChildren();
  if (!maps.length) { note.textContent = "The result has no pressure maps."; return; }
  const shown = maps.length > 1 ? [maps[0], maps[maps.length - 1]] : [maps[0]];
  let pMax = 0;
  for (const m of shown) for (const row of m.pressure_mpa) for (const p of row) pMax = Math.max(pMax, p);
  const { svg, umPerPx, cells } = pressureSvg(shown, pMax, Boolean(result.surface));
  setSvgFigure(BOX, svg);
  box.innerHTML = svg;
  const rough = result.surface ? ` Rough disc: the contact cells (p > 0) at full resolution, one pixel per ${+umPerPx.toPrecision(3)} µm cell; white, no contact.` : "";
  note.textContent = `Colour: contact pressure, 0 to ${pMax.toFixed(0)} MPa on both maps; both maps at one scale, ${+umPerPx.toPrecision(3)} µm per pixel; x along the sliding direction, y across the track.${rough}`;
  $(BOX).dataset.points = String(cells);
  addReadout(box, shown);
}

// The pressure under the cursor, in words, under the maps.
function addReadout(box, shown) {
  const readout = document.createElement("p");
  readout.className = "muted";
  readout.setAttribute("aria-live", "polite");
  box.appendChild(readout);
  box.querySelector("svg").addEventListener("mousemove", (e) => {
    const g = e.target.closest("g[data-cycle]");
    if (!g) { readout.textContent = ""; return; }
    const m = shown[Number(g.dataset.index)];
    const r = g.querySelector("rect.frame").getBoundingClientRect();
    const fx = (e.clientX - r.left) / r.width, fy = 1 - (e.clientY - r.top) / r.height;
    const i = Math.floor(fx * m.x_um.length), j = Math.floor(fy * m.y_um.length);
    if (i < 0 || j < 0 || i >= m.x_um.length || j >= m.y_um.length) { readout.textContent = ""; return; }
    readout.textContent = `cycle ${m.cycle}: x ${m.x_um[i].toFixed(1)} µm, y ${m.y_um[j].toFixed(1)} µm, pressure ${Math.round(m.pressure_mpa[j][i])} MPa`;
  });
}

/**
 * A map of values (`rows[j][i]`, j along y) as a canvas of one pixel per cell, y up, each
 * cell coloured at its value over `vMax`; the cells `drawn` refuses stay transparent.
 */
export function cellCanvas(rows, nx, ny, vMax, drawn = () => true) {
  const canvas = document.createElement("canvas");
  canvas.width = nx; canvas.height = ny;
  const ctx = canvas.getContext("2d");
  const image = ctx.createImageData(nx, ny);
  for (let j = 0; j < ny; j++) {
    const row = rows[j] || [];
    for (let i = 0; i < nx; i++) {
      const v = row[i] || 0;
      if (!drawn(v)) continue;
      image.data.set([...rgb(v / (vMax || 1)), 255], 4 * ((ny - 1 - j) * nx + i));
    }
  }
  ctx.putImageData(image, 0, 0);
  return canvas;
}

// A map's contact cells (p > 0) as a PNG of one pixel per cell, y up; the rest transparent.
const contactPng = (m, pMax) => cellCanvas(m.pressure_mpa, m.x_um.length, m.y_um.length, pMax, (p) => p > 0).toDataURL("image/png");

/** A map's cell size and its edges, in µm, from its cell centres `x_um` and `y_um`. */
export function extent(m) {
  const dx = m.x_um.length > 1 ? m.x_um[1] - m.x_um[0] : 1, dy = m.y_um.length > 1 ? m.y_um[1] - m.y_um[0] : 1;
  return { dx, dy, x0: m.x_um[0] - dx / 2, x1: m.x_um[m.x_um.length - 1] + dx / 2, y0: m.y_um[0] - dy / 2, y1: m.y_um[m.y_um.length - 1] + dy / 2 };
}

// A smooth disc's contact cells as coloured rectangles; returns how many cells the map has.
function cellRects(out, m, e, umPerPx, pMax) {
  let cells = 0;
  for (let j = 0; j < m.y_um.length; j++) {
    const row = m.pressure_mpa[j] || [];
    for (let i = 0; i < m.x_um.length; i++) {
      cells++;
      const p = row[i] || 0;
      if (p <= 0) continue;
      const cx = (m.x_um[i] - e.dx / 2 - e.x0) / umPerPx, cy = (e.y1 - (m.y_um[j] + e.dy / 2)) / umPerPx;
      out.push(`<rect x="${cx.toFixed(2)}" y="${cy.toFixed(2)}" width="${(e.dx / umPerPx + 0.3).toFixed(2)}" height="${(e.dy / umPerPx + 0.3).toFixed(2)}" fill="${colour(p / (pMax || 1))}"/>`);
    }
  }
  return cells;
}

// The frame's ticks and axis labels, in µm.
function mapAxes(out, e, pw, ph, umPerPx) {
  const nx = Math.max(2, Math.floor(pw / 40));
  for (const v of niceTicks(e.x0, e.x1, nx)) {
    const px = (v - e.x0) / umPerPx;
    out.push(`<line x1="${px.toFixed(1)}" x2="${px.toFixed(1)}" y1="${ph}" y2="${ph + 4}" stroke="#1b1f24"/><text ${FONT} x="${px.toFixed(1)}" y="${ph + 16}" text-anchor="middle">${v}</text>`);
  }
  out.push(`<text ${FONT} x="${(pw / 2).toFixed(1)}" y="${ph + 34}" text-anchor="middle">x (µm)</text>`);
  for (const v of niceTicks(e.y0, e.y1, Math.max(2, Math.floor(ph / 35)))) {
    const py = (e.y1 - v) / umPerPx;
    out.push(`<line x1="-4" x2="0" y1="${py.toFixed(1)}" y2="${py.toFixed(1)}" stroke="#1b1f24"/><text ${FONT} x="-6" y="${(py + 4).toFixed(1)}" text-anchor="end">${v}</text>`);
  }
  out.push(`<text ${FONT} transform="translate(-38,${(ph / 2).toFixed(1)}) rotate(-90)" text-anchor="middle">y (µm)</text>`);
}

// One map at (x, T): its cells (or, on a rough disc, its contact image), frame and axes.
function mapSvg(m, k, e, x, { umPerPx, pMax, rough }) {
  const pw = (e.x1 - e.x0) / umPerPx, ph = (e.y1 - e.y0) / umPerPx;
  const out = [`<g data-cycle="${m.cycle}" data-index="${k}" data-um-per-px="${umPerPx}" transform="translate(${x.toFixed(2)},${T})">`];
  out.push(`<rect class="frame" x="0" y="0" width="${pw.toFixed(2)}" height="${ph.toFixed(2)}" fill="${rough ? "#fff" : colour(0)}"/>`);
  out.push('<g shape-rendering="crispEdges">');
  let cells = 0;
  if (rough) {
    cells = m.x_um.length * m.y_um.length;
    out.push(`<image class="contact" x="0" y="0" width="${pw.toFixed(2)}" height="${ph.toFixed(2)}" preserveAspectRatio="none" image-rendering="pixelated" href="${contactPng(m, pMax)}"/>`);
  } else {
    cells = cellRects(out, m, e, umPerPx, pMax);
  }
  out.push("</g>");
  out.push(`<rect x="0" y="0" width="${pw.toFixed(2)}" height="${ph.toFixed(2)}" fill="none" stroke="#1b1f24"/>`);
  out.push(`<text ${FONT} x="${(pw / 2).toFixed(1)}" y="-8" text-anchor="middle">cycle ${m.cycle}</text>`);
  mapAxes(out, e, pw, ph, umPerPx);
  out.push("</g>");
  return { svg: out.join(""), width: pw, cells };
}

// The colour bar, with its maximum labelled and a round tick about every 40 px; ticks that
// would crowd the maximum's label are left out.
function colourBar(bx, PH, pMax) {
  const bw = 12;
  const parts = [];
  const stops = VIRIDIS.map((_, i) => `<stop offset="${i / (VIRIDIS.length - 1)}" stop-color="${colour(i / (VIRIDIS.length - 1))}"/>`).join("");
  parts.push(`<defs><linearGradient id="pbar" x1="0" y1="1" x2="0" y2="0">${stops}</linearGradient></defs>`);
  parts.push(`<rect x="${bx}" y="${T}" width="${bw}" height="${PH}" fill="url(#pbar)" stroke="#1b1f24"/>`);
  parts.push(`<text ${FONT} x="${bx + bw + 4}" y="${T + 4}">${Math.round(pMax)} max</text>`);
  for (const v of niceTicks(0, pMax, Math.max(2, Math.floor(PH / 40)))) {
    const py = T + PH - (v / (pMax || 1)) * PH;
    if (py - T < 14) continue;
    parts.push(`<text ${FONT} x="${bx + bw + 4}" y="${(py + 4).toFixed(1)}">${Math.round(v)}</text>`);
  }
  parts.push(`<text ${FONT} x="${bx}" y="${T + PH + 16}">MPa</text>`);
  return { parts, width: bw };
}

function pressureSvg(maps, pMax, rough) {
  const ext = maps.map(extent);
  // The longest side of any map gets 240 px; every map is drawn at that one scale. A rough
  // disc's contact is many islands a cell or two across: its maps are drawn at one cell per
  // pixel instead, the contact cells (p > 0) in colour on white, so each island shows.
  const umPerPx = rough ? Math.min(...ext.map((e) => Math.min(e.dx, e.dy)))
    : Math.max(...ext.map((e) => Math.max(e.x1 - e.x0, e.y1 - e.y0))) / 240;
  const PH = Math.max(...ext.map((e) => (e.y1 - e.y0) / umPerPx));
  const parts = [];
  let x = L, cells = 0;
  maps.forEach((m, k) => {
    const map = mapSvg(m, k, ext[k], x, { umPerPx, pMax, rough });
    parts.push(map.svg);
    cells += map.cells;
    x += map.width + GAP + L;
  });
  const bx = x - L + 4;
  const bar = colourBar(bx, PH, pMax);
  parts.push(...bar.parts);
  const W = Math.ceil(bx + bar.width + 64), H = Math.ceil(T + PH + B);
  const label = `Contact pressure maps at cycles ${maps.map((m) => m.cycle).join(" and ")}, up to ${pMax.toFixed(0)} MPa, ${+umPerPx.toPrecision(3)} µm per pixel`;
  const svg = `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" viewBox="0 0 ${W} ${H}" role="img" aria-label="${esc(label)}" data-um-per-px="${umPerPx}"><rect width="${W}" height="${H}" fill="#fff"/>${parts.join("")}</svg>`;
  return { svg, umPerPx, cells };
}
