// What the SVG figures (the pressure maps, the exported line charts) share: round ticks,
// escaping and the font.

/** About `count` round ticks (1, 2 or 5 times a power of ten) from lo to hi. */
export function niceTicks(lo, hi, count) {
  const span = hi - lo || 1;
  const step0 = span / count;
  const mag = 10 ** Math.floor(Math.log10(step0));
  const step = [1, 2, 5, 10].map((m) => m * mag).find((s) => s >= step0);
  const ticks = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) ticks.push(+v.toPrecision(12));
  return ticks;
}

/** Text escaped for SVG markup. */
export const esc = (s) => String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");

export const FONT_FAMILY = 'font-family="system-ui, -apple-system, Segoe UI, sans-serif" fill="#1b1f24"';
export const FONT = FONT_FAMILY + ' font-size="12"';
