// Small helpers on the document, shared by the modules.

/** The element with this id. */
export const $ = (id) => document.getElementById(id);

/** A plain button that calls `onClick`. */
export function button(text, onClick) {
  const b = document.createElement("button");
  b.type = "button";
  b.textContent = text;
  b.addEventListener("click", onClick);
  return b;
}

/** Brings a panel's top into view when it is not (on a phone the panels are below the list). */
export function reveal(panel, focus) {
  const top = panel.getBoundingClientRect().top;
  if (top < 0 || top > window.innerHeight * 0.6) panel.scrollIntoView({ block: "start" });
  if (focus) panel.focus({ preventScroll: true });
}

/** Saves a blob under a name, as a download. */
export function saveBlob(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 60000);
}

/** Resolves after `ms` milliseconds. */
export const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
