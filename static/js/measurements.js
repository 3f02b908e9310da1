// The measurements attached to the run shown: listed, attached from a CSV (or JSON) table,
// removed; their points are what the run's figures draw beside the model.
import { api, errorText } from "./api.js";
import { $, button } from "./dom.js";
import { MEASURE } from "./ids.js";
import { topic } from "./topic.js";
import { readable } from "./words.js";

const NAMES = { wear_volume: "wear volume", profile: "groove profile", ocp: "open-circuit potential (OCP)" };

let jobId = null;
let tables = null;
const changed = topic();

/** Listens for the attached tables having been read anew (to redraw the figures). */
export const onChange = changed.on;

/** Forgets the tables and hides their box (another run is shown, or none). */
export function forget() {
  jobId = null;
  tables = null;
  $(MEASURE.box).hidden = true;
  $(MEASURE.read).textContent = "";
}

// How the server read a table's headers under the documented names, in words; "" when
// every header was a documented name already.
const readAs = (renamed) => (renamed && renamed.length
  ? `Read ${renamed.map((r) => `“${r.header}” as ${r.column}`).join(", ")}.`
  : "");

// The longest column of a table.
const rowCount = (table) => Math.max(0, ...Object.values(table).map((c) => (Array.isArray(c) ? c.length : 0)));

/** Reads job `id`'s attached tables and lists them, then announces them. */
export async function load(id) {
  jobId = id;
  const r = await api(`/api/v1/jobs/${id}/measurements`);
  if (jobId !== id) return;
  tables = r.ok ? r.body : null;
  $(MEASURE.box).hidden = !r.ok;
  $(MEASURE.list).replaceChildren(...Object.entries(tables || {}).filter(([, t]) => t).map(([kind, table]) => {
    const li = document.createElement("li");
    li.textContent = `${NAMES[kind] || kind}: ${rowCount(table)} points (${Object.keys(table).join(", ")}) `;
    const del = button("Remove", async () => {
      await api(`/api/v1/jobs/${id}/measurements/${kind}`, { method: "DELETE" });
      load(id);
    });
    del.setAttribute("aria-label", `Remove the attached ${NAMES[kind] || kind}`);
    li.appendChild(del);
    return li;
  }));
  changed.emit();
}

async function attach(event) {
  event.preventDefault();
  const id = jobId;
  const kind = $(MEASURE.kind).value;
  const file = $(MEASURE.file).files[0];
  const text = file ? await file.text() : $(MEASURE.text).value;
  $(MEASURE.errors).textContent = "";
  $(MEASURE.read).textContent = "";
  if (!text.trim()) { $(MEASURE.errors).textContent = "Choose a CSV file or paste a table first."; return; }
  const json = /^\s*[[{]/.test(text);
  const r = await api(`/api/v1/jobs/${id}/measurements/${kind}`, {
    method: "PUT", headers: { "Content-Type": json ? "application/json" : "text/csv" }, body: text,
  });
  if (!r.ok) {
    $(MEASURE.errors).textContent = "Not attached: " + readable(errorText(r));
    return;
  }
  $(MEASURE.file).value = "";
  $(MEASURE.text).value = "";
  $(MEASURE.read).textContent = readAs(r.body.renamed);
  await load(id);
}

/** An attached table's points as [x, y] pairs sorted by x, or [] when there is none. */
export function attachedPoints(kind, xOf, yOf) {
  const table = tables && tables[kind];
  if (!table) return [];
  const n = rowCount(table);
  const pts = [];
  for (let i = 0; i < n; i++) {
    const x = xOf(table, i), y = yOf(table, i);
    if (Number.isFinite(x) && Number.isFinite(y)) pts.push([x, y]);
  }
  return pts.sort((a, b) => a[0] - b[0]);
}

/** Wires the attach form. */
export function init() {
  $(MEASURE.form).addEventListener("submit", attach);
}
