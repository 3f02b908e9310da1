// Accessibility: contrast against WCAG AA, a phone's width, and the keyboard alone.
import assert from "node:assert/strict";
import path from "node:path";

import { FORM, JOBS, RUN, RUN_PLOT, fieldId } from "../../../static/js/ids.js";
import { RUN_LIMIT, openPage, sel, shots, step } from "../lib.mjs";

async function contrast(page) {
  step("contrast: focus ring, status colours and chart lines against WCAG AA");
  // A keyboard move, so that the focus ring (:focus-visible) shows.
  await page.focus(sel(fieldId("test.cycles")));
  await page.keyboard.press("Tab");
  const ratios = await page.evaluate((jobs) => {
    const rgb = (c) => c.match(/\d+(\.\d+)?/g).slice(0, 3).map(Number);
    const lum = (c) => {
      const [r, g, b] = rgb(c).map((v) => { v /= 255; return v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4; });
      return 0.2126 * r + 0.7152 * g + 0.0722 * b;
    };
    const ratio = (a, b) => { const [x, y] = [lum(a), lum(b)].sort((p, q) => q - p); return (x + 0.05) / (y + 0.05); };
    const white = "rgb(255, 255, 255)", selected = getComputedStyle(document.querySelector(`#${jobs} tr.selected`) || document.body).backgroundColor;
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
    return { ring: ratio(ring, white), status, muted, lines: Math.min(...e2e.plots.COLORS.map((c) => ratio(`rgb(${parseInt(c.slice(1, 3), 16)}, ${parseInt(c.slice(3, 5), 16)}, ${parseInt(c.slice(5, 7), 16)})`, white))) };
  }, JOBS.table);
  console.log(`   contrast: ${JSON.stringify(ratios)}`);
  assert.ok(ratios.ring >= 3, "focus ring below 3:1");
  assert.ok(ratios.lines >= 3, "a chart colour below 3:1");
  assert.ok(ratios.muted >= 4.5, "muted text below 4.5:1");
  for (const [s, r] of Object.entries(ratios.status)) assert.ok(r >= 4.5, `status ${s} below 4.5:1`);
}

async function phone(page) {
  step("phone width (390 px): no horizontal scroll, no chart or input past the edge; a job lower in the list brings its plots into view");
  await page.setViewportSize({ width: 390, height: 844 });
  await page.waitForTimeout(400);
  const widths = await page.evaluate((runForm) => {
    const past = [...document.querySelectorAll(`.plot, canvas, .heatmaps svg, #${runForm} input, #${runForm} select, #${runForm} textarea, #${runForm} button`)]
      .filter((el) => el.offsetParent && el.getBoundingClientRect().right > document.documentElement.clientWidth + 0.5)
      .map((el) => el.id || el.className || el.tagName);
    // Shown ones only: a hidden input (the rig's stroke fields on the disc) has no width.
    const cut = [...document.querySelectorAll(`#${runForm} input:not([type=checkbox]), #${runForm} select`)]
      .filter((el) => el.offsetParent && el.getBoundingClientRect().width < 60).map((el) => el.id);
    return { scrollWidth: document.documentElement.scrollWidth, clientWidth: document.documentElement.clientWidth, past, cut };
  }, FORM.form);
  console.log(`   phone: ${JSON.stringify(widths)}`);
  assert.ok(widths.scrollWidth <= widths.clientWidth, `the page scrolls sideways: ${widths.scrollWidth} > ${widths.clientWidth}`);
  assert.deepEqual(widths.past, []);
  assert.deepEqual(widths.cut, []);
  await page.evaluate(() => window.scrollTo(0, 0));
  const lowest = page.locator(`${sel(JOBS.table)} tbody tr`).last();
  await lowest.locator("button.view").click();
  await page.waitForFunction(([panel, volume]) => {
    const top = document.getElementById(panel).getBoundingClientRect().top;
    const plot = document.getElementById(volume).getBoundingClientRect();
    return top >= -1 && top < window.innerHeight / 2 && plot.top < window.innerHeight;
  }, [RUN.panel, RUN_PLOT.volume]);
  await page.screenshot({ path: path.join(shots, "phone.png"), fullPage: false });
  await phoneLink(page);
  await page.setViewportSize({ width: 1440, height: 1000 });
}

// A run's link opened afresh at phone width shows the run where the page opens, with no
// scroll: scrolled down to, a headless `--screenshot` of the link caught a blank page.
async function phoneLink(page) {
  step("a run's link opened at phone width: the run at the top of the page, not scrolled to");
  const hash = await page.evaluate(() => location.hash);
  assert.match(hash, /^#run=/);
  await openPage(page, hash);
  await page.waitForFunction((panel) => !document.getElementById(panel).hidden, RUN.panel);
  const where = await page.evaluate((panel) => ({
    scrollY: window.scrollY,
    top: document.getElementById(panel).getBoundingClientRect().top,
    height: window.innerHeight,
  }), RUN.panel);
  console.log(`   run link: ${JSON.stringify(where)}`);
  assert.equal(where.scrollY, 0);
  assert.ok(where.top >= 0 && where.top < where.height / 2, `the run panel's top at ${where.top} px`);
}

// The page's elements the Tab key went through, and the steps that went back up the page.
const tabOrder = (page) => page.evaluate(() => {
  const seq = window.tabbed.filter((el) => el.isConnected);
  const back = [];
  for (let i = 1; i < seq.length; i++) {
    if (seq[i] !== seq[i - 1] && !(seq[i - 1].compareDocumentPosition(seq[i]) & Node.DOCUMENT_POSITION_FOLLOWING)) back.push(`${seq[i - 1].tagName}#${seq[i - 1].id || seq[i - 1].className} -> ${seq[i].tagName}#${seq[i].id || seq[i].className}`);
  }
  return { count: seq.length, back, seq: seq.map((el) => `${el.tagName}#${el.id || el.className}`) };
});

async function keyboard(page) {
  step("keyboard only, from a fresh load: a run started and viewed; the tab order follows the page");
  const rows = `${sel(JOBS.table)} tbody tr`;
  await openPage(page);
  await page.waitForSelector(rows);
  await page.evaluate(() => { window.tabbed = []; });
  const tabTo = async (selector, limit = 60) => {
    for (let i = 0; i < limit; i++) {
      await page.keyboard.press("Tab");
      const hit = await page.evaluate((s) => { window.tabbed.push(document.activeElement); return document.activeElement.matches(s); }, selector);
      if (hit) return;
    }
    throw new Error(`Tab never reached ${selector}`);
  };
  await tabTo(sel(fieldId("test.cycles")));
  await page.keyboard.press("Control+A");
  await page.keyboard.type("20");
  await tabTo(sel(fieldId("numerics.grid")));
  await page.keyboard.press("Control+A");
  await page.keyboard.type("32");
  assert.match(await page.inputValue(sel(FORM.name)), /cycles 20, grid 32/);
  await tabTo(sel(FORM.submit));
  const known = await page.$$eval(rows, (trs) => trs.map((tr) => tr.dataset.id));
  await page.keyboard.press("Enter");
  await page.waitForFunction(([r, ids]) => [...document.querySelectorAll(r)].some((tr) => !ids.includes(tr.dataset.id)), [rows, known]);
  const keyRun = await page.$eval(rows, (tr) => tr.dataset.id);
  assert.ok(!known.includes(keyRun), "the newest row is not the keyboard's run");
  const keyRow = `${sel(JOBS.table)} tr[data-id="${keyRun}"]`;
  await page.waitForFunction((row) => /succeeded/.test(document.querySelector(row).textContent), keyRow, { timeout: RUN_LIMIT });
  await tabTo(`${keyRow} button.view`);
  await page.keyboard.press("Enter");
  await page.waitForFunction(([panel, status]) => document.activeElement.id === panel && document.getElementById(status).textContent.startsWith("succeeded"), [RUN.panel, RUN.status]);
  await page.waitForFunction((id) => Number(document.getElementById(id).dataset.points) > 0, RUN_PLOT.depth);
  const order = await tabOrder(page);
  console.log(`   ${order.count} tab stops, backwards: ${JSON.stringify(order.back)}`);
  if (order.back.length) console.log(`   tab stops: ${order.seq.join(" ")}`);
  assert.deepEqual(order.back, [], "the tab order jumps back in the page");
}

export async function access(page) {
  await contrast(page);
  await phone(page);
  await keyboard(page);
}
