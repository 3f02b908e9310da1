// The attached measurements scored against the run shown (GET .../scores): a small table
// under each figure that draws them (the model's value at each measured point, the
// residual measured − model, the z-score against the given spread), and the scores' CSV.
import { api, download } from "./api.js";
import { $, button } from "./dom.js";
import { RUN_PLOT } from "./ids.js";

const FIGURE = { wear_volume: RUN_PLOT.volume, profile: RUN_PLOT.profile, ocp: RUN_PLOT.potential };

const fmt = (v) => (v == null ? "—" : Number(v).toPrecision(4));

// The scores box of figure `id`, made on first use under its chart.
function box(id) {
  const figure = $(id);
  let div = figure.querySelector(".scores");
  if (!div) {
    div = document.createElement("div");
    div.className = "scores scroll-x";
    figure.appendChild(div);
  }
  return div;
}

/** Removes every scores table (another run is shown, or its measurements changed). */
export function clear() {
  for (const id of Object.values(FIGURE)) {
    const div = $(id).querySelector(".scores");
    if (div) div.replaceChildren();
  }
}

// One kind's table: a caption naming the columns and the rms residual, a row per point.
function table(score) {
  const t = document.createElement("table");
  t.className = "scores-table";
  const caption = t.createCaption();
  const rms = score.rms_residual == null ? "no point within the run" : `rms residual ${fmt(score.rms_residual)}`;
  caption.textContent = `Measured ${score.column} against the model's ${score.model_column}: ${rms}`;
  const head = t.createTHead().insertRow();
  for (const h of [score.x_column, "measured", "model", "residual", "z-score"]) {
    const th = document.createElement("th");
    th.textContent = h;
    head.appendChild(th);
  }
  const body = t.createTBody();
  for (const p of score.points) {
    const row = body.insertRow();
    for (const v of [p.x, p.measured, p.model, p.residual, p.z_score]) row.insertCell().textContent = fmt(v);
  }
  return t;
}

/** Reads job `id`'s scores and draws each kind's table under its figure; `current()` says
 * whether the job is still the one shown. */
export async function show(id, current) {
  const r = await api(`/api/v1/jobs/${id}/scores`);
  if (!current()) return;
  clear();
  if (!r.ok || !r.body) return;
  for (const [kind, figure] of Object.entries(FIGURE)) {
    const score = r.body[kind];
    const div = box(figure);
    div.dataset.points = score ? String(score.points.length) : "0";
    if (!score) continue;
    const csv = button("Scores CSV", () => download(`/api/v1/jobs/${id}/scores.csv`, `tribosim-${id}.scores.csv`));
    div.replaceChildren(table(score), csv);
  }
}
