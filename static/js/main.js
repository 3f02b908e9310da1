// The page's entry point: wires the modules together and starts them. Everything talks to
// the API described in openapi.yaml; nothing is built or fetched from elsewhere.
//
// The modules, each importing only modules listed above it, so that no two import each
// other (in brackets, the page's own modules each one imports):
//   ids          the element ids, for the modules and the e2e test
//   dom, words, svg, sse, topic, hash   helpers: the document, values in words, SVG
//                text, server-sent events, listeners, the view in the address's hash
//   uplot        the vendored uPlot's global, as an import
//   api          the API, with the token (dom, ids)
//   plots        the uPlot charts by box id, and the SVG figures (uplot, dom)
//   scenes       the presets, and the scenes jobs were submitted with (api, words)
//   export       each figure as SVG and PNG (plots, svg)
//   pressure     the run's pressure maps (plots, svg)
//   stroke       the reciprocating rig's wear map, axial profile and cycle traces
//                (plots, pressure, svg)
//   measurements the tables attached to the run shown (api, topic)
//   scores       the attached tables scored against the run shown (api)
//   jobs         the job list (api, topic)
//   labels       the sample, tags and note of the run shown (api)
//   fig11        the Fig. 11 view's curves and its companion runs (api, jobs)
//   run-figures  the run's line figures (plots, measurements, scenes, fig11)
//   run          the run panel (jobs, labels, measurements, scores, pressure, stroke,
//                fig11, run-figures, scenes, sse, topic, hash)
//   rig          the new-run form's rig: the disc, or the reciprocating stroke's fields
//   form         the new-run form (run, scenes, rig)
//   compare      the comparison of runs (jobs, plots, hash)
//   studies      the studies (form, jobs, compare, plots, hash)
//   calibration  the fits (form, run, plots)
//   main         this file
// A module tells the modules above it what happened through a topic they listen to (jobs:
// View, a deletion, the list drawn; run: "Edit and run again"; measurements: tables read).
import * as calibration from "./calibration.js";
import * as compare from "./compare.js";
import { $ } from "./dom.js";
import { addExportButtons } from "./export.js";
import { COMPANION_TAG } from "./fig11.js";
import * as form from "./form.js";
import { readHash } from "./hash.js";
import { TOKEN } from "./ids.js";
import * as jobs from "./jobs.js";
import * as measurements from "./measurements.js";
import { resizeAll } from "./plots.js";
import * as run from "./run.js";
import * as studies from "./studies.js";

function useToken(event) {
  event.preventDefault();
  sessionStorage.setItem("tribosim-token", $(TOKEN.input).value);
  $(TOKEN.form).hidden = true;
  form.loadPresets();
  jobs.refresh();
}

// The charts follow the window's width, once it has stopped changing for 150 ms.
function followResize() {
  let resizeTimer;
  window.addEventListener("resize", () => {
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(resizeAll, 150);
  });
}

// Opens the view the address asks for (scrolled into place), else the newest run (where it
// is, so the page does not jump): the newest the user ran, not a Fig. 11 companion, which
// the view submitted for itself after the run it was asked beside; true when something
// was opened.
async function openAsked() {
  const asked = readHash();
  // On one column (a phone), a linked view comes before the form, so that it opens in
  // place: scrolled down to, a headless screenshot of the link caught a blank page.
  if (asked) document.querySelector("main").classList.add("linked");
  if (asked && asked.kind === "run") { jobs.view(asked.value, { scroll: true }); return true; }
  if (asked && asked.kind === "compare") {
    jobs.tick(asked.value.split(","));
    await jobs.refresh();
    await compare.open();
    return true;
  }
  if (asked && asked.kind === "study") { await studies.select(asked.value, { scroll: true }); return true; }
  const newest = jobs.newest((job) => !(job.tags || []).includes(COMPANION_TAG)) || jobs.newest();
  if (newest) jobs.view(newest.id);
  return Boolean(newest);
}

async function start() {
  form.init();
  jobs.init();
  addExportButtons();
  run.init();
  measurements.init();
  compare.init();
  studies.init();
  calibration.init();
  $(TOKEN.form).addEventListener("submit", useToken);
  followResize();
  await form.loadPresets();
  await Promise.all([jobs.refresh(), studies.refresh()]);
  await openAsked();
  window.addEventListener("hashchange", openAsked);
}

start();
