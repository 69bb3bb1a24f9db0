// axiscal workbench: interactive plots (uPlot, vendored), the CSRF header for htmx requests and
// every failed htmx request shown where the user acted.
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
    var width = fitWidth(el);
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

  // The chart takes its container's width (a phone's 412 px, a folded section's parent when
  // it is closed), at most 1100 px; it is drawn again at the new width when the window
  // changes or a folded section opens.
  function fitWidth(el) {
    var box = el;
    while (box && !box.clientWidth) { box = box.parentElement; }
    var w = box ? box.clientWidth : 900;
    return Math.max(240, Math.min(w, 1100));
  }

  function refit() {
    document.querySelectorAll(".uplot-chart").forEach(function (el) {
      if (el.uplot && el.clientWidth) {
        var w = fitWidth(el);
        if (Math.abs(w - el.uplot.width) > 2) { el.uplot.setSize({ width: w, height: 380 }); }
      }
    });
  }
  var refitTimer = null;
  window.addEventListener("resize", function () {
    clearTimeout(refitTimer);
    refitTimer = setTimeout(refit, 100);
  });
  document.addEventListener("toggle", function () { refit(); }, true);

  function init(root) {
    (root || document).querySelectorAll(".uplot-chart").forEach(function (el) {
      if (!el.dataset.drawn) { el.dataset.drawn = "1"; chart(el); }
    });
  }

  // Errors are never silent (issue 40). htmx swaps nothing on a 4xx/5xx answer; the answer
  // (the workbench's error page, or a fragment) is read for its words and shown at the top of
  // the form the user sent, which keeps everything typed. An ended session (401) keeps what was
  // typed in this tab (sessionStorage) and goes to the login, which comes back here; the page
  // then fills the form in again.
  var KEPT = "axiscal-kept:";
  var WORDS = { 401: "Your session has ended: log in again.",
                403: "Refused (403).", 404: "Not found (404).",
                413: "Too large for the workbench (413).",
                422: "The form could not be read (422).", 429: "Too many requests (429).",
                500: "The server could not do it (500): its log has the details." };

  function wordsOf(xhr) {
    var found = "";
    try {
      var doc = new DOMParser().parseFromString(xhr.responseText || "", "text/html");
      var el = doc.querySelector('[role="alert"]');
      found = el ? el.textContent.replace(/\s+/g, " ").trim() : "";
    } catch (err) { found = ""; }
    var head = WORDS[xhr.status] || ("The request failed (HTTP " + xhr.status + ").");
    return found ? head.replace(/\.$/, ":") + " " + found : head;
  }

  function show(elt, text) {
    var form = elt && elt.closest && elt.closest("form");
    var box = form ? form.querySelector(":scope > .request-error")
                   : (elt && elt.nextElementSibling);
    if (!box || !box.classList.contains("request-error")) {
      box = document.createElement("div");
      box.className = "error request-error";
      box.setAttribute("role", "alert");
      if (form) { form.insertBefore(box, form.firstChild); }
      else if (elt && elt.parentNode) { elt.parentNode.insertBefore(box, elt.nextSibling); }
      else { document.querySelector("main").prepend(box); }
    }
    box.textContent = text;
    box.scrollIntoView({ block: "nearest" });
  }

  function fields(form) {
    var out = {};
    form.querySelectorAll("input, textarea, select").forEach(function (el) {
      if (!el.name || el.type === "hidden" || el.type === "file" || el.type === "password" ||
          el.type === "submit") { return; }
      if ((el.type === "checkbox" || el.type === "radio") && !el.checked) { return; }
      out[el.name] = el.value;
    });
    return out;
  }

  function keep(elt) {
    var form = elt && elt.closest && elt.closest("form");
    if (!form) { return; }
    try {
      sessionStorage.setItem(KEPT + location.pathname, JSON.stringify(
        { form: form.id || "", values: fields(form) }));
    } catch (err) { /* storage refused: the login still comes back here */ }
  }

  function restore() {
    var raw = null;
    try { raw = sessionStorage.getItem(KEPT + location.pathname); } catch (err) { raw = null; }
    if (!raw) { return; }
    sessionStorage.removeItem(KEPT + location.pathname);
    var kept = JSON.parse(raw);
    var form = kept.form ? document.getElementById(kept.form) : document.querySelector("main form");
    if (!form) { return; }
    Object.keys(kept.values).forEach(function (name) {
      form.querySelectorAll('[name="' + name.replace(/"/g, "") + '"]').forEach(function (el) {
        if (el.type === "checkbox" || el.type === "radio") { el.checked = el.value === kept.values[name]; }
        else { el.value = kept.values[name]; }
      });
    });
    var note = document.createElement("div");
    note.className = "card warning request-error";
    note.setAttribute("role", "status");
    note.id = "restored";
    note.textContent = "You were logged in again: what you had typed here is filled in again. " +
      "Send it again when it is right.";
    form.insertBefore(note, form.firstChild);
    form.scrollIntoView({ block: "start" });
  }

  document.addEventListener("htmx:responseError", function (e) {
    var xhr = e.detail.xhr;
    if (xhr.status === 401) {
      keep(e.detail.elt);
      show(e.detail.elt, WORDS[401] + " Taking you to the login; what you typed is kept.");
      location.assign("/login?expired=1&next=" +
                      encodeURIComponent(location.pathname + location.search));
      return;
    }
    show(e.detail.elt, wordsOf(xhr));
  });
  document.addEventListener("htmx:sendError", function (e) {
    show(e.detail.elt, "The workbench did not answer (stopped, or the network is down): " +
         "nothing was sent; what you typed is still here.");
  });
  document.addEventListener("htmx:beforeRequest", function (e) {
    var form = e.detail.elt && e.detail.elt.closest && e.detail.elt.closest("form");
    var box = form && form.querySelector(":scope > .request-error");
    if (box) { box.remove(); }
  });

  // A signed-in page the browser brings back from its back/forward cache (which may keep even
  // a "Cache-Control: no-store" page) is asked for again: after log-out, Back shows the login.
  window.addEventListener("pageshow", function (e) {
    if (e.persisted && document.querySelector("header .who form")) { location.reload(); }
  });

  document.addEventListener("DOMContentLoaded", function () { init(document); restore(); });
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
