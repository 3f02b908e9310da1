// Scenes as dotted paths, and values in words with their units: what the form, the run
// panel, the comparison, the studies and the calibration all say the same way.

/** The value at a dotted path ("test.load_n"), or undefined. */
export function getPath(obj, path) {
  return path.split(".").reduce((o, k) => (o == null ? undefined : o[k]), obj);
}

/** Sets the value at a dotted path, making the objects on the way. */
export function setPath(obj, path, value) {
  const keys = path.split(".");
  let o = obj;
  for (const k of keys.slice(0, -1)) o = o[k] ??= {};
  o[keys[keys.length - 1]] = value;
}

/** A scene as dotted paths to values (lists are values: a hardness table is one field). */
export function flatten(obj, prefix = "", out = {}) {
  for (const [k, v] of Object.entries(obj || {})) {
    const path = prefix ? `${prefix}.${k}` : k;
    if (v && typeof v === "object" && !Array.isArray(v)) flatten(v, path, out);
    else out[path] = v;
  }
  return out;
}

/**
 * The paths whose values are not the same in all the scenes, in the scenes' order; the name
 * is what a run is called, not what it ran.
 */
export function differingPaths(scenes) {
  const flats = scenes.map((s) => flatten(s));
  const paths = [...new Set(flats.flatMap(Object.keys))].filter((p) => p !== "name");
  return paths.filter((p) => new Set(flats.map((f) => JSON.stringify(f[p] ?? null))).size > 1);
}

// A field in words with its unit, from its JSON name's unit suffix: "test.load_n" is "load (N)".
const UNIT_SUFFIXES = [["v_per_decade", "V/decade"], ["a_cm2", "A/cm²"], ["g_cm3", "g/cm³"], ["g_mol", "g/mol"],
  ["mm3", "mm³"], ["mm2", "mm²"], ["cm2", "cm²"], ["rpm", "rpm"], ["mpa", "MPa"], ["gpa", "GPa"], ["mm", "mm"],
  ["um", "µm"], ["hz", "Hz"], ["n", "N"], ["s", "s"], ["v", "V"]];

/** A field's name in words and its unit: { name: "load", unit: "N" } for "test.load_n". */
export function fieldName(path) {
  const parts = path.split(".");
  let key = parts[parts.length - 1];
  let unit = "";
  for (const [suffix, u] of UNIT_SUFFIXES) {
    if (key.endsWith("_" + suffix)) { key = key.slice(0, -suffix.length - 1); unit = u; break; }
  }
  // Ball and disc share field names, and a nested field is named with its parent.
  const owner = parts.length > 2 ? parts[parts.length - 2] + " " : ["ball", "disc"].includes(parts[0]) ? parts[0] + " " : "";
  return { name: (owner + key).replace(/_/g, " "), unit };
}

/** A field's name with its unit in brackets: "load (N)". */
export function fieldLabel(path) {
  const { name, unit } = fieldName(path);
  return name + (unit ? ` (${unit})` : "");
}

/** A value for people: four significant figures, "not set", or JSON. */
export function fmtValue(v) {
  if (typeof v === "number") return String(+v.toPrecision(4));
  if (v == null) return "not set";
  return typeof v === "object" ? JSON.stringify(v) : String(v);
}

/** A field and its value in words: "load 10 N". */
export function describe(path, v) {
  const { name, unit } = fieldName(path);
  return `${name} ${fmtValue(v)}${unit && typeof v === "number" ? " " + unit : ""}`;
}

/** Server text for people: µm, mm³ and mm², and enum names (WearTrack) as words. */
export function readable(text) {
  return text
    .replace(/\bum\b/g, "µm")
    .replace(/\bmm\^3\b/g, "mm³")
    .replace(/\bmm\^2\b/g, "mm²")
    .replace(/\b([A-Z][a-z]+)((?:[A-Z][a-z]+)+)\b/g, (w) => w.replace(/([a-z])([A-Z])/g, "$1 $2").toLowerCase());
}

/** The summary's quantities: [field, words, unit, factor to the unit shown]. */
/** The reference electrodes of `corrosion.reference_electrode`: in full, and short for an axis. */
const REFERENCES = { ag_agcl_3m_kcl: ["Ag/AgCl (3 M KCl)", "Ag/AgCl"], ag_agcl_sat_kcl: ["Ag/AgCl (sat. KCl)", "Ag/AgCl sat."], sce: ["SCE", "SCE"], she: ["SHE", "SHE"] };

/** The electrode a scene's potentials are against, in words (the paper's by default). */
export const referenceLabel = (name) => (REFERENCES[name] || REFERENCES.ag_agcl_3m_kcl)[0];

/** The same, short enough for an axis label. */
export const referenceShort = (name) => (REFERENCES[name] || REFERENCES.ag_agcl_3m_kcl)[1];

export const METRICS = [
  ["cycles", "cycles simulated", "", 1],
  ["wear_volume_mm3", "wear volume", "10⁻³ mm³", 1e3],
  ["max_depth_um", "maximum depth", "µm", 1],
  ["wac_volume_mm3", "WAC volume", "10⁻³ mm³", 1e3],
  ["total_volume_mm3", "total volume, mechanical + WAC", "10⁻³ mm³", 1e3],
  ["mechanical_volume_mm3", "mechanical volume", "10⁻³ mm³", 1e3],
  ["charge_c", "anodic charge", "C", 1],
  ["potential_v", "potential at the last cycle", "V vs the reference electrode", 1],
  ["archard_k", "Archard k", "–", 1],
  ["solves", "contact solves", "", 1],
  ["wall_s", "wall time", "s", 1],
];

/** A metric's value in the unit shown, or null when the summary has none. */
export const metricValue = (summary, [key, , , factor]) => (summary && summary[key] != null ? summary[key] * factor : null);

/** A metric's words with its unit: "wear volume (10⁻³ mm³)". */
export const metricLabel = ([, words, unit]) => words + (unit ? ` (${unit})` : "");
