// The new-run form's materials: a disc and a ball of the server's library
// (GET /api/v1/materials, docs/materials.md), and whether the run predicts the wear alone.
// A named material's values fill the scene's fields the form does not give; the form's
// disc hardness shows the material's, so that the preset's 316L value is not sent for it.
import { api } from "./api.js";
import { $ } from "./dom.js";
import { MATERIALS } from "./ids.js";

let library = { discs: [], balls: [] };

const disc = () => library.discs.find((d) => d.name === $(MATERIALS.disc).value) || null;
const ball = () => library.balls.find((b) => b.name === $(MATERIALS.ball).value) || null;

// What the chosen materials cannot give, in words.
function note() {
  const words = [];
  const d = disc(), b = ball();
  if (d) {
    const hardness = d.hardness_mpa.value == null ? ` No hardness: ${d.hardness_mpa.note}.` : "";
    const chemistry = d.electrochemistry ? "" : " No electrochemical constants in chloride: the run predicts the wear alone, or paste a scene that gives them.";
    words.push(`${d.label}.${hardness}${chemistry}`);
  }
  if (b) {
    const missing = ["youngs_modulus_gpa", "poisson_ratio"].filter((k) => b[k].value == null);
    words.push(`${b.label}.${missing.map((k) => ` No ${k}: ${b[k].note}.`).join("")}`);
  }
  const paper = (!d || d.name === "aisi_316l") && (!b || b.name === "alumina");
  if (!paper) words.push("Another pair than the paper's: give its Archard k.");
  $(MATERIALS.note).textContent = words.join(" ");
}

/** The disc hardness the chosen disc gives (null: none sourced), or undefined for the preset's. */
export function discHardness() {
  const d = disc();
  return d ? d.hardness_mpa.value : undefined;
}

/** Sets the materials and the wear-alone choice into a scene's overrides. */
export function applyMaterials(overrides) {
  const d = disc(), b = ball();
  if (d) { overrides.disc = overrides.disc || {}; overrides.disc.material = d.name; }
  if (b) { overrides.ball = overrides.ball || {}; overrides.ball.material = b.name; }
  if ($(MATERIALS.wearOnly).checked) overrides.corrosion = null;
}

/** Shows a scene's materials (a re-run's), or the preset's none. */
export function showMaterials(scene) {
  $(MATERIALS.disc).value = (scene && scene.disc && scene.disc.material) || "";
  $(MATERIALS.ball).value = (scene && scene.ball && scene.ball.material) || "";
  $(MATERIALS.wearOnly).checked = Boolean(scene && scene.corrosion === null);
  note();
}

/** Disables the choices while a pasted scene is what the form submits. */
export function lockMaterials(on) {
  for (const id of [MATERIALS.disc, MATERIALS.ball, MATERIALS.wearOnly]) $(id).disabled = on;
}

/**
 * Reads the library into the two lists; `changed(discChanged)` runs on every choice, with
 * true when the disc changed.
 */
export async function loadMaterials(changed) {
  const r = await api("/api/v1/materials");
  if (!r.ok) return;
  library = r.body;
  const options = (entries, none) => [new Option(none, ""), ...entries.map((e) => new Option(e.label, e.name))];
  $(MATERIALS.disc).replaceChildren(...options(library.discs, "as the preset gives it"));
  $(MATERIALS.ball).replaceChildren(...options(library.balls, "as the preset gives it"));
  $(MATERIALS.disc).addEventListener("change", () => {
    const d = disc();
    if (d && !d.electrochemistry) $(MATERIALS.wearOnly).checked = true;
    note();
    changed(true);
  });
  $(MATERIALS.ball).addEventListener("change", () => { note(); changed(false); });
  $(MATERIALS.wearOnly).addEventListener("change", () => changed(false));
}
