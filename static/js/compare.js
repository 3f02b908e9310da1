// The comparison of several ended runs: wear volume, depth, potential and WAC against
// cycles or time, the profiles at a chosen cycle, and the summaries side by side; each run
// in its colour, its legend naming what differs between the scenes ("load 10 N").
import { api, download } from "./api.js";
import { $, reveal } from "./dom.js";
import { setHash } from "./hash.js";
import { COMPARE, COMPARE_PLOT, COMPARE_X, JOBS } from "./ids.js";
import * as jobs from "./jobs.js";
import { COLORS, joinTables, linePlot, lineSeries } from "./plots.js";
import { METRICS, describe, differingPaths, fieldLabel, fieldName, fmtValue, getPath, metricLabel, metricValue } from "./words.js";

// The runs in the panel: { job, result, label, colour }, oldest first.
let compared = [];

/** The runs compared, oldest first: { job, result, label, colour } (the e2e test reads them). */
export const comparedRuns = () => compared;

const scenesOf = (runs) => runs.map((r) => r.result.scene || {});

// A run's legend label: what differs in its scene from the others' (e.g. "load 10 N").
function compareLabels(runs) {
  const paths = differingPaths(scenesOf(runs));
  const labels = runs.map((r) => {
    const words = paths.slice(0, 3).map((p) => describe(p, getPath(r.result.scene, p)));
    if (paths.length > 3) words.push(`${paths.length - 3} more`);
    return words.length ? words.join(", ") : r.job.name;
  });
  // Runs of one scene are told apart by their names.
  return labels.map((l, i) => (labels.indexOf(l) !== labels.lastIndexOf(l) ? `${l} (${runs[i].job.name}, ${i + 1})` : l));
}

// The ticked runs with a result, oldest first, labelled and coloured.
async function loadRuns() {
  const runs = [];
  for (const id of jobs.tickedIds()) {
    const r = await api(`/api/v1/jobs/${id}/result`);
    if (r.ok && r.body && Array.isArray(r.body.cycles)) runs.push({ job: jobs.find(id), result: r.body });
  }
  const labels = compareLabels(runs);
  runs.forEach((run, i) => { run.label = labels[i]; run.colour = COLORS[i % COLORS.length]; });
  return runs;
}

function noteText(runs) {
  const paths = differingPaths(scenesOf(runs));
  return runs.length < 2
    ? "Fewer than two of the ticked runs have a result to compare."
    : `${runs.length} runs, oldest first. ${paths.length ? `They differ in: ${paths.map((p) => fieldName(p).name).join(", ")}.` : "Their scenes are the same."}`
      + (runs.some((r) => r.result.complete === false) ? " Partial results (stopped runs) are drawn as far as they go." : "");
}

// The cycles with profiles, the ones not in every run said so; the last common one chosen.
function fillCycles(runs) {
  const cycles = [...new Set(runs.flatMap((r) => (r.result.profiles || []).map((p) => p.cycle)))].sort((a, b) => a - b);
  const common = cycles.filter((c) => runs.every((r) => (r.result.profiles || []).some((p) => p.cycle === c)));
  $(COMPARE.cycle).replaceChildren(...cycles.map((c) => new Option(`${c}${common.includes(c) ? "" : " (not in every run)"}`, String(c))));
  $(COMPARE.cycle).value = String(common.length ? common[common.length - 1] : cycles[cycles.length - 1]);
}

/** Opens the panel on the ticked runs. */
export async function open() {
  const runs = await loadRuns();
  compared = runs;
  $(COMPARE.note).textContent = noteText(runs);
  fillCycles(runs);
  $(COMPARE.panel).hidden = false;
  draw();
  setHash("compare", jobs.tickedIds().join(","));
  reveal($(COMPARE.panel), true);
}

// A figure's heading against the x axis chosen: "Wear volume against time".
function retitle(plotId, against) {
  const h3 = $(plotId).querySelector("h3");
  h3.textContent = `${h3.textContent.split(" against ")[0]} against ${against}`;
}

function draw() {
  const runs = compared;
  const byTime = document.querySelector(`input[name="${COMPARE_X}"]:checked`).value === "time";
  const xLabel = byTime ? "time (s)" : "cycles (passes of the ball)";
  for (const [plotId, key, yLabel, scale] of [
    [COMPARE_PLOT.volume, "wear_volume_mm3", "wear volume (10⁻³ mm³)", 1e3],
    [COMPARE_PLOT.depth, "max_depth_um", "maximum wear depth (µm)", 1],
    [COMPARE_PLOT.potential, "potential_v", "potential (V vs Ag/AgCl)", 1],
    [COMPARE_PLOT.wac, "wac_volume_mm3", "WAC volume (10⁻³ mm³)", 1e3],
  ]) {
    const tables = runs.map((run) => {
      const cs = run.result.cycles;
      return [cs.map((r) => (byTime ? r.time_s : r.cycle)), cs.map((r) => (r[key] == null ? null : r[key] * scale))];
    });
    const curves = tables.filter((t) => t[1].some((v) => v != null)).length;
    const note = $(plotId).querySelector(".note");
    if (note) note.textContent = curves < runs.length ? `${runs.length - curves} of the runs have no corrosion model: no curve for them.` : "";
    $(plotId).dataset.curves = String(curves);
    retitle(plotId, byTime ? "time" : "cycles");
    linePlot(plotId, joinTables(tables), runs.map((run) => lineSeries(run.label, run.colour)), xLabel, yLabel, tables.reduce((s, t) => s + t[0].length, 0), { rebuild: true });
  }
  drawProfiles();
  renderTable();
}

// Each run's profile at the chosen cycle (or its last profile before it, said in the legend).
function drawProfiles() {
  const cycle = Number($(COMPARE.cycle).value);
  const tables = [], series = [];
  for (const run of compared) {
    const before = (run.result.profiles || []).filter((p) => p.cycle <= cycle);
    const p = before[before.length - 1];
    if (!p) continue;
    tables.push([p.y_um, p.depth_um.map((d) => -Math.abs(d))]);
    series.push(lineSeries(p.cycle === cycle ? run.label : `${run.label} (cycle ${p.cycle})`, run.colour));
  }
  const box = $(COMPARE_PLOT.profile);
  box.querySelector("h3").textContent = `Wear track profile at cycle ${cycle}`;
  box.querySelector(".note").textContent = "Surface height −D(y) across the track.";
  box.dataset.curves = String(tables.length);
  if (!tables.length) return;
  linePlot(COMPARE_PLOT.profile, joinTables(tables), series, "y across the track (µm)", "surface height −D (µm)", tables.reduce((s, t) => s + t[0].length, 0), { rebuild: true });
}

// The header: each run's label beside a square of its colour.
function tableHead(runs) {
  const head = document.createElement("tr");
  head.innerHTML = "<th scope=col>quantity</th>";
  for (const run of runs) {
    const th = document.createElement("th");
    th.scope = "col";
    th.className = "num";
    // The colour through the DOM: the content policy refuses style attributes in markup.
    const square = document.createElement("span");
    square.style.color = run.colour;
    square.setAttribute("aria-hidden", "true");
    square.textContent = "■";
    th.append(square, " ");
    th.append(run.label);
    head.appendChild(th);
  }
  return head;
}

// A row of values, each later one with its difference to the first when `diff` is given;
// marked when the values differ.
function tableRow(title, values, diff) {
  const tr = document.createElement("tr");
  const th = document.createElement("th");
  th.scope = "row";
  th.textContent = title;
  tr.appendChild(th);
  values.forEach((v, i) => {
    const td = document.createElement("td");
    td.className = "num";
    td.textContent = fmtValue(v) + (i > 0 && diff && typeof v === "number" && typeof values[0] === "number" ? ` (${diff(v, values[0])})` : "");
    tr.appendChild(td);
  });
  if (new Set(values.map((v) => JSON.stringify(v ?? null))).size > 1) tr.classList.add("differs");
  return tr;
}

const relative = (v, v0) => (v0 === 0 ? "—" : `${v >= v0 ? "+" : "−"}${Math.abs((100 * (v - v0)) / v0).toPrecision(3)} %`);
const absolute = (v, v0) => `${v >= v0 ? "+" : "−"}${+Math.abs(v - v0).toPrecision(3)} V`;

// The summaries side by side: first the scene fields that differ, then the totals, each
// later run with its difference to the first (relative; a potential's in volts).
function renderTable() {
  const runs = compared;
  const table = $(COMPARE.table);
  table.querySelector("thead").replaceChildren(tableHead(runs));
  const rows = [];
  for (const p of differingPaths(scenesOf(runs))) {
    rows.push(tableRow(fieldLabel(p), runs.map((r) => getPath(r.result.scene, p)), null));
  }
  for (const m of METRICS) {
    const values = runs.map((r) => metricValue(r.result.summary, m));
    if (values.every((v) => v == null)) continue;
    rows.push(tableRow(metricLabel(m), values, m[0] === "potential_v" ? absolute : relative));
  }
  table.querySelector("tbody").replaceChildren(...rows);
}

/** Wires the job list's compare button and the panel's controls. */
export function init() {
  $(JOBS.compare).addEventListener("click", open);
  $(COMPARE.close).addEventListener("click", () => { $(COMPARE.panel).hidden = true; });
  $(COMPARE.report).addEventListener("click", () =>
    download(`/api/v1/report?jobs=${compared.map((r) => r.job.id).join(",")}`, "comparison.report.html"));
  for (const radio of document.querySelectorAll(`input[name="${COMPARE_X}"]`)) radio.addEventListener("change", draw);
  $(COMPARE.cycle).addEventListener("change", drawProfiles);
}
