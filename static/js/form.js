// The new-run form: a preset, the main fields (or a pasted scene JSON), a measured height
// map for a rough disc; the run's name follows the fields until the user types one, and
// the server's refusals are shown next to the fields they name.
import { api, postJson } from "./api.js";
import { $ } from "./dom.js";
import { FORM, fieldId } from "./ids.js";
import { applyMaterials, discHardness, loadMaterials, lockMaterials, showMaterials } from "./materials.js";
import { RIG_PATHS, applyRig, initRig, lockRig, rigChanges, rigInputs, showRig } from "./rig.js";
import * as run from "./run.js";
import { allPresets, closestPreset, loadPresets as readPresets, presetNamed, withOverrides } from "./scenes.js";
import { describe, differingPaths, flatten, getPath, setPath } from "./words.js";

// The main fields: [scene path, label with unit, kind]. kind "grid" accepts "auto" too.
const FIELDS = [
  ["test.load_n", "Load (N)", "number"],
  ["test.speed_rpm", "Speed (rpm)", "number"],
  ["test.cycles", "Cycles", "integer"],
  ["test.friction_coefficient", "Friction coefficient (–)", "number"],
  ["wear.archard_k", "Archard k (–)", "number"],
  ["disc.hardness_mpa", "Disc hardness (MPa)", "number"],
  ["numerics.grid", "Grid (cells per side, or auto)", "grid"],
];

let nameEdited = false; // the user typed the run name: it no longer follows the fields
let formExtra = null;   // a re-run's fields that have no input in the form: {from, overrides}
let surface = null;     // the uploaded height map the form's scene runs on

const mainInputs = () => [...document.querySelectorAll(`#${FORM.mainFields} input`)];
// Every input that shows a scene's value at its path: the main fields and the rig's.
const fieldInputs = () => [...mainInputs(), ...rigInputs()];
const currentPreset = () => presetNamed($(FORM.preset).value);

function buildFields() {
  const box = $(FORM.mainFields);
  for (const [path, label, kind] of FIELDS) {
    const id = fieldId(path);
    const div = document.createElement("div");
    div.className = "field";
    div.dataset.path = path;
    div.innerHTML = `<label for="${id}"></label><input id="${id}" data-path="${path}" data-kind="${kind}" placeholder="default"
      ${kind === "grid" ? 'type="text"' : 'type="number" step="any"'} aria-describedby="err-${id}">
      <span class="error" id="err-${id}" role="alert"></span>`;
    div.querySelector("label").textContent = label;
    box.appendChild(div);
  }
}

// Each main field and the rig show the scene's values.
function showValues(scene) {
  for (const input of fieldInputs()) {
    const v = getPath(scene, input.dataset.path);
    input.value = v == null ? "" : String(v);
  }
  showRig(scene);
}

function fillFromPreset() {
  const preset = currentPreset();
  if (!preset) return;
  formExtra = null;
  $(FORM.base).textContent = "";
  $(FORM.presetDescription).textContent = preset.description;
  showValues(preset.scene);
  showMaterials(preset.scene);
  nameEdited = false;
  followFields();
}

// A disc chosen from the library: the hardness field shows its value (empty where it has
// none, so the server names the field), not the preset's 316L; back to the preset's disc,
// the preset's.
function materialChanged(discChanged) {
  if (discChanged) {
    const library = discHardness();
    const hardness = library === undefined ? getPath(currentPreset().scene, "disc.hardness_mpa") : library;
    $(fieldId("disc.hardness_mpa")).value = hardness == null ? "" : String(+hardness.toFixed(1));
  }
  followFields();
}

function fieldValue(input) {
  const raw = input.value.trim();
  if (input.dataset.kind === "grid" && raw === "auto") return "auto";
  return raw !== "" && !Number.isNaN(Number(raw)) ? Number(raw) : raw;
}

// The run's name while the user has not typed one: the preset's, or the preset's id and
// what the fields change, so that a 10 N run is not called "5 N".
function autoName() {
  const preset = currentPreset();
  if (!preset) return $(FORM.name).value;
  const changes = [];
  for (const input of mainInputs()) {
    const value = fieldValue(input);
    if (value === "" || JSON.stringify(value) === JSON.stringify(getPath(preset.scene, input.dataset.path))) continue;
    changes.push(describe(input.dataset.path, value));
  }
  changes.push(...rigChanges(preset.scene, fieldValue));
  if (formExtra) {
    const extra = Object.entries(flatten(formExtra.overrides)).filter(([p]) => p !== "name");
    changes.push(...extra.slice(0, 3).map(([p, v]) => describe(p, v)));
    if (extra.length > 3) changes.push(`${extra.length - 3} more`);
  }
  return changes.length ? `${preset.name}: ${changes.join(", ")}` : preset.scene.name ?? preset.name;
}

// After a field changes: the name follows (until typed), and so does the JSON box (until
// it is chosen for submitting; then it is the user's).
function followFields() {
  if (!nameEdited) $(FORM.name).value = autoName();
  if (!isJsonMode()) $(FORM.sceneJson).value = JSON.stringify(sceneFromFields(), null, 2);
}

/** Whether the pasted JSON, not the fields, is what the form submits. */
export const isJsonMode = () => $(FORM.useJson).checked;

/** The pasted scene's text. */
export const sceneJsonText = () => $(FORM.sceneJson).value;

/**
 * The scene from the form: the preset plus every main field as an override (and a re-run's
 * other fields). A field that is not a number is sent as typed, so the server names it.
 */
export function sceneFromFields() {
  const overrides = formExtra ? structuredClone(formExtra.overrides) : {};
  const name = $(FORM.name).value.trim();
  if (name) overrides.name = name;
  for (const input of mainInputs()) {
    const value = fieldValue(input);
    if (value !== "") setPath(overrides, input.dataset.path, value);
  }
  const preset = currentPreset();
  applyRig(overrides, preset && preset.scene, fieldValue);
  applyMaterials(overrides);
  if (surface) {
    setPath(overrides, "disc.surface", { kind: "measured", id: surface.id, remove_tilt: $(FORM.surfaceTilt).checked });
  }
  return { preset: $(FORM.preset).value, overrides };
}

// The uploaded map in words.
function surfaceText(m) {
  const st = m.statistics;
  return `${m.name}: ${m.nx} × ${m.ny} pixels of ${+m.pixel_x_um.toPrecision(4)} µm (${m.format}), rms height ${+st.rms_height_um.toPrecision(3)} µm, rms slope ${+st.rms_slope.toPrecision(3)}; surface ${m.id}.`;
}

// A height map chosen: uploaded as it is (the server reads it as `tribosim run --surface`
// does), and its id goes into the scene's disc.surface.
async function uploadSurface() {
  const file = $(FORM.surfaceFile).files[0];
  if (!file) return;
  const status = $(FORM.surfaceStatus);
  const query = new URLSearchParams({ name: file.name });
  const pixel = $(FORM.surfacePixel).value.trim();
  if (pixel !== "") query.set("pixel_um", pixel);
  status.textContent = `Uploading ${file.name}…`;
  try {
    const r = await api(`/api/v1/surfaces?${query}`, {
      method: "POST", headers: { "Content-Type": "application/octet-stream" }, body: await file.arrayBuffer(),
    });
    if (!r.ok) {
      status.textContent = `${file.name} refused: ${(r.body && r.body.error) || r.status}`;
      return;
    }
    surface = r.body;
    status.textContent = surfaceText(surface);
    $(FORM.surfaceClear).hidden = false;
    followFields();
  } catch (e) {
    status.textContent = "Could not reach the server: " + e.message;
  }
}

function clearSurface() {
  surface = null;
  $(FORM.surfaceFile).value = "";
  $(FORM.surfaceClear).hidden = true;
  $(FORM.surfaceStatus).textContent = "None: the disc is smooth.";
  followFields();
}

// JSON mode: the JSON is what is submitted, so the fields show its values and cannot be
// edited (they would contradict it).
function setJsonMode() {
  const on = isJsonMode();
  for (const input of [...mainInputs(), $(FORM.name)]) input.readOnly = on;
  $(FORM.preset).disabled = on;
  lockMaterials(on);
  lockRig(on);
  $(FORM.fieldsToJson).disabled = on;
  if (on) fieldsFromJson();
  else followFields();
}

function fieldsFromJson() {
  let doc;
  try { doc = JSON.parse(sceneJsonText()); } catch {
    $(FORM.jsonErrors).textContent = "Not valid JSON yet: the fields show the last valid scene.";
    return;
  }
  $(FORM.jsonErrors).textContent = "";
  if (!doc || typeof doc !== "object") return;
  const scene = doc.preset ? withOverrides(doc) : doc;
  if (doc.preset && allPresets().some((p) => p.name === doc.preset)) $(FORM.preset).value = doc.preset;
  showValues(scene);
  $(FORM.name).value = (scene && scene.name) || "";
}

function clearErrors() {
  for (const el of document.querySelectorAll(".field .error")) el.textContent = "";
  for (const el of document.querySelectorAll(".field.invalid")) el.classList.remove("invalid");
  for (const el of document.querySelectorAll("[aria-invalid]")) el.removeAttribute("aria-invalid");
  $(FORM.errors).textContent = "";
  $(FORM.jsonErrors).textContent = "";
}

// Puts each of the server's field errors next to its field; the ones without a field in
// the form (or all of them, for a pasted scene) go in a list under the JSON box.
function showErrors(body, fromJson) {
  const rest = [];
  for (const f of body.fields || []) {
    const path = f.path.replace(/^overrides\./, "");
    const field = fromJson ? null : document.querySelector(`.field[data-path="${CSS.escape(path)}"]`);
    if (field) {
      field.classList.add("invalid");
      field.querySelector("input, select").setAttribute("aria-invalid", "true");
      field.querySelector(".error").textContent = f.message;
    } else {
      rest.push(`${f.path || "(scene)"}: ${f.message}`);
    }
  }
  $(fromJson ? FORM.jsonErrors : FORM.errors).textContent =
    (body.error || "The server refused the scene.") + (rest.length ? " — " + rest.join("; ") : "");
  const first = document.querySelector(".field.invalid :is(input, select)");
  if (first) first.focus();
}

// The scene to submit, or null (and the reason shown) when the pasted JSON does not parse.
function sceneToSubmit(fromJson) {
  if (!fromJson) return sceneFromFields();
  try { return JSON.parse(sceneJsonText()); } catch (e) {
    $(FORM.jsonErrors).textContent = "Not valid JSON: " + e.message;
    return null;
  }
}

async function submitRun(event) {
  event.preventDefault();
  clearErrors();
  const fromJson = isJsonMode();
  const scene = sceneToSubmit(fromJson);
  if (!scene) return;
  $(FORM.submit).disabled = true;
  try {
    // The lab's labels go in the query: the body is the scene alone.
    const labels = new URLSearchParams();
    if ($(FORM.sample).value.trim()) labels.set("sample", $(FORM.sample).value.trim());
    if ($(FORM.tags).value.trim()) labels.set("tags", $(FORM.tags).value.trim());
    const r = await postJson(`/api/v1/jobs${labels.size ? "?" + labels : ""}`, scene);
    if (!r.ok) {
      if (r.status === 429) r.body.error += " Try again in a moment.";
      showErrors(r.body || {}, fromJson);
      return;
    }
    await run.showNewJob(r.body.id, fromJson ? null : withOverrides(scene));
  } catch (e) {
    $(FORM.errors).textContent = "Could not reach the server: " + e.message;
  } finally {
    $(FORM.submit).disabled = false;
    // Disabling the focused button sent focus to the body, and the next Tab to wherever the
    // browser's starting point had moved (the run panel, once revealed): keep the place.
    if (document.activeElement === document.body) $(FORM.submit).focus({ preventScroll: true });
  }
}

// "Edit and run again": the form takes the run's scene; the fields it has no input for
// are kept as overrides, and said so under the form.
function editAgain(scene) {
  const preset = scene && closestPreset(scene);
  if (!preset) return;
  $(FORM.useJson).checked = false;
  $(FORM.preset).value = preset.name;
  $(FORM.presetDescription).textContent = preset.description;
  const inForm = new Set([...FIELDS.map((f) => f[0]), ...RIG_PATHS, "disc.material", "ball.material"]);
  const overrides = {};
  for (const path of differingPaths([scene, preset.scene])) {
    const v = getPath(scene, path);
    if (!inForm.has(path) && v !== undefined) setPath(overrides, path, v);
  }
  const kept = Object.keys(flatten(overrides));
  formExtra = kept.length ? { from: scene.name, overrides } : null;
  showValues(scene);
  showMaterials(scene);
  nameEdited = false;
  setJsonMode();
  $(FORM.base).textContent = kept.length
    ? `From the run "${scene.name}", with its other changes to the preset kept: ${kept.map((p) => describe(p, getPath(scene, p))).join(", ")}. Choosing a preset clears them.`
    : `From the run "${scene.name}".`;
  $(FORM.form).scrollIntoView({ block: "start" });
  $(fieldId(FIELDS[0][0])).focus({ preventScroll: true });
}

/** Reads the presets into the preset list and fills the form from the first; marks the page ready. */
export async function loadPresets() {
  if (!(await readPresets())) return;
  await loadMaterials(materialChanged);
  $(FORM.preset).replaceChildren(...allPresets().map((p) => new Option(p.name, p.name)));
  fillFromPreset();
  document.body.dataset.ready = "true";
}

/** Builds the main fields and wires the form. */
export function init() {
  buildFields();
  $(FORM.form).addEventListener("submit", submitRun);
  $(FORM.surfaceFile).addEventListener("change", uploadSurface);
  $(FORM.surfaceClear).addEventListener("click", clearSurface);
  $(FORM.surfaceTilt).addEventListener("change", followFields);
  $(FORM.preset).addEventListener("change", fillFromPreset);
  $(FORM.fieldsToJson).addEventListener("click", () => { $(FORM.sceneJson).value = JSON.stringify(sceneFromFields(), null, 2); });
  $(FORM.mainFields).addEventListener("input", followFields);
  $(FORM.name).addEventListener("input", () => { nameEdited = $(FORM.name).value.trim() !== ""; followFields(); });
  $(FORM.useJson).addEventListener("change", setJsonMode);
  $(FORM.sceneJson).addEventListener("input", () => { if (isJsonMode()) fieldsFromJson(); });
  initRig(followFields);
  run.onEditAgain(editAgain);
}
