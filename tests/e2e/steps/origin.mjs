// A page of another origin against the server without a token (docs/operations.md): served
// from another loopback port, it tries a height map and a job sent as "simple" requests
// (fetch in no-cors mode, form posts), a JSON job and a DELETE through CORS, and framing the
// page; a page under another host name (DNS rebinding: Chromium maps rebind.test to
// 127.0.0.1, page.test.mjs) tries the API as its own origin. Each fails, and the server's
// lists show nothing stored or deleted. Then a report, rendered under the policy it is
// served with, looks as it does with none.
import assert from "node:assert/strict";
import http from "node:http";

import { base, step } from "../lib.mjs";

/** A height map the server would store: a text matrix of heights in m, pixel 1 um. */
const MATRIX = Array.from({ length: 16 }, (_, y) => Array.from({ length: 16 }, (_, x) =>
  (1e-7 * Math.sin(0.9 * x) * Math.cos(0.7 * y)).toExponential(6)).join(" ")).join("\n") + "\n";

/** The server's lists, read as a client without Origin reads them. */
async function stored() {
  const list = async (path) => (await (await fetch(base + path)).json()).map((r) => r.id).sort();
  return { jobs: await list("/api/v1/jobs"), surfaces: await list("/api/v1/surfaces") };
}

/** A static server on another loopback port: the other site's page. Resolves to it. */
async function otherSite() {
  const html = `<!doctype html><title>another site</title><h1>another site</h1>
<iframe name="victim" src="${base}/" width="800" height="400"></iframe>
<iframe name="sink"></iframe>`;
  const server = http.createServer((req, res) => {
    res.writeHead(200, { "content-type": "text/html; charset=utf-8" });
    res.end(html);
  });
  await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
  return server;
}

/** What the other site's page tries; the outcome of each fetch. */
const attack = ([target, matrix, victim]) => (async () => {
  const tried = {};
  const attempt = async (name, url, init) => {
    try { tried[name] = `sent (${(await fetch(url, init)).type})`; } catch (e) { tried[name] = `failed: ${e.name}`; }
  };
  const scene = JSON.stringify({ preset: "dalmau2018-316l", overrides: { name: "from another site" } });
  await attempt("no-cors text/plain map", `${target}/api/v1/surfaces?pixel_um=1`, { method: "POST", mode: "no-cors", headers: { "Content-Type": "text/plain" }, body: matrix });
  await attempt("no-cors job", `${target}/api/v1/jobs`, { method: "POST", mode: "no-cors", headers: { "Content-Type": "application/json" }, body: scene });
  await attempt("cors JSON job", `${target}/api/v1/jobs`, { method: "POST", headers: { "Content-Type": "application/json" }, body: scene });
  await attempt("cors DELETE", `${target}/api/v1/jobs/${victim}`, { method: "DELETE" });
  // Form posts: a text/plain form's body is `name=value`; the map's last line, `#=`, is a comment.
  const post = (action, name) => new Promise((resolve) => {
    const form = Object.assign(document.createElement("form"), { method: "post", action, enctype: "text/plain", target: "sink" });
    form.append(Object.assign(document.createElement("input"), { type: "hidden", name, value: "" }));
    document.body.append(form);
    document.querySelector("iframe[name=sink]").addEventListener("load", resolve, { once: true });
    setTimeout(resolve, 5000);
    form.submit();
  });
  await post(`${target}/api/v1/surfaces?pixel_um=1`, matrix + "#");
  await post(`${target}/api/v1/jobs`, scene.slice(0, -1) + ', "pad": "');
  return tried;
})();

/** A request to the server with another `Host` header, as a rebound name sends it: its status. */
const withHost = (method, path, host) => new Promise((resolve, reject) => {
  const url = new URL(base);
  const request = http.request({ host: url.hostname, port: url.port, method, path, headers: { host, "content-type": "application/json" } }, (res) => { res.resume(); resolve(res.statusCode); });
  request.on("error", reject);
  request.end(method === "POST" ? JSON.stringify({ preset: "dalmau2018-316l" }) : undefined);
});

async function anotherOrigin(page, victim) {
  step("a page on another port: maps and jobs as simple requests, CORS requests, form posts, framing the page; all refused");
  const site = await otherSite();
  const attacker = await page.context().newPage();
  // The changes the page asked for, each with its answer: the status, or why the browser
  // kept the answer from the page (a no-cors fetch's 403 is blocked by its
  // Cross-Origin-Resource-Policy: the server's log shows the 403; a CORS request fails at
  // its preflight, which the server does not allow, and is never sent).
  const sent = [];
  const changes = (r) => r.url().startsWith(base) && r.method() !== "GET";
  attacker.on("request", (r) => { if (changes(r)) sent.push(r); });
  const answer = async (r) => {
    const response = await r.response();
    return `${r.method()} ${new URL(r.url()).pathname} ${response ? response.status() : r.failure()?.errorText}`;
  };
  const console_ = [];
  attacker.on("console", (m) => console_.push(m.text()));
  try {
    await attacker.goto(`http://127.0.0.1:${site.address().port}/`);
    const tried = await attacker.evaluate(attack, [base, MATRIX, victim]);
    console.log(`   fetches: ${JSON.stringify(tried)}`);
    const answers = await Promise.all(sent.map(answer));
    console.log(`   answered: ${JSON.stringify(answers)}`);
    for (const [name, outcome] of Object.entries(tried)) assert.match(outcome, /^failed/, `${name}: ${outcome}`);
    const blocked = "net::ERR_BLOCKED_BY_RESPONSE.NotSameOrigin";
    assert.deepEqual(answers, [
      `POST /api/v1/surfaces ${blocked}`, `POST /api/v1/jobs ${blocked}`,
      "POST /api/v1/jobs net::ERR_FAILED", `DELETE /api/v1/jobs/${victim} net::ERR_FAILED`,
      "POST /api/v1/surfaces 403", "POST /api/v1/jobs 403",
    ]);
    // The framed page: refused by frame-ancestors, so its document never loads.
    await attacker.waitForTimeout(1000);
    const framed = attacker.frames().find((f) => f.name() === "victim");
    const ready = await framed.evaluate(() => document.body && document.body.dataset.ready).catch((e) => `unreadable: ${e.message}`);
    console.log(`   the framed page: ${framed.url()}, ready=${ready}; console: ${JSON.stringify(console_.filter((t) => /frame/i.test(t)))}`);
    assert.notEqual(ready, "true", "the page rendered in another site's frame");
    assert.ok(console_.some((t) => t.includes("frame-ancestors")), "no frame-ancestors refusal in the console");
  } finally {
    await attacker.close();
    site.close();
  }
}

async function rebound(page) {
  step("a page under another host name (DNS rebinding): the page and the API refused (421)");
  const port = new URL(base).port;
  const other = await page.context().newPage();
  try {
    const response = await other.goto(`http://rebind.test:${port}/`);
    assert.equal(response.status(), 421);
    const statuses = await other.evaluate(async () => {
      const scene = JSON.stringify({ preset: "dalmau2018-316l" });
      const post = await fetch("/api/v1/jobs", { method: "POST", headers: { "Content-Type": "application/json" }, body: scene });
      const list = await fetch("/api/v1/jobs");
      return [post.status, list.status, (await list.json()).error];
    });
    console.log(`   in the browser: ${JSON.stringify(statuses)}`);
    assert.deepEqual(statuses.slice(0, 2), [421, 421]);
    assert.match(statuses[2], /--allowed-host/);
  } finally {
    await other.close();
  }
  const direct = [await withHost("POST", "/api/v1/jobs", `rebind.test:${port}`), await withHost("GET", "/healthz", "rebind.test")];
  console.log(`   from node with Host rebind.test: ${JSON.stringify(direct)}`);
  assert.deepEqual(direct, [421, 421]);
}

async function reportPolicy(page, job) {
  step("a report under the policy it is served with looks as it does without one");
  const response = await fetch(`${base}/api/v1/jobs/${job}/report`);
  assert.equal(response.status, 200);
  const policy = response.headers.get("content-security-policy");
  assert.match(policy, /sandbox/);
  const html = await response.text();
  const view = await page.context().newPage();
  const refused = [];
  view.on("console", (m) => { if (/Content Security Policy/i.test(m.text())) refused.push(m.text()); });
  try {
    const shot = async (headers) => {
      await view.route(`${base}/report-view`, (route) => route.fulfill({ status: 200, contentType: "text/html; charset=utf-8", headers, body: html }));
      await view.goto(`${base}/report-view`);
      await view.unroute(`${base}/report-view`);
      return view.screenshot({ fullPage: true });
    };
    const plain = await shot({});
    const secured = await shot({ "content-security-policy": policy });
    assert.deepEqual(refused, [], "the report's policy refused some of it");
    assert.ok(plain.equals(secured), "the report renders differently under its policy");
  } finally {
    await view.close();
  }
}

export async function origin(page) {
  const before = await stored();
  assert.ok(before.jobs.length > 0, "no job to attack");
  const victim = before.jobs[0];
  await anotherOrigin(page, victim);
  await rebound(page);
  assert.deepEqual(await stored(), before, "something was stored or deleted");
  await reportPolicy(page, (await (await fetch(`${base}/api/v1/jobs?status=succeeded`)).json())[0].id);
}
