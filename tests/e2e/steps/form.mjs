// The page loads, and the form shows the server's refusals where they belong.
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";

import * as ids from "../../../static/js/ids.js";
import { FORM, COMPARE_X, MATERIALS, fieldId } from "../../../static/js/ids.js";
import { openPage, sel, shots, step } from "../lib.mjs";

const TYPES = { ".js": "text/javascript", ".css": "text/css" };

export async function form(page) {
  step("open the page; the presets load");
  const files = [];
  const onResponse = (r) => {
    const url = new URL(r.url());
    if (url.pathname.startsWith("/static/")) files.push({ path: url.pathname, status: r.status(), type: r.headers()["content-type"] || "" });
  };
  page.on("response", onResponse);
  await openPage(page);
  page.off("response", onResponse);
  assert.equal(await page.inputValue(sel(FORM.preset)), "dalmau2018-316l");
  // Every file the page loads comes with its type, and every module of static/js is loaded.
  for (const f of files) {
    assert.equal(f.status, 200, `${f.path}: ${f.status}`);
    const type = TYPES[path.extname(f.path)];
    if (type) assert.ok(f.type.startsWith(type), `${f.path}: ${f.type}`);
  }
  const modules = fs.readdirSync("../../static/js").map((name) => `/static/js/${name}`).sort();
  assert.deepEqual(files.map((f) => f.path).filter((p) => p.startsWith("/static/js/")).sort(), modules);
  console.log(`   ${files.length} files loaded, ${modules.length} of them modules`);
  // Every id the modules and this test use names an element of the page.
  const every = Object.values(ids).filter((v) => typeof v === "object").flatMap(Object.values);
  const missing = await page.evaluate((list) => list.filter((id) => !document.getElementById(id)), every);
  assert.deepEqual(missing, [], "ids of static/js/ids.js not in the page");
  assert.equal(await page.locator(`input[name="${COMPARE_X}"]`).count(), 2);

  step("a bad field: load -1 is refused, and the message sits next to the load field");
  const load = sel(fieldId("test.load_n"));
  await page.fill(load, "-1");
  await page.click(sel(FORM.submit));
  const loadError = page.locator('.field[data-path="test.load_n"] .error');
  await loadError.filter({ hasText: /\S/ }).waitFor();
  console.log(`   load error: ${await loadError.textContent()}`);
  assert.equal(await page.getAttribute(load, "aria-invalid"), "true");
  await page.screenshot({ path: path.join(shots, "validation-error.png"), clip: { x: 0, y: 0, width: 720, height: 760 } });

  step("a pasted scene with a bad field: the error is listed under the JSON box");
  const speed = sel(fieldId("test.speed_rpm"));
  await page.check(sel(FORM.useJson));
  await page.fill(sel(FORM.sceneJson), JSON.stringify({ preset: "dalmau2018-316l", overrides: { test: { speed_rpm: -5 } } }));
  await page.click(sel(FORM.submit));
  await page.locator(sel(FORM.jsonErrors), { hasText: "test.speed_rpm" }).waitFor();
  console.log(`   json error: ${await page.textContent(sel(FORM.jsonErrors))}`);
  // In JSON mode the fields show the JSON's values and cannot be edited.
  assert.equal(await page.inputValue(speed), "-5");
  assert.equal(await page.$eval(speed, (el) => el.readOnly), true);
  await page.uncheck(sel(FORM.useJson));
  assert.equal(await page.$eval(speed, (el) => el.readOnly), false);
  await page.fill(speed, "60");

  step("a disc from the library: its hardness, the wear alone, and the pair's own k asked for");
  const hardness = sel(fieldId("disc.hardness_mpa"));
  await page.selectOption(sel(MATERIALS.disc), "ti6al4v");
  // docs/materials.md: HV1 349 x 9.80665 = 3422.5 MPa.
  assert.equal(await page.inputValue(hardness), "3422.5");
  assert.equal(await page.isChecked(sel(MATERIALS.wearOnly)), true);
  const chosen = await page.textContent(sel(MATERIALS.note));
  assert.match(chosen, /Ti-6Al-4V.*electrochemical.*Archard k/s);
  await page.click(sel(FORM.fieldsToJson));
  const sent = JSON.parse(await page.inputValue(sel(FORM.sceneJson)));
  assert.equal(sent.overrides.disc.material, "ti6al4v");
  assert.equal(sent.overrides.corrosion, null);
  await page.click(sel(FORM.submit));
  const kError = page.locator('.field[data-path="wear.archard_k"] .error');
  await kError.filter({ hasText: /\S/ }).waitFor();
  console.log(`   k error: ${await kError.textContent()}`);
  await page.selectOption(sel(MATERIALS.disc), "");
  await page.uncheck(sel(MATERIALS.wearOnly));
  assert.equal(await page.inputValue(hardness), "2473");
}
