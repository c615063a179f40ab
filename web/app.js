// The jumping-cylinder page: controls, the run (jc_web_simulate, the jumpcyl
// library compiled to WebAssembly), the animation to scale, live graphs, the
// event table, the setup in the URL and downloads. docs/web.md.
'use strict';
(() => {
const $ = (sel) => document.querySelector(sel);
const tid = (id) => document.querySelector(`[data-testid="${id}"]`);
const DEG = Math.PI / 180;
const PRESETS = ['paper', 'hoop', 'rocking-hoop', 'disc'];
// Samples per run for the animation and graphs: sample-dt = t_end / this
// (at least 1 ms); events are always sampled too.
const TARGET_SAMPLES = 1200;
const GRAPH_WINDOW_S = 4; // graphs of longer runs show this much around the current time

// The controls: one per row of the library's parameter table (jc_web_params:
// what `jumpcyl params --json` prints), made at start (makeControls). key:
// the tool's option name (request and URL key); a number's value is in the
// unit shown, and the request gives it with that unit ("10cm"), so that it
// is exactly the command line's text; a name-valued parameter is a select.
// The page shows lengths the table gives in metres in centimetres (a
// table-top ramp), every other value in the table's unit.
const PAGE_UNIT = { m: 'cm' };
let CONTROLS = [];
let BY_KEY = {};
const rodPart = (s) => s.body.parts.find((p) => p.kind === 'rod') || s.body.parts.find((p) => p.kind === 'point');
// A slider's step: a round number, about a hundredth of its span.
const niceStep = (span) => 10 ** Math.floor(Math.log10(span / 100));
function makeControls(table) {
  CONTROLS = table.params.map((p) => {
    const label = p.label.charAt(0).toUpperCase() + p.label.slice(1);
    if (p.choices) {
      return { key: p.name, name: p.name, label, help: p.help, choices: p.choices,
        defaults: p.defaults, sets: [] };
    }
    const unit = PAGE_UNIT[p.unit] || p.unit;
    const u = p.units.find((x) => x.name === unit);
    const perSi = p.quantity === 'angle' ? 180 / Math.PI : 1 / (u ? u.si : 1); // display value = SI * perSi
    const lo = +(p.typical_min * perSi).toPrecision(12), hi = +(p.typical_max * perSi).toPrecision(12);
    return { key: p.name, name: p.name, label, help: p.help, unit, suffix: unit, perSi, min: lo, max: hi,
      step: niceStep(hi - lo), defaults: p.defaults, body: p.body, sets: p.sets ? p.sets.split(' ') : [] };
  });
  BY_KEY = Object.fromEntries(CONTROLS.map((c) => [c.key, c]));
}

const state = {
  jc: null, preset: 'paper', overrides: {}, presetSetups: {},
  run: null, request: null, t: 0, playing: false, speed: 4, lastFrame: 0, view: null,
};

// ---- the engine ----
function call(fn, request) {
  const ptr = state.jc.ccall(fn, 'number', ['string'], [JSON.stringify(request)]);
  if (!ptr) throw new Error('out of memory');
  const text = state.jc.UTF8ToString(ptr);
  state.jc.ccall('jc_web_free', null, ['number'], [ptr]);
  return text;
}
// A call without arguments that answers a string (jc_web_params).
function call0(fn) {
  const ptr = state.jc.ccall(fn, 'number', [], []);
  if (!ptr) throw new Error('out of memory');
  const text = state.jc.UTF8ToString(ptr);
  state.jc.ccall('jc_web_free', null, ['number'], [ptr]);
  return text;
}
// A run. The samples come as binary columns (sample-format "binary"): the
// answer names the library's numeric sample columns ("t_s", "x_m", ...) and
// gives the address of count doubles for each in the wasm memory, copied
// here into one Float64Array per column and freed; no printing and no
// parsing of numbers (7 times faster than the JSON columns, docs/web.md).
function simulate(request) {
  const run = JSON.parse(call('jc_web_simulate', { ...request, 'sample-format': 'binary' }));
  const S = run.ok ? run.samples : null;
  if (S && S.buffer) {
    const n = S.count, base = S.buffer / 8;
    S.columns.forEach((c, k) => { S[c] = state.jc.HEAPF64.slice(base + k * n, base + (k + 1) * n); });
    state.jc.ccall('jc_web_free', null, ['number'], [S.buffer]);
    delete S.buffer;
    delete S.columns;
  }
  return run;
}

// A number as the request's text: shortest form that reads back the same.
const num = (v) => String(+v);

// The request: the preset and what the user changed, with units, as the
// command line would give them. For the hoop presets (a point mass, no rod)
// the "rod" sliders rewrite the body as --part strings.
function buildRequest() {
  const req = { preset: state.preset };
  const base = state.presetSetups[state.preset];
  const hasRod = base && base.body.parts.some((p) => p.kind === 'rod');
  let partsChanged = false;
  for (const [key, v] of Object.entries(state.overrides)) {
    const c = BY_KEY[key];
    if (!hasRod && (key === 'rod-mass' || key === 'rod-offset')) { partsChanged = true; continue; }
    req[key] = c.choices ? v : num(v) + c.suffix;
  }
  if (partsChanged && base) {
    req.part = base.body.parts.map((p) => {
      let mass = p.mass * 1000, offset = p.offset * 100;
      if (p === rodPart(base)) {
        if ('rod-mass' in state.overrides) mass = state.overrides['rod-mass'];
        if ('rod-offset' in state.overrides) offset = state.overrides['rod-offset'];
      }
      let text = `${p.kind}:mass=${num(mass)}g`;
      if (offset) text += `,offset=${num(offset)}cm`;
      if ((p.kind === 'rod' || p.kind === 'point') && p.radius) text += `,radius=${num(p.radius * 100)}cm`;
      if (p.angle) text += `,angle=${num(p.angle / DEG)}deg`;
      return text;
    });
  }
  return req;
}

function recompute() {
  const t0 = performance.now();
  state.lastRuns = 0;
  const req = buildRequest();
  // Sampled for the animation (sampling never changes the events): with the
  // last run's spacing when it gives a sensible count, else a first run with
  // events only tells the length of the run.
  const sampled = (dtMs) => { state.lastRuns++; return simulate({ ...req, 'sample-dt': `${dtMs}ms` }); };
  const spacing = (tEnd) => Number((Math.max(1e-3, tEnd / TARGET_SAMPLES) * 1000).toPrecision(2));
  let run = state.dtMs ? sampled(state.dtMs) : simulate(req);
  if (run.ok && (!state.dtMs || run.samples.count > 2 * TARGET_SAMPLES ||
                 (run.samples.count < TARGET_SAMPLES / 3 && state.dtMs > 1))) {
    if (state.dtMs) { state.lastRuns++; run = simulate(req); }
    if (run.ok) { state.dtMs = spacing(run.t_end); run = sampled(state.dtMs); }
  }
  const t1 = performance.now();
  const err = tid('error');
  if (!run.ok) {
    err.textContent = run.error;
    err.hidden = false;
    showTiming(t1 - t0, 0);
    return false;
  }
  err.hidden = true;
  state.request = req;
  state.sampledRequest = { ...req, 'sample-dt': `${state.dtMs}ms` }; // what the run was
  document.body.dataset.sampleDt = state.sampledRequest['sample-dt'];
  state.run = run;
  prepareRun(run);
  state.t = Math.min(state.t, run.t_end);
  showSummary(run);
  showEvents(run);
  updateUrl();
  draw();
  showTiming(t1 - t0, performance.now() - t1);
  timeFrame(t0);
  sweepSetupChanged();
  return true;
}
// The browser's share of a change: a message posted from the next animation
// frame's callback arrives after that frame's style, layout and paint, which
// the page's own clock (runs + redraw) does not see. body[data-render-ms]:
// from that callback to the message; [data-frame-ms]: from the change to
// the message, which adds the wait for the display's next frame.
function timeFrame(t0) {
  const seq = (state.frameSeq = (state.frameSeq || 0) + 1);
  requestAnimationFrame(() => {
    const tf = performance.now(), ch = new MessageChannel();
    ch.port1.onmessage = () => {
      if (seq !== state.frameSeq) return;
      const now = performance.now(), d = document.body.dataset;
      d.renderMs = (now - tf).toFixed(2);
      d.frameMs = (now - t0).toFixed(2);
      d.frameSeq = String(seq);
    };
    ch.port2.postMessage(null);
  });
}
// The time of the last recompute: the runs (wasm, the answer read) and the
// redraw (derived columns, summary, events, URL, scene and graphs), shown
// small in the corner and kept in body[data-recompute-ms], [data-run-ms],
// [data-draw-ms] for the browser tests.
function showTiming(runMs, drawMs) {
  const ms = runMs + drawMs;
  tid('recompute-ms').textContent = ms.toFixed(ms < 10 ? 1 : 0);
  const d = document.body.dataset;
  d.recomputeMs = ms.toFixed(2);
  d.runMs = runMs.toFixed(2);
  d.drawMs = drawMs.toFixed(2);
  d.runs = String(state.lastRuns);
}

// ---- derived data for drawing ----
function prepareRun(run) {
  const s = run.setup, S = run.samples;
  const a = s.incline_deg * DEG;
  const Mg = s.body.mass * s.g;
  const n = S.count;
  const ratioN = new Float64Array(n), ratioF = new Float64Array(n), gapMm = new Float64Array(n);
  const K = new Float64Array(n), U = new Float64Array(n), L = new Float64Array(n), E = new Float64Array(n);
  for (let i = 0; i < n; ++i) {
    const contact = S.mode[i] !== 'flight';
    ratioN[i] = S.normal_N[i] / (Mg * Math.cos(a));
    ratioF[i] = contact && S.normal_N[i] > 1e-9 * Mg ? Math.abs(S.friction_N[i]) / S.normal_N[i] : NaN;
    gapMm[i] = S.gap_m[i] * 1000;
    K[i] = S.kinetic_J[i] * 1000;
    U[i] = S.potential_J[i] * 1000;
    L[i] = (S.friction_loss_J[i] + S.impact_loss_J[i] + S.air_loss_J[i] + S.rolling_resistance_loss_J[i]) * 1000;
    E[i] = K[i] + U[i] + L[i];
  }
  // The body's CM direction in the body (angle of the mass-weighted offsets).
  let sx = 0, sy = 0;
  for (const p of s.body.parts) { sx += p.mass * p.offset * Math.sin(p.angle); sy += p.mass * p.offset * Math.cos(p.angle); }
  run.derived = { a, Mg, ratioN, ratioF, gapMm, K, U, L, E, cmAngle: Math.atan2(sx, sy) };
  run.view = null;
  run.path = null;
}

// Index i with t[i] <= t < t[i+1] (binary search).
function sampleAt(t) {
  const T = state.run.samples.t_s;
  let lo = 0, hi = T.length - 1;
  if (t <= T[0]) return 0;
  if (t >= T[hi]) return hi;
  while (hi - lo > 1) { const m = (lo + hi) >> 1; if (T[m] <= t) lo = m; else hi = m; }
  return lo;
}
// In flight without air forces the centre of mass is ballistic and the spin
// constant: the centre C between two samples, exactly (a loop of C around
// the CM is not cut into straight pieces by a coarse sampling).
function ballistic(i, t) {
  const run = state.run, S = run.samples, s = run.setup, d = s.body.cm_offset, a = run.derived.a;
  const th = S.theta_rad[i], w = S.omega_radps[i], tau = t - S.t_s[i];
  const gx = S.x_m[i] + d * Math.sin(th), gy = S.y_m[i] + d * Math.cos(th);
  const vgx = S.vx_mps[i] + d * w * Math.cos(th), vgy = S.vy_mps[i] - d * w * Math.sin(th);
  const th2 = th + w * tau;
  const gX = gx + vgx * tau + 0.5 * s.g * Math.sin(a) * tau * tau;
  const gY = gy + vgy * tau - 0.5 * s.g * Math.cos(a) * tau * tau;
  return { x: gX - d * Math.sin(th2), y: gY - d * Math.cos(th2), theta: th2 };
}
const airFree = (s) => !s.drag_coefficient && !s.lift_coefficient && !s.spin_drag;
// The state at time t: between samples ballistic in flight (no air), else linear.
function stateAt(t) {
  const S = state.run.samples, i = sampleAt(t), j = Math.min(i + 1, S.count - 1);
  if (S.mode[i] === 'flight' && j > i && t > S.t_s[i] && t < S.t_s[j] && airFree(state.run.setup)) {
    return { i, ...ballistic(i, t), normal: 0, friction: 0, mode: 'flight' };
  }
  const span = S.t_s[j] - S.t_s[i];
  const f = span > 0 ? Math.min(1, Math.max(0, (t - S.t_s[i]) / span)) : 0;
  const lerp = (c) => S[c][i] + f * (S[c][j] - S[c][i]);
  return { i, x: lerp('x_m'), y: lerp('y_m'), theta: lerp('theta_rad'), normal: S.normal_N[f < 0.5 ? i : j],
           friction: S.friction_N[f < 0.5 ? i : j], mode: S.mode[f < 0.5 ? i : j] };
}

// The centre's path for drawing: the samples, with flights cut finer.
function centrePath(run) {
  const S = run.samples, t = [], x = [], y = [];
  const fine = airFree(run.setup);
  for (let i = 0; i < S.count; ++i) {
    t.push(S.t_s[i]); x.push(S.x_m[i]); y.push(S.y_m[i]);
    if (fine && S.mode[i] === 'flight' && i + 1 < S.count) {
      const span = S.t_s[i + 1] - S.t_s[i], m = Math.min(40, Math.ceil(span / 0.002));
      for (let k = 1; k < m; ++k) { const tk = S.t_s[i] + span * k / m, b = ballistic(i, tk); t.push(tk); x.push(b.x); y.push(b.y); }
    }
  }
  return { t, x, y };
}

// ---- the scene ----
// The canvases' widths in CSS pixels, kept by a ResizeObserver rather than
// read from clientWidth at every draw: after the event table and summary
// change, that read forces a layout of the whole page inside the recompute
// (measured in Chromium: fitCanvas was 5 of a recompute's 9 ms, the largest
// single cost; the layout then happens once, with the paint).
const cssWidths = new Map();
const sizeWatch = typeof ResizeObserver === 'function' ? new ResizeObserver((entries) => {
  let changed = false;
  for (const e of entries) {
    const w = e.contentRect.width;
    if (w > 0 && cssWidths.get(e.target) !== w) { cssWidths.set(e.target, w); changed = true; }
  }
  if (changed && state.run) { draw(); drawSweep(); }
}) : null;
function cssWidth(canvas) {
  let w = cssWidths.get(canvas);
  if (w === undefined || !sizeWatch) {
    w = canvas.clientWidth || canvas.width;
    if (sizeWatch) { cssWidths.set(canvas, w); sizeWatch.observe(canvas); }
  }
  return w;
}
function fitCanvas(canvas) {
  const dpr = window.devicePixelRatio || 1;
  const w = cssWidth(canvas);
  const h = Math.round(w * (canvas.dataset.aspect ? +canvas.dataset.aspect : canvas.height / canvas.width));
  if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(h * dpr);
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  return { ctx, w, h };
}

// Picture coordinates (cli/films/draw.h): X = x cos a + y sin a, Y = -x sin a + y cos a.
function picture(a, x, y) { return [x * Math.cos(a) + y * Math.sin(a), -x * Math.sin(a) + y * Math.cos(a)]; }

function sceneView(w, h) {
  const run = state.run, s = run.setup, S = run.samples, a = run.derived.a, r = s.body.radius;
  let xlo = 0, xhi = 0, yhi = 2 * r;
  for (let i = 0; i < S.count; ++i) { xlo = Math.min(xlo, S.x_m[i]); xhi = Math.max(xhi, S.x_m[i]); yhi = Math.max(yhi, S.y_m[i] + r); }
  // The whole ramp, unless it is a floor or much longer than the stretch
  // travelled (as `jumpcyl animate`'s fixed camera, LONG_RAMP_FACTOR 3).
  if (a > 0 && s.ramp_length <= 3 * Math.max(xhi - xlo, r)) xhi = Math.max(xhi, s.ramp_length);
  const pts = [[xlo - 1.5 * r, 0], [xhi + 1.5 * r, 0], [xlo - 1.5 * r, yhi + r], [xhi + 1.5 * r, yhi + r],
               [xlo - 1.5 * r, -0.04], [xhi + 1.5 * r, -0.04]];
  let Xlo = Infinity, Xhi = -Infinity, Ylo = Infinity, Yhi = -Infinity;
  for (const [x, y] of pts) { const [X, Y] = picture(a, x, y); Xlo = Math.min(Xlo, X); Xhi = Math.max(Xhi, X); Ylo = Math.min(Ylo, Y); Yhi = Math.max(Yhi, Y); }
  if (state.zoom) { // follow the body: a window of a few radii around it
    const [X, Y] = picture(a, state.now.x, state.now.y);
    const half = 4.5 * r * Math.max(1, (w / h) / 1.6);
    Xlo = X - half; Xhi = X + half; Ylo = Y - 2.2 * r; Yhi = Y + 2.2 * r;
  }
  const pad = 14;
  const scale = Math.min((w - 2 * pad) / (Xhi - Xlo), (h - 2 * pad - 18) / (Yhi - Ylo));
  const ox = pad + ((w - 2 * pad) - scale * (Xhi - Xlo)) / 2 - scale * Xlo;
  const oy = pad + ((h - 2 * pad - 18) - scale * (Yhi - Ylo)) / 2 + scale * Yhi;
  const px = (x, y) => { const [X, Y] = picture(a, x, y); return [ox + scale * X, oy - scale * Y]; };
  // The ground reaches the right edge of the picture (x of the incline's
  // line there), not only the stretch travelled: a floor wider than the run
  // is drawn to the edge.
  const xEdge = (w - ox) / scale / Math.cos(a);
  const xLeft = a === 0 ? Math.min(xlo - 1.5 * r, -ox / scale) : xlo - 1.5 * r; // a floor: both edges
  return { scale, px, xlo: xLeft, xhi: Math.max(xhi + 1.5 * r, xEdge) };
}

function arrow(ctx, x0, y0, x1, y1, color, label) {
  const dx = x1 - x0, dy = y1 - y0, len = Math.hypot(dx, dy);
  if (len < 2) return;
  const ux = dx / len, uy = dy / len, hs = Math.min(9, len * 0.4);
  ctx.strokeStyle = ctx.fillStyle = color;
  ctx.lineWidth = 2.5;
  ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1 - ux * hs, y1 - uy * hs); ctx.stroke();
  ctx.beginPath(); ctx.moveTo(x1, y1); ctx.lineTo(x1 - ux * hs - uy * hs * 0.5, y1 - uy * hs + ux * hs * 0.5);
  ctx.lineTo(x1 - ux * hs + uy * hs * 0.5, y1 - uy * hs - ux * hs * 0.5); ctx.closePath(); ctx.fill();
  if (label) { ctx.font = 'bold 13px system-ui, sans-serif'; ctx.fillText(label, x1 + ux * 4 + 3, y1 + uy * 4 - 3); }
}

function drawScene() {
  const canvas = $('#scene');
  const aspect = window.innerWidth < 760 ? '0.75' : '0.5';
  if (canvas.dataset.aspect !== aspect) canvas.dataset.aspect = aspect; // a write restyles it
  const { ctx, w, h } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  const run = state.run;
  if (!run) return;
  const s = run.setup, S = run.samples, d = run.derived, r = s.body.radius, a = d.a;
  const now = stateAt(state.t);
  state.now = now;
  const v = sceneView(w, h);
  const { px, scale } = v;
  // The ground under the ramp.
  const rampEnd = Math.min(s.ramp_length, v.xhi);
  const [gx0, gy0] = px(v.xlo, 0), [gx1, gy1] = px(rampEnd, 0);
  ctx.fillStyle = '#e6e1d6';
  ctx.beginPath(); ctx.moveTo(gx0, gy0); ctx.lineTo(gx1, gy1); ctx.lineTo(gx1, h); ctx.lineTo(gx0, h); ctx.closePath(); ctx.fill();
  ctx.strokeStyle = '#5a5347'; ctx.lineWidth = 2;
  ctx.beginPath(); ctx.moveTo(gx0, gy0); ctx.lineTo(gx1, gy1); ctx.stroke();
  // The cm scale along the ramp: a tick every 1, 5, 10 or 50 cm, labels every 5 ticks or so.
  const pxPerCm = scale / 100;
  const tick = [1, 2, 5, 10, 20, 50, 100].find((c) => c * pxPerCm >= 6) || 100;
  const labelEvery = [5, 10, 20, 50, 100, 200, 500].find((c) => c % tick === 0 && c * pxPerCm >= 46) || 500;
  ctx.fillStyle = '#3b3630'; ctx.strokeStyle = '#3b3630'; ctx.lineWidth = 1;
  ctx.font = '11px system-ui, sans-serif'; ctx.textAlign = 'center';
  const nx = Math.sin(a), ny = Math.cos(a); // the outward normal on screen: (sin a, -cos a) in pixels
  ctx.beginPath(); // every tick in one path: one stroke, not hundreds
  for (let c = 0; c <= rampEnd * 100 + 1e-9; c += tick) {
    const [tx, ty] = px(c / 100, 0);
    const big = Math.abs(c % labelEvery) < 1e-9;
    const len = big ? 9 : 5;
    ctx.moveTo(tx, ty); ctx.lineTo(tx - nx * -len, ty + ny * len);
    if (big) ctx.fillText(`${Math.round(c)}`, tx + nx * 16, ty + ny * 20);
  }
  ctx.stroke();
  {
    const [tx, ty] = px(rampEnd, 0);
    ctx.textAlign = 'right'; ctx.fillText('cm', tx - 4, ty + ny * 34 + 2);
  }
  ctx.textAlign = 'left';
  // Marks on the ramp: the paper's measured band, its printed point, our first lift-off.
  // Labels already drawn, as boxes: on a steep incline the two marks' tops
  // come close, and a label that would cover another moves below it.
  const labelBoxes = [];
  const mark = (x, color, label, up, left) => {
    const [mx, my] = px(x, 0), [mx2, my2] = px(x, up);
    ctx.strokeStyle = ctx.fillStyle = color; ctx.lineWidth = 2;
    ctx.setLineDash([5, 3]); ctx.beginPath(); ctx.moveTo(mx, my); ctx.lineTo(mx2, my2); ctx.stroke(); ctx.setLineDash([]);
    ctx.font = 'bold 12px system-ui, sans-serif';
    const wText = ctx.measureText(label).width, hText = 13;
    const x0 = left ? mx2 - 4 - wText : mx2 + 4; // the two labels on either side of their lines
    let yBase = my2 - 2;
    for (let k = 0; k < 4; ++k) {
      const hit = labelBoxes.find(b => x0 < b.x + b.w && b.x < x0 + wText && yBase - hText < b.y && b.y - hText < yBase);
      if (!hit) break;
      yBase = hit.y + hText + 1;
    }
    ctx.textAlign = 'left';
    ctx.fillText(label, x0, yBase);
    labelBoxes.push({ x: x0, y: yBase, w: wText });
  };
  const pr = run.paper_row;
  if (pr) {
    const [b0x, b0y] = px(pr.measured_x_m - pr.measured_error_m, 0), [b1x, b1y] = px(pr.measured_x_m + pr.measured_error_m, 0);
    ctx.strokeStyle = 'rgba(39,160,80,.55)'; ctx.lineWidth = 10;
    ctx.beginPath(); ctx.moveTo(b0x, b0y); ctx.lineTo(b1x, b1y); ctx.stroke();
    mark(pr.printed_x_m, '#1f5fbf', 'paper', 3.2 * r, true);
  }
  if (run.first_liftoff) mark(run.first_liftoff.x, '#c0392b', 'lift-off', 2.4 * r);
  // The centre's path: all of it faint, up to now strong.
  const path = run.path || (run.path = centrePath(run));
  ctx.lineWidth = 1; ctx.strokeStyle = 'rgba(142,68,173,.3)';
  ctx.beginPath();
  for (let k = 0; k < path.t.length; ++k) { const [qx, qy] = px(path.x[k], path.y[k]); if (k) ctx.lineTo(qx, qy); else ctx.moveTo(qx, qy); }
  ctx.stroke();
  ctx.lineWidth = 2; ctx.strokeStyle = '#8e44ad';
  ctx.beginPath();
  for (let k = 0; k < path.t.length && path.t[k] <= state.t; ++k) { const [qx, qy] = px(path.x[k], path.y[k]); if (k) ctx.lineTo(qx, qy); else ctx.moveTo(qx, qy); }
  { const [qx, qy] = px(now.x, now.y); ctx.lineTo(qx, qy); }
  ctx.stroke();
  // The body: rim, disc, parts, spoke, CM.
  const [cx, cy] = px(now.x, now.y);
  const R = r * scale;
  for (const p of s.body.parts) {
    if (p.kind === 'disc' && p.offset === 0) {
      ctx.fillStyle = 'rgba(170,190,215,.55)';
      ctx.beginPath(); ctx.arc(cx, cy, p.radius * scale, 0, 2 * Math.PI); ctx.fill();
    }
  }
  ctx.strokeStyle = '#1a1a1a'; ctx.lineWidth = 2.5;
  ctx.beginPath(); ctx.arc(cx, cy, R, 0, 2 * Math.PI); ctx.stroke();
  const partPoint = (offset, angle) => {
    const psi = now.theta - d.cmAngle + angle;
    return px(now.x + offset * Math.sin(psi), now.y + offset * Math.cos(psi));
  };
  // A spoke, to see the turning.
  {
    const [sx, sy] = partPoint(r, Math.PI);
    ctx.strokeStyle = '#7a7f88'; ctx.lineWidth = 1.5;
    ctx.beginPath(); ctx.moveTo(cx, cy); ctx.lineTo(sx, sy); ctx.stroke();
  }
  for (const p of s.body.parts) {
    if (p.kind === 'rod' || p.kind === 'point') {
      const [rx, ry] = partPoint(p.offset, p.angle);
      ctx.strokeStyle = '#7a7f88'; ctx.lineWidth = 1.5;
      ctx.beginPath(); ctx.moveTo(cx, cy); ctx.lineTo(rx, ry); ctx.stroke();
      ctx.fillStyle = p.kind === 'rod' ? '#b8860b' : '#333';
      ctx.beginPath(); ctx.arc(rx, ry, Math.max(3.5, p.radius * scale), 0, 2 * Math.PI); ctx.fill();
    } else if (p.kind === 'hoop' && p.radius < r - 1e-9) {
      ctx.strokeStyle = '#555'; ctx.lineWidth = 1.5;
      ctx.beginPath(); ctx.arc(cx, cy, p.radius * scale, 0, 2 * Math.PI); ctx.stroke();
    }
  }
  ctx.fillStyle = '#1a1a1a';
  ctx.beginPath(); ctx.arc(cx, cy, 2.5, 0, 2 * Math.PI); ctx.fill();
  {
    const [gx, gy] = partPoint(s.body.cm_offset, d.cmAngle);
    const g = 5.5;
    ctx.fillStyle = '#fff'; ctx.strokeStyle = '#1a1a1a'; ctx.lineWidth = 1.5;
    ctx.beginPath(); ctx.arc(gx, gy, g, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
    ctx.fillStyle = '#1a1a1a';
    ctx.beginPath(); ctx.moveTo(gx, gy); ctx.arc(gx, gy, g, -Math.PI / 2, 0); ctx.closePath(); ctx.fill();
    ctx.beginPath(); ctx.moveTo(gx, gy); ctx.arc(gx, gy, g, Math.PI / 2, Math.PI); ctx.closePath(); ctx.fill();
  }
  // N and F at the contact point, M g = 2 r on the screen.
  if (now.mode !== 'flight') {
    const [kx, ky] = px(now.x, 0);
    const k = 2 * R / d.Mg;
    const [nX, nY] = [Math.sin(a), -Math.cos(a)]; // screen direction of +y (incline normal)
    const [fX, fY] = [Math.cos(a), Math.sin(a)];  // screen direction of +x (downhill)
    arrow(ctx, kx, ky, kx + nX * now.normal * k, ky + nY * now.normal * k, '#1f7a3a', 'N');
    arrow(ctx, kx, ky, kx + fX * now.friction * k, ky + fY * now.friction * k, '#c0392b', 'F');
  }
  // Readouts.
  ctx.fillStyle = '#1a1a1a'; ctx.font = '13px system-ui, sans-serif'; ctx.textAlign = 'left';
  ctx.fillText(`t = ${state.t.toFixed(3)} s   x = ${(now.x * 100).toFixed(1)} cm   ${now.mode}`, 10, h - 10);
  ctx.font = '12px system-ui, sans-serif'; ctx.fillStyle = '#444';
  ctx.fillText(`arrows N, F: M g = ${(2 * r * 100).toFixed(0)} cm on the ramp's scale`, 10, 18);
}

// ---- graphs ----
// An axis' tick spacing: 1, 2 or 5 times a power of ten, about span / count.
const tickStep = (span, count) => {
  const raw = span / count, p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * p).find((v) => v >= raw);
};
function plot(canvasId, series, opts = {}) {
  const canvas = document.getElementById(canvasId);
  const { ctx, w, h } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  const run = state.run;
  if (!run) return;
  const T = run.samples.t_s, n = T.length;
  const L = 44, R = 8, Tp = 20, B = 22;
  // A long run (the hoop rocks for a minute): a window of GRAPH_WINDOW_S
  // seconds that follows the current time.
  let t0 = 0, t1 = Math.max(run.t_end, 1e-9);
  if (t1 > GRAPH_WINDOW_S * 1.2) {
    t0 = Math.min(Math.max(0, state.t - GRAPH_WINDOW_S / 2), t1 - GRAPH_WINDOW_S);
    t1 = t0 + GRAPH_WINDOW_S;
  }
  let i0 = 0, i1 = n;
  if (t0 > 0 || t1 < run.t_end) { i0 = Math.max(0, sampleAt(t0) - 1); i1 = Math.min(n, sampleAt(t1) + 2); }
  let lo = opts.min !== undefined ? opts.min : Infinity, hi = opts.max !== undefined ? opts.max : -Infinity;
  if (opts.min === undefined || opts.max === undefined) {
    for (const s of series) for (let i = i0; i < i1; ++i) { const y = s.y[i]; if (Number.isFinite(y)) { if (opts.min === undefined) lo = Math.min(lo, y); if (opts.max === undefined) hi = Math.max(hi, y); } }
  }
  if (opts.clampMax !== undefined) hi = Math.min(hi, opts.clampMax);
  if (!Number.isFinite(lo) || !Number.isFinite(hi)) { lo = 0; hi = 1; }
  if (hi - lo < 1e-12) { hi += 0.5; lo -= 0.5; }
  const padY = (hi - lo) * 0.06; hi += padY; if (opts.min === undefined) lo -= padY;
  const X = (t) => L + (w - L - R) * (t - t0) / (t1 - t0);
  const Y = (y) => Tp + (h - Tp - B) * (hi - y) / (hi - lo);
  // Grid and axes.
  ctx.font = '11px system-ui, sans-serif'; ctx.fillStyle = '#444'; ctx.strokeStyle = '#e1e3e8'; ctx.lineWidth = 1;
  const ys = tickStep(hi - lo, 4);
  ctx.textAlign = 'right';
  for (let y = Math.ceil(lo / ys) * ys; y <= hi; y += ys) {
    ctx.beginPath(); ctx.moveTo(L, Y(y)); ctx.lineTo(w - R, Y(y)); ctx.stroke();
    ctx.fillText(String(+y.toPrecision(6)), L - 4, Y(y) + 4);
  }
  const ts = tickStep(t1 - t0, 6);
  ctx.textAlign = 'center';
  for (let t = Math.ceil(t0 / ts) * ts; t <= t1 + 1e-12; t += ts) {
    if (X(t) > w - R - 34) continue; // room for the axis' name
    ctx.beginPath(); ctx.moveTo(X(t), Tp); ctx.lineTo(X(t), h - B); ctx.stroke();
    ctx.fillText(String(+t.toPrecision(6)), X(t), h - 8);
  }
  ctx.textAlign = 'right'; ctx.fillText('t (s)', w - R, h - 8 - 0);
  if (opts.band) {
    const yb = Y(Math.min(opts.band, hi));
    ctx.fillStyle = 'rgba(192,57,43,.12)'; ctx.fillRect(L, Tp, w - L - R, Math.max(0, yb - Tp));
    ctx.strokeStyle = 'rgba(192,57,43,.7)'; ctx.setLineDash([4, 3]);
    ctx.beginPath(); ctx.moveTo(L, yb); ctx.lineTo(w - R, yb); ctx.stroke(); ctx.setLineDash([]);
  }
  if (lo < 0 && hi > 0) { ctx.strokeStyle = '#999'; ctx.beginPath(); ctx.moveTo(L, Y(0)); ctx.lineTo(w - R, Y(0)); ctx.stroke(); }
  // The curves, clipped to the plot, broken at NaN.
  ctx.save(); ctx.beginPath(); ctx.rect(L, Tp, w - L - R, h - Tp - B); ctx.clip();
  for (const s of series) {
    ctx.strokeStyle = s.color; ctx.lineWidth = s.width || 1.6;
    ctx.beginPath();
    let pen = false;
    for (let i = i0; i < i1; ++i) {
      const y = s.y[i];
      if (!Number.isFinite(y)) { pen = false; continue; }
      if (pen) ctx.lineTo(X(T[i]), Y(y)); else { ctx.moveTo(X(T[i]), Y(y)); pen = true; }
    }
    ctx.stroke();
  }
  ctx.restore();
  // Legend and the current time.
  ctx.textAlign = 'left'; ctx.font = '11px system-ui, sans-serif';
  let lx = L + 2;
  for (const s of series) {
    if (!s.name) continue;
    ctx.fillStyle = s.color; ctx.fillRect(lx, 6, 12, 3);
    ctx.fillStyle = '#222'; ctx.fillText(s.name, lx + 15, 12);
    lx += 20 + ctx.measureText(s.name).width + 8;
  }
  ctx.strokeStyle = '#d35400'; ctx.lineWidth = 1.5;
  ctx.beginPath(); ctx.moveTo(X(state.t), Tp); ctx.lineTo(X(state.t), h - B); ctx.stroke();
}

function drawGraphs() {
  const run = state.run;
  if (!run) return;
  const d = run.derived;
  plot('g-normal', [{ name: 'N / (M g cos α)', color: '#1f7a3a', y: d.ratioN }], { min: Math.min(0, ...[0]) });
  plot('g-friction', [{ name: '|F| / N', color: '#c0392b', y: d.ratioF }],
       { min: 0, max: Math.max(1.5 * run.setup.mu_s, 0.1), band: run.setup.mu_s });
  plot('g-gap', [{ name: 'gap', color: '#8e44ad', y: d.gapMm }], { min: 0 });
  plot('g-energy', [
    { name: 'K', color: '#1f5fbf', y: d.K }, { name: 'U', color: '#1f7a3a', y: d.U },
    { name: 'losses', color: '#c0392b', y: d.L }, { name: 'sum', color: '#1a1a1a', y: d.E, width: 2 }]);
}

function draw() {
  drawScene();
  drawGraphs();
  const run = state.run;
  if (!run) return;
  const scrub = $('#scrub');
  scrub.value = String(Math.round(1000 * state.t / Math.max(run.t_end, 1e-12)));
  $('#tnow').textContent = `${state.t.toFixed(3)} s`;
  highlightEvent();
}

// ---- the sweep and the spread of the jump site ----
// One parameter over a range, the rest of the setup as the controls have it:
// jc_web_sweep, a grid of the library's studies (jc_study_run), the rows
// `jumpcyl sweep` writes for the same options. jc_web_uncertainty: the
// library's default tolerances (jc_study_default_spreads) as a Monte Carlo,
// the first lift-off's median and 95 % interval, as `jumpcyl mc` gives them.
// The sweep runs when its panel comes into view, on the button, and again
// SWEEP_DEBOUNCE_MS after the last change of the setup or the range while it
// is in view, if the last one took at most SWEEP_AUTO_MS; otherwise it is
// marked out of date until the button is pressed. A change of the setup
// never waits for a sweep.
const SWEEP_AUTO_MS = 400;
const SWEEP_DEBOUNCE_MS = 400;
const SWEEP_LIFT = '#c0392b', SWEEP_SLIP = '#1f5fbf', SWEEP_NOW = '#d35400', SWEEP_BAND = '#27a050';
const SWEEP_INVALID = '#eceef2';
const sweep = { answer: null, shown: '', ms: 0, timer: 0, stale: true, visible: false, spread: null, seq: 0 };

function buildSweep() {
  const sel = $('#sw-param');
  for (const c of CONTROLS) {
    if (c.choices) continue;
    const o = document.createElement('option');
    o.value = c.key;
    o.textContent = c.unit ? `${c.label} (${c.unit})` : c.label;
    sel.appendChild(o);
  }
  sel.value = BY_KEY.incline ? 'incline' : sel.options[0].value;
  sweepRangeFromTable();
  sel.addEventListener('change', () => { sweepRangeFromTable(); scheduleSweep(0); });
  for (const id of ['#sw-lo', '#sw-hi', '#sw-n']) $(id).addEventListener('input', () => scheduleSweep(SWEEP_DEBOUNCE_MS));
  $('#sw-run').addEventListener('click', () => runSweep(true));
  $('#sp-run').addEventListener('click', () => runSpread());
  if (typeof IntersectionObserver === 'function') {
    new IntersectionObserver((entries) => {
      sweep.visible = entries.some((e) => e.isIntersecting);
      if (!sweep.visible || !sweep.stale) return;
      if (!sweep.answer || sweep.ms <= SWEEP_AUTO_MS) scheduleSweep(0);
      else { showSweepStatus(); drawSweep(); }
    }).observe($('#sweep'));
  }
  drawSweep();
}
// The range: the parameter's typical span from the table, in the unit shown.
function sweepRangeFromTable() {
  const c = BY_KEY[$('#sw-param').value];
  $('#sw-lo').value = fmt(c.min, c.step);
  $('#sw-hi').value = fmt(c.max, c.step);
  $('#sw-unit').textContent = c.unit;
}
function scheduleSweep(ms) {
  clearTimeout(sweep.timer);
  sweep.timer = setTimeout(() => runSweep(false), ms);
}
// Out of view nothing is drawn: the panel is brought up to date when it
// comes into view.
function sweepSetupChanged() {
  if (!sweep.answer) return;
  sweep.stale = true;
  if (sweep.spread) sweep.spread = null;
  if (!sweep.visible) return;
  showSpread();
  if (sweep.ms <= SWEEP_AUTO_MS) { scheduleSweep(SWEEP_DEBOUNCE_MS); return; }
  showSweepStatus();
  drawSweep();
}

// The request: the current setup, the parameter, its range with the unit
// shown (as the controls give values: "10deg"), the number of points.
function sweepRequest() {
  const c = BY_KEY[$('#sw-param').value];
  const text = (id) => { const v = $(id).value.trim(); return v === '' || !Number.isFinite(+v) ? v : num(v) + c.suffix; };
  const n = $('#sw-n').value.trim();
  return { setup: buildRequest(), vary: c.key, lo: text('#sw-lo'), hi: text('#sw-hi'), n: n === '' ? n : +n };
}
function runSweep(force) {
  clearTimeout(sweep.timer);
  if (!state.jc) return;
  const req = sweepRequest(), key = JSON.stringify(req);
  if (!force && key === sweep.shown && !sweep.stale) return;
  const t0 = performance.now();
  const ans = JSON.parse(call('jc_web_sweep', req));
  const ms = performance.now() - t0;
  const d = document.body.dataset;
  if (!ans.ok) {
    sweep.error = ans.error;
    sweep.stale = true;
    showSweepStatus();
    d.sweepSeq = String(++sweep.seq);
    return;
  }
  sweep.error = null;
  Object.assign(sweep, { answer: ans, shown: key, ms, stale: false });
  d.sweepMs = ms.toFixed(1);
  d.sweepRows = String(ans.rows.length);
  d.sweepSeq = String(++sweep.seq);
  showSweepStatus();
  drawSweep();
}
function showSweepStatus() {
  const el = tid('sweep-status');
  el.classList.toggle('error', !!sweep.error);
  if (sweep.error) { el.textContent = sweep.error; return; }
  const a = sweep.answer;
  if (!a) { el.textContent = ''; return; }
  const lifts = a.rows.filter((r) => r.liftoff_x_m !== null).length;
  const bad = a.rows.filter((r) => r.kind === 'invalid_setup' || r.kind === 'failed').length;
  let text = `${a.rows.length} runs in ${sweep.ms < 10 ? sweep.ms.toFixed(1) : sweep.ms.toFixed(0)} ms: `
    + `${lifts} lift off on the ramp, ${a.rows.length - lifts - bad} do not`;
  if (bad) text += `, ${bad} are no valid setup`;
  text += '.';
  if (sweep.stale) text += ' The setup has changed since: press Run sweep to update it.';
  el.textContent = text;
}

function runSpread() {
  if (!state.jc) return;
  const t0 = performance.now();
  const ans = JSON.parse(call('jc_web_uncertainty', { setup: buildRequest(), samples: Math.round(+$('#sp-n').value) }));
  sweep.spread = { ...ans, ms: performance.now() - t0 };
  document.body.dataset.spreadSeq = String((+document.body.dataset.spreadSeq || 0) + 1);
  showSpread();
  drawSweep();
}
function showSpread() {
  const el = tid('spread-result'), s = sweep.spread;
  el.classList.toggle('error', !!(s && !s.ok));
  if (!s) { el.textContent = ''; return; }
  if (!s.ok) { el.textContent = s.error; return; }
  const x = s.first_liftoff_x_m, cm = (v) => (v * 100).toFixed(1);
  const ms = s.ms < 1000 ? `${s.ms.toFixed(0)} ms` : `${(s.ms / 1000).toFixed(1)} s`;
  const varied = s.spreads.map((p) => p.name).join(', ');
  el.title = s.spreads.map((p) => `${p.name}: ${p.why}`).join('\n');
  el.textContent = x.count
    ? `First lift-off over ${s.samples} samples of ${varied}: median ${cm(x.p50)} cm, 95 % between `
      + `${cm(x.p2_5)} and ${cm(x.p97_5)} cm; ${x.count} of ${s.valid} lift off on the ramp (${ms}).`
    : `None of ${s.samples} samples of ${varied} lifts off on the ramp (${ms}).`;
}

// First lift-off and first slip (cm along the ramp) against the parameter,
// in the unit its control shows; values that make no valid setup shaded;
// the current value marked, with the current run's lift-off, and beside it
// the spread of the jump site when computed.
function drawSweep() {
  const canvas = $('#g-sweep');
  if (!canvas) return;
  const aspect = window.innerWidth < 760 ? '0.62' : '0.34';
  if (canvas.dataset.aspect !== aspect) canvas.dataset.aspect = aspect;
  const { ctx, w, h } = fitCanvas(canvas);
  ctx.clearRect(0, 0, w, h);
  const a = sweep.answer;
  if (!a) {
    ctx.font = '13px system-ui, sans-serif'; ctx.fillStyle = '#4a4a4a'; ctx.textAlign = 'center';
    ctx.fillText('Not computed yet: the sweep runs when this panel comes into view, or with Run sweep.', w / 2, h / 2, w - 20);
    return;
  }
  const c = BY_KEY[a.vary];
  const px = a.rows.map((r) => r.value_si * c.perSi);
  const cm = (v) => (v === null ? NaN : v * 100);
  const series = [
    { name: 'first lift-off', color: SWEEP_LIFT, y: a.rows.map((r) => cm(r.liftoff_x_m)) },
    { name: 'first slip', color: SWEEP_SLIP, y: a.rows.map((r) => cm(r.slip_x_m)) },
  ];
  const invalid = a.rows.map((r) => r.kind === 'invalid_setup' || r.kind === 'failed');
  const x0 = px[0], x1 = px[px.length - 1];
  const now = controlValue(c), run = state.run;
  const nowIn = now !== null && now >= x0 && now <= x1;
  const nowX = nowIn && run && run.first_liftoff ? run.first_liftoff.x * 100 : NaN;
  const spread = sweep.spread && sweep.spread.ok && sweep.spread.first_liftoff_x_m.count ? sweep.spread.first_liftoff_x_m : null;
  const sp = nowIn ? spread : null;
  // The legend, in as many lines as the width needs: the plot starts below it.
  const legend = [...series];
  if (invalid.some(Boolean)) legend.push({ name: 'no valid setup', color: SWEEP_INVALID, box: true });
  if (sp) legend.push({ name: '95 % of the jump site (tolerances)', color: SWEEP_BAND });
  if (nowIn) legend.push({ name: `this setup (${fmt(now, c.step)}${c.unit ? ` ${c.unit}` : ''})`, color: SWEEP_NOW });
  ctx.font = '11px system-ui, sans-serif';
  const L = 52, R = 10, B = 24;
  let lx = L + 2, ly = 12;
  for (const s of legend) {
    const wText = 20 + ctx.measureText(s.name).width + 8;
    if (lx > L + 2 && lx + wText > w - R) { lx = L + 2; ly += 14; }
    Object.assign(s, { lx, ly });
    lx += wText;
  }
  const Tp = ly + 10;
  let lo = Infinity, hi = -Infinity;
  for (const v of [...series[0].y, ...series[1].y, ...(sp ? [sp.p2_5 * 100, sp.p97_5 * 100] : [])]) {
    if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  }
  if (!Number.isFinite(lo)) { lo = 0; hi = 1; }
  lo = Math.min(0, lo);
  if (hi - lo < 1e-9) hi = lo + 1;
  hi += (hi - lo) * 0.08;
  const X = (v) => L + (w - L - R) * (v - x0) / (x1 - x0);
  const Y = (v) => Tp + (h - Tp - B) * (hi - v) / (hi - lo);
  ctx.globalAlpha = sweep.stale ? 0.45 : 1;
  // Values that make no valid setup: each one's half-way span to its neighbours.
  ctx.fillStyle = SWEEP_INVALID;
  for (let i = 0; i < px.length; ++i) {
    if (!invalid[i]) continue;
    const left = i ? (px[i - 1] + px[i]) / 2 : px[i], right = i + 1 < px.length ? (px[i] + px[i + 1]) / 2 : px[i];
    ctx.fillRect(X(left), Tp, Math.max(1, X(right) - X(left)), h - Tp - B);
  }
  // Grid, ticks and the axes' names.
  ctx.fillStyle = '#444'; ctx.strokeStyle = '#e1e3e8'; ctx.lineWidth = 1;
  const ys = tickStep(hi - lo, h > 300 ? 6 : 4);
  ctx.textAlign = 'right';
  for (let y = Math.ceil(lo / ys) * ys; y <= hi; y += ys) {
    ctx.beginPath(); ctx.moveTo(L, Y(y)); ctx.lineTo(w - R, Y(y)); ctx.stroke();
    ctx.fillText(String(+y.toPrecision(6)), L - 4, Y(y) + 4);
  }
  const xName = c.unit ? `${c.label} (${c.unit})` : c.label;
  const nameW = ctx.measureText(xName).width;
  const xs = tickStep(x1 - x0, Math.max(3, Math.round((w - L - R) / 90)));
  ctx.textAlign = 'center';
  for (let v = Math.ceil(x0 / xs - 1e-9) * xs; v <= x1 + 1e-9 * Math.abs(xs); v += xs) {
    ctx.beginPath(); ctx.moveTo(X(v), Tp); ctx.lineTo(X(v), h - B); ctx.stroke();
    if (X(v) < w - R - nameW - 20) ctx.fillText(String(+v.toPrecision(6)), X(v), h - 8);
  }
  ctx.textAlign = 'right'; ctx.fillText(xName, w - R, h - 8);
  ctx.save(); ctx.translate(13, Tp + (h - Tp - B) / 2); ctx.rotate(-Math.PI / 2);
  ctx.textAlign = 'center'; ctx.fillText('x along the ramp (cm)', 0, 0); ctx.restore();
  // The curves: points, joined where neighbours are close (a leap of the
  // lift-off is left as a gap, not drawn as a slope).
  ctx.save(); ctx.beginPath(); ctx.rect(L, Tp - 4, w - L - R, h - Tp - B + 8); ctx.clip();
  const leap = 0.12 * (hi - lo);
  for (const s of series) {
    ctx.strokeStyle = ctx.fillStyle = s.color; ctx.lineWidth = 1.4;
    ctx.beginPath();
    for (let i = 1; i < px.length; ++i) {
      const y0 = s.y[i - 1], y1 = s.y[i];
      if (Number.isFinite(y0) && Number.isFinite(y1) && Math.abs(y1 - y0) <= leap) { ctx.moveTo(X(px[i - 1]), Y(y0)); ctx.lineTo(X(px[i]), Y(y1)); }
    }
    ctx.stroke();
    const r = (w - L - R) / px.length < 6 ? 1.6 : 2.4;
    ctx.beginPath();
    for (let i = 0; i < px.length; ++i) {
      if (Number.isFinite(s.y[i])) { ctx.moveTo(X(px[i]) + r, Y(s.y[i])); ctx.arc(X(px[i]), Y(s.y[i]), r, 0, 2 * Math.PI); }
    }
    ctx.fill();
  }
  ctx.restore();
  ctx.globalAlpha = 1;
  // The current value: a line, the current run's lift-off on it, and just
  // beside it the spread of the jump site (2.5 to 97.5 %, the median).
  if (nowIn) {
    const xn = X(now);
    ctx.strokeStyle = SWEEP_NOW; ctx.lineWidth = 1.5; ctx.setLineDash([5, 3]);
    ctx.beginPath(); ctx.moveTo(xn, Tp); ctx.lineTo(xn, h - B); ctx.stroke(); ctx.setLineDash([]);
    if (sp) {
      const xb = xn + (xn + 24 < w - R ? 11 : -11), y0 = Y(sp.p2_5 * 100), y1 = Y(sp.p97_5 * 100);
      ctx.strokeStyle = SWEEP_BAND; ctx.lineWidth = 3;
      ctx.beginPath(); ctx.moveTo(xb, y0); ctx.lineTo(xb, y1); ctx.stroke();
      ctx.lineWidth = 2;
      ctx.beginPath();
      for (const y of [y0, y1]) { ctx.moveTo(xb - 5, y); ctx.lineTo(xb + 5, y); }
      ctx.moveTo(xb - 7, Y(sp.p50 * 100)); ctx.lineTo(xb + 7, Y(sp.p50 * 100));
      ctx.stroke();
    }
    if (Number.isFinite(nowX)) {
      ctx.strokeStyle = SWEEP_NOW; ctx.fillStyle = '#fff'; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(xn, Y(nowX), 4.5, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
    }
  }
  ctx.textAlign = 'left';
  for (const s of legend) {
    ctx.fillStyle = s.color;
    if (s.box) ctx.fillRect(s.lx, s.ly - 8, 12, 9); else ctx.fillRect(s.lx, s.ly - 6, 12, 3);
    ctx.fillStyle = '#222'; ctx.fillText(s.name, s.lx + 15, s.ly);
  }
}

// ---- summary and events ----
function showSummary(run) {
  const fl = run.first_liftoff;
  tid('first-liftoff-cm').textContent = fl ? (fl.x * 100).toFixed(2) : 'none';
  tid('first-liftoff-t').textContent = fl ? fl.t.toFixed(4) : '—';
  $('#fl-rest').hidden = !fl;
  tid('termination').textContent = run.termination;
  tid('t-end').textContent = run.t_end.toFixed(4);
  tid('event-count').textContent = String(run.events.length);
  tid('version').textContent = run.version;
  const note = tid('paper-note');
  const pr = run.paper_row;
  if (pr) {
    const dx = fl ? ` Ours: ${(fl.x * 100).toFixed(2)} cm.` : '';
    note.textContent = `The paper (Table 1, ${pr.incline_deg}°): printed jump point ${(pr.printed_x_m * 100).toFixed(1)} cm, `
      + `measured ${(pr.measured_x_m * 100).toFixed(1)} ± ${(pr.measured_error_m * 100).toFixed(1)} cm.${dx}`;
    note.hidden = false;
  } else {
    note.hidden = true;
  }
  $('.paper-keys').hidden = !pr; // the paper's marks are drawn only for its rows
  // The same beside the event table.
  const cmp = tid('paper-compare');
  cmp.hidden = !pr;
  if (pr) {
    $('#cmp-incline').textContent = String(pr.incline_deg);
    $('#cmp-ours-x').textContent = fl ? (fl.x * 100).toFixed(2) : 'none';
    $('#cmp-ours-th').textContent = fl ? (fl.theta / DEG).toFixed(1) : '—';
    $('#cmp-printed-x').textContent = (pr.printed_x_m * 100).toFixed(1);
    $('#cmp-printed-th').textContent = (pr.printed_theta_rad / DEG).toFixed(1);
    $('#cmp-measured-x').textContent = `${(pr.measured_x_m * 100).toFixed(1)} ± ${(pr.measured_error_m * 100).toFixed(1)}`;
  }
}

const MAX_ROWS = 300;
// The rows are kept and only their changed cells rewritten: a table built
// anew from innerHTML made the browser lay out some 190 of the page's 450
// boxes after every change (measured with Chromium's trace: 2.4 ms of
// layout a change, the largest part of its rendering).
function showEvents(run) {
  const body = $('#event-rows');
  const n = Math.min(run.events.length, MAX_ROWS);
  while (body.rows.length > n) body.deleteRow(-1);
  for (let k = 0; k < n; ++k) {
    const e = run.events[k];
    let tr = body.rows[k];
    if (!tr) {
      tr = body.insertRow();
      tr.tabIndex = 0;
      tr.insertCell().textContent = String(k + 1);
      for (let c = 0; c < 4; ++c) tr.insertCell();
    }
    if (tr.dataset.t !== String(e.t)) tr.dataset.t = String(e.t);
    if (tr.dataset.kind !== e.kind) {
      if (tr.dataset.kind) tr.classList.remove(tr.dataset.kind);
      tr.classList.add(e.kind);
      tr.dataset.kind = e.kind;
    }
    const text = [e.kind, e.t.toFixed(4), (e.x * 100).toFixed(2), (e.theta / DEG).toFixed(1)];
    for (let c = 0; c < 4; ++c) { const td = tr.cells[c + 1]; if (td.textContent !== text[c]) td.textContent = text[c]; }
  }
  const more = $('#events-more');
  more.hidden = run.events.length <= MAX_ROWS;
  if (!more.hidden) more.textContent = `The first ${MAX_ROWS} of ${run.events.length} events; all of them are in the JSON download.`;
}
function highlightEvent() {
  const run = state.run;
  let cur = -1;
  for (let k = 0; k < Math.min(run.events.length, MAX_ROWS); ++k) { if (run.events[k].t <= state.t + 1e-12) cur = k; else break; }
  const rows = $('#event-rows').children;
  for (let k = 0; k < rows.length; ++k) rows[k].classList.toggle('current', k === cur);
}

// ---- controls ----
// The preset's value in the control's unit (the table's defaults), null when
// the preset has none (rod-mass of the hoop: its "rod" is the point mass).
function presetValue(c) {
  const v = c.defaults[state.preset];
  if (c.choices) return v === null ? c.choices[0] : c.choices[v];
  if (v !== null) return v * c.perSi;
  const s = state.presetSetups[state.preset], p = s && rodPart(s);
  if (p && c.key === 'rod-mass') return p.mass * c.perSi;
  if (p && c.key === 'rod-offset') return p.offset * c.perSi;
  return null;
}
function controlValue(c) {
  if (c.key in state.overrides) return state.overrides[c.key];
  // a shortcut (mu) shows what the rows it sets were given
  for (const k of c.sets) if (k in state.overrides) return state.overrides[k];
  return presetValue(c);
}
const fmt = (v, step) => {
  const dec = Math.max(0, Math.min(6, -Math.floor(Math.log10(step)) + 1));
  return String(+(+v).toFixed(dec));
};

function buildControls() {
  const box = $('#sliders');
  for (const c of CONTROLS) {
    const row = document.createElement('div');
    row.className = c.choices ? 'row row-select' : 'row';
    row.dataset.key = c.key;
    row.title = `--${c.name}: ${c.help}`;
    if (c.choices) {
      row.innerHTML = `<label for="c-${c.key}">${c.label}</label><select id="c-${c.key}" name="${c.key}">`
        + c.choices.map((v) => `<option value="${v}">${v.charAt(0).toUpperCase()}${v.slice(1)}</option>`).join('')
        + '</select>';
      box.appendChild(row);
      row.querySelector('select').addEventListener('change', (e) => setOverride(c.key, e.target.value));
      continue;
    }
    row.innerHTML = `<label for="c-${c.key}">${c.label}</label>`
      + `<input type="range" id="c-${c.key}-range" aria-label="${c.label} (slider)" min="${c.min}" max="${c.max}" step="${c.step}">`
      + `<input type="number" id="c-${c.key}" name="${c.key}" step="any" inputmode="decimal">`
      + `<span class="unit">${c.unit}</span>`;
    box.appendChild(row);
    const range = row.querySelector('input[type=range]'), number = row.querySelector('input[type=number]');
    range.addEventListener('input', () => { number.value = range.value; setOverride(c.key, +range.value); });
    number.addEventListener('input', () => {
      if (number.value === '' || !Number.isFinite(+number.value)) return;
      const v = +number.value;
      if (v < +range.min) range.min = String(v);
      if (v > +range.max) range.max = String(v);
      range.value = String(v);
      setOverride(c.key, v);
    });
  }
}

function syncControls() {
  const base = state.presetSetups[state.preset];
  const hasRod = base && base.body.parts.some((p) => p.kind === 'rod');
  for (const c of CONTROLS) {
    const v = controlValue(c);
    const row = $(`.row[data-key="${c.key}"]`);
    row.classList.toggle('changed', c.key in state.overrides);
    if (c.choices) {
      document.getElementById(`c-${c.key}`).value = v;
      continue;
    }
    const range = document.getElementById(`c-${c.key}-range`), number = document.getElementById(`c-${c.key}`);
    // a body parameter the preset's body has no part for (the hoop's disc mass) cannot be set
    const none = v === null;
    range.disabled = none;
    number.disabled = none;
    row.classList.toggle('none', none);
    if (none) {
      number.value = '';
      continue;
    }
    if (v < +range.min) range.min = String(v);
    if (v > +range.max) range.max = String(v);
    if (document.activeElement !== number) number.value = fmt(v, c.step);
    range.value = String(v);
    const label = row.querySelector('label');
    if (c.key === 'rod-mass') label.textContent = hasRod ? 'Rod mass' : 'Point mass';
    if (c.key === 'rod-offset') label.textContent = hasRod ? 'Rod offset' : 'Point offset';
  }
  $('#c-preset').value = state.preset;
}

function setOverride(key, v) {
  state.overrides[key] = v;
  // a shortcut (mu: mu-s and mu-k) and the rows it sets exclude each other
  for (const c of CONTROLS) {
    if (c.key === key) for (const k of c.sets) delete state.overrides[k];
    else if (c.sets.includes(key)) delete state.overrides[c.key];
  }
  $(`.row[data-key="${key}"]`).classList.add('changed');
  recompute();
}

// ---- the URL ----
// Rewritten 150 ms after the last change, not on every input event: in
// Chromium history.replaceState costs 1 to 40 ms (and is throttled when
// called hundreds of times a minute, as a dragged slider would), more than
// the run. body[data-url-pending] while one is due.
function updateUrl() {
  clearTimeout(state.urlTimer);
  document.body.dataset.urlPending = 'true';
  state.urlTimer = setTimeout(() => { writeUrl(); delete document.body.dataset.urlPending; }, 150);
}
function writeUrl() {
  const p = new URLSearchParams();
  p.set('preset', state.preset);
  for (const c of CONTROLS) {
    if (c.key in state.overrides) p.set(c.key, c.choices ? state.overrides[c.key] : num(state.overrides[c.key]));
  }
  history.replaceState(null, '', `${location.pathname}?${p.toString()}`);
}
function readUrl() {
  const p = new URLSearchParams(location.search);
  const preset = p.get('preset');
  if (preset && PRESETS.includes(preset)) state.preset = preset;
  for (const c of CONTROLS) {
    const v = p.get(c.key);
    if (v === null || v === '') continue;
    if (c.choices ? c.choices.includes(v) : Number.isFinite(+v)) state.overrides[c.key] = c.choices ? v : +v;
  }
  for (const c of CONTROLS) { // a shortcut with a row it sets (mu and mu-s): the rows win
    if (c.key in state.overrides && c.sets.some((k) => k in state.overrides)) delete state.overrides[c.key];
  }
}

// ---- downloads ----
function download(name, type, text) {
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement('a');
  a.href = url; a.download = name;
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}
function fileStem() {
  const inc = state.run ? `${+state.run.setup.incline_deg.toFixed(2)}deg` : '';
  return `jumpcyl-${state.preset}-${inc}`;
}

// ---- playback ----
function frame(now) {
  if (!state.playing) return;
  const dt = Math.min(0.1, (now - state.lastFrame) / 1000);
  state.lastFrame = now;
  state.t += dt / state.speed;
  if (state.t >= state.run.t_end) { state.t = state.run.t_end; setPlaying(false); }
  draw();
  if (state.playing) requestAnimationFrame(frame);
}
function setPlaying(on) {
  if (on && state.run && state.t >= state.run.t_end) state.t = 0;
  state.playing = on;
  const b = $('#play');
  b.textContent = on ? 'Pause' : 'Play';
  b.setAttribute('aria-pressed', String(on));
  if (on) { state.lastFrame = performance.now(); requestAnimationFrame(frame); }
}
function stepFrame(dir) {
  setPlaying(false);
  const T = state.run.samples.t_s;
  let i = sampleAt(state.t);
  if (dir > 0) { while (i < T.length - 1 && T[i] <= state.t + 1e-12) ++i; } else if (T[i] >= state.t - 1e-12 && i > 0) --i;
  state.t = T[i];
  draw();
}

function wire() {
  $('#c-preset').addEventListener('change', (e) => {
    state.preset = e.target.value; state.overrides = {}; state.t = 0; state.dtMs = 0;
    syncControls(); recompute();
  });
  $('#reset').addEventListener('click', () => { state.overrides = {}; syncControls(); recompute(); });
  $('#play').addEventListener('click', () => setPlaying(!state.playing));
  $('#step-fwd').addEventListener('click', () => stepFrame(1));
  $('#step-back').addEventListener('click', () => stepFrame(-1));
  $('#zoom').addEventListener('change', (e) => { state.zoom = e.target.checked; draw(); });
  $('#speed').addEventListener('change', (e) => { state.speed = +e.target.value; });
  $('#scrub').addEventListener('input', (e) => { setPlaying(false); state.t = state.run.t_end * (+e.target.value) / 1000; draw(); });
  $('#event-rows').addEventListener('click', (e) => {
    const tr = e.target.closest('tr'); if (!tr) return;
    setPlaying(false); state.t = +tr.dataset.t; draw();
  });
  $('#event-rows').addEventListener('keydown', (e) => {
    if (e.key !== 'Enter' && e.key !== ' ') return;
    const tr = e.target.closest('tr'); if (!tr) return;
    e.preventDefault(); setPlaying(false); state.t = +tr.dataset.t; draw();
  });
  // The run's samples as `jumpcyl simulate --csv` writes them for the same
  // options: the wasm writes them with the library's table of columns.
  $('#dl-csv').addEventListener('click', () => {
    const ans = JSON.parse(call('jc_web_csv', state.sampledRequest));
    if (!ans.ok) { tid('error').textContent = ans.error; tid('error').hidden = false; return; }
    download(`${fileStem()}.csv`, 'text/csv', ans.csv);
  });
  $('#dl-json').addEventListener('click', () => {
    const { derived, view, path, ...doc } = state.run;
    const samples = {};
    for (const [k, v] of Object.entries(doc.samples)) samples[k] = ArrayBuffer.isView(v) ? Array.from(v, (x) => (Number.isFinite(x) ? x : null)) : v;
    download(`${fileStem()}.json`, 'application/json', `${JSON.stringify({ ...doc, samples }, null, 1)}\n`);
  });
  $('#dl-config').addEventListener('click', () => {
    const ans = JSON.parse(call('jc_web_config', state.request));
    if (!ans.ok) { tid('error').textContent = ans.error; tid('error').hidden = false; return; }
    download(`${fileStem()}.ini`, 'text/plain', ans.config);
  });
  $('#copy-link').addEventListener('click', async () => {
    try { await navigator.clipboard.writeText(location.href); $('#copy-link').textContent = 'Link copied'; } catch (err) { $('#copy-link').textContent = 'Copy the address bar'; }
    setTimeout(() => { $('#copy-link').textContent = 'Copy link to this setup'; }, 2000);
  });
  window.addEventListener('resize', () => { draw(); drawSweep(); });
  // Keys, outside text fields and menus: space plays/pauses, arrows step a frame.
  document.addEventListener('keydown', (e) => {
    const el = e.target;
    if (el.closest && el.closest('input, select, textarea, button, tr')) return;
    if (e.key === ' ') { e.preventDefault(); setPlaying(!state.playing); }
    else if (e.key === 'ArrowRight') { e.preventDefault(); stepFrame(1); }
    else if (e.key === 'ArrowLeft') { e.preventDefault(); stepFrame(-1); }
  });
}

// After the first picture, a few recomputes of the paper's inclines in idle
// slices, each undone in the same task (so none is ever shown): the first
// changes of a fresh page ran on unoptimised code (the engine's WebAssembly
// before its optimising tier, the drawing before the JIT's) and took 25 to
// 60 ms against 8 ms later; with runs and redraws alone as the warm-up, the
// first change still took 25 ms (the summary, table and URL code). Going
// through recompute() warms all of it. body[data-warm] when done.
const WARM_UP_RUNS = 18;
function warmUp(left) {
  if (left <= 0) { document.body.dataset.warm = 'true'; return; }
  if (state.run) {
    const keep = { overrides: state.overrides, dtMs: state.dtMs, t: state.t };
    state.overrides = { ...keep.overrides, incline: [15, 30, 45][left % 3] + (left % 2 ? 0.5 : 0) };
    recompute();
    Object.assign(state, keep);
    recompute();
  }
  setTimeout(() => warmUp(left - 1), 0);
}

async function start() {
  try {
    const variant = typeof createJumpcyl === 'function' ? 'inlined jumpcyl-single.js'
      : location.protocol === 'file:' ? 'jumpcyl-single.js' : 'jumpcyl.js';
    tid('module-variant').textContent = variant;
    if (typeof createJumpcyl !== 'function') {
      await new Promise((resolve, reject) => {
        const sc = document.createElement('script');
        sc.src = variant; sc.onload = resolve; sc.onerror = () => reject(new Error(`could not load ${variant}`));
        document.head.appendChild(sc);
      });
    }
    state.jc = await createJumpcyl();
    makeControls(JSON.parse(call0('jc_web_params')));
    for (const p of PRESETS) { // each preset's body, for the hoop's "rod" (its point mass)
      const r = simulate({ preset: p, 't-max': '1ms' });
      if (!r.ok) throw new Error(r.error);
      state.presetSetups[p] = r.setup;
    }
    buildControls();
    buildSweep();
    readUrl();
    wire();
    syncControls();
    recompute();
    document.body.dataset.firstRecomputeMs = document.body.dataset.recomputeMs; // before the warm-up's
    clearTimeout(state.urlTimer); // the first URL at once
    writeUrl();
    delete document.body.dataset.urlPending;
    document.body.dataset.ready = 'true';
    setTimeout(() => warmUp(WARM_UP_RUNS), 0);
  } catch (err) {
    const e = tid('error');
    e.textContent = `the engine failed: ${err.message}`;
    e.hidden = false;
    tid('first-liftoff-cm').textContent = '—';
  }
}
window.jumpcylPage = { state, recompute, simulate: (r) => simulate(r), controls: () => CONTROLS, sweep,
  runSweep: () => runSweep(), runSpread: () => runSpread(),
  seek: (t) => { setPlaying(false); state.t = t; draw(); } };
start();
})();
