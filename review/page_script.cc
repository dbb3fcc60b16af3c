#include "review/page_script.h"

namespace birotor {

const char* const kReviewPageScript = R"JS(
var graphs = [], syncing = false, errors = [], fitAll = false;
window.addEventListener('error', function (e) { errors.push(String(e.message)); });
var EVENT_COLORS = {'fault': '#d62728', 'true fault': '#8b0000', 'mismatch': '#1f3fbf', 'fallback': '#ff7f0e',
                    'reset': '#9467bd', 'lost': '#000000'};
function syncRange(me, initial) {
  if (initial || syncing) return;
  syncing = true;
  var range = me.xAxisRange();
  graphs.forEach(function (g) {
    if (g === me) return;
    var r = g.xAxisRange();
    if (r[0] !== range[0] || r[1] !== range[1]) g.updateOptions({dateWindow: range});
  });
  syncing = false;
}
function laneTicker(names) {
  return function () { return names.map(function (n, i) { return {v: i + 0.4, label: n}; }); };
}
// A vertical line per event (faults red, the true fault dark red dashed,
// fallbacks orange, resets purple, the loss black), labelled at the top.
function drawEvents(ctx, area, g) {
  REVIEW.events.forEach(function (e, i) {
    var x = g.toDomXCoord(e.t);
    if (x < area.x || x > area.x + area.w) return;
    ctx.save();
    ctx.strokeStyle = ctx.fillStyle = EVENT_COLORS[e.kind] || '#444';
    ctx.lineWidth = e.kind === 'lost' ? 2.5 : 1.5;
    ctx.setLineDash(e.kind === 'true fault' ? [5, 3] : []);
    ctx.beginPath(); ctx.moveTo(x, area.y); ctx.lineTo(x, area.y + area.h); ctx.stroke();
    ctx.font = '11px sans-serif';
    ctx.fillText(e.label, x + 3, area.y + 11 + 12 * (i % 3));
    ctx.restore();
  });
}
// "NaN" in the page's rows (a bucket whose samples were all NaN or infinite)
// becomes NaN, which dygraphs draws as a gap.
function withGaps(rows, bands) {
  rows.forEach(function (row) {
    for (var i = 1; i < row.length; ++i) {
      if (row[i] === 'NaN') row[i] = bands ? [NaN, NaN, NaN] : NaN;
    }
  });
  return rows;
}
function addChart(c) {
  var box = document.createElement('div');
  box.className = 'chart';
  box.innerHTML = '<h3></h3><div class=plot></div><p class=note></p>';
  box.querySelector('h3').textContent = c.title;
  box.querySelector('.note').textContent = c.samples + ' log samples, drawn as ' + c.rows +
      ' rows (min and max per bucket)' + (c.yrange ? '; y axis fits 99 % of the values after convergence (' +
      c.outside + ' outside: "fit every value")' : '');
  document.getElementById('charts').appendChild(box);
  var options = {labels: c.labels, ylabel: c.ylabel, xlabel: 't [s]', customBars: c.bands,
                 connectSeparatedPoints: true, legend: 'always', labelsSeparateLines: false,
                 drawCallback: syncRange, underlayCallback: drawEvents, animatedZooms: false, series: {},
                 maxNumberWidth: 10, digitsAfterDecimal: 4};
  if (c.colors.length) options.colors = c.colors;
  c.dashed.forEach(function (label) { options.series[label] = {strokePattern: [7, 4], strokeWidth: 1.6}; });
  if (c.yrange) options.valueRange = c.yrange;
  if (c.lanes) {
    options.stepPlot = true;
    options.fillAlpha = 0.7;
    options.valueRange = [-0.2, c.labels.length - 1 + 0.2];
    options.axes = {y: {ticker: laneTicker(c.labels.slice(1)), axisLabelWidth: 140}};
    options.legend = 'onmouseover';
  }
  var g = new Dygraph(box.querySelector('.plot'), withGaps(c.data, c.bands), options);
  g.reviewChart = c;
  graphs.push(g);
  return box;
}
// The x-z path (equal scales) with a dot where each event happened.
function drawPath() {
  var p = REVIEW.path;
  if (!p.lines.length) return null;
  var box = document.createElement('div');
  box.className = 'chart';
  box.innerHTML = '<h3>Path in the x-z plane (equal scales; dots: events)</h3><canvas width=900 height=300>' +
      '</canvas><p class=note></p>';
  var canvas = box.querySelector('canvas'), ctx = canvas.getContext('2d');
  var xs = [], zs = [];
  p.lines.forEach(function (l) { l.points.forEach(function (q) {
    if (q[0] !== null && q[1] !== null) { xs.push(q[0]); zs.push(q[1]); } }); });
  var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs);
  var z0 = Math.min.apply(null, zs), z1 = Math.max.apply(null, zs);
  var pad = 40, span = Math.max(x1 - x0, z1 - z0, 0.02);
  var scale = Math.min((canvas.width - 2 * pad) / Math.max(x1 - x0, span / 4),
                       (canvas.height - 2 * pad) / Math.max(z1 - z0, span / 4));
  function X(x) { return pad + (x - x0) * scale; }
  function Z(z) { return canvas.height - pad - (z - z0) * scale; }
  p.lines.forEach(function (l, i) {
    ctx.strokeStyle = l.color; ctx.lineWidth = 1.5; ctx.setLineDash(l.dashed ? [7, 4] : []);
    ctx.beginPath();
    l.points.forEach(function (q, n) { if (q[0] !== null && q[1] !== null) ctx[n ? 'lineTo' : 'moveTo'](X(q[0]), Z(q[1])); });
    ctx.stroke();
    ctx.setLineDash([]); ctx.fillStyle = l.color; ctx.font = '12px sans-serif';
    ctx.fillText(l.label, canvas.width - 160, 16 + 14 * i);
  });
  p.marks.forEach(function (m) {
    if (m.x === null || m.z === null) return;
    ctx.fillStyle = EVENT_COLORS[m.kind] || '#444';
    ctx.beginPath(); ctx.arc(X(m.x), Z(m.z), 4, 0, 2 * Math.PI); ctx.fill();
    ctx.fillText(m.label, X(m.x) + 6, Z(m.z) - 6);
  });
  ctx.fillStyle = '#444';
  ctx.fillText('x ' + x0.toFixed(2) + ' .. ' + x1.toFixed(2) + ' m, z ' + z0.toFixed(2) + ' .. ' + z1.toFixed(2) +
               ' m', pad, canvas.height - 8);
  box.querySelector('.note').textContent = p.lines.map(function (l) {
    return l.label + ': ' + l.points.length + ' points'; }).join(', ');
  return box;
}
REVIEW.charts.forEach(function (c) {
  var box = addChart(c);
  if (c.id === 'attitude') { var path = drawPath(); if (path) document.getElementById('charts').appendChild(path); }
});
if (!REVIEW.charts.some(function (c) { return c.id === 'attitude'; })) {
  var path = drawPath();
  if (path) document.getElementById('charts').appendChild(path);
}
document.getElementById('reset').onclick = function () {
  graphs.forEach(function (g) { g.updateOptions({dateWindow: null}); });
};
document.getElementById('fit-all').onclick = function () {
  fitAll = !fitAll;
  graphs.forEach(function (g) {
    if (g.reviewChart.yrange) g.updateOptions({valueRange: fitAll ? null : g.reviewChart.yrange});
  });
};
var headline = {};
document.querySelectorAll('#headline tr').forEach(function (tr) {
  var cells = tr.querySelectorAll('td');
  if (cells.length) headline[tr.querySelector('th').textContent] = Array.prototype.map.call(cells,
      function (td) { return td.textContent; });
});
document.getElementById('review-summary').textContent = JSON.stringify({
  charts: graphs.map(function (g) {
    return {id: g.reviewChart.id, samples: g.reviewChart.samples, rows: g.numRows()};
  }),
  path: document.querySelectorAll('canvas[width="900"]').length,
  headline: headline,
  headline_bottom_px: document.getElementById('headline').getBoundingClientRect().bottom,
  first_chart_top_px: graphs.length ? graphs[0].graphDiv.getBoundingClientRect().top : -1,
  errors: errors});
)JS";

const char* const kReviewPageStyle = R"CSS(
body { font-family: sans-serif; margin: 0.6em 1.5em; }
h1 { font-size: 1.3em; margin: 0.2em 0; }
.chart .plot { width: 100%; height: 260px; }
.chart h3 { margin: 1em 0 0.2em 0; font-size: 1em; }
.note { color: #666; font-size: 0.8em; margin: 0.2em 0; }
table { border-collapse: collapse; margin: 0.5em 0; }
td, th { border: 1px solid #ccc; padding: 2px 8px; text-align: right; }
td:first-child, #headline td, #headline th { text-align: left; }
#headline { font-size: 1.05em; }
#headline td.alarm, tr.alarm td { background: #fdd; font-weight: bold; }
#missing { color: #555; font-size: 0.9em; margin: 0.3em 0; }
#review-summary { display: none; }
)CSS";

}  // namespace birotor
