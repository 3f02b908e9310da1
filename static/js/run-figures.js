// The run panel's line figures: volume, depth, potential and WAC from the cycle records
// (live or final; the potential from the result's OCP trace once it has one), with the
// paper's Table 3 and the attached measurements where they belong, the paper's Fig. 11 view
// of the volume, and the groove's profiles with the ball once the run has a result.
import { $ } from "./dom.js";
import { MATERIALS, fig11Note, fig11State } from "./fig11.js";
import { RUN, RUN_PLOT } from "./ids.js";
import { attachedPoints } from "./measurements.js";
import { ATTACHED_COLOR, COLORS, MEASURED_COLOR, chart, dropChart, joinTables, linePlot, lineSeries, markerSeries } from "./plots.js";
import { presetNamed } from "./scenes.js";
import { getPath, referenceShort } from "./words.js";

// The preset whose `measured` points are the paper's Table 3 (GET /api/v1/presets).
const TABLE3_PRESET = "dalmau2018-316l";
// What Table 3 was measured under, as the preset's scene holds it: a run that differs in
// any of these is another experiment, and the measured points do not belong beside it.
const TABLE3_CONDITIONS = ["test.load_n", "test.speed_rpm", "test.track_radius_mm", "ball", "disc"];
// Fig. 11's colours: elastic blue and EPP red, as the paper draws them.
const FIG11_COLORS = { elastic: COLORS[0], epp: COLORS[1] };

const CYCLES_LABEL = "cycles (passes of the ball)";
const WAITING = "Shown after the run ends.";

// The conditions in words; the ball and the disc are named by the part that differs.
const CONDITION_WORDS = { "test.load_n": "load", "test.speed_rpm": "speed", "test.track_radius_mm": "track radius" };

// What of Table 3's conditions the scene does not share, in words ([] when it shares all);
// null when the preset or the scene is not known.
function table3Differences(scene) {
  const preset = presetNamed(TABLE3_PRESET);
  if (!preset || !scene) return null;
  const same = (path) => JSON.stringify(getPath(scene, path)) === JSON.stringify(getPath(preset.scene, path));
  const words = [];
  for (const path of TABLE3_CONDITIONS.filter((p) => !same(p))) {
    if (CONDITION_WORDS[path]) { words.push(CONDITION_WORDS[path]); continue; }
    const keys = new Set([...Object.keys(getPath(scene, path) || {}), ...Object.keys(getPath(preset.scene, path) || {})]);
    for (const key of [...keys].filter((k) => !same(`${path}.${k}`))) words.push(`${path}'s ${key.replace(/_/g, " ")}`);
  }
  return words;
}

// "a", "a and b", "a, b and c".
const listed = (words) => (words.length < 2 ? words.join("") : `${words.slice(0, -1).join(", ")} and ${words[words.length - 1]}`);

/**
 * Enables the Table 3 checkbox and the Fig. 11 view only for a run whose scene matches, and
 * says why when it does not. True when the volume figure is drawn already (and should be
 * drawn again).
 */
export function updateTable3Choice(scene) {
  const differences = table3Differences(scene);
  const applies = Boolean(differences) && !differences.length;
  const box = $(RUN.showTable3);
  if (box.disabled === applies) box.checked = applies;
  box.disabled = !applies;
  if (!applies) $(RUN.showFig11).checked = false;
  $(RUN.showFig11).disabled = !applies;
  $(RUN.table3Note).textContent = applies ? ""
    : differences ? `Table 3 and the Fig. 11 view are not shown: this run's ${listed(differences)} ${differences.length > 1 ? "differ" : "differs"} from the measured test's.`
      : "Table 3 and the Fig. 11 view are shown once the run's scene is known and matches the measured test.";
  return Boolean(chart(RUN_PLOT.volume));
}

// Table 3's wear volumes from the preset's `measured` points: [cycles, 1e-3 mm^3, the
// spread in 1e-3 mm^3], its seconds turned into cycles at the preset's speed.
function table3Points() {
  const preset = presetNamed(TABLE3_PRESET);
  if (!preset) return [];
  const rpm = getPath(preset.scene, "test.speed_rpm");
  return (preset.measured || []).map((m) => [(m.time_s * rpm) / 60, m.wear_volume_mm3 * 1e3, m.spread_mm3 * 1e3]);
}

const volumeTable = (records) => [records.map((r) => r.cycle), records.map((r) => r.wear_volume_mm3 * 1e3)];

// The volume figure's curves and the cycle its measured points end at: the run's own, or
// with the Fig. 11 view on, the EPP and elastic curves that have come over the view's cycles.
function volumeCurves(cycles, c, scene, fig11) {
  if (!fig11) {
    const end = getPath(scene, "test.cycles") || (c.length ? c[c.length - 1] : 0);
    return { tables: [volumeTable(cycles)], series: [lineSeries("simulated", COLORS[0])], end, points: c.length };
  }
  const drawn = fig11.curves.filter((curve) => curve.records && curve.records.length);
  return {
    tables: drawn.map((curve) => volumeTable(curve.records)),
    series: drawn.map((curve) => lineSeries(MATERIALS[curve.material].label, FIG11_COLORS[curve.material])),
    end: fig11.cycles,
    points: drawn.reduce((n, curve) => n + curve.records.length, 0),
  };
}

// Wear volume against cycles, with Table 3 (when ticked, and always in the Fig. 11 view
// `fig11`) and attached wear volumes, each only within the cycles drawn.
function drawVolume(cycles, c, scene, fig11) {
  const box = $(RUN_PLOT.volume);
  const { tables, series: volSeries, end, points } = volumeCurves(cycles, c, scene, fig11);
  const measured = fig11 || $(RUN.showTable3).checked ? table3Points().filter((p) => p[0] <= end) : [];
  if (measured.length) {
    tables.push([measured.map((p) => p[0]), measured.map((p) => p[1])]);
    volSeries.push(markerSeries("Table 3, measured", MEASURED_COLOR, new Map(measured.map((p) => [p[0], p[2]]))));
  }
  // Attached wear volumes: at their cycles, or at their times turned into cycles at the run's speed.
  const rpm = getPath(scene, "test.speed_rpm") || 60;
  const attachedVol = attachedPoints("wear_volume",
    (tb, i) => (tb.cycles ? tb.cycles[i] : tb.time_s ? (tb.time_s[i] * rpm) / 60 : NaN), (tb, i) => tb.volume_mm3[i] * 1e3)
    .filter((p) => !fig11 || p[0] <= end);
  if (attachedVol.length) {
    tables.push([attachedVol.map((p) => p[0]), attachedVol.map((p) => p[1])]);
    volSeries.push(markerSeries("attached measurement", ATTACHED_COLOR));
  }
  box.dataset.measured = String(measured.length);
  box.dataset.attached = String(attachedVol.length);
  box.dataset.fig11 = fig11 ? fig11State(fig11) : "";
  $(RUN.fig11Note).textContent = fig11 ? fig11Note(fig11) : "";
  if (!tables.length) { dropChart(RUN_PLOT.volume); box.dataset.points = "0"; return; }
  linePlot(RUN_PLOT.volume, joinTables(tables), volSeries, CYCLES_LABEL, "wear volume (10⁻³ mm³)", points);
}

// The rubbing on the record's clock: from `test.ocp_before_s` for the run's cycles.
function rubbingBand(scene) {
  const start = getPath(scene, "test.ocp_before_s") || 0;
  const cycles = getPath(scene, "test.cycles");
  const rpm = getPath(scene, "test.speed_rpm") || 60;
  return cycles ? { from: start, to: start + (cycles * 60) / rpm, label: "rubbing (the ball sliding)" } : null;
}

/**
 * The potential as the potentiostat records it: the result's OCP trace (E_corr before, the
 * rubbing, the recovery after) once the run has one, else the solved cycles so far; the
 * rubbing shaded, E_corr dashed, and attached potentials on the same clock (the record's,
 * `test.ocp_before_s` before the ball starts).
 */
function drawPotential(cycles, scene, trace) {
  const box = $(RUN_PLOT.potential);
  const start = getPath(scene, "test.ocp_before_s") || 0;
  const live = cycles.filter((r) => r.potential_v != null).map((r) => [start + r.time_s, r.potential_v]);
  const points = trace && trace.length ? trace.map((p) => [p.time_s, p.potential_v]) : live;
  const hasCorrosion = points.length > 0;
  box.querySelector(".note").textContent = cycles.length && !hasCorrosion ? "This scene has no corrosion model: nothing to plot."
    : hasCorrosion ? "Shaded: the rubbing. Before it the passive film holds E_corr; after it the bare metal repassivates." : "";
  const t = points.map((p) => p[0]);
  const series = [lineSeries("potential", COLORS[4])];
  const cols = [t, points.map((p) => p[1])];
  const ecorr = getPath(scene, "corrosion.corrosion_potential_v");
  if (ecorr != null) {
    cols.push(t.map(() => ecorr));
    series.push({ label: "E_corr, free corrosion potential", stroke: "#444", width: 1.5, dash: [6, 4], spanGaps: true, points: { show: false } });
  }
  const parts = [cols];
  const attached = attachedPoints("ocp", (tb, i) => tb.time_s[i], (tb, i) => tb.potential_v[i]);
  box.dataset.attached = String(attached.length);
  if (attached.length) {
    parts.push([attached.map((p) => p[0]), attached.map((p) => p[1])]);
    series.push(markerSeries("attached measurement", ATTACHED_COLOR));
  }
  const band = hasCorrosion ? rubbingBand(scene) : null;
  box.dataset.trace = String(trace ? trace.length : 0);
  box.dataset.rubbing = band ? `${band.from} ${band.to}` : "";
  const unit = `potential (V vs ${referenceShort(getPath(scene, "corrosion.reference_electrode"))})`;
  linePlot(RUN_PLOT.potential, joinTables(parts), series, "time since the record started (s)", unit, points.length, { band });
}

// The WAC volume against the rubbing time.
function drawWac(cycles) {
  const box = $(RUN_PLOT.wac);
  const hasCorrosion = cycles.some((r) => r.wac_volume_mm3 != null);
  box.querySelector(".note").textContent = cycles.length && !hasCorrosion ? "This scene has no corrosion model: nothing to plot." : "";
  const ys = cycles.map((r) => (r.wac_volume_mm3 == null ? null : r.wac_volume_mm3 * 1e3));
  linePlot(RUN_PLOT.wac, [cycles.map((r) => r.time_s), ys], [lineSeries("WAC volume", COLORS[3])],
    "time of rubbing (s)", "WAC volume (10⁻³ mm³)", hasCorrosion ? ys.filter((v) => v != null).length : 0);
}

/**
 * Volume, depth, potential and WAC from the cycle records of a run of this scene; the
 * potential from the result's OCP `trace` once it has one; the volume as the Fig. 11 view
 * `fig11` (fig11.js's `fig11Curves`) when it is on.
 */
export function drawSeries(cycles, scene, trace, fig11) {
  const c = cycles.map((r) => r.cycle);
  drawVolume(cycles, c, scene, fig11);
  linePlot(RUN_PLOT.depth, [c, cycles.map((r) => r.max_depth_um)],
    [{ label: "maximum depth", stroke: COLORS[2], width: 2, points: { show: false } }],
    CYCLES_LABEL, "maximum wear depth (µm)", c.length);
  drawPotential(cycles, scene, trace);
  drawWac(cycles);
}

/** Empties the profile figure until a result comes. */
export function resetProfiles() {
  dropChart(RUN_PLOT.profile);
  $(RUN_PLOT.profile).dataset.points = "0";
  $(RUN_PLOT.profile).querySelector(".note").textContent = WAITING;
  $(RUN_PLOT.profile).querySelector(".profile-picks").replaceChildren();
}

// The checkboxes of the cycles to show: the first, middle and last profile at first.
function addPicks(picks, profiles, result) {
  const n = profiles.length;
  const chosen = new Set([0, Math.floor((n - 1) / 2), n - 1]);
  profiles.forEach((p, i) => {
    const label = document.createElement("label");
    label.innerHTML = `<input type="checkbox" value="${i}"${chosen.has(i) ? " checked" : ""}> cycle ${p.cycle}`;
    label.querySelector("input").addEventListener("change", () => drawProfiles(result));
    picks.appendChild(label);
  });
}

// The ball's section, radius R, with its lowest point at the profile's deepest point.
function ballTable(profile, radiusUm) {
  let k = 0;
  profile.depth_um.forEach((d, i) => { if (Math.abs(d) > Math.abs(profile.depth_um[k])) k = i; });
  const bottom = -Math.abs(profile.depth_um[k]);
  const y0 = profile.y_um[k];
  return [profile.y_um, profile.y_um.map((y) => {
    const dy = y - y0;
    if (Math.abs(dy) >= radiusUm) return null;
    return bottom + (radiusUm - Math.sqrt(radiusUm * radiusUm - dy * dy));
  })];
}

/**
 * D(y): the groove's depth across the track at chosen cycles (drawn as the surface height
 * -D, so the groove dips), and the ball's section touching the deepest point of the last
 * chosen profile.
 */
export function drawProfiles(result) {
  const profiles = result.profiles || [];
  const box = $(RUN_PLOT.profile);
  const picks = box.querySelector(".profile-picks");
  const note = box.querySelector(".note");
  if (!profiles.length) { note.textContent = "The result has no profiles."; return; }
  if (!picks.children.length) addPicks(picks, profiles, result);
  const selected = [...picks.querySelectorAll("input:checked")].map((i) => profiles[Number(i.value)]);
  const radiusUm = (getPath(result.scene, "ball.radius_mm") || 3) * 1000;
  note.textContent = `Surface height −D(y); the ball (R = ${radiusUm / 1000} mm) is drawn touching the deepest point of the last chosen profile.`;
  if (!selected.length) {
    dropChart(RUN_PLOT.profile);
    box.dataset.points = "0";
    return;
  }
  const tables = selected.map((p) => [p.y_um, p.depth_um.map((d) => -Math.abs(d))]);
  tables.push(ballTable(selected[selected.length - 1], radiusUm));
  const series = selected.map((p, i) => lineSeries(`−D at cycle ${p.cycle}`, COLORS[i % COLORS.length]));
  series.push({ label: "ball", stroke: "#444", width: 1.5, dash: [6, 4], spanGaps: true, points: { show: false } });
  const attached = attachedPoints("profile", (tb, i) => tb.y_mm[i] * 1000, (tb, i) => -Math.abs(tb.depth_um[i]));
  if (attached.length) {
    tables.push([attached.map((p) => p[0]), attached.map((p) => p[1])]);
    series.push(markerSeries("attached measurement", ATTACHED_COLOR));
  }
  box.dataset.attached = String(attached.length);
  const maxDepth = Math.max(...selected.map((p) => Math.max(...p.depth_um.map(Math.abs))), ...attached.map((p) => -p[1]), 0.01);
  linePlot(RUN_PLOT.profile, joinTables(tables), series, "y across the track (µm)", "surface height −D (µm)",
    selected.reduce((s, p) => s + p.y_um.length, 0),
    { rebuild: true, scales: { y: { range: [-1.3 * maxDepth, 0.5 * maxDepth] } } });
}
