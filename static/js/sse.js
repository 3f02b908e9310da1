// Server-sent events read from a fetch response (fetch rather than EventSource, so that
// the token header goes along).

// One event's lines: its type ("message" unless named), id and data joined, as JSON.
function parseEvent(block) {
  let type = "message", eventId = null;
  const data = [];
  for (const line of block.split("\n")) {
    if (line.startsWith(":")) continue;
    const colon = line.indexOf(":");
    const field = colon < 0 ? line : line.slice(0, colon);
    const val = colon < 0 ? "" : line.slice(colon + 1).replace(/^ /, "");
    if (field === "event") type = val;
    else if (field === "data") data.push(val);
    else if (field === "id") eventId = val;
  }
  return data.length ? { type, id: eventId, payload: JSON.parse(data.join("\n")) } : null;
}

/**
 * Calls `handle({ type, id, payload })` for each event with data, in order, awaiting each;
 * stops when it returns false. True when the stream ended, false when `handle` stopped it.
 */
export async function readEvents(response, handle) {
  const reader = response.body.pipeThrough(new TextDecoderStream()).getReader();
  let buffer = "";
  for (;;) {
    const { value, done } = await reader.read();
    if (done) return true;
    buffer += value.replace(/\r\n?/g, "\n");
    let cut;
    while ((cut = buffer.indexOf("\n\n")) >= 0) {
      const event = parseEvent(buffer.slice(0, cut));
      buffer = buffer.slice(cut + 2);
      if (event && (await handle(event)) === false) return false;
    }
  }
}
