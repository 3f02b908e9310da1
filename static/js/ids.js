// The ids of the page's elements that the modules look up, written once: the modules and
// the e2e test (tests/e2e) import them from here, and index.html carries each on its
// element. The e2e test checks that every id here names an element of the page.

/** The token form, shown when the server asks for a token. */
export const TOKEN = Object.freeze({ form: "token-form", input: "token" });

/** The new-run form. */
export const FORM = Object.freeze({
  form: "run-form",
  preset: "preset",
  presetDescription: "preset-description",
  name: "f-name",
  sample: "f-sample",
  tags: "f-tags",
  mainFields: "main-fields",
  surfaceFile: "surface-file",
  surfacePixel: "surface-pixel",
  surfaceTilt: "surface-tilt",
  surfaceStatus: "surface-status",
  surfaceClear: "surface-clear",
  useJson: "use-json",
  sceneJson: "scene-json",
  fieldsToJson: "fields-to-json",
  jsonErrors: "json-errors",
  base: "form-base",
  errors: "form-errors",
  submit: "submit",
});

/** The new-run form's materials. */
export const MATERIALS = Object.freeze({
  disc: "disc-material",
  ball: "ball-material",
  wearOnly: "wear-only",
  note: "material-note",
});

/**
 * The new-run form's rig: the rotating disc or the reciprocating one, and the box of the
 * stroke's fields (their inputs are named by fieldId, as the main fields').
 */
export const RIG = Object.freeze({ kind: "rig-kind", fields: "rig-fields" });

/** A main field's input, by its scene path: "test.load_n" is "f-test-load_n". */
export const fieldId = (path) => "f-" + path.replace(/\./g, "-");

/** The job list. */
export const JOBS = Object.freeze({
  table: "jobs",
  message: "jobs-message",
  compare: "compare-button",
  filter: "jobs-filter",
  status: "jobs-status",
  name: "jobs-name",
  more: "jobs-more",
});

/** The run panel. */
export const RUN = Object.freeze({
  panel: "run-panel",
  title: "run-title",
  status: "run-status",
  progress: "run-progress",
  reason: "run-reason",
  partial: "run-partial",
  warnings: "run-warnings",
  downloadJson: "download-json",
  downloadCsv: "download-csv",
  downloadReport: "download-report",
  downloadCompact: "download-compact",
  downloadProfiles: "download-profiles",
  downloadPressure: "download-pressure",
  editAgain: "edit-again",
  showTable3: "show-table3",
  table3Note: "table3-note",
  showFig11: "show-fig11",
  fig11Note: "fig11-note",
  params: "run-params",
  paramsDiff: "params-diff",
  paramsTable: "params-table",
  paramsJson: "params-json",
  models: "run-models",
  summary: "run-summary",
});

/** The run panel's labels form. */
export const LABELS = Object.freeze({
  form: "labels-form",
  sample: "labels-sample",
  tags: "labels-tags",
  note: "labels-note",
  save: "labels-save",
  status: "labels-status",
});

/** The run panel's figures. */
export const RUN_PLOT = Object.freeze({
  volume: "plot-volume",
  depth: "plot-depth",
  potential: "plot-potential",
  wac: "plot-wac",
  profile: "plot-profile",
  pressure: "plot-pressure",
});

/** The reciprocating rig's figures: shown for a result with `stroke`, never for a disc's. */
export const STROKE_PLOT = Object.freeze({
  map: "plot-stroke-map",
  profile: "plot-stroke-profile",
  potential: "plot-stroke-potential",
  current: "plot-stroke-current",
});

/** The measurements attached to the run shown. */
export const MEASURE = Object.freeze({
  box: "measurements",
  form: "measure-form",
  kind: "measure-kind",
  file: "measure-file",
  text: "measure-text",
  attach: "measure-attach",
  errors: "measure-errors",
  read: "measure-read",
  list: "measure-list",
});

/** The comparison panel; its x-axis radios are named COMPARE_X. */
export const COMPARE = Object.freeze({
  panel: "compare-panel",
  note: "cmp-note",
  table: "cmp-table",
  cycle: "cmp-cycle",
  close: "compare-close",
  report: "compare-report",
});

/** The name (not an id) of the comparison's radios: against cycles or time. */
export const COMPARE_X = "cmp-x";

/** The comparison's figures. */
export const COMPARE_PLOT = Object.freeze({
  volume: "cmp-volume",
  depth: "cmp-depth",
  potential: "cmp-potential",
  wac: "cmp-wac",
  profile: "cmp-profile",
});

/** The study form, the study list and the study panel. */
export const STUDY = Object.freeze({
  new: "study-new",
  form: "study-form",
  axes: "study-axes",
  submit: "study-submit",
  errors: "study-errors",
  message: "studies-message",
  table: "studies",
  panel: "study-panel",
  title: "study-title",
  status: "study-status",
  progress: "study-progress",
  axis: "study-axis",
  report: "study-report",
  compare: "study-compare",
  members: "study-members",
});

/** The study panel's figures. */
export const STUDY_PLOT = Object.freeze({
  volume: "study-volume",
  depth: "study-depth",
  wac: "study-wac",
  potential: "study-potential",
});

/** The calibration form and panel, with its one figure. */
export const CALIB = Object.freeze({
  new: "calib-new",
  form: "calib-form",
  kind: "calib-kind",
  regime: "calib-regime",
  file: "calib-file",
  text: "calib-text",
  submit: "calib-submit",
  errors: "calib-errors",
  list: "calib-list",
  panel: "calib-panel",
  title: "calib-title",
  status: "calib-status",
  run: "calib-run",
  note: "calib-note",
  values: "calib-values",
  residuals: "calib-residuals",
  plot: "calib-plot",
});
