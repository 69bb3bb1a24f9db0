// axiscal workbench: interactive plots (uPlot, vendored) and the CSRF header for htmx requests.
// Every element with class "uplot-chart" names a <script type="application/json"> holding
// {"title", "x_label", "y_label", "x": [...], "x_time" (optional: x are dates, seconds since 1970 UTC),
//  "series": [{"label", "values", "color", "dash", "points", "size" (of the points, px), "thin" (a 1 px line),
//   "legend" (false: no legend row)}]}.
(function () {
  "use strict";

  function chart(el) {
    var spec = JSON.parse(document.getElementById(el.dataset.source).textContent);
    var series = [{ label: spec.x_label }];
    var data = [spec.x];
    spec.series.forEach(function (s) {
      series.push({
        label: s.label,
        stroke: s.color || "#1f77b4",
        width: s.points ? 0 : (s.thin ? 1 : 1.5),
        dash: s.dash ? [6, 4] : undefined,
        points: { show: !!s.points, size: s.size || 5, fill: s.color },
        spanGaps: true,
        value: function (u, v) { return v == null ? "—" : v.toFixed(3); }
      });
      data.push(s.values);
    });
    var width = Math.max(320, Math.min(el.clientWidth || 900, 1100));
    el.uplot = new uPlot({     // kept on the element: the browser tests read its scales
      title: spec.title,
      width: width,
      height: 380,
      series: series,
      scales: { x: spec.x_time ? { time: true, range: timeRange(spec.x) } : { time: false } },
      tzDate: function (ts) { return uPlot.tzDate(new Date(ts * 1e3), "Etc/UTC"); },
      axes: [{ label: spec.x_label }, { label: spec.y_label }],
      cursor: { drag: { x: true, y: true } }
    }, data, el);
    // A series with "legend": false (every run's readings after the first) has no legend row.
    var rows = el.querySelectorAll(".u-legend .u-series");
    spec.series.forEach(function (s, i) {
      if (s.legend === false && rows[i + 1]) { rows[i + 1].style.display = "none"; }
    });
  }

  // A date axis (x in seconds since 1970, UTC; "x_time": true) keeps a month in view when
  // every point shares one date, instead of uPlot's span of decades.
  // uPlot asks for the whole data (auto range: answered with the data's own span, padded) or
  // for a zoom (answered as asked).
  function timeRange(x) {
    var first = Math.min.apply(null, x), last = Math.max.apply(null, x);
    var pad = last - first < 86400 ? 15 * 86400 : 0.03 * (last - first);
    return function (u, lo, hi) {
      return lo <= first && hi >= last ? [first - pad, last + pad] : [lo, hi];
    };
  }

  function init(root) {
    (root || document).querySelectorAll(".uplot-chart").forEach(function (el) {
      if (!el.dataset.drawn) { el.dataset.drawn = "1"; chart(el); }
    });
  }

  document.addEventListener("DOMContentLoaded", function () { init(document); });
  // a form with data-confirm (merging machines or axes: every test moves) asks first
  document.addEventListener("submit", function (e) {
    var form = e.target, words = form && form.dataset ? form.dataset.confirm : null;
    if (words && !window.confirm(words)) { e.preventDefault(); e.stopImmediatePropagation(); }
  }, true);
  document.addEventListener("htmx:afterSwap", function (e) { init(e.target); });
  document.addEventListener("htmx:configRequest", function (e) {
    var meta = document.querySelector('meta[name="csrf-token"]');
    if (meta) { e.detail.headers["X-CSRF-Token"] = meta.content; }
  });
})();
