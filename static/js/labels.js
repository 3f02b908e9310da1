// The lab's labels of the run shown: its sample, tags and note, read with the job and
// changed with PATCH /api/v1/jobs/{id}; the job list finds a run by any of them (?q).
import { api, errorText } from "./api.js";
import { $ } from "./dom.js";
import { LABELS } from "./ids.js";
import { readable } from "./words.js";

let jobId = null;

// The form's fields from a job record.
function fill(job) {
  $(LABELS.sample).value = job.sample || "";
  $(LABELS.tags).value = (job.tags || []).join(", ");
  $(LABELS.note).value = job.note || "";
}

/** Reads job `id`'s labels into the form. */
export async function load(id) {
  jobId = id;
  $(LABELS.status).textContent = "";
  const r = await api(`/api/v1/jobs/${id}`);
  if (jobId === id && r.ok && r.body) fill(r.body);
}

async function save(event, saved) {
  event.preventDefault();
  const id = jobId;
  const tags = $(LABELS.tags).value.split(",").map((t) => t.trim()).filter(Boolean);
  const body = { sample: $(LABELS.sample).value.trim() || null, note: $(LABELS.note).value.trim() || null, tags };
  const r = await api(`/api/v1/jobs/${id}`, { method: "PATCH", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
  if (id !== jobId) return;
  if (!r.ok) { $(LABELS.status).textContent = "Not saved: " + readable(errorText(r)); return; }
  fill(r.body);
  $(LABELS.status).textContent = "Saved.";
  saved();
}

/** Wires the form; `saved()` is called after each change stored (to list the jobs again). */
export function init(saved) {
  $(LABELS.form).addEventListener("submit", (event) => save(event, saved));
}
