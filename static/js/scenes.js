// The scenes the page knows: the server's presets, and the whole scene each job was
// submitted with from this page (read before the server's copy arrives).
import { api } from "./api.js";
import { differingPaths } from "./words.js";

let presets = [];
const submitted = new Map();

/** Reads the presets from the server; false when it refused. */
export async function loadPresets() {
  const r = await api("/api/v1/presets");
  if (r.ok) presets = r.body;
  return r.ok;
}

/** The presets, in the server's order. */
export const allPresets = () => presets;

/** The preset of this name, if any. */
export const presetNamed = (name) => presets.find((p) => p.name === name);

/** The preset a scene is closest to: the fewest fields changed. */
export function closestPreset(scene) {
  let best = null, fewest = Infinity;
  for (const p of presets) {
    const n = differingPaths([scene, p.scene]).length;
    if (n < fewest) { best = p; fewest = n; }
  }
  return best;
}

/**
 * The whole scene a `{preset, overrides}` submission runs: the preset's scene with the
 * overrides merged in (the form's overrides are plain values, so the merge is key by key).
 */
export function withOverrides(input) {
  const preset = presetNamed(input.preset);
  if (!preset) return null;
  const merge = (base, over) => {
    const out = { ...base };
    for (const [k, v] of Object.entries(over)) {
      out[k] = v && typeof v === "object" && !Array.isArray(v) && base[k] && typeof base[k] === "object" ? merge(base[k], v) : v;
    }
    return out;
  };
  return merge(preset.scene, input.overrides || {});
}

/** Keeps the scene a job was submitted with. */
export const remember = (id, scene) => { submitted.set(id, scene); };

/** The scene a job was submitted with from this page, or null. */
export const submittedScene = (id) => submitted.get(id) || null;
