// The paper's Fig. 11 beside a run of its scene: the wear volume of the elastic and of the
// elastic-perfectly-plastic (EPP) disc over the first 300 cycles. The material the run is
// not comes from a companion run: the same scene with the other `wear.plasticity`, an
// ordinary job, tagged and noted so that a user sees what it is and the next view finds it
// again instead of computing it anew.
import { api, errorText, postJson } from "./api.js";
import { sleep } from "./dom.js";
import * as jobs from "./jobs.js";
import { differingPaths, getPath, readable } from "./words.js";

/** Fig. 11's span: the first 300 cycles (300 s at 60 rpm). */
export const FIG11_CYCLES = 300;
/** The tag every companion run carries, by which it is found again. */
export const COMPANION_TAG = "fig11";
// Companions listed when looking for one; the search asks the scene of those of the
// wanted length only, so a few hundred cost a few requests.
const LISTED = 500;
const POLL_MS = 1000;
const STOPPED = new Set(["failed", "cancelled", "damaged"]);

/** The two materials of Fig. 11: the plasticity a companion runs with, its legend, its word. */
export const MATERIALS = Object.freeze({
  epp: { plasticity: "on", label: "EPP (elastic-perfectly-plastic)", word: "EPP" },
  elastic: { plasticity: "off", label: "elastic (perfectly elastic)", word: "elastic" },
});

// Companion runs by `<run id> <material>`: { status, job, records, reason }, status one of
// looking, queued, running, ready, failed.
const companions = new Map();

/** The material of a scene's disc: elastic with the cap off, else EPP. */
export const materialOf = (scene) => (getPath(scene, "wear.plasticity") === "off" ? "elastic" : "epp");

/** The view's cycles: Fig. 11's 300, or the run's own if fewer. */
export const viewCycles = (scene) => Math.min(FIG11_CYCLES, getPath(scene, "test.cycles") || FIG11_CYCLES);

/** The scene of the companion in `material` of a run of `scene` (the scene as run). */
export function companionScene(scene, material) {
  const copy = structuredClone(scene);
  copy.name = `${scene.name || "run"}: ${MATERIALS[material].word}, Fig. 11`;
  copy.wear = { ...(copy.wear || {}), plasticity: MATERIALS[material].plasticity };
  copy.test = { ...(copy.test || {}), cycles: viewCycles(scene) };
  return copy;
}

// A companion already asked for: a job tagged so whose scene is `wanted` but for its name,
// succeeded or on its way (a succeeded one first); null when there is none.
async function findCompanion(wanted) {
  const query = new URLSearchParams({ tag: COMPANION_TAG, status: "succeeded,running,queued", limit: String(LISTED) });
  const r = await api(`/api/v1/jobs?${query}`);
  if (!r.ok) throw new Error(`the job list could not be read: ${readable(errorText(r))}`);
  const rank = (job) => (job.status === "succeeded" ? 0 : 1);
  const candidates = r.body.filter((job) => job.cycles_total === getPath(wanted, "test.cycles")).sort((a, b) => rank(a) - rank(b));
  for (const job of candidates) {
    const s = await api(`/api/v1/jobs/${job.id}/scene`);
    if (s.ok && s.body && !differingPaths([wanted, s.body]).length) return job;
  }
  return null;
}

// Submits the companion in `material` of run `runId`, labelled with what it is.
async function submit(runId, wanted, material) {
  const query = new URLSearchParams({ note: `Fig. 11 ${MATERIALS[material].word} companion of ${runId}`, tags: COMPANION_TAG });
  const r = await postJson(`/api/v1/jobs?${query}`, wanted);
  if (!r.ok) throw new Error(`the server refused it: ${readable(errorText(r))}`);
  jobs.refresh();
  return r.body;
}

// Follows the entry's job to its end, then reads its cycle records.
async function follow(entry, changed) {
  while (entry.job.status !== "succeeded") {
    if (STOPPED.has(entry.job.status)) {
      throw new Error(`job ${entry.job.id} ${entry.job.status}${entry.job.error ? ": " + readable(entry.job.error) : ""}`);
    }
    entry.status = entry.job.status;
    changed();
    await sleep(POLL_MS);
    const r = await api(`/api/v1/jobs/${entry.job.id}`);
    if (!r.ok) throw new Error(r.status === 404 ? `job ${entry.job.id} was deleted` : readable(errorText(r)));
    entry.job = r.body;
  }
  const r = await api(`/api/v1/jobs/${entry.job.id}/result?compact=true`);
  if (!r.ok || !r.body || !Array.isArray(r.body.cycles)) throw new Error(`the result of job ${entry.job.id} could not be read: ${readable(errorText(r))}`);
  entry.records = r.body.cycles;
  entry.status = "ready";
  changed();
}

// The companion of `key`: found or submitted once, then followed; `changed()` on each news.
function companion(key, runId, scene, material, changed) {
  if (companions.has(key)) return companions.get(key);
  const entry = { status: "looking", job: null, records: null, reason: "" };
  companions.set(key, entry);
  const wanted = companionScene(scene, material);
  (async () => {
    entry.job = (await findCompanion(wanted)) || (await submit(runId, wanted, material));
    await follow(entry, changed);
  })().catch((e) => {
    entry.status = "failed";
    entry.reason = e.message;
    changed();
  });
  return entry;
}

/** Forgets the companions that failed, so that the view asks for them anew. */
export function forgetFailed() {
  for (const [key, entry] of companions) if (entry.status === "failed") companions.delete(key);
}

/**
 * The view of run `runId` (its scene as run and its cycle `records`, `ended` once it has
 * stopped): `{ cycles, curves }`, a curve per material `{ material, records, entry }`: the
 * run's own records when it is that material and they reach the view's end (or it is still
 * running), else its companion's (`entry`; records null until they come). `changed()` is
 * called when a companion has news.
 */
export function fig11Curves(runId, scene, records, ended, changed) {
  const cycles = viewCycles(scene);
  const last = records.length ? records[records.length - 1].cycle : 0;
  const ownCovers = !ended || last >= cycles;
  const curves = Object.keys(MATERIALS).map((material) => {
    if (material === materialOf(scene) && ownCovers) return { material, records: records.filter((r) => r.cycle <= cycles), entry: null };
    const entry = companion(`${runId} ${material}`, runId, scene, material, changed);
    return { material, records: entry.records, entry };
  });
  return { cycles, curves };
}

// One curve's source in words.
function curveWords(curve) {
  const { entry } = curve;
  const word = MATERIALS[curve.material].word;
  if (!entry) return `${word}: this run`;
  if (entry.status === "looking") return `looking for the ${word} companion…`;
  if (entry.status === "queued" || entry.status === "running") {
    return `computing the ${word} companion… ${entry.job.cycles_done} / ${entry.job.cycles_total} cycles (job ${entry.job.id})`;
  }
  if (entry.status === "failed") return `the ${word} companion failed: ${entry.reason}; tick the view again to retry`;
  return `${word}: the companion run ${entry.job.id}`;
}

/** The view's sources and state in words: where each curve comes from, what is computing or failed. */
export const fig11Note = (view) => `Fig. 11 over cycles 1 to ${view.cycles} — ${view.curves.map(curveWords).join("; ")}`;

/** "ready" when both curves are drawn, "failed" when a companion failed, else "computing". */
export function fig11State(view) {
  if (view.curves.some((c) => c.entry && c.entry.status === "failed")) return "failed";
  return view.curves.every((c) => c.records) ? "ready" : "computing";
}
