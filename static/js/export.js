// Each figure as SVG, and as PNG at print resolution, with its legend and axis labels.
import { $, button, saveBlob } from "./dom.js";
import { COMPARE_PLOT, STUDY, STUDY_PLOT, RUN } from "./ids.js";
import { BAND_COLOR, chart, spec, svgFigure } from "./plots.js";
import { FONT, FONT_FAMILY, esc, niceTicks } from "./svg.js";

// The exported line chart's frame: width, margins and plot height, in px.
const W = 760, L = 84, R = 24, T = 40, PH = 320, PW = W - L - R;

// The axes and their labels, with round ticks over the ranges shown on the page.
function axesSvg(s, { X, Y, sx, sy }) {
  const out = [];
  for (const v of niceTicks(sx.min, sx.max, 8)) {
    const px = X(v).toFixed(1);
    out.push(`<line x1="${px}" x2="${px}" y1="${T}" y2="${T + PH + 5}" stroke="#e5e5e5"/><text ${FONT} x="${px}" y="${T + PH + 19}" text-anchor="middle">${v}</text>`);
  }
  for (const v of niceTicks(sy.min, sy.max, 6)) {
    const py = Y(v).toFixed(1);
    out.push(`<line x1="${L - 5}" x2="${L + PW}" y1="${py}" y2="${py}" stroke="#e5e5e5"/><text ${FONT} x="${L - 8}" y="${(+py + 4).toFixed(1)}" text-anchor="end">${v}</text>`);
  }
  out.push(`<rect x="${L}" y="${T}" width="${PW}" height="${PH}" fill="none" stroke="#1b1f24"/>`);
  out.push(`<text ${FONT} x="${L + PW / 2}" y="${T + PH + 40}" text-anchor="middle">${esc(s.xLabel)}</text>`);
  out.push(`<text ${FONT} transform="translate(20,${T + PH / 2}) rotate(-90)" text-anchor="middle">${esc(s.yLabel)}</text>`);
  return out;
}

// A marker series' error bars (its `yErrors`, by x), with 4 px caps.
function errorBarsSvg(series, xs, ys, { X, Y }) {
  if (!series.yErrors) return "";
  const bars = [];
  xs.forEach((x, i) => {
    const e = series.yErrors.get(x);
    if (ys[i] == null || !e) return;
    const cx = X(x), top = Y(ys[i] + e).toFixed(2), bottom = Y(ys[i] - e).toFixed(2);
    bars.push(`M${cx.toFixed(2)} ${top}V${bottom}M${(cx - 4).toFixed(2)} ${top}h8M${(cx - 4).toFixed(2)} ${bottom}h8`);
  });
  return `<path class="error-bars" fill="none" stroke="${series.stroke}" stroke-width="1.5" d="${bars.join("")}"/>`;
}

// Each series as a polyline, or as dots for measured points, with their error bars.
function seriesSvg(s, { X, Y }) {
  const xs = s.data[0];
  return s.series.map((series, k) => {
    const ys = s.data[k + 1];
    const pts = [];
    for (let i = 0; i < xs.length; i++) if (ys[i] != null && xs[i] != null) pts.push([X(xs[i]).toFixed(2), Y(ys[i]).toFixed(2)]);
    if (series.marker) {
      return `<g clip-path="url(#plotarea)" fill="${series.stroke}" data-series="${esc(series.label)}">${errorBarsSvg(series, xs, ys, { X, Y })}${pts.map(([a, b]) => `<circle cx="${a}" cy="${b}" r="4"/>`).join("")}</g>`;
    }
    if (!pts.length) return "";
    const dash = series.dash ? ` stroke-dasharray="${series.dash.join(" ")}"` : "";
    return `<polyline clip-path="url(#plotarea)" data-series="${esc(series.label)}" fill="none" stroke="${series.stroke}" stroke-width="${series.width || 2}"${dash} points="${pts.map((p) => p.join(",")).join(" ")}"/>`;
  }).filter((part) => part);
}

// A shaded band of x under the series, clipped to the plot.
function bandSvg(s, { X }) {
  if (!s.band) return [];
  const left = Math.max(L, X(s.band.from)), right = Math.min(L + PW, X(s.band.to));
  if (right <= left) return [];
  return [`<rect data-band="${esc(s.band.label)}" x="${left.toFixed(2)}" y="${T}" width="${(right - left).toFixed(2)}" height="${PH}" fill="${BAND_COLOR}"/>`];
}

// The legend under the plot; returns its parts and the y below it.
function legendSvg(s) {
  const out = [];
  let y = T + PH + 62;
  if (s.band) {
    out.push(`<rect x="${L}" y="${y - 11}" width="24" height="12" fill="${BAND_COLOR}"/><text ${FONT} x="${L + 32}" y="${y}">${esc(s.band.label)}</text>`);
    y += 20;
  }
  for (const series of s.series) {
    const swatch = series.marker
      ? `<circle cx="${L + 12}" cy="${y - 4}" r="4" fill="${series.stroke}"/>`
      : `<line x1="${L}" x2="${L + 24}" y1="${y - 4}" y2="${y - 4}" stroke="${series.stroke}" stroke-width="${series.width || 2}"${series.dash ? ` stroke-dasharray="${series.dash.join(" ")}"` : ""}/>`;
    out.push(`${swatch}<text ${FONT} x="${L + 32}" y="${y}">${esc(series.label)}</text>`);
    y += 20;
  }
  return { out, y };
}

// A line plot as SVG: the axes' ranges as shown on the page, round ticks, axis labels and
// the legend under the plot.
function lineChartSvg(plotId) {
  const s = spec(plotId), u = chart(plotId);
  const title = $(plotId).querySelector("h3").textContent;
  const sx = u.scales.x, sy = u.scales.y;
  const X = (v) => L + ((v - sx.min) / (sx.max - sx.min || 1)) * PW;
  const Y = (v) => T + PH - ((v - sy.min) / (sy.max - sy.min || 1)) * PH;
  const frame = { X, Y, sx, sy };
  const out = [`<text ${FONT_FAMILY} font-size="15" font-weight="600" x="${L}" y="24">${esc(title)}</text>`];
  out.push(`<defs><clipPath id="plotarea"><rect x="${L}" y="${T}" width="${PW}" height="${PH}"/></clipPath></defs>`);
  out.push(...bandSvg(s, frame), ...axesSvg(s, frame), ...seriesSvg(s, frame));
  const legend = legendSvg(s);
  out.push(...legend.out);
  const H = legend.y + 4;
  return { svg: `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" viewBox="0 0 ${W} ${H}"><rect width="${W}" height="${H}" fill="#fff"/>${out.join("")}</svg>`, width: W, height: H };
}

function figureSvg(plotId) {
  const svg = svgFigure(plotId);
  if (svg !== undefined) {
    if (!svg) return null;
    const doc = new DOMParser().parseFromString(svg, "image/svg+xml").documentElement;
    return { svg, width: Number(doc.getAttribute("width")), height: Number(doc.getAttribute("height")) };
  }
  return spec(plotId) && chart(plotId) ? lineChartSvg(plotId) : null;
}

// PNG at three times the SVG's size (a 760 px figure becomes 2280 px: 300 dpi over 19 cm).
const PNG_SCALE = 3;
async function svgToPng({ svg, width, height }) {
  const img = new Image();
  img.src = "data:image/svg+xml;charset=utf-8," + encodeURIComponent(svg);
  await img.decode();
  const canvas = document.createElement("canvas");
  canvas.width = width * PNG_SCALE;
  canvas.height = height * PNG_SCALE;
  const ctx = canvas.getContext("2d");
  ctx.scale(PNG_SCALE, PNG_SCALE);
  ctx.drawImage(img, 0, 0, width, height);
  return new Promise((resolve) => canvas.toBlob(resolve, "image/png"));
}

// The file's name: the panel's (the comparison, the study, else the run) and the figure's.
function fileName(plotId) {
  const prefix = Object.values(COMPARE_PLOT).includes(plotId) ? "comparison"
    : Object.values(STUDY_PLOT).includes(plotId) ? $(STUDY.title).textContent : $(RUN.title).textContent || "run";
  const base = prefix + "-" + $(plotId).querySelector("h3").textContent;
  return base.toLowerCase().replace(/[^a-z0-9µ]+/g, "-").replace(/^-|-$/g, "").slice(0, 80);
}

async function exportFigure(plotId, format) {
  const fig = figureSvg(plotId);
  if (!fig) { alert("Nothing drawn yet to export."); return; }
  const name = fileName(plotId);
  if (format === "svg") saveBlob(new Blob([fig.svg], { type: "image/svg+xml" }), name + ".svg");
  else saveBlob(await svgToPng(fig), name + ".png");
}

/** Gives each figure's heading its two export buttons. */
export function addExportButtons() {
  for (const box of document.querySelectorAll(".plot")) {
    const h3 = box.querySelector("h3");
    const head = document.createElement("div");
    head.className = "plot-head";
    h3.replaceWith(head);
    const exports = document.createElement("span");
    exports.className = "exports";
    for (const format of ["svg", "png"]) {
      const b = button(format.toUpperCase(), () => exportFigure(box.id, format));
      b.className = "export-" + format;
      b.setAttribute("aria-label", `Download the figure "${h3.textContent}" as ${format.toUpperCase()}`);
      exports.appendChild(b);
    }
    head.append(h3, exports);
  }
}
