// The view shown, in the address's hash, so that a run, a comparison or a study can be
// bookmarked, shared and reopened: #run=<id>, #compare=<id>,<id>,..., #study=<id>.

/** Records the view shown (without a history entry per view). */
export function setHash(kind, value) {
  const hash = `#${kind}=${value}`;
  if (location.hash !== hash) history.replaceState(null, "", hash);
}

/** The view the address asks for: { kind, value }, or null. */
export function readHash() {
  const match = /^#(run|compare|study)=([0-9a-f,-]+)$/i.exec(location.hash);
  return match ? { kind: match[1], value: match[2] } : null;
}
