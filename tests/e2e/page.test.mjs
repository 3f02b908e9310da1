// End-to-end test of the results page in headless Chromium (Debian's package), driven by
// playwright-core. Needs TRIBOSIM_URL (a running `tribosim serve`); SCREENSHOT_DIR (default
// docs/screenshots) receives the screenshots. The steps are in steps/, run in this order
// on one page: each leaves the page (and the jobs on the server) as the next expects.
import { chromium } from "playwright-core";
import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";

import { LONG } from "./lib.mjs";
import { access } from "./steps/access.mjs";
import { calibration } from "./steps/calibration.mjs";
import { cancel } from "./steps/cancel.mjs";
import { compare } from "./steps/compare.mjs";
import { fig11 } from "./steps/fig11.mjs";
import { figures } from "./steps/figures.mjs";
import { form } from "./steps/form.mjs";
import { listing } from "./steps/listing.mjs";
import { measurements } from "./steps/measurements.mjs";
import { ocp } from "./steps/ocp.mjs";
import { origin } from "./steps/origin.mjs";
import { report } from "./steps/report.mjs";
import { rough } from "./steps/rough.mjs";
import { run } from "./steps/run.mjs";
import { stroke } from "./steps/stroke.mjs";
import { study } from "./steps/study.mjs";
import { views } from "./steps/views.mjs";

const profile = fs.mkdtempSync(path.join(os.tmpdir(), "tribosim-chromium-"));
// A fresh, empty profile directory (Playwright's way of passing --user-data-dir).
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  headless: true,
  args: [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    // A name of another site that resolves to the server, as after DNS rebinding (steps/origin.mjs).
    "--host-resolver-rules=MAP rebind.test 127.0.0.1",
  ],
  viewport: { width: 1440, height: 1000 },
  acceptDownloads: true,
});

let failed = false;
try {
  const page = context.pages()[0] || await context.newPage();
  page.setDefaultTimeout(LONG);
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  // Nothing of the page is refused by its content policy: Chromium logs each refusal, and
  // the securitypolicyviolation event is reported too.
  await context.addInitScript(() => document.addEventListener("securitypolicyviolation",
    (e) => console.error(`securitypolicyviolation: ${e.violatedDirective} ${e.blockedURI}`)));
  page.on("console", (m) => { if (/securitypolicyviolation|Content Security Policy/i.test(m.text())) errors.push(m.text()); });
  // Nothing the page asks for is missing (a browser asks for /favicon.ico without an icon).
  page.on("response", (r) => { if (r.status() === 404 && !r.url().includes("/api/")) errors.push(`404 ${r.url()}`); });
  // What one step finds and a later one uses (the runs' ids, the run's length, ...).
  const found = {};
  for (const scenario of [form, run, measurements, report, compare, access, study, calibration, listing, cancel, rough, ocp, views, figures, fig11, stroke, origin]) {
    await scenario(page, found);
  }
  assert.deepEqual(errors, [], "errors in the page");
  console.log("e2e: all checks passed");
} catch (e) {
  failed = true;
  console.error("e2e FAILED:", e);
} finally {
  await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
