// Line charts drawn in the browser on a canvas, for data that streams (a job's particles): axes
// with 1-2-5 ticks, one line per series, a legend. The colours are viz's chart palette
// (viz/src/line_chart.cc), so a chart here matches `dlmfd chart`.
"use strict";

const charts = {};
charts.palette = ["#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000"];

charts.ticks = function (lo, hi, count) {
  if (!(hi > lo)) { const d = Math.abs(lo) || 1; lo -= d / 2; hi += d / 2; }
  const raw = (hi - lo) / Math.max(1, count);
  const mag = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((m) => m * mag).find((s) => s >= raw) || 10 * mag;
  const out = [];
  for (let t = Math.ceil(lo / step) * step; t <= hi + step * 1e-9; t += step) out.push(Math.abs(t) < step * 1e-9 ? 0 : t);
  return { lo: Math.min(lo, out[0]), hi: Math.max(hi, out[out.length - 1]), ticks: out };
};

charts.label = (v) => {
  const a = Math.abs(v);
  return a !== 0 && (a < 1e-3 || a >= 1e5) ? v.toExponential(1) : String(Number(v.toPrecision(4)));
};

// series: [{name, x: [], y: []}]; options: {title, xlabel, ylabel}.
charts.draw = function (canvas, series, options) {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth || 600, height = canvas.clientHeight || 280;
  canvas.width = Math.round(width * ratio);
  canvas.height = Math.round(height * ratio);
  const g = canvas.getContext("2d");
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  g.fillStyle = "#fff";
  g.fillRect(0, 0, width, height);
  g.font = "12px 'DejaVu Sans', sans-serif";
  let xmin = Infinity, xmax = -Infinity, ymin = Infinity, ymax = -Infinity;
  for (const s of series) {
    for (let k = 0; k < s.x.length; ++k) {
      const x = s.x[k], y = s.y[k];
      if (x === null || y === null || !isFinite(x) || !isFinite(y)) continue;
      xmin = Math.min(xmin, x); xmax = Math.max(xmax, x); ymin = Math.min(ymin, y); ymax = Math.max(ymax, y);
    }
  }
  const left = 64, right = 130, top = 26, bottom = 40;
  g.fillStyle = "#1d2330";
  g.fillText(options.title || "", left, 16);
  if (!isFinite(xmin)) {
    g.fillStyle = "#6b7385";
    g.fillText("no particle data yet", left + 10, top + 30);
    return;
  }
  const xs = charts.ticks(xmin, xmax, 6), ys = charts.ticks(ymin, ymax, 5);
  const pw = width - left - right, ph = height - top - bottom;
  const px = (x) => left + (x - xs.lo) / (xs.hi - xs.lo) * pw;
  const py = (y) => top + ph - (y - ys.lo) / (ys.hi - ys.lo) * ph;
  g.strokeStyle = "#e3e6ec";
  g.lineWidth = 1;
  g.textAlign = "center";
  g.fillStyle = "#4a5060";
  for (const t of xs.ticks) { g.beginPath(); g.moveTo(px(t), top); g.lineTo(px(t), top + ph); g.stroke(); g.fillText(charts.label(t), px(t), top + ph + 15); }
  g.textAlign = "right";
  for (const t of ys.ticks) { g.beginPath(); g.moveTo(left, py(t)); g.lineTo(left + pw, py(t)); g.stroke(); g.fillText(charts.label(t), left - 6, py(t) + 4); }
  g.strokeStyle = "#1d2330";
  g.strokeRect(left, top, pw, ph);
  g.textAlign = "center";
  g.fillText(options.xlabel || "", left + pw / 2, height - 6);
  g.save(); g.translate(14, top + ph / 2); g.rotate(-Math.PI / 2); g.fillText(options.ylabel || "", 0, 0); g.restore();
  g.textAlign = "left";
  series.forEach((s, i) => {
    const colour = charts.palette[i % charts.palette.length];
    g.strokeStyle = colour;
    g.lineWidth = 1.6;
    g.setLineDash(i >= charts.palette.length ? [6, 3] : []);
    g.beginPath();
    let pen = false;
    for (let k = 0; k < s.x.length; ++k) {
      const x = s.x[k], y = s.y[k];
      if (x === null || y === null || !isFinite(x) || !isFinite(y)) { pen = false; continue; }
      if (pen) g.lineTo(px(x), py(y)); else g.moveTo(px(x), py(y));
      pen = true;
    }
    g.stroke();
    g.setLineDash([]);
    g.fillStyle = colour;
    g.fillRect(left + pw + 12, top + 6 + i * 16, 14, 3);
    g.fillStyle = "#1d2330";
    g.fillText(s.name, left + pw + 30, top + 11 + i * 16);
  });
};
