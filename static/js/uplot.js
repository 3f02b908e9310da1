// uPlot (MIT, static/vendor/uplot/), loaded by index.html as the vendored IIFE file before
// the modules run: the one place that reads its global, so that the modules import it.
export default globalThis.uPlot;
