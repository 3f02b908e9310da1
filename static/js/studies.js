// Studies: the form's scene across the combinations of some of its values. The list with
// each study's progress, and the panel with its members, their final results against an
// axis, and the members ticked for comparison.
import { api, download, errorText, postJson } from "./api.js";
import { $, button, reveal } from "./dom.js";
import * as compare from "./compare.js";
import * as form from "./form.js";
import { setHash } from "./hash.js";
import { STUDY, STUDY_PLOT } from "./ids.js";
import * as jobs from "./jobs.js";
import { COLORS, joinTables, linePlot } from "./plots.js";
import { describe, fieldLabel, fieldName, fmtValue, readable } from "./words.js";

const STUDY_ACTIVE = new Set(["queued", "running"]);

let studies = [];      // the study records
let study = null;      // the study shown in the panel
let summary = null;    // its summary: each member's values and summary
let picks = new Set(); // job ids of its members ticked for comparison
let timer = null;

const studyEnded = (s) => s.members.filter((m) => !STUDY_ACTIVE.has(m.status)).length;

// The study's base: the form's scene, or its pasted JSON (null, with the reason shown, when
// that does not parse).
function baseScene() {
  if (!form.isJsonMode()) return form.sceneFromFields();
  try { return JSON.parse(form.sceneJsonText()); } catch (e) {
    $(STUDY.errors).textContent = "The scene JSON is not valid: " + e.message;
    return null;
  }
}

async function submitStudy(event) {
  event.preventDefault();
  $(STUDY.errors).textContent = "";
  let axes;
  try { axes = JSON.parse($(STUDY.axes).value); } catch (e) {
    $(STUDY.errors).textContent = "The axes are not valid JSON: " + e.message;
    return;
  }
  const base = baseScene();
  if (!base) return;
  $(STUDY.submit).disabled = true;
  try {
    const r = await postJson("/api/v1/studies", { base, axes });
    if (!r.ok) { $(STUDY.errors).textContent = "Not started: " + readable(errorText(r)); return; }
    await refresh();
    await jobs.refresh();
    select(r.body.id, { scroll: true });
  } catch (e) {
    $(STUDY.errors).textContent = "Could not reach the server: " + e.message;
  } finally {
    $(STUDY.submit).disabled = false;
  }
}

/** Reads the list (and the study shown); polls again in a second while one is active, else in five. */
export async function refresh() {
  clearTimeout(timer);
  const r = await api("/api/v1/studies?limit=50");
  if (!r.ok) {
    $(STUDY.message).textContent = r.status === 404 ? "This server runs no studies." : "";
    return;
  }
  studies = r.body;
  renderList();
  if (study) {
    const record = studies.find((s) => s.id === study.id);
    if (record) { study = record; await loadSummary(); }
  }
  const busy = studies.some((s) => STUDY_ACTIVE.has(s.status));
  timer = setTimeout(refresh, busy ? 1000 : 5000);
}

async function deleteStudy(s, active) {
  if (!confirm(active ? `Cancel the study "${s.name}" and its members that have not ended?` : `Delete the study "${s.name}"?`)) return;
  const r = await api(`/api/v1/studies/${s.id}`, { method: "DELETE" });
  if (!r.ok && r.status !== 404) alert("Error: " + errorText(r));
  if (!active && study && study.id === s.id) { study = null; $(STUDY.panel).hidden = true; }
  await refresh();
  jobs.refresh();
}

function listRow(s) {
  const tr = document.createElement("tr");
  tr.dataset.id = s.id;
  if (study && study.id === s.id) tr.className = "selected";
  tr.innerHTML = `<td><span class="name"></span><br><span class="muted"></span></td><td class="status-${s.status}"></td>
      <td><progress max="${s.members.length}" value="${studyEnded(s)}"></progress><br><span class="muted"></span></td><td class="actions"></td>`;
  tr.querySelector(".name").textContent = s.name;
  tr.querySelector("td .muted").textContent = s.axes.map((a) => `${fieldName(a.path).name}: ${a.values.map(fmtValue).join(", ")}`).join("; ");
  tr.children[1].textContent = s.status;
  tr.children[2].querySelector(".muted").textContent = `${studyEnded(s)} of ${s.members.length} ended`;
  tr.children[2].querySelector("progress").setAttribute("aria-label", `${s.name}: ${studyEnded(s)} of ${s.members.length} members ended`);
  const view = button("View", () => select(s.id, { scroll: true, focus: true }));
  view.className = "view";
  view.setAttribute("aria-label", `View the study ${s.name}`);
  const active = STUDY_ACTIVE.has(s.status);
  const del = button(active ? "Cancel" : "Delete", () => deleteStudy(s, active));
  del.className = active ? "cancel" : "delete";
  del.setAttribute("aria-label", `${active ? "Cancel" : "Delete"} the study ${s.name}`);
  tr.querySelector(".actions").append(view, del);
  return tr;
}

function renderList() {
  $(STUDY.table).hidden = !studies.length;
  $(STUDY.message).textContent = studies.length ? "" : "No studies yet.";
  $(STUDY.table).querySelector("tbody").replaceChildren(...studies.map(listRow));
}

/** Shows study `id` (one of those listed): (id, { scroll, focus }). */
export async function select(id, how = {}) {
  study = studies.find((s) => s.id === id) || null;
  if (!study) return;
  setHash("study", id);
  picks = new Set();
  $(STUDY.panel).hidden = false;
  const numeric = study.axes.filter((a) => a.values.every((v) => typeof v === "number"));
  $(STUDY.axis).replaceChildren(...numeric.map((a) => new Option(fieldLabel(a.path), a.path)));
  renderList();
  await loadSummary();
  if (how.scroll) reveal($(STUDY.panel), how.focus);
}

async function loadSummary() {
  const shown = study;
  const r = await api(`/api/v1/studies/${shown.id}/summary`);
  if (!study || study.id !== shown.id) return;
  summary = r.ok ? r.body : { members: [] };
  renderStudy();
}

function membersHead() {
  const head = document.createElement("tr");
  head.innerHTML = "<th><span class=sr-only>Compare</span></th><th>#</th>";
  for (const a of study.axes) {
    const th = document.createElement("th");
    th.textContent = fieldLabel(a.path);
    head.appendChild(th);
  }
  head.insertAdjacentHTML("beforeend", "<th>status</th><th class=num>wear volume (10⁻³ mm³)</th><th class=num>maximum depth (µm)</th><th class=num>WAC (10⁻³ mm³)</th><th class=num>potential (V)</th>");
  return head;
}

// A member's tick box, for comparing ended members.
function memberPick(m) {
  const pick = document.createElement("input");
  pick.type = "checkbox";
  pick.disabled = !jobs.ENDED.has(m.status);
  pick.checked = picks.has(m.job_id);
  pick.setAttribute("aria-label", `Compare member ${m.index + 1}`);
  pick.addEventListener("change", () => {
    if (pick.checked) picks.add(m.job_id); else picks.delete(m.job_id);
    $(STUDY.compare).disabled = picks.size < 2;
  });
  const cell = document.createElement("td");
  cell.appendChild(pick);
  return cell;
}

function memberRow(m, row) {
  const tr = document.createElement("tr");
  const warned = (row.summary && row.summary.warnings) || [];
  const status = m.status + (row.error ? ": " + readable(row.error) : "") +
    (warned.length ? `, with ${warned.length} warning${warned.length > 1 ? "s" : ""}: ${warned.join("; ")}` : "");
  const cells = [String(m.index + 1), ...study.axes.map((a) => fmtValue(m.values[a.path])), status];
  for (const key of ["wear_volume_mm3", "max_depth_um", "wac_volume_mm3", "potential_v"]) {
    const v = row.summary && row.summary[key];
    cells.push(v == null ? "" : fmtValue(key.endsWith("mm3") ? v * 1e3 : v));
  }
  tr.appendChild(memberPick(m));
  cells.forEach((text, i) => {
    const td = document.createElement("td");
    td.textContent = text;
    if (i > study.axes.length + 1) td.className = "num";
    tr.appendChild(td);
  });
  return tr;
}

function renderStudy() {
  const ended = studyEnded(study);
  $(STUDY.title).textContent = `Study: ${study.name}`;
  $(STUDY.status).textContent = `${study.status}: ${ended} of ${study.members.length} members ended` +
    Object.entries(study.counts).filter(([, n]) => n).map(([k, n]) => `, ${n} ${k}`).join("");
  $(STUDY.status).className = "status-" + (study.status === "partial" ? "failed" : study.status);
  $(STUDY.progress).max = study.members.length;
  $(STUDY.progress).value = ended;
  const rows = new Map((summary.members || []).map((m) => [m.index, m]));
  $(STUDY.members).querySelector("thead").replaceChildren(membersHead());
  $(STUDY.members).querySelector("tbody").replaceChildren(...study.members.map((m) => memberRow(m, rows.get(m.index) || {})));
  $(STUDY.compare).disabled = picks.size < 2;
  drawPlots();
}

// The members with a summary, grouped by their values on the axes other than `axis`.
function groupsBy(axis, members) {
  const others = study.axes.map((a) => a.path).filter((p) => p !== axis);
  const groups = new Map();
  for (const m of members) {
    const key = others.map((p) => describe(p, m.values[p])).join(", ") || "members";
    if (!groups.has(key)) groups.set(key, []);
    groups.get(key).push(m);
  }
  return groups;
}

// Each final quantity against the chosen axis: one line per combination of the other axes.
function drawPlots() {
  const axis = $(STUDY.axis).value;
  const members = (summary.members || []).filter((m) => m.summary);
  if (!axis) return;
  const groups = groupsBy(axis, members);
  const { name } = fieldName(axis);
  const keys = [...groups.keys()];
  for (const [plotId, key, yLabel, scale] of [
    [STUDY_PLOT.volume, "wear_volume_mm3", "wear volume (10⁻³ mm³)", 1e3],
    [STUDY_PLOT.depth, "max_depth_um", "maximum wear depth (µm)", 1],
    [STUDY_PLOT.wac, "wac_volume_mm3", "WAC volume (10⁻³ mm³)", 1e3],
    [STUDY_PLOT.potential, "potential_v", "potential (V vs Ag/AgCl)", 1],
  ]) {
    const tables = keys.map((k) => {
      const ms = groups.get(k).slice().sort((a, b) => a.values[axis] - b.values[axis]);
      return [ms.map((m) => m.values[axis]), ms.map((m) => (m.summary[key] == null ? null : m.summary[key] * scale))];
    });
    const count = tables.reduce((s, t) => s + t[1].filter((v) => v != null).length, 0);
    const note = $(plotId).querySelector(".note");
    if (note) note.textContent = members.length && !count ? "The members have no corrosion model: nothing to plot." : "";
    const h3 = $(plotId).querySelector("h3");
    h3.textContent = `${h3.textContent.split(" against ")[0]} against ${name}`;
    if (!tables.length) continue;
    const series = keys.map((k, i) => ({ label: k, stroke: COLORS[i % COLORS.length], width: 2, spanGaps: true, points: { show: true, size: 7 } }));
    linePlot(plotId, joinTables(tables), series, fieldLabel(axis), yLabel, count, { rebuild: true });
  }
}

async function compareMembers() {
  jobs.tick(picks);
  await jobs.refresh();
  await compare.open();
}

/** Wires the study form and the panel's controls. */
export function init() {
  $(STUDY.form).addEventListener("submit", submitStudy);
  $(STUDY.axis).addEventListener("change", drawPlots);
  $(STUDY.compare).addEventListener("click", compareMembers);
  $(STUDY.report).addEventListener("click", () => {
    if (study) download(`/api/v1/studies/${study.id}/report`, `tribosim-study-${study.id}.report.html`);
  });
}
