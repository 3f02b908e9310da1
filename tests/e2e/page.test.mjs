// End-to-end test of the results page in headless Chromium (Debian's package), driven by
// playwright-core. Needs TRIBOSIM_URL (a running `tribosim serve`); SCREENSHOT_DIR (default
// docs/screenshots) receives the screenshots. Every wait is for a condition, with generous
// time limits: the machine may be a loaded 2-core box.
import { chromium } from "playwright-core";
import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";

const base = process.env.TRIBOSIM_URL;
assert.ok(base, "TRIBOSIM_URL is not set");
const shots = path.resolve(process.env.SCREENSHOT_DIR || "../../docs/screenshots");
fs.mkdirSync(shots, { recursive: true });
const LONG = 120_000;

const profile = fs.mkdtempSync(path.join(os.tmpdir(), "tribosim-chromium-"));
// A fresh, empty profile directory (Playwright's way of passing --user-data-dir).
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  headless: true,
  args: [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
  ],
  viewport: { width: 1440, height: 1000 },
  acceptDownloads: true,
});

let failed = false;
const step = (name) => console.log(`-- ${name}`);
const points = (page, id) => page.$eval(`#${id}`, (el) => Number(el.dataset.points));

try {
  const page = context.pages()[0] || await context.newPage();
  page.setDefaultTimeout(LONG);
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));

  step("open the page; the presets load");
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]");
  assert.equal(await page.inputValue("#preset"), "dalmau2018-316l");

  step("a bad field: load -1 is refused, and the message sits next to the load field");
  await page.fill("#f-test-load_n", "-1");
  await page.click("#submit");
  const loadError = page.locator('.field[data-path="test.load_n"] .error');
  await loadError.filter({ hasText: /\S/ }).waitFor();
  console.log(`   load error: ${await loadError.textContent()}`);
  assert.equal(await page.getAttribute("#f-test-load_n", "aria-invalid"), "true");
  await page.screenshot({ path: path.join(shots, "validation-error.png"), clip: { x: 0, y: 0, width: 720, height: 760 } });

  step("a pasted scene with a bad field: the error is listed under the JSON box");
  await page.check("#use-json");
  await page.fill("#scene-json", JSON.stringify({ preset: "dalmau2018-316l", overrides: { test: { speed_rpm: -5 } } }));
  await page.click("#submit");
  await page.locator("#json-errors", { hasText: "test.speed_rpm" }).waitFor();
  console.log(`   json error: ${await page.textContent("#json-errors")}`);
  // In JSON mode the fields show the JSON's values and cannot be edited.
  assert.equal(await page.inputValue("#f-test-speed_rpm"), "-5");
  assert.equal(await page.$eval("#f-test-speed_rpm", (el) => el.readOnly), true);
  await page.uncheck("#use-json");
  assert.equal(await page.$eval("#f-test-speed_rpm", (el) => el.readOnly), false);
  await page.fill("#f-test-speed_rpm", "60");

  step("start the preset on a small grid, driven by the keyboard-usable form");
  await page.fill("#f-test-load_n", "5");
  await page.fill("#f-numerics-grid", process.env.E2E_GRID || "64");
  await page.fill("#f-test-cycles", process.env.E2E_CYCLES || "3600");
  // Samples, every frame, the run's progress bar and the live volume plot's point count,
  // to show that both moved while the job was running (not only at its end).
  await page.evaluate(() => {
    window.samples = [];
    const sample = () => {
      const p = document.getElementById("run-progress");
      window.samples.push([p.value, p.max, Number(document.getElementById("plot-volume").dataset.points),
        document.getElementById("run-status").textContent]);
      if (!document.getElementById("run-status").textContent.startsWith("succeeded")) requestAnimationFrame(sample);
    };
    requestAnimationFrame(sample);
  });
  await page.focus("#submit");
  await page.keyboard.press("Enter");
  await page.waitForSelector("#run-panel:not([hidden])");
  assert.equal(await loadError.textContent(), "", "the load error stayed after a good submit");

  step("the progress moves and the live plots fill");
  await page.waitForFunction(() => {
    const p = document.getElementById("run-progress");
    return p.value > 0 && p.value < p.max && Number(document.getElementById("plot-volume").dataset.points) > 0;
  }, null, { polling: "raf" });

  step("the run ends; the final plots hold data");
  await page.waitForFunction(() => document.getElementById("run-status").textContent.startsWith("succeeded"), null, { timeout: 600_000 });
  await page.waitForFunction(() => Number(document.getElementById("plot-pressure").dataset.points) > 0);
  const cyclesTotal = await page.$eval("#run-progress", (p) => p.max);
  const samples = await page.evaluate(() => window.samples);
  const mid = samples.filter(([v, max, n]) => v > 0 && v < max && n > 0);
  const distinct = new Set(mid.map(([v]) => v));
  console.log(`   ${samples.length} frames sampled; ${mid.length} mid-run, at ${distinct.size} distinct progress values`);
  assert.ok(distinct.size >= 2, "the progress did not move during the run");
  const counts = {};
  for (const id of ["plot-volume", "plot-depth", "plot-potential", "plot-wac", "plot-profile", "plot-pressure"]) {
    counts[id] = await points(page, id);
  }
  console.log(`   data points: ${JSON.stringify(counts)}`);
  for (const [id, n] of Object.entries(counts)) assert.ok(n > 0, `${id} holds no data`);
  // The charts really drew: uPlot's canvases exist and are not blank.
  const inked = await page.$$eval("#plot-volume canvas, #plot-depth canvas", (canvases) => canvases.map((c) => {
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 3; i < d.length; i += 4) if (d[i] > 0) n++;
    return n;
  }));
  assert.ok(inked.length >= 2 && inked.every((n) => n > 100), `blank canvas: ${inked}`);
  // The job list shows it finished, with a full progress bar and a Delete button.
  const row = page.locator("#jobs tbody tr.selected");
  assert.match(await row.textContent(), /succeeded/);
  assert.equal(await row.locator("progress").evaluate((p) => p.value === p.max), true);
  await row.locator("button.delete").waitFor();
  await page.screenshot({ path: path.join(shots, "after-run.png"), fullPage: true });

  step("the preset's run: Table 3 beside it, within the run's cycles; E_corr on the potential plot");
  const table3Cycles = [10, 60, 300, 1800, 3600];
  const volumePlot = await page.evaluate(() => ({
    measured: Number(document.getElementById("plot-volume").dataset.measured),
    enabled: !document.getElementById("show-table3").disabled,
    xMax: state.plots["plot-volume"].scales.x.max,
  }));
  console.log(`   volume plot: ${JSON.stringify(volumePlot)}`);
  assert.equal(volumePlot.measured, table3Cycles.filter((c) => c <= cyclesTotal).length);
  assert.ok(volumePlot.enabled, "the Table 3 choice is disabled for the preset's scene");
  assert.ok(volumePlot.xMax <= cyclesTotal, `the x axis runs to ${volumePlot.xMax}, past the run's ${cyclesTotal} cycles`);
  // The cursor on Table 3's 60 s point: every series reads that one row (cycle 60).
  const hover = await page.evaluate(() => {
    const u = state.plots["plot-volume"];
    u.setCursor({ left: u.valToPos(60, "x"), top: 10 });
    return { x: u.data[0][u.cursor.idx], rows: u.cursor.idxs.slice(1), legend: document.querySelector("#plot-volume .u-legend").textContent };
  });
  console.log(`   hover: ${JSON.stringify(hover)}`);
  assert.equal(hover.x, 60);
  assert.ok(hover.rows.every((i) => i === hover.rows[0]), `the legend reads rows ${hover.rows}`);
  assert.match(hover.legend, /simulated\s*\d/, "no simulated value at cycle 60");
  const potential = await page.evaluate(() => {
    const u = state.plots["plot-potential"];
    return { axis: u.axes[1].label, ecorr: u.data[2][0], series: u.series.map((s) => s.label) };
  });
  console.log(`   potential plot: ${JSON.stringify(potential)}`);
  assert.equal(potential.axis, "potential (V vs Ag/AgCl)");
  assert.equal(potential.ecorr, -0.1, "the dashed line is not the preset's E_corr (-0.1 V)");
  assert.ok(potential.series.some((l) => /E_corr/.test(l)));
  assert.doesNotMatch(await page.textContent("#run-panel"), /\bum\b/, "the run panel says um, not µm");
  assert.doesNotMatch(await page.textContent("#run-panel"), /--|WearTrack/, "a legend or a reason says -- or WearTrack");

  step("the pressure maps: both at one length scale, x and y alike");
  const maps = await page.evaluate(() => [...document.querySelectorAll("#plot-pressure svg g[data-cycle]")].map((g) => {
    const map = state.result.pressure_maps.find((m) => m.cycle === Number(g.dataset.cycle));
    const frame = g.querySelector("rect.frame");
    const span = (c) => c[c.length - 1] - c[0] + (c[1] - c[0]);
    return { cycle: map.cycle, spanX: span(map.x_um), spanY: span(map.y_um), width: Number(frame.getAttribute("width")), height: Number(frame.getAttribute("height")), umPerPx: Number(g.dataset.umPerPx) };
  }));
  console.log(`   maps: ${JSON.stringify(maps)}`);
  assert.equal(maps.length, 2);
  assert.equal(maps[0].umPerPx, maps[1].umPerPx);
  // Each frame is its span at the one scale, to the 0.005 px of its two written decimals.
  for (const m of maps) {
    assert.ok(Math.abs(m.spanX / maps[0].umPerPx - m.width) <= 0.0051, `map ${m.cycle}: x not at the common scale`);
    assert.ok(Math.abs(m.spanY / maps[0].umPerPx - m.height) <= 0.0051, `map ${m.cycle}: y not at the common scale`);
  }

  step("the run's parameters: the scene as run, and what differs from the preset");
  assert.match(await page.textContent("#params-diff"), /Differs from the preset dalmau2018-316l in \d+ fields?:.*grid 64/);
  assert.match(await page.textContent("#params-json"), /"load_n": 5/);

  step("download the JSON and the CSV");
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#download-json")]);
  const file = await download.path();
  const result = JSON.parse(fs.readFileSync(file, "utf8"));
  assert.equal(result.cycles.length, counts["plot-depth"]);
  assert.equal(result.cycles[result.cycles.length - 1].cycle, cyclesTotal);
  assert.ok(result.pressure_maps.length >= 1 && result.profiles.length >= 1);
  console.log(`   ${download.suggestedFilename()}: ${result.cycles.length} cycles, ${result.profiles.length} profiles`);
  const [csvDownload] = await Promise.all([page.waitForEvent("download"), page.click("#download-csv")]);
  const csv = fs.readFileSync(await csvDownload.path(), "utf8").trim().split("\n");
  assert.equal(csv.length, result.cycles.length + 1);
  assert.ok(csv[0].trim().split(",").includes("cycles_stepped_over"), `the CSV does not say which cycles were stepped over: ${csv[0]}`);
  console.log(`   ${csvDownload.suggestedFilename()}: ${csv.length - 1} rows`);

  step("measurements attached to the run: a bad table refused with its column named, then three kinds drawn");
  await page.click("#measurements summary");
  const attach = async (kind, csv, asFile) => {
    await page.selectOption("#measure-kind", kind);
    if (asFile) await page.setInputFiles("#measure-file", { name: `${kind}.csv`, mimeType: "text/csv", buffer: Buffer.from(csv) });
    else await page.fill("#measure-text", csv);
    await page.click("#measure-attach");
  };
  await attach("wear_volume", "cycles,volume_mm3\n10,-0.001\n", false);
  await page.locator("#measure-errors", { hasText: "volume_mm3" }).waitFor();
  console.log(`   refused: ${await page.textContent("#measure-errors")}`);
  await attach("wear_volume", "cycles,volume_mm3\n10,0.00097\n60,0.00109\n300,0.00118\n", true);
  await page.waitForFunction(() => document.getElementById("plot-volume").dataset.attached === "3");
  await attach("profile", "y_mm,depth_um\n-0.1,0.4\n0,3.1\n0.1,0.4\n", false);
  await page.waitForFunction(() => document.getElementById("plot-profile").dataset.attached === "3");
  await attach("potential", "time_s,potential_v\n100,-0.30\n1000,-0.35\n", false);
  await page.waitForFunction(() => document.getElementById("plot-potential").dataset.attached === "2");
  assert.equal(await page.textContent("#measure-errors"), "");
  const drawn = await page.evaluate(() => ["plot-volume", "plot-profile", "plot-potential"].map((id) => {
    const u = state.plots[id];
    const k = u.series.findIndex((s) => s.label === "attached measurement");
    return [id, k > 0 ? u.data[k].filter((v) => v != null).length : 0];
  }));
  console.log(`   attached points drawn: ${JSON.stringify(drawn)}`);
  assert.deepEqual(drawn, [["plot-volume", 3], ["plot-profile", 3], ["plot-potential", 2]]);
  // Stored with the job: the API returns them.
  const stored = await page.evaluate(async () => (await api(`/api/v1/jobs/${state.selected}/measurements`)).body);
  assert.deepEqual(stored.wear_volume.cycles, [10, 60, 300]);

  step("a 10 N run: no Table 3 beside it, and the page says why");
  await page.fill("#f-test-load_n", "10");
  const presetRun = await page.$eval("#jobs tbody tr.selected", (tr) => tr.dataset.id);
  await page.click("#submit");
  await page.waitForFunction((id) => {
    const tr = document.querySelector("#jobs tbody tr.selected");
    return tr && tr.dataset.id !== id;
  }, presetRun);
  await page.waitForFunction(() => document.getElementById("run-status").textContent.startsWith("succeeded"), null, { timeout: 600_000 });
  await page.waitForFunction(() => Number(document.getElementById("plot-pressure").dataset.points) > 0);
  assert.equal(await page.$eval("#plot-volume", (el) => el.dataset.measured), "0");
  assert.equal(await page.isDisabled("#show-table3"), true);
  assert.match(await page.textContent("#table3-note"), /differ/);
  const tenRun = await page.$eval("#jobs tbody tr.selected", (tr) => tr.dataset.id);

  step("edit and run again: the form takes the run's values, and the name follows the fields");
  await page.click("#edit-again");
  assert.equal(await page.inputValue("#f-test-load_n"), "10");
  assert.equal(await page.inputValue("#f-numerics-grid"), "64");
  assert.match(await page.inputValue("#f-name"), /load 10 N/);
  await page.fill("#f-test-load_n", "7");
  assert.match(await page.inputValue("#f-name"), /load 7 N/);
  assert.doesNotMatch(await page.inputValue("#f-name"), /10 N/);
  await page.fill("#f-test-load_n", "5");

  step("compare the 5 N and the 10 N runs: both curves, a legend from their scenes, summaries side by side");
  for (const id of [presetRun, tenRun]) await page.check(`#jobs tr[data-id="${id}"] .compare-pick`);
  await page.click("#compare-button");
  await page.waitForSelector("#compare-panel:not([hidden])");
  for (const id of ["cmp-volume", "cmp-depth", "cmp-potential", "cmp-wac", "cmp-profile"]) {
    await page.waitForFunction((plotId) => document.getElementById(plotId).dataset.curves === "2", id);
  }
  const compared = await page.evaluate(() => {
    const u = state.plots["cmp-volume"];
    return {
      labels: u.series.slice(1).map((s) => s.label),
      points: u.data.slice(1).map((col) => col.filter((v) => v != null).length),
      colours: u.series.slice(1).map((s) => s._stroke || s.stroke),
      table: document.getElementById("cmp-table").innerText,
    };
  });
  console.log(`   comparison: ${JSON.stringify({ labels: compared.labels, points: compared.points })}`);
  assert.deepEqual(compared.labels, ["load 5 N", "load 10 N"]);
  assert.ok(compared.points.every((n) => n > 10), `a curve is missing: ${compared.points}`);
  assert.notEqual(compared.colours[0], compared.colours[1]);
  assert.match(compared.table, /load \(N\)\s+5\s+10/);
  assert.match(compared.table, /wear volume \(10⁻³ mm³\)\s+[\d.]+\s+[\d.]+ \(\+[\d.]+ %\)/);
  await page.check('input[name="cmp-x"][value="time"]');
  assert.equal(await page.evaluate(() => state.specs["cmp-volume"].xLabel), "time (s)");
  await page.check('input[name="cmp-x"][value="cycles"]');
  await page.locator("#compare-panel").screenshot({ path: path.join(shots, "comparison.png") });

  step("export the comparison's volume figure as SVG and PNG, and open both");
  const [svgDownload] = await Promise.all([page.waitForEvent("download"), page.click("#cmp-volume .export-svg")]);
  const svgText = fs.readFileSync(await svgDownload.path(), "utf8");
  const svg = await page.evaluate((text) => {
    const doc = new DOMParser().parseFromString(text, "image/svg+xml");
    const root = doc.documentElement;
    return {
      error: doc.querySelector("parsererror") ? doc.querySelector("parsererror").textContent : null,
      width: Number(root.getAttribute("width")), height: Number(root.getAttribute("height")),
      lines: [...doc.querySelectorAll("polyline")].map((l) => [l.getAttribute("data-series"), l.getAttribute("points").split(" ").length]),
      texts: [...doc.querySelectorAll("text")].map((t) => t.textContent),
    };
  }, svgText);
  console.log(`   ${svgDownload.suggestedFilename()}: ${svg.width} x ${svg.height}, lines ${JSON.stringify(svg.lines)}`);
  assert.equal(svg.error, null);
  assert.deepEqual(svg.lines.map((l) => l[0]), ["load 5 N", "load 10 N"]);
  assert.ok(svg.lines.every((l) => l[1] > 10));
  for (const text of ["wear volume (10⁻³ mm³)", "cycles (passes of the ball)", "load 5 N", "load 10 N"]) assert.ok(svg.texts.includes(text), `the SVG lacks "${text}"`);
  const [pngDownload] = await Promise.all([page.waitForEvent("download"), page.click("#cmp-volume .export-png")]);
  const png = fs.readFileSync(await pngDownload.path());
  assert.equal(png.subarray(1, 4).toString("latin1"), "PNG");
  const pngSize = [png.readUInt32BE(16), png.readUInt32BE(20)];
  const decoded = await page.evaluate(async (b64) => {
    const bitmap = await createImageBitmap(await (await fetch("data:image/png;base64," + b64)).blob());
    return [bitmap.width, bitmap.height];
  }, png.toString("base64"));
  console.log(`   ${pngDownload.suggestedFilename()}: ${pngSize.join(" x ")} px, ${png.length} bytes`);
  assert.deepEqual(pngSize, [svg.width * 3, svg.height * 3]);
  assert.deepEqual(decoded, pngSize);
  const [mapDownload] = await Promise.all([page.waitForEvent("download"), page.click("#plot-pressure .export-svg")]);
  const mapRects = await page.evaluate((text) => new DOMParser().parseFromString(text, "image/svg+xml").querySelectorAll("g[data-cycle] rect").length, fs.readFileSync(await mapDownload.path(), "utf8"));
  assert.ok(mapRects > 100, `the pressure maps' SVG has ${mapRects} cells`);

  step("contrast: focus ring, status colours and chart lines against WCAG AA");
  // A keyboard move, so that the focus ring (:focus-visible) shows.
  await page.focus("#f-test-cycles");
  await page.keyboard.press("Tab");
  const contrast = await page.evaluate(() => {
    const rgb = (c) => c.match(/\d+(\.\d+)?/g).slice(0, 3).map(Number);
    const lum = (c) => {
      const [r, g, b] = rgb(c).map((v) => { v /= 255; return v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4; });
      return 0.2126 * r + 0.7152 * g + 0.0722 * b;
    };
    const ratio = (a, b) => { const [x, y] = [lum(a), lum(b)].sort((p, q) => q - p); return (x + 0.05) / (y + 0.05); };
    const white = "rgb(255, 255, 255)", selected = getComputedStyle(document.querySelector("#jobs tr.selected") || document.body).backgroundColor;
    const focusStyle = getComputedStyle(document.activeElement);
    const ring = focusStyle.outlineStyle === "none" ? white : focusStyle.outlineColor;
    const probe = document.createElement("span");
    document.body.appendChild(probe);
    const status = {};
    for (const s of ["succeeded", "failed", "running", "cancelled", "damaged"]) {
      probe.className = "status-" + s;
      status[s] = Math.min(ratio(getComputedStyle(probe).color, white), ratio(getComputedStyle(probe).color, selected.startsWith("rgba(0, 0, 0, 0)") ? white : selected));
    }
    probe.className = "muted";
    const muted = ratio(getComputedStyle(probe).color, white);
    probe.remove();
    return { ring: ratio(ring, white), status, muted, lines: Math.min(...COLORS.map((c) => ratio(`rgb(${parseInt(c.slice(1, 3), 16)}, ${parseInt(c.slice(3, 5), 16)}, ${parseInt(c.slice(5, 7), 16)})`, white))) };
  });
  console.log(`   contrast: ${JSON.stringify(contrast)}`);
  assert.ok(contrast.ring >= 3, "focus ring below 3:1");
  assert.ok(contrast.lines >= 3, "a chart colour below 3:1");
  assert.ok(contrast.muted >= 4.5, "muted text below 4.5:1");
  for (const [s, r] of Object.entries(contrast.status)) assert.ok(r >= 4.5, `status ${s} below 4.5:1`);

  step("phone width (390 px): no horizontal scroll, no chart or input past the edge; a job lower in the list brings its plots into view");
  await page.setViewportSize({ width: 390, height: 844 });
  await page.waitForTimeout(400);
  const phone = await page.evaluate(() => {
    const past = [...document.querySelectorAll(".plot, canvas, .heatmaps svg, #run-form input, #run-form select, #run-form textarea, #run-form button")]
      .filter((el) => el.offsetParent && el.getBoundingClientRect().right > document.documentElement.clientWidth + 0.5)
      .map((el) => el.id || el.className || el.tagName);
    const cut = [...document.querySelectorAll("#run-form input:not([type=checkbox]), #run-form select")]
      .filter((el) => el.getBoundingClientRect().width < 60).map((el) => el.id);
    return { scrollWidth: document.documentElement.scrollWidth, clientWidth: document.documentElement.clientWidth, past, cut };
  });
  console.log(`   phone: ${JSON.stringify(phone)}`);
  assert.ok(phone.scrollWidth <= phone.clientWidth, `the page scrolls sideways: ${phone.scrollWidth} > ${phone.clientWidth}`);
  assert.deepEqual(phone.past, []);
  assert.deepEqual(phone.cut, []);
  await page.evaluate(() => window.scrollTo(0, 0));
  const lowest = page.locator("#jobs tbody tr").last();
  await lowest.locator("button.view").click();
  await page.waitForFunction(() => {
    const top = document.getElementById("run-panel").getBoundingClientRect().top;
    const plot = document.getElementById("plot-volume").getBoundingClientRect();
    return top >= -1 && top < window.innerHeight / 2 && plot.top < window.innerHeight;
  });
  await page.screenshot({ path: path.join(shots, "phone.png"), fullPage: false });
  await page.setViewportSize({ width: 1440, height: 1000 });

  step("keyboard only, from a fresh load: a run started and viewed; the tab order follows the page");
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]");
  await page.waitForSelector("#jobs tbody tr");
  await page.evaluate(() => { window.tabbed = []; });
  const tabTo = async (selector, limit = 60) => {
    for (let i = 0; i < limit; i++) {
      await page.keyboard.press("Tab");
      const hit = await page.evaluate((sel) => { window.tabbed.push(document.activeElement); return document.activeElement.matches(sel); }, selector);
      if (hit) return;
    }
    throw new Error(`Tab never reached ${selector}`);
  };
  await tabTo("#f-test-cycles");
  await page.keyboard.press("Control+A");
  await page.keyboard.type("20");
  await tabTo("#f-numerics-grid");
  await page.keyboard.press("Control+A");
  await page.keyboard.type("32");
  assert.match(await page.inputValue("#f-name"), /cycles 20, grid 32/);
  await tabTo("#submit");
  const known = await page.$$eval("#jobs tbody tr", (trs) => trs.map((tr) => tr.dataset.id));
  await page.keyboard.press("Enter");
  await page.waitForFunction((ids) => [...document.querySelectorAll("#jobs tbody tr")].some((tr) => !ids.includes(tr.dataset.id)), known);
  const keyRun = await page.$eval("#jobs tbody tr", (tr) => tr.dataset.id);
  assert.ok(!known.includes(keyRun), "the newest row is not the keyboard's run");
  await page.waitForFunction((id) => /succeeded/.test(document.querySelector(`#jobs tr[data-id="${id}"]`).textContent), keyRun, { timeout: 600_000 });
  await tabTo(`#jobs tr[data-id="${keyRun}"] button.view`);
  await page.keyboard.press("Enter");
  await page.waitForFunction(() => document.activeElement.id === "run-panel" && document.getElementById("run-status").textContent.startsWith("succeeded"));
  await page.waitForFunction(() => Number(document.getElementById("plot-depth").dataset.points) > 0);
  const order = await page.evaluate(() => {
    const seq = window.tabbed.filter((el) => el.isConnected);
    const back = [];
    for (let i = 1; i < seq.length; i++) {
      if (seq[i] !== seq[i - 1] && !(seq[i - 1].compareDocumentPosition(seq[i]) & Node.DOCUMENT_POSITION_FOLLOWING)) back.push(`${seq[i - 1].tagName}#${seq[i - 1].id || seq[i - 1].className} -> ${seq[i].tagName}#${seq[i].id || seq[i].className}`);
    }
    return { count: seq.length, back, seq: seq.map((el) => `${el.tagName}#${el.id || el.className}`) };
  });
  console.log(`   ${order.count} tab stops, backwards: ${JSON.stringify(order.back)}`);
  if (order.back.length) console.log(`   tab stops: ${order.seq.join(" ")}`);
  assert.deepEqual(order.back, [], "the tab order jumps back in the page");

  step("a study: the form's scene at 2 and 5 N; its members' results against the load; two members compared");
  await page.fill("#f-test-cycles", "20");
  await page.fill("#f-numerics-grid", "32");
  await page.click("#study-new summary");
  await page.fill("#study-axes", JSON.stringify({ "test.load_n": [2, 5] }));
  await page.click("#study-submit");
  await page.waitForSelector("#study-panel:not([hidden])");
  await page.waitForFunction(() => document.getElementById("study-status").textContent.startsWith("succeeded"), null, { timeout: 600_000 });
  await page.waitForFunction(() => Number(document.getElementById("study-volume").dataset.points) === 2);
  const study = await page.evaluate(() => ({
    rows: [...document.querySelectorAll("#study-members tbody tr")].map((tr) => tr.innerText.replace(/\s+/g, " ").trim()),
    xLabel: state.specs["study-volume"].xLabel,
    volumes: state.plots["study-volume"].data[1],
  }));
  console.log(`   study: ${JSON.stringify(study)}`);
  assert.equal(study.rows.length, 2);
  assert.equal(study.xLabel, "load (N)");
  assert.ok(study.volumes[1] > study.volumes[0], "the 5 N member did not wear more than the 2 N one");
  for (const box of await page.$$("#study-members tbody input[type=checkbox]")) await box.check();
  await page.click("#study-compare");
  await page.waitForFunction(() => document.getElementById("cmp-volume").dataset.curves === "2" && state.compared.length === 2);
  assert.deepEqual(await page.evaluate(() => state.compared.map((r) => r.label)), ["load 2 N", "load 5 N"]);
  await page.click("#compare-close");

  step("a calibration: a table the fit cannot use is refused; the hardness law fitted to Table 3's hardness; the fitted scene run");
  await page.click("#calib-new summary");
  const hardnessCsv = path.resolve("../../docs/calibration/table3_hardness.csv");
  await page.selectOption("#calib-kind", "tafel");
  await page.setInputFiles("#calib-file", hardnessCsv);
  await page.click("#calib-submit");
  await page.locator("#calib-errors", { hasText: /potential_v|current_density/ }).waitFor();
  console.log(`   refused: ${await page.textContent("#calib-errors")}`);
  await page.selectOption("#calib-kind", "hardness");
  await page.setInputFiles("#calib-file", hardnessCsv);
  await page.click("#calib-submit");
  await page.waitForFunction(() => document.getElementById("calib-status").textContent === "succeeded", null, { timeout: 300_000 });
  const calib = await page.evaluate(() => ({
    values: [...document.querySelectorAll("#calib-values tbody tr")].map((tr) => tr.innerText.replace(/\s+/g, " ").trim()),
    residuals: document.querySelectorAll("#calib-residuals tbody tr").length,
    plotted: Number(document.getElementById("calib-plot").dataset.points),
  }));
  console.log(`   calibration: ${JSON.stringify(calib)}`);
  // docs/calibration.md: A = 2454.99 ± 26.98 MPa, B = 63.38 ± 4.96 MPa over the five points and the bulk value.
  assert.deepEqual(calib.values, ["a (MPa) 2455 26.98", "b (MPa) 63.38 4.955"]);
  assert.equal(calib.residuals, 6);
  assert.equal(calib.plotted, 6);
  const beforeFit = await page.$$eval("#jobs tbody tr", (trs) => trs.map((tr) => tr.dataset.id));
  await page.click("#calib-run");
  await page.waitForFunction((ids) => state.selected && !ids.includes(state.selected), beforeFit);
  await page.waitForFunction(() => document.getElementById("run-status").textContent.startsWith("succeeded"), null, { timeout: 600_000 });

  step("an Archard fit with a change of regime at 300 cycles: both k's and the better model shown");
  await page.selectOption("#calib-kind", "archard");
  await page.fill("#calib-regime", "300");
  await page.setInputFiles("#calib-file", path.resolve("../../docs/calibration/table3_wear.csv"));
  const previous = await page.evaluate(() => state.calibration.id);
  await page.click("#calib-submit");
  await page.waitForFunction((id) => document.getElementById("calib-errors").textContent
    || (state.calibration.id !== id && document.getElementById("calib-status").textContent !== "running"), previous, { timeout: 300_000 });
  assert.equal(await page.textContent("#calib-errors"), "");
  const regimes = await page.evaluate(() => ({
    status: document.getElementById("calib-status").textContent,
    values: [...document.querySelectorAll("#calib-values tbody tr")].map((tr) => tr.cells[0].innerText.trim()),
    note: document.getElementById("calib-note").textContent,
    residuals: document.querySelectorAll("#calib-residuals tbody tr").length,
  }));
  console.log(`   regimes: ${JSON.stringify(regimes)}`);
  assert.equal(regimes.status, "succeeded");
  assert.equal(regimes.values.length, 3, "one k, k before and k after");
  assert.match(regimes.note, /change cycle/i);
  assert.equal(regimes.residuals, 5, "Table 3's five points");

  step("cancel a running job (after a confirmation), see why it stopped, then delete it; a job queued behind it shows its place");
  await page.fill("#f-test-cycles", "1000000");
  await page.click("#submit");
  await page.waitForFunction(() => (document.querySelector("#jobs tbody tr .status") || {}).textContent === "running");
  await page.click("#submit");
  const queued = page.locator("#jobs tbody tr").first();
  await queued.locator(".progress", { hasText: "number 1 in the queue" }).waitFor();
  console.log(`   queued: ${(await queued.locator(".progress").innerText()).replace(/\s+/g, " ")}`);
  page.once("dialog", (d) => d.accept());
  await queued.locator("button.cancel").click();
  await queued.locator("td", { hasText: "cancelled" }).waitFor();
  const withQueued = await page.locator("#jobs tbody tr").count();
  page.once("dialog", (d) => d.accept());
  await queued.locator("button.delete").click();
  await page.waitForFunction((n) => document.querySelectorAll("#jobs tbody tr").length === n - 1, withQueued);
  // Some cycles done before the cancel, so that there is a partial result to see; the
  // long run is also the one the screenshot of a run in progress shows.
  await page.waitForFunction(() => document.querySelector("#jobs tbody tr progress").value > 0);
  await page.locator("#jobs tbody tr").first().locator("button.view").click();
  await page.waitForFunction(() => document.getElementById("run-status").textContent.startsWith("running") && Number(document.getElementById("plot-volume").dataset.points) > 20);
  console.log(`   during the run: ${await page.$eval("#run-status", (el) => el.textContent)}`);
  await page.screenshot({ path: path.join(shots, "during-run.png"), fullPage: true });
  const newest = page.locator("#jobs tbody tr").first();
  let question = "";
  page.once("dialog", (d) => { question = d.message(); d.accept(); });
  await newest.locator("button.cancel").click();
  await newest.locator("td", { hasText: "cancelled" }).waitFor();
  assert.match(question, /^Cancel the run/);
  await newest.locator(".reason", { hasText: /Cancelled on request after \d+ of 1000000 cycles/ }).waitFor();

  step("the cancelled run keeps what it computed: drawn, and downloadable as CSV");
  await newest.locator("button.view").click();
  await page.locator("#run-partial", { hasText: "Partial result" }).waitFor();
  await page.waitForFunction(() => Number(document.getElementById("plot-depth").dataset.points) > 0 && !document.getElementById("download-csv").disabled);
  const [partialCsv] = await Promise.all([page.waitForEvent("download"), page.click("#download-csv")]);
  const partialRows = fs.readFileSync(await partialCsv.path(), "utf8").trim().split("\n");
  console.log(`   ${await page.textContent("#run-partial")} (${partialRows.length - 1} CSV rows)`);
  assert.ok(partialRows.length > 1, "the partial CSV has no rows");
  assert.ok(partialRows[0].trim().split(",").includes("cycles_stepped_over"), `the CSV does not say which cycles were stepped over: ${partialRows[0]}`);
  page.once("dialog", (d) => d.accept());
  const before = await page.locator("#jobs tbody tr").count();
  await newest.locator("button.delete").click();
  await page.waitForFunction((n) => document.querySelectorAll("#jobs tbody tr").length === n - 1, before);

  step("failed, damaged and re-run jobs show their reasons in the page's text");
  const fakes = [
    { status: "failed", error: "internal error: the simulation panicked: test", rerun_reason: null },
    { status: "damaged", error: "stored scene damaged: bad CRC", rerun_reason: null },
    { status: "queued", error: null, rerun_reason: "the stored result was damaged: bad CRC" },
  ].map((f, i) => ({
    id: `00000000-0000-4000-8000-00000000000${i}`, name: `fake ${f.status}`, cycles_done: 3, cycles_total: 10,
    eta_s: null, created_at: new Date().toISOString(), started_at: null, finished_at: null, ...f,
  }));
  // The service cannot be made to fail or damage a job from outside; the page's rendering
  // of such records is what is tested, so the job list is answered with them added.
  const jobList = (url) => url.pathname === "/api/v1/jobs";
  await page.route(jobList, async (route) => {
    if (route.request().method() !== "GET") return route.continue();
    const response = await route.fetch();
    route.fulfill({ response, json: [...fakes, ...(await response.json())] });
  });
  await page.evaluate(() => refreshJobs());
  for (const [name, text] of [["fake failed", "Failed: internal error"], ["fake damaged", "Damaged: stored scene damaged"], ["fake queued", "Run again: the stored result was damaged"]]) {
    const reason = page.locator("#jobs tbody tr", { hasText: name }).locator(".reason");
    await reason.filter({ hasText: text }).waitFor();
    assert.ok(await reason.isVisible(), `${name}: the reason is not visible`);
  }
  await page.unroute(jobList);

  step("phone width again, with the study and calibration panels open: no sideways scroll");
  await page.setViewportSize({ width: 390, height: 844 });
  await page.waitForTimeout(400);
  const phoneAgain = await page.evaluate(() => ({
    open: ["study-panel", "calib-panel"].filter((id) => !document.getElementById(id).hidden),
    scrollWidth: document.documentElement.scrollWidth, clientWidth: document.documentElement.clientWidth,
  }));
  console.log(`   ${JSON.stringify(phoneAgain)}`);
  assert.deepEqual(phoneAgain.open, ["study-panel", "calib-panel"]);
  assert.ok(phoneAgain.scrollWidth <= phoneAgain.clientWidth, `the page scrolls sideways: ${phoneAgain.scrollWidth} > ${phoneAgain.clientWidth}`);

  step("a rough run on an uploaded height map: its contact cells drawn one cell per pixel, to scale");
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]");
  // A 64 x 64 text matrix of heights in m, 1 µm pixels: ripples of about 0.1 µm.
  const side = 64;
  const rows = Array.from({ length: side }, (_, j) => Array.from({ length: side },
    (_, i) => (1e-7 * (Math.sin(0.9 * i) + Math.cos(0.7 * j + 0.3 * i))).toExponential(6)).join(" "));
  await page.fill("#surface-pixel", "1");
  await page.setInputFiles("#surface-file", { name: "ripples.txt", mimeType: "text/plain", buffer: Buffer.from(rows.join("\n") + "\n") });
  await page.locator("#surface-status", { hasText: "64 × 64 pixels" }).waitFor();
  console.log(`   ${await page.textContent("#surface-status")}`);
  await page.fill("#f-numerics-grid", "128");
  await page.fill("#f-test-cycles", "3");
  const surfaceInScene = JSON.parse(await page.inputValue("#scene-json")).overrides.disc.surface;
  assert.equal(surfaceInScene.kind, "measured");
  await page.click("#submit");
  await page.waitForFunction(() => document.getElementById("run-status").textContent.startsWith("succeeded"), null, { timeout: 600_000 });
  await page.waitForFunction(() => Number(document.getElementById("plot-pressure").dataset.points) > 0);
  const roughMaps = await page.evaluate(async () => Promise.all([...document.querySelectorAll("#plot-pressure svg g[data-cycle]")].map(async (g) => {
    const map = state.result.pressure_maps.find((m) => m.cycle === Number(g.dataset.cycle));
    const frame = g.querySelector("rect.frame"), image = g.querySelector("image.contact");
    const picture = new Image();
    picture.src = image.getAttribute("href");
    await picture.decode();
    const canvas = document.createElement("canvas");
    canvas.width = picture.naturalWidth; canvas.height = picture.naturalHeight;
    const ctx = canvas.getContext("2d");
    ctx.drawImage(picture, 0, 0);
    const alpha = ctx.getImageData(0, 0, canvas.width, canvas.height).data.filter((_, k) => k % 4 === 3);
    const span = (c) => c[c.length - 1] - c[0] + (c[1] - c[0]);
    return {
      cycle: map.cycle, cellUm: map.x_um[1] - map.x_um[0], umPerPx: Number(g.dataset.umPerPx),
      spanX: span(map.x_um), spanY: span(map.y_um), width: Number(frame.getAttribute("width")), height: Number(frame.getAttribute("height")),
      imageWidth: Number(image.getAttribute("width")), cells: [map.x_um.length, map.y_um.length], pixels: [picture.naturalWidth, picture.naturalHeight],
      contact: map.pressure_mpa.flat().filter((p) => p > 0).length, drawn: alpha.filter((a) => a > 0).length,
      surface: Boolean(state.result.surface),
    };
  })));
  console.log(`   rough maps: ${JSON.stringify(roughMaps)}`);
  assert.ok(roughMaps.length >= 1 && roughMaps.every((m) => m.surface));
  for (const m of roughMaps) {
    // One cell per pixel, to the float error of x_um's differences; frames and images at
    // that one scale to the 0.005 px of their two written decimals.
    assert.ok(Math.abs(m.umPerPx / m.cellUm - 1) < 1e-9, `map ${m.cycle}: ${m.umPerPx} µm per px, cells of ${m.cellUm} µm`);
    assert.ok(Math.abs(m.spanX / m.umPerPx - m.width) <= 0.0051 && Math.abs(m.spanY / m.umPerPx - m.height) <= 0.0051, `map ${m.cycle}: not to scale`);
    assert.equal(m.imageWidth, m.width);
    assert.deepEqual(m.pixels, m.cells, `map ${m.cycle}: the image is not one pixel per cell`);
    assert.ok(m.contact > 0 && m.drawn === m.contact, `map ${m.cycle}: ${m.drawn} pixels drawn for ${m.contact} contact cells`);
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
