// The job list, polled from /api/v1/jobs: each job's status, progress and why it is where
// it is, with View, Cancel and Delete, and the ticks that choose runs to compare. The page
// asks for the newest jobs it shows (a page of PAGE, more on "Show older jobs"), narrowed by
// the status and name filters, so polling costs the same however many jobs the server keeps.
import { api } from "./api.js";
import { $, button } from "./dom.js";
import { JOBS } from "./ids.js";
import { topic } from "./topic.js";
import { readable } from "./words.js";

const ACTIVE = new Set(["queued", "running"]);
/** Jobs asked for at a time. */
const PAGE = 50;
/** The most the server gives in one page (openapi.yaml, `limit`). */
const MOST = 1000;
let wanted = PAGE;
/** Jobs that may have a result, whole or partial, to show and compare. */
export const ENDED = new Set(["succeeded", "failed", "cancelled"]);

let jobs = [];
let highlighted = null;
let ticked = new Set();
let pollTimer = null;
const viewed = topic();
const deleted = topic();
const listed = topic();

/** Listens for View: (id, { scroll, focus }). */
export const onView = viewed.on;
/** Listens for a job deleted (not cancelled): (id). */
export const onDeleted = deleted.on;
/** Listens for the list drawn anew: (jobs). */
export const onListed = listed.on;

/** Shows job `id` in the run panel: (id, { scroll, focus }). */
export const view = (id, how = {}) => viewed.emit(id, how);

/** The newest job listed for which `keep(job)` holds (any job without it), or null. */
export const newest = (keep = () => true) => jobs.find(keep) || null;

/** The job of this id, as last listed. */
export const find = (id) => jobs.find((j) => j.id === id);

/** The ids of the ticked jobs, oldest first. */
export const tickedIds = () => jobs.filter((j) => ticked.has(j.id)).map((j) => j.id).reverse();

/** Ticks exactly these jobs. */
export const tick = (ids) => { ticked = new Set(ids); };

/** Marks the job shown in the run panel (or none) in the list. */
export function highlight(id) {
  highlighted = id;
  for (const row of document.querySelectorAll(`#${JOBS.table} tr[data-id]`)) row.classList.toggle("selected", row.dataset.id === id);
}

/** Reads the list and draws it; polls again in a second while a job is active, else in five. */
export async function refresh() {
  clearTimeout(pollTimer);
  try {
    const query = new URLSearchParams({ limit: String(wanted) });
    if ($(JOBS.status).value) query.set("status", $(JOBS.status).value);
    if ($(JOBS.name).value.trim()) query.set("q", $(JOBS.name).value.trim());
    const r = await api("/api/v1/jobs?" + query);
    if (r.ok) {
      jobs = r.body;
      $(JOBS.more).hidden = !/rel="next"/.test(r.link || "") || wanted >= MOST;
      render();
    } else {
      $(JOBS.message).textContent = r.status === 401 ? "Enter the server's token to see the jobs." : "Error: " + r.body.error;
    }
  } catch (e) {
    $(JOBS.message).textContent = "Could not reach the server: " + e.message;
  }
  const busy = jobs.some((j) => ACTIVE.has(j.status));
  pollTimer = setTimeout(refresh, busy ? 1000 : 5000);
}

/** Wires the filters and "Show older jobs". */
export function init() {
  $(JOBS.filter).addEventListener("submit", (event) => { event.preventDefault(); refresh(); });
  $(JOBS.status).addEventListener("change", () => { wanted = PAGE; refresh(); });
  let typing;
  $(JOBS.name).addEventListener("input", () => {
    clearTimeout(typing);
    typing = setTimeout(() => { wanted = PAGE; refresh(); }, 300);
  });
  $(JOBS.more).addEventListener("click", () => { wanted = Math.min(wanted + PAGE, MOST); refresh(); });
}

/** "3 / 10", with the time left of a running job or the place of a queued one. */
export function progressText(job) {
  let text = `${job.cycles_done} / ${job.cycles_total}`;
  if (job.status === "running" && job.eta_s != null) text += `, ${Math.ceil(job.eta_s)} s left`;
  if (job.status === "queued" && job.queue_position != null) text += `, number ${job.queue_position} in the queue`;
  return text;
}

/**
 * Why a job is where it is, in words: a failure's or a damage's message, a cancel, and why a
 * finished job is running again. Empty for a job on its normal course.
 */
export function jobReason(job) {
  const parts = [];
  if (job.status === "failed") parts.push("Failed: " + (job.error || "no reason was recorded."));
  else if (job.status === "damaged") parts.push("Damaged: " + (job.error || "no detail was recorded."));
  else if (job.status === "cancelled") parts.push(`Cancelled on request after ${job.cycles_done} of ${job.cycles_total} cycles.`);
  else if (job.error) parts.push(job.error);
  if (job.rerun_reason) parts.push("Run again: " + job.rerun_reason);
  return readable(parts.join(" "));
}

/** Moves a job's bar in the list to `cycle` as its event stream reports it. */
export function showProgress(id, cycle) {
  const rowBar = document.querySelector(`#${JOBS.table} tr[data-id="${id}"] progress`);
  if (rowBar) {
    rowBar.value = Math.max(rowBar.value, cycle);
    rowBar.nextElementSibling.nextElementSibling.textContent = `${rowBar.value} / ${rowBar.max}`;
  }
}

// The row's tick box, for comparing ended runs.
function comparePick(tr, job) {
  const pick = tr.querySelector(".compare-pick");
  pick.setAttribute("aria-label", `Compare ${job.name}`);
  pick.disabled = !ENDED.has(job.status);
  pick.checked = ticked.has(job.id);
  pick.addEventListener("change", () => {
    if (pick.checked) ticked.add(job.id); else ticked.delete(job.id);
    updateCompareButton();
  });
}

// View, and Cancel (an active job) or Delete.
function actions(tr, job) {
  const cell = tr.querySelector(".actions");
  const view = button("View", () => viewed.emit(job.id, { scroll: true, focus: true }));
  view.setAttribute("aria-label", `View ${job.name}`);
  view.className = "view";
  cell.appendChild(view);
  const active = ACTIVE.has(job.status);
  const del = button(active ? "Cancel" : "Delete", () => deleteJob(job));
  del.setAttribute("aria-label", `${active ? "Cancel" : "Delete"} ${job.name}`);
  del.className = active ? "cancel" : "delete";
  cell.appendChild(del);
}

function row(job) {
  const tr = document.createElement("tr");
  tr.dataset.id = job.id;
  if (job.id === highlighted) tr.className = "selected";
  const created = new Date(job.created_at).toLocaleString();
  tr.innerHTML = `<td><input type="checkbox" class="compare-pick"></td><td><span class="name"></span><br><span class="muted"></span></td>
      <td class="status-${job.status}"><span class="status"></span><span class="reason"></span></td>
      <td class="progress"><progress max="${job.cycles_total}" value="${job.cycles_done}"></progress><br><span class="muted"></span></td>
      <td class="actions"></td>`;
  comparePick(tr, job);
  tr.querySelector(".name").textContent = job.name;
  const labels = [job.sample, ...(job.tags || []).map((t) => `#${t}`)].filter(Boolean);
  tr.querySelector("td .muted").textContent = labels.length ? `${created} · ${labels.join(" ")}` : created;
  tr.querySelector(".status").textContent = job.status;
  tr.querySelector(".reason").textContent = jobReason(job);
  tr.querySelector(".progress .muted").textContent = progressText(job);
  tr.querySelector(".progress progress").setAttribute("aria-label", `${job.name}: ${progressText(job)} cycles`);
  actions(tr, job);
  return tr;
}

function render() {
  const tbody = document.querySelector(`#${JOBS.table} tbody`);
  $(JOBS.table).hidden = jobs.length === 0;
  const filtered = $(JOBS.status).value || $(JOBS.name).value.trim();
  $(JOBS.message).textContent = jobs.length ? "" : filtered ? "No job matches." : "No jobs yet.";
  for (const id of ticked) if (!jobs.some((j) => j.id === id && ENDED.has(j.status))) ticked.delete(id);
  const rows = jobs.map(row);
  // Re-rendering must not take the keyboard's place: the focused control is found again.
  const focused = document.activeElement && document.activeElement.closest(`#${JOBS.table} tr[data-id]`);
  const focusKey = focused && [focused.dataset.id, document.activeElement.className];
  tbody.replaceChildren(...rows);
  if (focusKey) {
    const again = tbody.querySelector(`tr[data-id="${focusKey[0]}"] .${focusKey[1] ? focusKey[1].split(" ")[0] : "view"}`);
    if (again) again.focus();
  }
  updateCompareButton();
  listed.emit(jobs);
}

function updateCompareButton() {
  const n = ticked.size;
  $(JOBS.compare).disabled = n < 2;
  $(JOBS.compare).textContent = n ? `Compare the ticked runs (${n})` : "Compare the ticked runs";
}

async function deleteJob(job) {
  const question = ACTIVE.has(job.status)
    ? `Cancel the run "${job.name}"? It stops within a cycle and cannot be resumed.`
    : `Delete the run "${job.name}" and its result?`;
  if (!confirm(question)) return;
  const r = await api(`/api/v1/jobs/${job.id}`, { method: "DELETE" });
  if (!r.ok && r.status !== 404) alert("Error: " + r.body.error);
  if (r.status === 204) deleted.emit(job.id);
  await refresh();
}
