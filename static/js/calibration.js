// Calibration: the model's parameters fitted on the server to a table of the lab's
// measurements; the fitted values with their standard errors, each point's residual, the
// measured and fitted points, and the fitted scene run on request.
import { api, errorText, postJson } from "./api.js";
import { $, reveal, sleep } from "./dom.js";
import * as form from "./form.js";
import { CALIB } from "./ids.js";
import { COLORS, MEASURED_COLOR, linePlot, lineSeries, markerSeries } from "./plots.js";
import * as run from "./run.js";
import { describe, fieldLabel, fmtValue, readable } from "./words.js";

// The calibration shown: its record, and its result once fitted.
let calibration = null;

/** The calibration shown (its record, with its result once fitted), or null (the e2e test reads it). */
export const current = () => calibration;

// The table goes as the user wrote it: CSV text (the server names a bad cell by its row as
// written), or a pasted JSON table as JSON.
function parseTable(text) {
  return /^\s*[[{]/.test(text) ? JSON.parse(text) : text;
}

// The request: the table, the form's scene, and a change of regime when one is given.
function request(table) {
  const scene = form.isJsonMode() ? JSON.parse(form.sceneJsonText()) : form.sceneFromFields();
  const regime = $(CALIB.regime).value.trim();
  const body = { kind: $(CALIB.kind).value, table, scene };
  if (regime) body.options = { regime_change: /^\d+$/.test(regime) ? Number(regime) : regime };
  return body;
}

async function submitCalibration(event) {
  event.preventDefault();
  $(CALIB.errors).textContent = "";
  const file = $(CALIB.file).files[0];
  const text = file ? await file.text() : $(CALIB.text).value;
  if (!text.trim()) { $(CALIB.errors).textContent = "Choose a CSV file or paste a table first."; return; }
  let table;
  try { table = parseTable(text); } catch (e) { $(CALIB.errors).textContent = "The table is not valid JSON: " + e.message; return; }
  const r = await postJson("/api/v1/calibrations", request(table));
  if (!r.ok) { $(CALIB.errors).textContent = "Not fitted: " + readable(errorText(r)); return; }
  $(CALIB.panel).hidden = false;
  reveal($(CALIB.panel), false);
  follow(r.body);
}

// Polls the calibration's record until it has ended.
async function follow(record) {
  calibration = record;
  for (;;) {
    render(calibration);
    if (calibration.status !== "running") return;
    await sleep(500);
    const r = await api(`/api/v1/calibrations/${record.id}`);
    if (!r.ok || !calibration || calibration.id !== record.id) return;
    calibration = r.body;
  }
}

const isFitted = (v) => v && typeof v === "object" && !Array.isArray(v) && "value" in v && "standard_error" in v;

// A fit with a change of regime nests its two models: shown as one table of values and the
// better model's residuals, as a one-model fit is.
function flattenRegimes(result) {
  if (!result || !result.two_regimes) return result;
  const better = result.comparison.better === "two_regimes" ? "two_regime" : "one_regime";
  return {
    archard_k: result.one_regime.archard_k,
    archard_k_before: result.two_regimes.archard_k_before,
    archard_k_after: result.two_regimes.archard_k_after,
    change_cycle: result.two_regimes.change_cycle,
    better_model: result.comparison.better.replace(/_/g, " "),
    aic_difference: result.comparison.aic_difference,
    residuals: result.points.map((p) => ({
      cycles: p.cycles, volume_mm3: p.volume_mm3,
      model_mm3: p[better + "_model_mm3"], residual_mm3: p[better + "_residual_mm3"],
    })),
    scene: result.scene,
  };
}

// The fitted values, each with its standard error.
function renderValues(result) {
  const fitted = result ? Object.entries(result).filter(([, v]) => isFitted(v)) : [];
  $(CALIB.values).querySelector("tbody").replaceChildren(...fitted.map(([k, v]) => {
    const tr = document.createElement("tr");
    for (const [text, cls] of [[fieldLabel(k), ""], [fmtValue(v.value), "num"], [fmtValue(v.standard_error), "num"]]) {
      const td = document.createElement("td");
      td.textContent = text;
      td.className = cls;
      tr.appendChild(td);
    }
    return tr;
  }));
}

// Each point's residual, a column per field of the result's points.
function renderResiduals(residuals, cols) {
  const head = document.createElement("tr");
  for (const c of cols) {
    const th = document.createElement("th");
    th.textContent = fieldLabel(c);
    th.className = "num";
    head.appendChild(th);
  }
  $(CALIB.residuals).querySelector("thead").replaceChildren(head);
  $(CALIB.residuals).querySelector("tbody").replaceChildren(...residuals.map((row) => {
    const tr = document.createElement("tr");
    for (const c of cols) {
      const td = document.createElement("td");
      td.className = "num";
      td.textContent = fmtValue(row[c]);
      tr.appendChild(td);
    }
    return tr;
  }));
  $(CALIB.residuals).hidden = !residuals.length;
}

function render(record) {
  const result = flattenRegimes(record.result || null);
  $(CALIB.title).textContent = `Calibration: ${(record.kind || "").replace(/_/g, " ")}`;
  $(CALIB.status).textContent = record.status;
  $(CALIB.status).className = "status-" + record.status;
  $(CALIB.run).disabled = !(result && result.scene);
  $(CALIB.note).textContent = record.error ? readable("Not fitted: " + record.error) : "";
  renderValues(result);
  const others = result ? Object.entries(result).filter(([k, v]) => !isFitted(v) && k !== "scene" && k !== "residuals" && (v === null || typeof v !== "object")) : [];
  if (others.length) $(CALIB.note).textContent = ($(CALIB.note).textContent + " " + others.map(([k, v]) => describe(k, v)).join("; ") + ".").trim();
  const residuals = result && Array.isArray(result.residuals) ? result.residuals : [];
  const cols = residuals.length ? Object.keys(residuals[0]) : [];
  renderResiduals(residuals, cols);
  draw(residuals, cols);
}

// The measured points and the fitted curve at them, against the table's first column.
function draw(residuals, cols) {
  const fittedCol = cols.find((c) => c.startsWith("fitted") || c.startsWith("model"));
  const measuredCol = cols.find((c, i) => i > 0 && c !== fittedCol && !c.startsWith("residual"));
  if (!residuals.length || !fittedCol || !measuredCol) { $(CALIB.plot).hidden = true; return; }
  $(CALIB.plot).hidden = false;
  const rows = residuals.slice().sort((a, b) => a[cols[0]] - b[cols[0]]);
  linePlot(CALIB.plot, [rows.map((r) => r[cols[0]]), rows.map((r) => r[measuredCol]), rows.map((r) => r[fittedCol])],
    [markerSeries("measured", MEASURED_COLOR), lineSeries("fitted", COLORS[0])],
    fieldLabel(cols[0]), fieldLabel(measuredCol), rows.length, { rebuild: true });
}

async function runFittedScene() {
  const result = calibration && calibration.result;
  if (!result || !result.scene) return;
  const r = await postJson("/api/v1/jobs", result.scene);
  if (!r.ok) { $(CALIB.note).textContent = "Not started: " + readable(errorText(r)); return; }
  await run.showNewJob(r.body.id, result.scene);
}

/** Wires the calibration form and the panel's button. */
export function init() {
  $(CALIB.form).addEventListener("submit", submitCalibration);
  $(CALIB.run).addEventListener("click", runFittedScene);
}
