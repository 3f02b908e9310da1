// The printable report of the run with its measurements: downloaded from the run panel,
// self-contained, printed by Chromium to A4 and Letter PDF, rendered to PNG by pdftoppm,
// with every figure and table there and nothing past the printable width.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";

import { RUN } from "../../../static/js/ids.js";
import { sel, step } from "../lib.mjs";

// CSS pixels per millimetre (96 per inch).
const PX_PER_MM = 96 / 25.4;
// The report's @page margin, mm: what is left of a page's width is the printable width.
const MARGIN_MM = 15;
const PAPERS = [{ format: "A4", widthMm: 210 }, { format: "Letter", widthMm: 215.9 }];
// Volume, depth, potential, WAC, profiles and pressure maps, as the run panel draws them.
const FIGURES = 6;
// Summary, the scene's differences from its preset, its fields, the models, a residual
// table per attached kind (volume, profile, potential), the run's provenance, the report's.
const TABLES = 9;
// pdftoppm's resolution for the pages' PNGs, dpi: the margin is 24 px wide at it.
const DPI = 40;

const count = (html, tag) => (html.match(new RegExp(`<${tag}[\\s>]`, "g")) || []).length;

// The text of every <figcaption>, with its entities as the PDF's text has them.
const captions = (html) => [...html.matchAll(/<figcaption>([^<]*)<\/figcaption>/g)]
  .map((m) => m[1].replace(/&#39;/g, "'").replace(/&quot;/g, '"').replace(/&lt;/g, "<").replace(/&gt;/g, ">").replace(/&amp;/g, "&"));

const words = (text) => text.replace(/\s+/g, " ");

// Elements whose right edge is past `limit` px, at the print media and the viewport set,
// and the page's own width when text runs past its box (an unbreakable line: Chromium would
// then shrink the whole page to fit the paper, so the margins stay blank).
const overflowing = (page, limit) => page.evaluate((edge) => {
  const wide = [...document.body.querySelectorAll("*")]
    .filter((el) => el.getBoundingClientRect().right > edge + 0.5)
    .slice(0, 5).map((el) => `${el.tagName} ${Math.round(el.getBoundingClientRect().right)} px`);
  const scroll = document.documentElement.scrollWidth;
  return scroll > edge ? [...wide, `the page is ${scroll} px wide`] : wide;
}, limit);

// How many pixels of the PNG (base64) are not white in the right margin's columns, less
// 3 mm so that anti-aliasing at the text's edge is not counted. Decoded by the browser.
const inkInRightMargin = (page, png, fraction) => page.evaluate(async ([data, f]) => {
  const image = new Image();
  image.src = `data:image/png;base64,${data}`;
  await image.decode();
  const canvas = document.createElement("canvas");
  canvas.width = image.width;
  canvas.height = image.height;
  const ctx = canvas.getContext("2d");
  ctx.drawImage(image, 0, 0);
  const from = Math.ceil(image.width * (1 - f));
  const pixels = ctx.getImageData(from, 0, image.width - from, image.height).data;
  let ink = 0;
  for (let i = 0; i < pixels.length; i += 4) if (pixels[i] < 245 || pixels[i + 1] < 245 || pixels[i + 2] < 245) ink++;
  return ink;
}, [png.toString("base64"), fraction]);

// What makes each figure readable, read from the SVGs as the print page lays them out:
// per figure, the tick labels of each axis (labels sharing a baseline, or a right edge)
// with their decimals, the distinct colours of its series' lines, the grid lines and the
// tick labels counted, and the texts of the pressure maps' axes and colour bar.
const figureFacts = (page) => page.evaluate(() => [...document.querySelectorAll("figure svg")].map((svg) => {
  const numeric = [...svg.querySelectorAll("text")]
    .map((t) => ({ text: t.textContent.trim(), box: t.getBoundingClientRect() }))
    .filter((t) => /^-?\d+(\.\d+)?(e-?\d+)?$/.test(t.text));
  // An axis's labels share their top (the x axis's) or their right edge (the y axis's).
  const axes = {};
  for (const t of numeric) {
    for (const key of [`top ${Math.round(t.box.top)}`, `right ${Math.round(t.box.right)}`]) (axes[key] ||= []).push(t.text);
  }
  const strokes = [...svg.querySelectorAll("polyline")].map((l) => (l.getAttribute("stroke") || "").toUpperCase())
    .filter((c) => c && c !== "#000000" && c !== "#5A5A5A");
  return {
    labels: numeric.map((t) => t.text),
    baselines: Object.values(axes).filter((g) => g.length > 1),
    colours: new Set(strokes).size,
    grid: svg.querySelectorAll('line[stroke="#E1E1E1"]').length,
    words: [...svg.querySelectorAll("text")].map((t) => t.textContent.trim()),
  };
}));

const decimals = (label) => (/\.(\d+)/.exec(label.split("e")[0]) || ["", ""])[1].length;

function assertReadable(facts) {
  for (const [i, f] of facts.entries()) {
    for (const row of f.baselines) {
      const widths = new Set(row.map(decimals));
      assert.equal(widths.size, 1, `figure ${i + 1}: the ticks ${row.join(", ")} differ in their decimals`);
    }
    assert.ok(f.grid <= f.labels.length, `figure ${i + 1}: ${f.grid} grid lines for ${f.labels.length} tick labels (a minor grid)`);
  }
  const profiles = facts.find((f) => f.words.some((w) => w.startsWith("-D at cycle")));
  const cycles = profiles.words.filter((w) => w.startsWith("-D at cycle")).length;
  assert.ok(cycles > 6, `the profiles figure has ${cycles} profiles: too few to test the palette`);
  assert.equal(profiles.colours, cycles, `${cycles} profiles drawn in ${profiles.colours} colours`);
  const maps = facts.find((f) => f.words.includes("pressure (MPa)"));
  assert.ok(maps, "the pressure maps have no colour bar");
  for (const title of ["x along the sliding (um)", "y across the track (um)"]) assert.ok(maps.words.includes(title), `the maps lack "${title}"`);
}

async function printed(page, html, dir, paper) {
  const printable = (paper.widthMm - 2 * MARGIN_MM) * PX_PER_MM;
  await page.setViewportSize({ width: Math.floor(printable), height: 1000 });
  assert.deepEqual(await overflowing(page, Math.floor(printable)), [], `${paper.format}: elements past the printable width`);
  const pdf = path.join(dir, `${paper.format}.pdf`);
  await page.pdf({ path: pdf, format: paper.format });
  const info = execFileSync("pdfinfo", [pdf], { encoding: "utf8" });
  const pages = Number(/^Pages:\s+(\d+)/m.exec(info)[1]);
  assert.match(info, paper.format === "A4" ? /595\.\d+ x 841\.\d+ pts|595\.\d+ x 842\.\d+ pts/ : /612 x 792 pts/, `${paper.format}: ${info}`);
  execFileSync("pdftoppm", ["-r", String(DPI), "-png", pdf, path.join(dir, paper.format)]);
  const pngs = fs.readdirSync(dir).filter((f) => f.startsWith(`${paper.format}-`) && f.endsWith(".png")).sort();
  assert.equal(pngs.length, pages, `${paper.format}: ${pngs.length} PNGs of ${pages} pages`);
  const text = words(execFileSync("pdftotext", [pdf, "-"], { encoding: "utf8" }));
  for (const title of ["pressure (MPa)", "x along the sliding (um)", "Table 3, measured (mean and spread)"]) {
    assert.ok(text.includes(title), `${paper.format}: "${title}" is not in the PDF's text`);
  }
  for (const caption of captions(html)) {
    assert.ok(text.includes(words(caption).slice(0, 40)), `${paper.format}: the figure "${caption}" is not in the PDF`);
  }
  const ink = [];
  for (const png of pngs) ink.push(await inkInRightMargin(page, fs.readFileSync(path.join(dir, png)), (MARGIN_MM - 3) / paper.widthMm));
  console.log(`   ${paper.format}: ${pages} pages; ink in the right margin per page: ${ink.join(" ")}`);
  assert.ok(pages >= 3, `${paper.format}: ${pages} pages`);
  assert.ok(ink.every((n) => n === 0), `${paper.format}: a page overflows into its right margin (${ink})`);
}

export async function report(page) {
  step("the printable report: downloaded from the run panel, every figure and table in it");
  const [download] = await Promise.all([page.waitForEvent("download"), page.click(sel(RUN.downloadReport))]);
  assert.match(download.suggestedFilename(), /\.report\.html$/);
  const html = fs.readFileSync(await download.path(), "utf8");
  for (const tag of ["script", "link", "img", "iframe"]) assert.equal(count(html, tag), 0, `the report holds <${tag}>`);
  assert.equal(count(html, "figure"), FIGURES);
  assert.equal(count(html, "svg"), FIGURES, "a figure without its SVG");
  assert.equal(count(html, "table"), TABLES);
  assert.equal(captions(html).length, FIGURES);

  step("printed to A4 and Letter by Chromium, pages rendered by pdftoppm: nothing fetched, nothing past the margin");
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), "tribosim-report-"));
  const print = await page.context().newPage();
  try {
    const fetched = [];
    await print.route("**/*", (route) => { fetched.push(route.request().url()); return route.abort(); });
    await print.setContent(html, { waitUntil: "load" });
    await print.emulateMedia({ media: "print" });
    assertReadable(await figureFacts(print));
    for (const paper of PAPERS) await printed(print, html, dir, paper);
    assert.deepEqual(fetched, [], "the report fetched something");
  } finally {
    await print.close();
    fs.rmSync(dir, { recursive: true, force: true });
  }
}
