// The new-run form's rig: the paper's rotating disc, or the reciprocating ball-on-flat rig
// (the scene's `test.reciprocating`, docs/scene.md) with its stroke, frequency and velocity
// law. form.js reads, fills and marks the stroke's fields as it does its main fields, so
// that a refusal at `test.reciprocating.stroke_mm` lands at its field; the fields left
// empty are not sent, and the server's defaults apply.
import { $ } from "./dom.js";
import { RIG, fieldId } from "./ids.js";
import { describe, getPath, setPath } from "./words.js";

const PATH = "test.reciprocating";
const FIELDS = ["stroke_mm", "frequency_hz", "velocity_law"].map((key) => `${PATH}.${key}`);

/** Every path the rig sets: a re-run's values there are the rig's, not extra overrides. */
export const RIG_PATHS = [PATH, ...FIELDS];

/** The stroke's inputs (the velocity law's is a select), each with its path in data-path. */
export const rigInputs = () => FIELDS.map((path) => $(fieldId(path)));

const reciprocating = () => $(RIG.kind).value === "reciprocating";

// The stroke's fields show on the reciprocating rig only.
const follow = () => { $(RIG.fields).hidden = !reciprocating(); };

/** Shows a scene's rig: reciprocating when it gives `test.reciprocating`. */
export function showRig(scene) {
  $(RIG.kind).value = getPath(scene, PATH) ? "reciprocating" : "disc";
  follow();
}

// The stroke's fields given, as { stroke_mm: 0.6, ... }; `valueOf` reads an input as the
// form reads its main fields.
function given(valueOf) {
  const out = {};
  for (const input of rigInputs()) {
    const value = valueOf(input);
    if (value !== "") out[input.dataset.path.slice(PATH.length + 1)] = value;
  }
  return out;
}

/**
 * Sets the rig into a scene's overrides of the preset's scene: on the reciprocating rig, the
 * fields given ({} when none: the defaults); on the disc, null over a reciprocating preset.
 */
export function applyRig(overrides, presetScene, valueOf) {
  if (reciprocating()) setPath(overrides, PATH, given(valueOf));
  else if (getPath(presetScene, PATH)) setPath(overrides, PATH, null);
}

/** What the rig changes of the preset's, in words, for the run's name. */
export function rigChanges(presetScene, valueOf) {
  const presetRig = getPath(presetScene, PATH);
  if (!reciprocating()) return presetRig ? ["on a rotating disc"] : [];
  // By the field's own name ("stroke 0.6 mm"), after the word "reciprocating" when the
  // preset is on the disc.
  const words = Object.entries(given(valueOf))
    .filter(([key, v]) => JSON.stringify(v) !== JSON.stringify(getPath(presetRig, key)))
    .map(([key, v]) => describe(key, v));
  return presetRig ? words : ["reciprocating", ...words];
}

/** Makes the rig read-only while a pasted scene is what the form submits. */
export function lockRig(on) {
  $(RIG.kind).disabled = on;
  for (const input of rigInputs()) {
    if (input.tagName === "SELECT") input.disabled = on;
    else input.readOnly = on;
  }
}

/** Wires the rig: `changed()` runs on every choice and keystroke. */
export function initRig(changed) {
  $(RIG.kind).addEventListener("change", () => { follow(); changed(); });
  $(RIG.fields).addEventListener("input", changed);
}
