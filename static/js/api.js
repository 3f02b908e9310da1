// The service's API (openapi.yaml), with the token the user gave, if any.
import { $, saveBlob } from "./dom.js";
import { TOKEN } from "./ids.js";

/** The Authorization header for the token in this tab's session storage, if any. */
export function authHeaders() {
  const token = sessionStorage.getItem("tribosim-token");
  return token ? { Authorization: "Bearer " + token } : {};
}

/**
 * Calls the API: { ok, status, body, link } with the body parsed as JSON (or { error: text })
 * and a list's Link header (its next page). A 401 shows the token form.
 */
export async function api(path, options = {}) {
  const response = await fetch(path, { ...options, headers: { ...authHeaders(), ...(options.headers || {}) } });
  if (response.status === 401) {
    $(TOKEN.form).hidden = false;
  }
  let body = null;
  if (response.status !== 204) {
    const text = await response.text();
    try { body = text ? JSON.parse(text) : null; } catch { body = { error: text }; }
  }
  return { ok: response.ok, status: response.status, body, link: response.headers.get("Link") };
}

/** Posts a JSON body. */
export const postJson = (path, body) =>
  api(path, { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });

/** A refusal in words: the server's error and each field (or column) it names. */
export function errorText(r) {
  const body = r.body || {};
  const fields = (body.fields || []).filter((f) => f.message && !(body.error || "").includes(f.message));
  return (body.error || `the server answered ${r.status}`) + (fields.length ? " — " + fields.map((f) => `${f.path || "(table)"}: ${f.message}`).join("; ") : "");
}

/** Downloads `path` through fetch, so that a token is sent; the file keeps the server's
 * name (its Content-Disposition), else `fallback`. */
export async function download(path, fallback) {
  const response = await fetch(path, { headers: authHeaders() });
  if (!response.ok) { alert("Download failed: " + response.status); return; }
  const disposition = response.headers.get("Content-Disposition") || "";
  const name = (disposition.match(/filename="?([^";]+)"?/) || [])[1] || fallback;
  saveBlob(await response.blob(), name);
}
