// The run panel: one job followed through its event stream (the live figures), then its
// result (the final figures and the downloads), its scene as run, the models it used and
// its summary.
import { api, authHeaders, download } from "./api.js";
import { $, reveal, sleep } from "./dom.js";
import { RUN } from "./ids.js";
import { setHash } from "./hash.js";
import * as jobs from "./jobs.js";
import * as labels from "./labels.js";
import * as measurements from "./measurements.js";
import * as scores from "./scores.js";
import { fig11Curves, forgetFailed } from "./fig11.js";
import { drawPressure, resetPressure } from "./pressure.js";
import { drawProfiles, drawSeries, resetProfiles, updateTable3Choice } from "./run-figures.js";
import { drawStroke, expectStroke, resetStroke } from "./stroke.js";
import { closestPreset, remember, submittedScene } from "./scenes.js";
import { readEvents } from "./sse.js";
import { topic } from "./topic.js";
import { METRICS, describe, differingPaths, fieldLabel, fmtValue, getPath, metricLabel, metricValue, readable, referenceLabel } from "./words.js";

let selected = null; // id of the job shown
let follow = null;   // AbortController of the event stream being read
let cycles = [];     // its cycle records, in order
let result = null;   // its result (complete or partial), once it has one
let scene = null;    // its scene as run, once known
let sceneAsRun = false; // whether `scene` is the server's (the Fig. 11 companion copies it)
const editRequested = topic();

/** The id of the job shown, or null (the e2e test reads it). */
export const selectedId = () => selected;
/** The shown job's result, once it has one (the e2e test reads it). */
export const currentResult = () => result;
/** Listens for "Edit and run again": (the scene as run). */
export const onEditAgain = editRequested.on;

// The Fig. 11 view's curves when it is on and the scene as run is known, else null.
function fig11View() {
  if (!$(RUN.showFig11).checked || !sceneAsRun) return null;
  const id = selected;
  return fig11Curves(id, scene, cycles, Boolean(result), () => { if (selected === id) redrawSeries(); });
}

function redrawSeries() {
  drawSeries(cycles, scene, result && result.ocp_trace, fig11View());
}

// The Table 3 choice for the scene known now, and the volume figure again if drawn.
function table3() {
  if (updateTable3Choice(scene)) redrawSeries();
}

/** Hides the panel and stops following its job. */
function close() {
  if (follow) follow.abort();
  selected = null;
  jobs.highlight(null);
  measurements.forget();
  $(RUN.panel).hidden = true;
}

/** Shows job `id`: what is known of it at once, then its scene, measurements and events. */
function select(id, how = {}) {
  if (follow) follow.abort();
  selected = id;
  cycles = [];
  result = null;
  scene = submittedScene(id);
  sceneAsRun = false;
  $(RUN.showFig11).checked = false;
  measurements.forget();
  scores.clear();
  $(RUN.panel).hidden = false;
  for (const b of [...DOWNLOADS.map((d) => d[0]), RUN.editAgain]) $(b).disabled = true;
  for (const d of [RUN.models, RUN.params, RUN.summary, RUN.warnings]) $(d).hidden = true;
  $(RUN.partial).textContent = "";
  jobs.highlight(id);
  const job = jobs.find(id);
  $(RUN.title).textContent = job ? job.name : "Run";
  table3();
  if (job) showJobStatus(job);
  resetProfiles();
  resetPressure();
  resetStroke();
  expectStroke(scene);
  redrawSeries();
  if (how.scroll) reveal($(RUN.panel), how.focus);
  setHash("run", id);
  labels.load(id);
  loadScene(id);
  measurements.load(id);
  followEvents(id);
}

/** Shows a job just submitted, keeping the scene it was sent with (when known). */
export async function showNewJob(id, sent) {
  if (sent) remember(id, sent);
  await jobs.refresh();
  select(id, { scroll: true });
}

function showJobStatus(job) {
  $(RUN.title).textContent = job.name;
  $(RUN.status).textContent = `${job.status}: ${jobs.progressText(job)} cycles`;
  $(RUN.reason).textContent = jobs.jobReason(job);
  $(RUN.status).className = "status-" + job.status;
  $(RUN.progress).max = job.cycles_total;
  $(RUN.progress).value = Math.max(job.cycles_done, cycles.length ? cycles[cycles.length - 1].cycle : 0);
}

// Redraws the live figures at most once a frame, while job `id` is shown.
function frameRedraw(id) {
  let scheduled = false;
  return () => {
    if (scheduled) return;
    scheduled = true;
    requestAnimationFrame(() => { scheduled = false; if (selected === id) redrawSeries(); });
  };
}

function onCycle(id, payload) {
  cycles.push(payload);
  const p = $(RUN.progress);
  p.value = Math.max(p.value, payload.cycle);
  $(RUN.status).textContent = `running: ${p.value} / ${p.max} cycles`;
  $(RUN.status).className = "status-running";
  jobs.showProgress(id, payload.cycle);
}

// One event of job `id`'s stream; false once another job is shown (stop reading).
async function onEvent(id, { type, id: eventId, payload }, stream) {
  if (type === "cycle") {
    if (eventId) stream.last = Number(eventId) || stream.last;
    if (selected !== id) return false;
    onCycle(id, payload);
    stream.redraw();
  } else if (type === "status") {
    stream.done = true;
    if (selected !== id) return false;
    showJobStatus(payload);
    if (jobs.ENDED.has(payload.status)) await loadResult(id);
  }
  return true;
}

// Reads the job's server-sent events, and reconnects with Last-Event-ID if the stream breaks
// before the final status event.
async function followEvents(id) {
  const controller = new AbortController();
  follow = controller;
  const stream = { last: 0, done: false, redraw: frameRedraw(id) };
  while (!stream.done && !controller.signal.aborted) {
    try {
      const headers = { ...authHeaders(), Accept: "text/event-stream" };
      if (stream.last) headers["Last-Event-ID"] = String(stream.last);
      const response = await fetch(`/api/v1/jobs/${id}/events`, { headers, signal: controller.signal });
      if (!response.ok) { stream.done = true; break; }
      if (!(await readEvents(response, (event) => onEvent(id, event, stream)))) return;
    } catch (e) {
      if (controller.signal.aborted) return;
    }
    if (!stream.done) await sleep(1000);
  }
  jobs.refresh();
}

function partialNote(res) {
  if (res.complete !== false) return "";
  const lastCycle = res.cycles.length ? res.cycles[res.cycles.length - 1].cycle : 0;
  return `Partial result: the cycles computed before the run stopped (to cycle ${lastCycle} of ${getPath(res.scene, "test.cycles") ?? "?"}). It is drawn below and downloads as JSON and CSV.`;
}

// What the run found wrong without failing: a potential capped at E_corr or outside the Tafel
// line's domain, more corrosion than the measured total, a hardness point off its law.
function renderWarnings(warnings) {
  $(RUN.warnings).querySelector("ul").replaceChildren(...warnings.map((w) => {
    const li = document.createElement("li");
    li.textContent = readable(w);
    return li;
  }));
  $(RUN.warnings).hidden = !warnings.length;
}

function renderModels(models) {
  $(RUN.models).querySelector("ul").replaceChildren(...models.map((m) => {
    const li = document.createElement("li");
    li.textContent = readable(`${m.name.replace(/_/g, " ")}: ${m.active ? "on" : "off"}${m.reason ? " — " + m.reason : ""}`);
    return li;
  }));
  $(RUN.models).hidden = !models.length;
}

// The result of an ended job: whole once it succeeded; what was computed before a failure
// or a cancel, when the server kept it (marked "complete": false).
async function loadResult(id) {
  const r = await api(`/api/v1/jobs/${id}/result`);
  if (!r.ok || selected !== id || !r.body || !Array.isArray(r.body.cycles)) return;
  result = r.body;
  cycles = r.body.cycles;
  if (r.body.scene) { scene = r.body.scene; sceneAsRun = true; }
  $(RUN.partial).textContent = partialNote(r.body);
  for (const [button] of DOWNLOADS) $(button).disabled = false;
  renderWarnings(r.body.warnings || []);
  renderModels(r.body.models || []);
  renderSummary(r.body);
  renderParams();
  table3();
  redrawSeries();
  drawProfiles(result);
  drawPressure(result);
  drawStroke(result);
  scores.show(id, () => selected === id);
}

// The scene as run, from the service (any status), else from the result or the form.
async function loadScene(id) {
  const r = await api(`/api/v1/jobs/${id}/scene`);
  if (selected !== id) return;
  if (r.ok && r.body && typeof r.body === "object") { scene = r.body; sceneAsRun = true; }
  expectStroke(scene);
  renderParams();
  table3();
}

function paramsDiff(preset, paths) {
  if (!preset) return "";
  return paths.length
    ? `Differs from the preset ${preset.name} in ${paths.length} field${paths.length > 1 ? "s" : ""}: ${paths.map((p) => describe(p, getPath(scene, p))).join(", ")}.`
    : `The preset ${preset.name}, unchanged.`;
}

// The run's parameters: what differs from its preset, and the whole scene as run.
function renderParams() {
  $(RUN.params).hidden = !scene;
  $(RUN.editAgain).disabled = !scene;
  if (!scene) return;
  const preset = closestPreset(scene);
  const paths = preset ? differingPaths([scene, preset.scene]) : [];
  $(RUN.paramsDiff).textContent = paramsDiff(preset, paths);
  $(RUN.paramsTable).hidden = !paths.length;
  $(RUN.paramsTable).querySelector("tbody").replaceChildren(...paths.map((p) => {
    const tr = document.createElement("tr");
    for (const text of [`${fieldLabel(p)} — ${p}`, fmtValue(getPath(scene, p)), fmtValue(getPath(preset.scene, p))]) {
      const td = document.createElement("td");
      td.textContent = text;
      tr.appendChild(td);
    }
    return tr;
  }));
  $(RUN.paramsJson).textContent = JSON.stringify(scene, null, 2);
}

// The run's totals as a table: the charts' text alternative.
function renderSummary(res) {
  const rows = METRICS.filter((m) => metricValue(res.summary, m) != null).map((m) => {
    const tr = document.createElement("tr");
    tr.innerHTML = "<th scope=row></th><td class=num></td>";
    tr.children[0].textContent = metricLabel(m);
    tr.children[1].textContent = fmtValue(metricValue(res.summary, m));
    return tr;
  });
  const reference = res.summary && res.summary.potential_reference;
  if (reference) {
    const tr = document.createElement("tr");
    tr.innerHTML = "<th scope=row>potentials against</th><td></td>";
    tr.children[1].textContent = referenceLabel(reference);
    rows.push(tr);
  }
  $(RUN.summary).querySelector("tbody").replaceChildren(...rows);
  $(RUN.summary).hidden = !rows.length;
}

// The run's downloads: the button's id, the route under the job, the name without a server's.
const DOWNLOADS = [
  [RUN.downloadJson, "result", "result.json"],
  [RUN.downloadCompact, "result?compact=true", "result.compact.json"],
  [RUN.downloadCsv, "result.csv", "result.csv"],
  [RUN.downloadProfiles, "profiles.csv", "profiles.csv"],
  [RUN.downloadPressure, "pressure.csv", "pressure.csv"],
  [RUN.downloadReport, "report", "report.html"],
];

/** Wires the panel's buttons, and follows the job list and the attached measurements. */
export function init() {
  for (const [button, route, name] of DOWNLOADS) {
    $(button).addEventListener("click", () => download(`/api/v1/jobs/${selected}/${route}`, `tribosim-${selected}.${name}`));
  }
  $(RUN.editAgain).addEventListener("click", () => editRequested.emit(scene));
  $(RUN.showTable3).addEventListener("change", redrawSeries);
  $(RUN.showFig11).addEventListener("change", () => {
    if ($(RUN.showFig11).checked) forgetFailed();
    redrawSeries();
  });
  labels.init(jobs.refresh);
  jobs.onView(select);
  jobs.onDeleted((id) => { if (id === selected) close(); });
  jobs.onListed(() => {
    const job = jobs.find(selected);
    if (job) showJobStatus(job);
  });
  measurements.onChange(() => {
    if (result || cycles.length) {
      redrawSeries();
      if (result) drawProfiles(result);
    }
    const id = selected;
    if (result && id) scores.show(id, () => selected === id);
  });
}
