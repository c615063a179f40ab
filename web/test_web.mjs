// The WebAssembly build against the native tool (make test-web):
//   node web/test_web.mjs --native build/jumpcyl --web out/web
// For the paper cylinder on 15, 30 and 45 degrees and the hoop preset, the
// wasm's first lift-off (x and t) equals `jumpcyl simulate --json`'s to
// REL_TOL, and the events match in count and kinds; a bad setup is a one-line
// error, not a crash; the one-file build answers the same as the two-file one.
// Prints the agreement it found, the time of a recompute and the file sizes.
import test, { after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import { mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { performance } from 'node:perf_hooks';

const REL_TOL = 1e-9;

function arg(name, fallback) {
  const i = process.argv.indexOf(name);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
}
const nativeTool = path.resolve(arg('--native', 'build/jumpcyl'));
const webDir = path.resolve(arg('--web', 'out/web'));
const require = createRequire(import.meta.url);

// Node has fetch(), which cannot read a file path: hand the module its
// bytes (a browser fetches jumpcyl.wasm beside jumpcyl.js itself).
async function loadModule(file) {
  const factory = require(path.join(webDir, file));
  const options = file === 'jumpcyl.js' ? { wasmBinary: readFileSync(path.join(webDir, 'jumpcyl.wasm')) } : {};
  return factory(options);
}

// The entry point's answer as text, the returned string freed.
function call(jc, request, fn = 'jc_web_simulate') {
  const ptr = jc.ccall(fn, 'number', ['string'], [JSON.stringify(request)]);
  assert.notEqual(ptr, 0, `${fn} returned NULL`);
  const text = jc.UTF8ToString(ptr);
  jc.ccall('jc_web_free', null, ['number'], [ptr]);
  return text;
}
const simulate = (jc, request) => JSON.parse(call(jc, request));
// sample-format "binary" (the page's way): the columns read from the wasm
// memory at samples.buffer, which is then freed.
function simulateBinary(jc, request) {
  const run = JSON.parse(call(jc, { ...request, 'sample-format': 'binary' }));
  const S = run.samples;
  if (S && S.buffer) {
    const n = S.count, base = S.buffer / 8;
    S.columns.forEach((c, k) => { S[c] = jc.HEAPF64.slice(base + k * n, base + (k + 1) * n); });
    jc.ccall('jc_web_free', null, ['number'], [S.buffer]);
  }
  return run;
}

function nativeRun(args) {
  return JSON.parse(execFileSync(nativeTool, ['simulate', '--json', ...args], { encoding: 'utf8' }));
}

const rel = (a, b) => (a === b ? 0 : Math.abs(a - b) / Math.max(Math.abs(a), Math.abs(b)));

const cases = [
  { name: 'paper 15 deg', request: { incline: 15 }, args: ['--incline', '15'] },
  { name: 'paper 30 deg', request: { incline: 30 }, args: ['--incline', '30'] },
  { name: 'paper 45 deg', request: { incline: 45 }, args: ['--incline', '45'] },
  { name: 'hoop', request: { preset: 'hoop' }, args: ['--preset', 'hoop'] },
];

const jc = await loadModule('jumpcyl.js');
const report = [];

for (const c of cases) {
  test(`${c.name}: first lift-off and events equal the native tool's`, () => {
    const native = nativeRun(c.args);
    const web = simulate(jc, c.request);
    assert.equal(web.ok, true, web.error);
    const nFirst = native.events.find((e) => e.kind === 'liftoff');
    assert.ok(nFirst, 'the native run lifts off');
    assert.ok(web.first_liftoff, 'the wasm run lifts off');
    assert.equal(web.events[web.first_liftoff.event].kind, 'liftoff');
    const dx = rel(web.first_liftoff.x, native.summary.first_liftoff_x);
    const dt = rel(web.first_liftoff.t, nFirst.t);
    assert.equal(web.events.length, native.events.length, 'event count');
    assert.deepEqual(web.events.map((e) => e.kind), native.events.map((e) => e.kind), 'event kinds');
    assert.equal(web.termination, native.termination);
    // The largest difference over every event's t, x, theta (informative).
    let worst = 0;
    web.events.forEach((e, i) => {
      for (const k of ['t', 'x', 'theta']) worst = Math.max(worst, rel(e[k], native.events[i][k]));
    });
    report.push({
      case: c.name, events: web.events.length,
      'x (cm)': (web.first_liftoff.x * 100).toFixed(6), 't (s)': web.first_liftoff.t.toFixed(9),
      'rel dx': dx, 'rel dt': dt, 'worst event rel': worst,
    });
    assert.ok(dx <= REL_TOL, `first lift-off x: wasm ${web.first_liftoff.x}, native ${native.summary.first_liftoff_x}`);
    assert.ok(dt <= REL_TOL, `first lift-off t: wasm ${web.first_liftoff.t}, native ${nFirst.t}`);
  });
}

// Random setups (a fixed seed), each run by both: the same answer or the
// same refusal, never an abort. Keeps the runs short (t-max 2 s).
test('random setups: the wasm and the native tool agree, and nothing aborts', () => {
  let seed = 20261125;
  const rnd = () => (seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648;
  const ranges = {
    incline: [0, 89], mu: [0, 1.5], restitution: [0, 1], theta0: [-180, 180], omega0: [-30, 30],
    'rod-mass': [0.001, 0.2], 'rod-offset': [0, 0.09], 'ramp-length': [0.2, 4],
    'drag-coefficient': [0, 1.5], 'rolling-resistance': [0, 0.005], g: [1, 25],
  };
  const presets = ['paper', 'hoop', 'rocking-hoop', 'disc'];
  let compared = 0, refused = 0, worst = 0;
  for (let i = 0; i < 30; ++i) {
    const request = { 't-max': 2 };
    if (rnd() < 0.3) request.preset = presets[Math.floor(rnd() * presets.length)];
    if (rnd() < 0.2) request['impact-law'] = ['poisson', 'newton'][Math.floor(rnd() * 2)];
    for (const [k, [a, b]] of Object.entries(ranges)) if (rnd() < 0.35) request[k] = a + (b - a) * rnd();
    const args = ['simulate', '--json', ...Object.entries(request).flatMap(([k, v]) => [`--${k}`, String(v)])];
    let native = null;
    try {
      native = JSON.parse(execFileSync(nativeTool, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }));
    } catch (err) {
      native = null; // refused (exit 2) or failed (exit 1): the wasm must refuse too
    }
    const web = simulate(jc, request);
    const label = JSON.stringify(request);
    if (!native) {
      assert.equal(web.ok, false, `${label}: the native tool refused it`);
      ++refused;
      continue;
    }
    assert.equal(web.ok, true, `${label}: ${web.error}`);
    assert.deepEqual(web.events.map((e) => e.kind), native.events.map((e) => e.kind), label);
    assert.equal(web.termination, native.termination, label);
    web.events.forEach((e, j) => {
      for (const k of ['t', 'x', 'theta']) worst = Math.max(worst, rel(e[k], native.events[j][k]));
    });
    if (web.first_liftoff) {
      assert.ok(rel(web.first_liftoff.x, native.summary.first_liftoff_x) <= REL_TOL, label);
    } else {
      assert.equal(native.summary.first_liftoff_x, null, label);
    }
    ++compared;
  }
  report.push({ case: `30 random setups: ${compared} compared, ${refused} refused by both`, 'worst event rel': worst });
  assert.ok(worst <= REL_TOL, `worst relative difference over the events: ${worst}`);
});

test('a bad setup is a one-line error, and the module goes on working', () => {
  for (const [request, word] of [
    [{ incline: 95 }, 'incline'],
    [{ incline: true }, 'incline'],
    [{ incline: '30furlongs' }, 'incline'],
    [{ inclin: 30 }, 'inclin'],
    [{ config: 'experiment.ini' }, 'config'],
    [{ 'dump-config': true }, 'dump-config'],
    [{ part: [1] }, 'part'],
    [{ preset: 'nope' }, 'preset'],
    [{ mu: 0.5, 'mu-s': 0.6 }, 'mu'],
    [{ part: ['rod:offset=1cm'] }, 'mass'],
    [{ 'sample-dt': -1 }, 'sample'],
  ]) {
    const out = simulate(jc, request);
    assert.equal(out.ok, false, JSON.stringify(request));
    assert.equal(typeof out.error, 'string');
    assert.ok(out.error.length > 0 && !out.error.includes('\n'), out.error);
    assert.ok(out.error.includes(word), `${JSON.stringify(request)}: ${out.error}`);
    if (request.incline === 95) report.push({ case: 'incline 95', error: out.error });
  }
  const notJson = jc.ccall('jc_web_simulate', 'number', ['string'], ['{incline: 30']);
  assert.equal(JSON.parse(jc.UTF8ToString(notJson)).ok, false);
  jc.ccall('jc_web_free', null, ['number'], [notJson]);
  assert.equal(simulate(jc, {}).ok, true);
});

// Values are read as the command line reads them (cli/commands/units.c):
// a unit string is the same run as its SI number, and as the tool's option.
test('values with units read as on the command line', () => {
  for (const [withUnit, plain, args] of [
    [{ 'rod-offset': '5.5cm' }, { 'rod-offset': 0.055 }, ['--rod-offset', '5.5cm']],
    [{ incline: '15deg', 'rod-mass': '32.1g' }, { incline: 15, 'rod-mass': 0.0321 }, ['--incline', '15deg', '--rod-mass', '32.1g']],
    [{ part: ['disc:mass=0.3kg', 'rod:mass=32.1g,offset=5.5cm,radius=4.75mm'], radius: '10cm' },
      { part: ['disc:mass=0.3', 'rod:mass=0.0321,offset=0.055,radius=0.00475'], radius: 0.1 },
      ['--part', 'disc:mass=0.3kg', '--part', 'rod:mass=32.1g,offset=5.5cm,radius=4.75mm', '--radius', '10cm']],
  ]) {
    const a = simulate(jc, withUnit), b = simulate(jc, plain);
    assert.equal(a.ok, true, a.error);
    assert.deepEqual(a, b, JSON.stringify(withUnit));
    const native = nativeRun(args);
    assert.deepEqual(a.setup, native.setup, JSON.stringify(args));
    assert.deepEqual(a.events.map((e) => e.kind), native.events.map((e) => e.kind), JSON.stringify(args));
  }
});

test('an unknown key is refused by its name', () => {
  const out = simulate(jc, { incline: 30, 'rod-ofset': 0.05 });
  assert.equal(out.ok, false);
  assert.ok(out.error.includes('rod-ofset'), out.error);
});

// The answer is `simulate --json`'s document with the page's extras.
test('the answer has simulate --json\'s fields, plus samples and first_liftoff', () => {
  const web = simulate(jc, { incline: 30 });
  const native = nativeRun(['--incline', '30']);
  const extras = ['ok', 'version', 'samples', 'final_mode', 'ode_steps', 'first_liftoff', 'paper_row'];
  assert.deepEqual(Object.keys(web).filter((k) => !extras.includes(k)), Object.keys(native));
  assert.deepEqual(Object.keys(web.setup), Object.keys(native.setup));
  assert.deepEqual(Object.keys(web.summary), Object.keys(native.summary));
  web.events.forEach((e, j) => assert.deepEqual(Object.keys(e), Object.keys(native.events[j])));
});

test('the sampled trajectory comes at the requested spacing', () => {
  const web = simulate(jc, { incline: 30, 'sample-dt': 0.01 });
  assert.equal(web.ok, true, web.error);
  const s = web.samples;
  assert.ok(s.count > 10);
  for (const k of ['t_s', 'x_m', 'y_m', 'theta_rad', 'mode', 'normal_N', 'friction_N', 'gap_m', 'kinetic_J', 'potential_J'])
    assert.equal(s[k].length, s.count, k);
  assert.ok(s.mode.includes('flight') && s.mode.includes('rolling'));
  // Fixed samples at k * 0.01 s, with the events' samples between them.
  const fixed = s.t_s.filter((t) => Math.abs(t / 0.01 - Math.round(t / 0.01)) < 1e-9);
  assert.ok(fixed.length >= Math.floor(web.t_end / 0.01), `${fixed.length} fixed samples up to ${web.t_end} s`);
  // Sampling does not change the events.
  assert.deepEqual(web.events, simulate(jc, { incline: 30 }).events);
});

// The samples against the tool's --csv, which prints 12 significant digits
// (9 for forces, slip, gap and losses): the same columns under the same
// names, in the same order; every value within half a unit of the CSV's
// last digit plus 1e-9 of its column's largest value; the modes equal.
// Half a unit in the last digit of a number printed with %g ("1.5e-05", "0.125").
function halfLastDigit(text) {
  const [mantissa, exponent = '0'] = text.toLowerCase().split('e');
  const decimals = mantissa.includes('.') ? mantissa.split('.')[1].length : 0;
  return 0.5 * 10 ** (Number(exponent) - decimals);
}

test('the samples equal the native tool\'s CSV', () => {
  const dir = mkdtempSync(path.join(tmpdir(), 'jc-web-'));
  try {
    for (const [request, args] of [
      [{ incline: 45, 'sample-dt': 0.01 }, ['--incline', '45']],
      [{ preset: 'hoop', 'sample-dt': 0.05, 't-max': 5 }, ['--preset', 'hoop', '--t-max', '5']],
    ]) {
      const csv = path.join(dir, 'run.csv');
      execFileSync(nativeTool, ['simulate', ...args, '--sample-dt', String(request['sample-dt']), '--csv', csv],
        { stdio: 'ignore' });
      const [head, ...rows] = readFileSync(csv, 'utf8').trim().split('\n').map((l) => l.split(','));
      const web = simulate(jc, request);
      assert.equal(web.ok, true, web.error);
      assert.equal(web.samples.count, rows.length, 'sample count');
      assert.deepEqual(Object.keys(web.samples), ['count', ...head]);
      let worst = 0;
      head.forEach((name, j) => {
        const col = web.samples[name];
        assert.ok(col, `column ${name}`);
        if (name === 'mode') {
          assert.deepEqual(col, rows.map((r) => r[j]));
          return;
        }
        const scale = Math.max(...col.map(Math.abs), 1e-300);
        col.forEach((v, i) => {
          const text = rows[i][j];
          const excess = Math.abs(v - Number(text)) - halfLastDigit(text);
          worst = Math.max(worst, excess / scale);
        });
      });
      report.push({ case: `samples ${JSON.stringify(args)}: beyond the CSV's rounding / column scale`, samples: rows.length, 'worst event rel': worst });
      assert.ok(worst <= REL_TOL, `${JSON.stringify(request)}: worst difference / column scale ${worst}`);
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

// C's printf("%.*g", p, v), written out: the text form of a sample column.
function formatG(v, p) {
  if (Number.isNaN(v)) return 'nan';
  if (!Number.isFinite(v)) return v < 0 ? '-inf' : 'inf';
  if (v === 0) return Object.is(v, -0) ? '-0' : '0';
  const [m, ex] = v.toExponential(p - 1).split('e');
  const e = Number(ex);
  const strip = (t) => (t.includes('.') ? t.replace(/0+$/, '').replace(/\.$/, '') : t);
  if (e < -4 || e >= p) return `${strip(m)}e${e < 0 ? '-' : '+'}${String(Math.abs(e)).padStart(2, '0')}`;
  return strip(v.toFixed(p - 1 - e));
}

// The page's CSV download (jc_web_csv) has simulate --csv's layout: the same
// header (the library's table of sample columns), a row per sample, each
// cell the wasm's own sample printed with the column's digits (12, or 9 for
// forces, slip, gap and losses), within the rounding of the native tool's.
test('jc_web_csv writes the samples as simulate --csv does', () => {
  const nine = new Set(['normal_N', 'friction_N', 'slip_mps', 'gap_m', 'friction_loss_J', 'impact_loss_J',
    'air_loss_J', 'rolling_resistance_loss_J']);
  const dir = mkdtempSync(path.join(tmpdir(), 'jc-web-'));
  try {
    for (const [request, args] of [
      [{ incline: 30, 'sample-dt': '10ms' }, ['--incline', '30', '--sample-dt', '10ms']],
      [{ preset: 'hoop', 'sample-dt': 0.05, 't-max': 5 }, ['--preset', 'hoop', '--sample-dt', '0.05', '--t-max', '5']],
      [{ incline: 45, 'drag-coefficient': 1.2, 'sample-dt': '1ms' },
        ['--incline', '45', '--drag-coefficient', '1.2', '--sample-dt', '1ms']],
    ]) {
      const file = path.join(dir, 'run.csv');
      execFileSync(nativeTool, ['simulate', ...args, '--csv', file], { stdio: 'ignore' });
      const ans = JSON.parse(call(jc, request, 'jc_web_csv'));
      assert.equal(ans.ok, true, ans.error);
      const [head, ...rows] = ans.csv.split('\n').slice(0, -1).map((l) => l.split(','));
      const [nhead, ...nrows] = readFileSync(file, 'utf8').split('\n').slice(0, -1).map((l) => l.split(','));
      assert.ok(ans.csv.endsWith('\n'));
      assert.deepEqual(head, nhead);
      assert.equal(rows.length, nrows.length, 'rows');
      const web = simulate(jc, request).samples;
      assert.equal(web.count, rows.length);
      let worst = 0;
      head.forEach((name, j) => {
        const col = web[name];
        if (name === 'mode') {
          rows.forEach((r, i) => { assert.equal(r[j], col[i]); assert.equal(r[j], nrows[i][j]); });
          return;
        }
        const scale = Math.max(...col.map(Math.abs), 1e-300);
        rows.forEach((r, i) => {
          assert.equal(r[j], formatG(col[i] === null ? NaN : col[i], nine.has(name) ? 9 : 12), `${name}[${i}]`);
          const excess = Math.abs(Number(r[j]) - Number(nrows[i][j])) - halfLastDigit(r[j]) - halfLastDigit(nrows[i][j]);
          worst = Math.max(worst, excess / scale);
        });
      });
      assert.ok(worst <= REL_TOL, `${JSON.stringify(request)}: worst difference / column scale ${worst}`);
    }
    const bad = JSON.parse(call(jc, { incline: 95 }, 'jc_web_csv'));
    assert.equal(bad.ok, false);
    assert.match(bad.error, /incline/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('the one-file build answers as the two-file one', async () => {
  const single = await loadModule('jumpcyl-single.js');
  for (const request of [{}, { preset: 'hoop', 'sample-dt': 0.05 }, { incline: 95 }])
    assert.equal(call(single, request), call(jc, request));
  const presets = JSON.parse(jc.UTF8ToString(jc.ccall('jc_web_presets', 'number', [], [])));
  assert.ok(presets.some((p) => p.name === 'hoop'));
});

test('binary samples (sample-format "binary") are the JSON columns, bit for bit', () => {
  for (const request of [{ incline: 45, 'sample-dt': '1ms' }, { preset: 'hoop', 'sample-dt': '10ms', 't-max': 5 },
    { incline: 30 }]) {
    const a = simulate(jc, request), b = simulateBinary(jc, request);
    assert.equal(b.samples.count, a.samples.count);
    assert.deepEqual(b.samples.mode, a.samples.mode);
    assert.equal(b.samples.columns.length, 19);
    for (const c of b.samples.columns) {
      assert.equal(b.samples[c].length, a.samples.count, c);
      for (let i = 0; i < a.samples.count; ++i) {
        const x = a.samples[c][i], y = b.samples[c][i];
        assert.ok(x === y || (x === null && !Number.isFinite(y)), `${c}[${i}]: ${x} vs ${y}`);
      }
    }
    const { samples: sa, ...ra } = a, { samples: sb, ...rb } = b;
    assert.deepEqual(rb, ra); // the rest of the answer is the same
  }
  const bad = simulate(jc, { 'sample-format': 'csv' });
  assert.equal(bad.ok, false);
  assert.match(bad.error, /sample-format/);
});

test('recompute time and sizes (measured, printed)', () => {
  const times = {};
  for (const [label, request] of [
    ['paper 30 deg, events only', { incline: 30 }],
    ['paper 30 deg, sample-dt 10 ms', { incline: 30, 'sample-dt': 0.01 }],
    ['paper 30 deg, sample-dt 1 ms', { incline: 30, 'sample-dt': 0.001 }],
    ['hoop (60 s), sample-dt 10 ms', { preset: 'hoop', 'sample-dt': 0.01 }],
  ]) {
    simulate(jc, request); // warm-up
    const ms = [];
    let bytes = 0;
    for (let i = 0; i < 15; ++i) {
      const t0 = performance.now();
      const text = call(jc, request);
      JSON.parse(text);
      ms.push(performance.now() - t0);
      bytes = text.length;
    }
    ms.sort((a, b) => a - b);
    times[label] = { 'median ms': +ms[7].toFixed(2), 'min ms': +ms[0].toFixed(2), 'answer kB': +(bytes / 1024).toFixed(1) };
  }
  for (const [label, request] of [
    ['paper 30 deg, sample-dt 1 ms, binary', { incline: 30, 'sample-dt': 0.001 }],
    ['hoop (60 s), sample-dt 10 ms, binary', { preset: 'hoop', 'sample-dt': 0.01 }],
  ]) {
    simulateBinary(jc, request);
    const ms = [];
    for (let i = 0; i < 15; ++i) {
      const t0 = performance.now();
      simulateBinary(jc, request);
      ms.push(performance.now() - t0);
    }
    ms.sort((a, b) => a - b);
    times[label] = { 'median ms': +ms[7].toFixed(2), 'min ms': +ms[0].toFixed(2), 'answer kB': null };
  }
  console.log('\nRecompute (jc_web_simulate + text + JSON.parse; binary: + the columns copied), 15 runs:');
  console.table(times);
  const sizes = {};
  for (const f of ['jumpcyl.wasm', 'jumpcyl.js', 'jumpcyl-single.js', 'index.html'])
    sizes[f] = { bytes: statSync(path.join(webDir, f)).size };
  console.log('Sizes:');
  console.table(sizes);
});
// After every test: what agreed how well (and the studies' times in wasm).
after(() => {
  console.log('Agreement with the native tool (relative differences):');
  console.table(report);
});

// The page's marks: Table 1's row for the paper's cylinder on 15, 30, 45 deg
// (the printed jump point as `jumpcyl paper --json` prints it), null otherwise.
test('paper_row: Table 1 for the paper cylinder on its inclines, else null', () => {
  const paper = JSON.parse(execFileSync(nativeTool, ['paper', '--json'], { encoding: 'utf8' }));
  for (const row of paper.rows) {
    const web = simulate(jc, { incline: row.incline_deg });
    assert.equal(web.paper_row.incline_deg, row.incline_deg);
    assert.equal(web.paper_row.printed_x_m, row.printed.x);
    assert.equal(web.paper_row.printed_theta_rad, row.printed.theta);
  }
  assert.equal(simulate(jc, { incline: 20 }).paper_row, null);
  assert.equal(simulate(jc, { incline: 30, 'rod-mass': '40g' }).paper_row, null);
  assert.equal(simulate(jc, { preset: 'hoop' }).paper_row, null);
  assert.notEqual(simulate(jc, { incline: 30, mu: 0.3 }).paper_row, null); // friction is not in the paper's model
});

// The page's "setup as experiment file": cli_config_write's text, as
// `simulate --dump-config` prints it for the same options.
test('jc_web_config is --dump-config\'s text', () => {
  const config = (request) => {
    const ptr = jc.ccall('jc_web_config', 'number', ['string'], [JSON.stringify(request)]);
    const text = jc.UTF8ToString(ptr);
    jc.ccall('jc_web_free', null, ['number'], [ptr]);
    return JSON.parse(text);
  };
  for (const [request, args] of [
    [{}, []],
    [{ preset: 'hoop', omega0: '120rpm', restitution: 0.45 }, ['--preset', 'hoop', '--omega0', '120rpm', '--restitution', '0.45']],
    [{ incline: '15deg', 'rod-offset': '6cm', 'impact-law': 'newton' }, ['--incline', '15deg', '--rod-offset', '6cm', '--impact-law', 'newton']],
  ]) {
    const ans = config(request);
    assert.equal(ans.ok, true, ans.error);
    assert.equal(ans.config, execFileSync(nativeTool, ['simulate', ...args, '--dump-config'], { encoding: 'utf8' }));
  }
  const bad = config({ incline: 95 });
  assert.equal(bad.ok, false);
  assert.match(bad.error, /incline/);
});

// ---- the studies: jc_web_sweep and jc_web_uncertainty ----

// A CSV's header and rows (no quoting in the tool's batch files).
function readCsv(file) {
  const [head, ...rows] = readFileSync(file, 'utf8').trim().split('\n').map((l) => l.split(','));
  return { head, rows };
}
// A number from the wasm against the tool's CSV text (12 digits): equal
// within the text's rounding plus REL_TOL of its size; null is an empty field.
function sameNumber(web, text) {
  if (web === null || text === '') return web === null && text === '';
  return Math.abs(web - Number(text)) <= halfLastDigit(text) + REL_TOL * Math.abs(Number(text));
}

// The page's sweep is the tool's sweep: for each setup and grid, the rows of
// `jumpcyl sweep --vary NAME=lo:hi:step` with the step the page's n makes
// ((hi - lo) / (n - 1) in SI, given with its SI unit: the same grid of
// doubles); the varied value, the first event, the first slip's and
// lift-off's x, the lift-offs and the termination of every row, within
// REL_TOL beyond the CSV's 12 digits (the wasm and the native build may
// differ in the last bits).
test('jc_web_sweep gives the rows of jumpcyl sweep for the same setup and grid', () => {
  const dir = mkdtempSync(path.join(tmpdir(), 'jc-web-'));
  try {
    for (const [setup, args, vary, lo, hi, n] of [
      [{ incline: 30 }, ['--incline', '30'], 'rod-offset', '2cm', '8cm', 25],
      [{ preset: 'hoop', restitution: 0.4, incline: 3 }, ['--preset', 'hoop', '--restitution', '0.4'], 'incline', '5deg', '40deg', 15],
      [{ incline: 45 }, ['--incline', '45'], 'mu', 0.05, 1.2, 24],
      [{ incline: 20, 'rod-mass': '40g' }, ['--incline', '20', '--rod-mass', '40g'], 'restitution', 0, 1, 11],
    ]) {
      const t0 = performance.now();
      const web = JSON.parse(call(jc, { setup, vary, lo, hi, n }, 'jc_web_sweep'));
      const ms = performance.now() - t0;
      assert.equal(web.ok, true, web.error);
      assert.equal(web.rows.length, n);
      const step = (web.rows[n - 1].value_si - web.rows[0].value_si) / (n - 1);
      const file = path.join(dir, 'sweep.csv');
      execFileSync(nativeTool, ['sweep', ...args, '--vary', `${vary}=${lo}:${hi}:${step}${web.si_unit}`, '--output', file,
        '--quiet'], { stdio: 'ignore' });
      const { head, rows } = readCsv(file);
      assert.equal(rows.length, n, `${vary}: the tool's rows`);
      const col = (name) => head.indexOf(name);
      const perColumn = web.si_unit === 'rad' ? 180 / Math.PI : 1; // the CSV's values: SI, angles in degrees
      let worst = 0;
      web.rows.forEach((r, i) => {
        const t = rows[i], label = `${vary} row ${i}`;
        assert.ok(sameNumber(r.value_si * perColumn, t[1]), `${label}: value ${r.value_si * perColumn} vs ${t[1]}`);
        assert.equal(r.first_event ?? '', t[col('first_event')], label);
        assert.equal(r.termination, t[col('termination')], label);
        assert.equal(r.liftoffs === null ? '' : String(r.liftoffs), t[col('liftoffs')], label);
        for (const [key, name] of [['slip_x_m', 'first_slip_x_m'], ['liftoff_x_m', 'first_liftoff_x_m']]) {
          const text = t[col(name)];
          assert.ok(sameNumber(r[key], text), `${label}: ${key} ${r[key]} vs the tool's ${text}`);
          if (r[key] !== null) worst = Math.max(worst, Math.max(0, Math.abs(r[key] - Number(text)) - halfLastDigit(text)) / (Math.abs(Number(text)) || 1));
        }
      });
      report.push({ case: `sweep ${vary} ${lo}..${hi}, ${n} points (${ms.toFixed(0)} ms in wasm)`, 'worst event rel': worst });
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('jc_web_sweep: the varied value replaces the setup\'s, and the current value is given', () => {
  const a = JSON.parse(call(jc, { setup: { incline: 12 }, vary: 'incline', lo: 10, hi: 40, n: 4 }, 'jc_web_sweep'));
  const b = JSON.parse(call(jc, { setup: {}, vary: 'incline', lo: '10deg', hi: '40deg', n: 4 }, 'jc_web_sweep'));
  assert.equal(a.ok, true, a.error);
  assert.deepEqual(a.rows, b.rows);
  assert.ok(Math.abs(a.current - 12) < 1e-12 && Math.abs(b.current - 30) < 1e-12, `${a.current}, ${b.current}`);
  assert.equal(a.unit, 'deg');
  assert.ok(Math.abs(a.rows[1].value - 20) < 1e-12 && Math.abs(a.rows[3].value - 40) < 1e-12);
  // a row of the grid is the single run of that value
  const single = simulate(jc, { incline: 20 });
  assert.ok(rel(a.rows[1].liftoff_x_m, single.first_liftoff.x) <= REL_TOL);
});

test('jc_web_sweep: a bad request is a one-line error naming the value and what is allowed', () => {
  for (const [request, words] of [
    [{ vary: 'incline', lo: 10, hi: 40, n: 1000 }, ['n: 1000', 'from 2 to 401']],
    [{ vary: 'incline', lo: 10, hi: 40, n: 1 }, ['n: 1 ', 'from 2 to 401']],
    [{ vary: 'incline', lo: 10, hi: 40, n: '20' }, ['n: "20"', 'from 2 to 401']],
    [{ vary: 'incline', lo: 10, hi: 95 }, ['hi: ', '95', '90']],
    [{ vary: 'incline', lo: 40, hi: 10 }, ['lo 40 deg', 'hi 10 deg']],
    [{ vary: 'incline', lo: '10furlongs', hi: 40 }, ['lo: ', 'furlongs']],
    [{ vary: 'impact-law', lo: 0, hi: 2 }, ['impact-law', 'names']],
    [{ vary: 'inclination', lo: 0, hi: 2 }, ['inclination', 'allowed: radius']],
    [{ vary: 'incline', hi: 40 }, ['lo: missing']],
    [{ vary: 'incline', lo: 10, hi: 40, points: 5 }, ["unknown key 'points'"]],
    [{ vary: 'incline', lo: 10, hi: 40, setup: { incline: 95 } }, ['incline 95 deg']],
    [{ vary: 'incline', lo: 10, hi: 40, setup: 30 }, ['setup: must be an object']],
    [{ vary: 'rod-mass', lo: 0.01, hi: 0.05, setup: { preset: 'hoop' } }, ['vary: ']],
  ]) {
    const out = JSON.parse(call(jc, request, 'jc_web_sweep'));
    assert.equal(out.ok, false, JSON.stringify(request));
    assert.ok(!out.error.includes('\n'), out.error);
    for (const w of words) assert.ok(out.error.includes(w), `${JSON.stringify(request)}: ${out.error}`);
    if (request.n === 1000 || request.vary === 'rod-mass') report.push({ case: `sweep ${JSON.stringify(request)}`, error: out.error });
  }
  assert.equal(JSON.parse(call(jc, { vary: 'incline', lo: 10, hi: 40, n: 3 }, 'jc_web_sweep')).ok, true);
});

// The spread of the jump site is `jumpcyl mc --json`'s for the same setup,
// samples and seed (the same Philox draws): the counts equal, the first
// lift-off's mean, sd and quantiles within REL_TOL.
test('jc_web_uncertainty is jumpcyl mc --json\'s summary', () => {
  for (const [request, args] of [
    [{ setup: { incline: 15 }, samples: 300 }, ['--incline', '15', '--samples', '300']],
    [{ setup: { incline: 30, mu: 0.4 }, samples: 200, seed: 7 }, ['--incline', '30', '--mu', '0.4', '--samples', '200', '--seed', '7']],
  ]) {
    const t0 = performance.now();
    const web = JSON.parse(call(jc, request, 'jc_web_uncertainty'));
    const ms = performance.now() - t0;
    assert.equal(web.ok, true, web.error);
    const mc = JSON.parse(execFileSync(nativeTool, ['mc', ...args, '--json'], { encoding: 'utf8' }));
    for (const k of ['samples', 'valid', 'invalid', 'slides_at_start', 'no_liftoff']) assert.equal(web[k], mc[k], k);
    let worst = 0;
    for (const k of ['count', 'fraction', 'mean', 'sd', 'p2_5', 'p50', 'p97_5']) {
      const d = rel(web.first_liftoff_x_m[k], mc.first_liftoff_x_m[k]);
      worst = Math.max(worst, d);
      assert.ok(d <= REL_TOL, `${k}: ${web.first_liftoff_x_m[k]} vs ${mc.first_liftoff_x_m[k]}`);
    }
    assert.ok(!web.spreads.some((s) => s.name === 'mu' && request.setup.mu !== undefined), 'a value set is not spread');
    report.push({ case: `spread ${JSON.stringify(request.setup)}, ${request.samples} samples (${ms.toFixed(0)} ms in wasm)`,
      'x (cm)': (web.first_liftoff_x_m.p50 * 100).toFixed(3), 'worst event rel': worst });
  }
  const bad = JSON.parse(call(jc, { samples: 5 }, 'jc_web_uncertainty'));
  assert.equal(bad.ok, false);
  assert.match(bad.error, /samples: 5 is not a whole number from 10 to 20000/);
});
