// web/afv.js -- the page's one script, run twice: as a Web Worker it owns
// the library (afv.wasm, built by `make web` from afv's own C sources) and
// steps the tissue; in the page it reads the controls, draws the cells and
// the plots.  The worker keeps the page responsive while a tissue relaxes
// (at P0 8.8 afv run's relaxation is its full 100000 steps).  No framework,
// no network: the page, this file and afv.wasm are all it loads.
'use strict';

// Indices of web_observe's numbers (web/afv_web.c, OBS_*).
const OBS = {energy: 0, giant: 1, omega: 2, clusters: 3, step: 4, time: 5,
             maxForce: 6, n: 7, box: 8, count: 9};
const AFV_EUNSTABLE = 8;

if (typeof document === 'undefined') workerMain(); else pageMain();

// ---- the worker: the library -------------------------------------------
function workerMain() {
  let lib = null;          // afv.wasm's exports
  const f64 = (ptr, n) => new Float64Array(lib.memory.buffer, ptr, n);
  const cString = (ptr) => {
    const bytes = new Uint8Array(lib.memory.buffer, ptr);
    let end = 0;
    while (bytes[end]) end++;
    return new TextDecoder().decode(bytes.subarray(0, end));
  };
  const writeScratch = (text) => {
    const ptr = lib.web_scratch();
    const bytes = new Uint8Array(lib.memory.buffer, ptr, 64);
    bytes.set(new TextEncoder().encode(text.slice(0, 63)));
    bytes[Math.min(text.length, 63)] = 0;
    return ptr;
  };
  // The numbers and the outlines of the tissue now (copies: the worker
  // hands them over; wasm memory may grow under any view of it).
  const snapshot = () => {
    const obsPtr = lib.web_observe();
    if (!obsPtr) return {obs: null, shapes: null};
    const obs = f64(obsPtr, OBS.count).slice();
    const len = lib.web_shapes();
    const shapes = f64(lib.web_shape_data(), len).slice();
    return {obs, shapes};
  };
  const send = (msg, snap) => postMessage(Object.assign(msg, snap),
                                          snap.shapes ? [snap.shapes.buffer] : []);
  const relaxProgress = (iter, energy, maxForce) =>
    send({type: 'relaxing', iter, energy, maxForce}, snapshot());

  const ready = fetch('afv.wasm')
    .then((r) => { if (!r.ok) throw new Error('afv.wasm: HTTP ' + r.status); return r.arrayBuffer(); })
    .then((bytes) => WebAssembly.instantiate(bytes, {
      env: {web_relax_progress: relaxProgress},
      // The library links no system call it uses here; any other import
      // of wasi-libc answers "not supported" (ENOSYS).
      wasi_snapshot_preview1: new Proxy({}, {get: () => () => 52})}))
    .then(({instance}) => { lib = instance.exports; lib._initialize(); });

  const commands = {
    reset(m) {
      const p = m.params;
      const st = lib.web_reset(p.N, p.P0, p.v0, p.Lambda, p.dt, p.cap, p.Dr,
                               Math.floor(p.seed / 4294967296), p.seed % 4294967296,
                               p.relax_max_steps, 500);
      const relax = {};
      for (const k of ['iterations', 'converged', 'at_kink', 'refused', 'energy0', 'energy', 'max_force'])
        relax[k] = lib.web_relax_get(writeScratch(k));
      return {status: st, error: st ? cString(lib.afv_strerror(st)) : '', relax,
              badCell: st === AFV_EUNSTABLE ? lib.web_bad_cell() : -1};
    },
    run(m) {
      const st = lib.web_step(m.steps);
      return {status: st, error: st ? cString(lib.afv_strerror(st)) : '',
              badCell: st === AFV_EUNSTABLE ? lib.web_bad_cell() : -1,
              badDisp: st === AFV_EUNSTABLE ? lib.web_bad_disp() : 0};
    },
    set(m) {
      const p = m.params;
      const st = lib.web_set(p.P0, p.v0, p.Lambda, p.dt, p.cap);
      return {status: st, error: st ? cString(lib.afv_strerror(st)) : ''};
    },
  };
  onmessage = (ev) => {
    const m = ev.data;
    ready.then(() => {
      const t0 = performance.now(), answer = commands[m.cmd](m), snap = snapshot();
      send(Object.assign({type: m.cmd, id: m.id, workMs: performance.now() - t0}, answer), snap);
    })
      .catch((err) => postMessage({type: 'fatal', id: m.id, error: String(err)}));
  };
}

// ---- the page ----------------------------------------------------------
function pageMain() {
  const $ = (id) => document.getElementById(id);
  const serveHint = 'open the page through a local server: make web, then ' +
    'python3 -m http.server -d web -b 127.0.0.1 8000 and http://127.0.0.1:8000/';
  let worker;
  try {
    worker = new Worker('afv.js');
  } catch (err) {   // a file:// address: no worker
    $('status').textContent = `The page cannot start its worker (${err.message}): ${serveHint}`;
    $('status').className = 'bad';
    return;
  }
  worker.onerror = (ev) => { console.error('afv.js worker: ' + ev.message); setStatus('the worker failed: ' + ev.message, true); };
  const pending = new Map();   // request id -> resolve
  let nextId = 1;
  const ask = (cmd, extra) => new Promise((resolve) => {
    const id = nextId++;
    pending.set(id, resolve);
    worker.postMessage(Object.assign({cmd, id}, extra));
  });

  // The controls: afv run's key, its accepted range (cmd/run.c, run_keys)
  // and the page's own limit; clamp() returns [value, reason or ''].
  const controls = {
    P0: {min: 1e-3, minOpen: true, why: 'P0 must be > 0 (afv run refuses P0 <= 0)'},
    v0: {},   // any finite number; |v0| dt <= L is checked in clampAll
    Lambda: {},
    dt: {min: 1e-5, minOpen: true, why: 'dt must be > 0 (afv run refuses dt <= 0)'},
    cap: {min: 0, why: 'cap must be >= 0 (afv run refuses a negative cap)'},
    N: {min: 3, max: 400, integer: true,
        why: 'N: afv run needs the box side L = sqrt(N pi / 0.5) >= 4 l, so N >= 3; the page draws at most 400 cells'},
    seed: {min: 0, max: Number.MAX_SAFE_INTEGER, integer: true,
           why: 'seed: an integer >= 0 (afv run takes up to 2^64 - 1; the page up to 2^53 - 1, the integers a JavaScript number holds)'},
    spf: {min: 1, max: 1000, integer: true, why: 'steps per frame: 1 .. 1000'},
  };
  let params = {};             // the values in use, clamped
  const readControl = (name) => {
    const c = controls[name], input = $(name), text = input.value.trim();
    let x = Number(text), why = '';
    if (text === '' || !Number.isFinite(x)) {
      x = params[name];
      why = `"${text}" is not a finite number: kept ${x}`;
    } else {
      if (c.integer && !Number.isInteger(x)) { x = Math.round(x); why = `rounded to ${x}`; }
      if (c.min !== undefined && (c.minOpen ? x <= 0 : x < c.min)) { x = c.min; why = `${c.why}: set to ${x}`; }
      if (c.max !== undefined && x > c.max) { x = c.max; why = `${c.why}: set to ${x}`; }
    }
    input.value = String(x);
    $(name + '-why').textContent = why;
    params[name] = x;
  };
  const boxSide = (N) => Math.sqrt(N * Math.PI / 0.5);
  const clampAll = () => {
    for (const name of Object.keys(controls)) readControl(name);
    const vmax = boxSide(params.N) / params.dt;
    if (Math.abs(params.v0) > vmax) {
      params.v0 = Math.sign(params.v0) * vmax;
      $('v0').value = String(params.v0);
      $('v0-why').textContent = `afv run refuses |v0| dt > L (the box side ${boxSide(params.N).toFixed(3)}): set to ${params.v0}`;
    }
  };

  // ---- state shown -------------------------------------------------------
  let running = false, busy = false, broken = false, current = null;
  let history = [];            // [t, N_GC/N, Omega, clusters]
  const setStatus = (text, bad) => { $('status').textContent = text; $('status').className = bad ? 'bad' : ''; };
  const setRunning = (on) => {
    running = on && !broken;
    $('start').textContent = running ? 'Pause' : 'Start';
  };

  const palette = ['#4e79a7', '#f28e2b', '#59a14f', '#e15759', '#b07aa1',
                   '#76b7b2', '#edc948', '#ff9da7', '#9c755f', '#86bcb6'];
  const isolatedColour = '#c8c8c8';
  // Colour of each cluster label: the largest cluster first; single cells grey.
  const clusterColours = (shapes) => {
    const size = new Map();
    for (let k = 0; k < shapes.length; k += 4 + 3 * shapes[k + 3])
      size.set(shapes[k + 2], (size.get(shapes[k + 2]) || 0) + 1);
    const order = [...size.keys()].sort((a, b) => size.get(b) - size.get(a) || a - b);
    const colour = new Map();
    order.forEach((label, rank) => colour.set(label, size.get(label) > 1 ? palette[rank % palette.length] : isolatedColour));
    return colour;
  };

  // The cells as the library computed them: straight contact edges and
  // arcs of radius l = 1, in the periodic box (images near its sides).
  const canvas = $('tissue'), ctx = canvas.getContext('2d');
  const draw = (obs, shapes) => {
    const px = canvas.width, L = obs[OBS.box], s = px / L;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = '#ffffff';
    ctx.fillRect(0, 0, px, px);
    const colour = clusterColours(shapes);
    ctx.lineWidth = Math.max(1, 0.04 * s);
    ctx.strokeStyle = '#333333';
    for (let k = 0; k < shapes.length; k += 4 + 3 * shapes[k + 3]) {
      const cx = shapes[k], cy = shapes[k + 1], m = shapes[k + 3];
      ctx.fillStyle = colour.get(shapes[k + 2]);
      for (const ox of [-L, 0, L]) for (const oy of [-L, 0, L]) {
        const x = cx + ox, y = cy + oy;
        if (x + 1 < 0 || x - 1 > L || y + 1 < 0 || y - 1 > L) continue;
        ctx.beginPath();
        for (let q = 0; q < m; q++) {
          const a = k + 4 + 3 * q, b = k + 4 + 3 * ((q + 1) % m);
          const sx = (x + shapes[a]) * s, sy = (L - y - shapes[a + 1]) * s;
          if (q === 0) ctx.moveTo(sx, sy);
          if (shapes[a + 2] >= 0) ctx.lineTo((x + shapes[b]) * s, (L - y - shapes[b + 1]) * s);
          else {
            // model angles run counter-clockwise with y up: on the screen
            // (y down) they are negated and the arc runs anticlockwise
            const t0 = Math.atan2(shapes[a + 1], shapes[a]);
            let t1 = m === 1 ? t0 + 2 * Math.PI : Math.atan2(shapes[b + 1], shapes[b]);
            if (t1 <= t0) t1 += 2 * Math.PI;
            ctx.arc(x * s, (L - y) * s, s, -t0, -t1, true);
          }
        }
        ctx.closePath();
        ctx.fill();
        ctx.stroke();
      }
    }
    ctx.strokeStyle = '#000000';
    ctx.lineWidth = 2;
    ctx.strokeRect(1, 1, px - 2, px - 2);
  };

  // Small time plots: N_GC/N, Omega (0..1) and the number of clusters.
  const plot = (id, col, fixedMax) => {
    const c = $(id), g = c.getContext('2d'), w = c.width, h = c.height;
    g.fillStyle = '#ffffff';
    g.fillRect(0, 0, w, h);
    g.strokeStyle = '#999999';
    g.strokeRect(0.5, 0.5, w - 1, h - 1);
    if (history.length < 1) return;
    const t0 = history[0][0], t1 = Math.max(history[history.length - 1][0], t0 + 1e-9);
    const ymax = fixedMax || Math.max(2, ...history.map((r) => r[col]));
    g.strokeStyle = '#4e79a7';
    g.lineWidth = 3;
    g.beginPath();
    history.forEach((r, i) => {
      const x = 2 + (w - 4) * (r[0] - t0) / (t1 - t0), y = h - 2 - (h - 4) * r[col] / ymax;
      if (i === 0) g.moveTo(x, y); else g.lineTo(x, y);
    });
    g.stroke();
    g.fillStyle = '#555555';
    g.font = '20px sans-serif';
    g.fillText(String(ymax), 6, 22);
  };

  const fmt = (x, d) => Number.isFinite(x) ? x.toFixed(d) : String(x);
  const show = (msg) => {
    if (!msg.obs) return;
    const o = msg.obs;
    current = {obs: Array.from(o)};
    $('r-step').textContent = `${o[OBS.step]}`;
    $('r-time').textContent = fmt(o[OBS.time], 2);
    $('r-energy').textContent = fmt(o[OBS.energy], 4);
    $('r-giant').textContent = fmt(o[OBS.giant], 3);
    $('r-omega').textContent = fmt(o[OBS.omega], 3);
    $('r-clusters').textContent = `${o[OBS.clusters]}`;
    draw(o, msg.shapes);
  };
  const record = (o) => {
    history.push([o[OBS.time], o[OBS.giant], o[OBS.omega], o[OBS.clusters]]);
    if (history.length > 800) history = history.filter((r, i) => i % 2 === 0);
    plot('p-giant', 1, 1);
    plot('p-omega', 2, 1);
    plot('p-clusters', 3, 0);
  };
  // A state that is not finite stops the page, as afv run stops.
  const nonFinite = (o) => [OBS.energy, OBS.giant, OBS.omega].find((k) => !Number.isFinite(o[k]));

  worker.onmessage = (ev) => {
    const m = ev.data;
    if (m.type === 'relaxing') {
      show(m);
      setStatus(`relaxing at v0 = 0 (afv run's protocol): step ${m.iter}, max |F| ${m.maxForce.toExponential(2)}`);
      return;
    }
    const resolve = pending.get(m.id);
    pending.delete(m.id);
    if (resolve) resolve(m);
  };

  // ---- actions -----------------------------------------------------------
  const fail = (text) => { broken = true; setRunning(false); setStatus(text, true); };
  // The answer to a request of steps: drawn and plotted, or the page
  // stops (as afv run stops) naming the step and the cell.
  const stepAnswer = (m) => {
    if (m.type === 'fatal') return fail(m.error), m;
    if (m.status === AFV_EUNSTABLE) {
      const step = m.obs[OBS.step] + 1, t = (step * params.dt).toPrecision(4);
      fail(`stopped at step ${step} (t = ${t}): cell ${m.badCell} would move ${m.badDisp} l in one step ` +
           `(a force that is not finite, or a runaway move > 1e8 l), as afv run stops; change the controls and press Reset`);
    } else if (m.status) fail(`stopped: ${m.error}; press Reset`);
    if (!m.obs) return fail('the clusters could not be computed; press Reset'), m;
    show(m);
    const bad = nonFinite(m.obs);
    if (bad !== undefined) fail(`stopped at step ${m.obs[OBS.step]}: ${Object.keys(OBS)[bad]} = ${m.obs[bad]} is not finite; press Reset`);
    if (!broken) record(m.obs);
    return m;
  };
  const reset = async (extra) => {
    setRunning(false);
    clampAll();
    broken = false;
    history = [];
    const p = Object.assign({Dr: 0.1, relax_max_steps: 100000}, params, extra || {});
    setStatus('relaxing at v0 = 0 (afv run\'s protocol) ...');
    $('start').disabled = $('step').disabled = true;
    const t0 = performance.now();
    const m = await ask('reset', {params: p});
    $('start').disabled = $('step').disabled = false;
    if (m.type === 'fatal') {
      fail(`${m.error}: ${serveHint}`);
      return m;
    }
    if (m.status) {
      show(m);
      fail(m.status === AFV_EUNSTABLE
        ? `the relaxation stopped: cell ${m.badCell} would move too far in one step (${m.error}); change the controls and press Reset`
        : `the start could not be built: ${m.error}`);
      return m;
    }
    const r = m.relax, how = r.converged ? 'converged (max |F| <= 1e-6)'
      : r.at_kink ? 'stopped at a kink of E, as afv run does'
      : r.refused ? 'stopped: a step would move a cell too far'
      : 'reached relax_max_steps, as afv run goes on from there';
    setStatus(`relaxed: ${r.iterations} steps at v0 = 0, ${how} (${((performance.now() - t0) / 1000).toFixed(1)} s); v0 on at step 0`);
    return stepAnswer(m);
  };
  // Time per animation frame, over the last second: the worker's (steps,
  // clusters, outlines) and the page's (drawing and plots).
  let workMs = 0, drawMs = 0, timed = 0, perFrame = {work: 0, draw: 0};
  const steps = async (k) => {
    const m = await ask('run', {steps: k}), t0 = performance.now();
    const answer = stepAnswer(m);
    workMs += m.workMs || 0;
    drawMs += performance.now() - t0;
    timed++;
    return answer;
  };
  const setLive = () => {
    clampAll();
    if (!broken) ask('set', {params}).then((m) => { if (m.status) fail(`these values cannot be used: ${m.error}`); });
  };

  // The animation: one request of `spf` steps per frame, the next asked
  // for when its answer is drawn.
  let frames = 0, fpsStart = performance.now(), fps = 0;
  const tick = (now) => {
    requestAnimationFrame(tick);
    if (now - fpsStart >= 1000) {
      fps = frames * 1000 / (now - fpsStart);
      if (timed) perFrame = {work: workMs / timed, draw: drawMs / timed};
      frames = timed = workMs = drawMs = 0;
      fpsStart = now;
      $('r-fps').textContent = running ? `${fps.toFixed(0)} frames/s, ${(fps * params.spf).toFixed(0)} steps/s` : '-';
    }
    if (!running || busy) return;
    busy = true;
    steps(params.spf).then(() => { busy = false; frames++; });
  };
  requestAnimationFrame(tick);

  // ---- presets (the paper's Fig. 7(b) and the time-step pair) -------------
  const presets = {
    'clustered-epithelial': {P0: 4, v0: 0.1, dt: 0.01, spf: 10},
    'clustered-mesenchymal': {P0: 8.8, v0: 0.1, dt: 0.01, spf: 10},
    'dispersed-epithelial': {P0: 4.4, v0: 2.6, dt: 0.01, spf: 10},
    'dispersed-mesenchymal': {P0: 8.8, v0: 2.6, dt: 0.01, spf: 10},
    // the pair advances the same time per frame, 0.2
    'detach-dt-0.01': {P0: 4, v0: 1.85, dt: 0.01, spf: 20},
    'detach-dt-0.0025': {P0: 4, v0: 1.85, dt: 0.0025, spf: 80},
  };
  const applyPreset = async (name, extra) => {
    const p = Object.assign({Lambda: 0.2, cap: 0, N: 400, seed: 1}, presets[name]);
    for (const k of Object.keys(p)) $(k).value = String(p[k]);
    $('preset-caption').textContent = $('preset-' + name).title;
    const m = await reset(extra);
    if (!(extra && extra.start === false) && !broken) setRunning(true);
    return m;
  };
  for (const name of Object.keys(presets))
    $('preset-' + name).addEventListener('click', () => applyPreset(name));

  $('start').addEventListener('click', () => setRunning(!running));
  $('step').addEventListener('click', () => { if (!broken && !running) steps(1); });
  $('reset').addEventListener('click', () => reset());
  for (const name of ['P0', 'v0', 'Lambda', 'dt', 'cap'])
    $(name).addEventListener('change', setLive);
  for (const name of ['N', 'seed'])
    $(name).addEventListener('change', () => { clampAll(); $(name + '-why').textContent ||= 'takes effect at Reset'; });
  $('spf').addEventListener('change', clampAll);

  // For test/web_check.py (and the curious, in the console).
  window.afvPage = {
    preset: applyPreset,
    reset,
    pause: () => setRunning(false),
    start: () => setRunning(true),
    // k steps now, the animation paused: resolves with the numbers after
    run: async (k) => { setRunning(false); while (busy) await new Promise((r) => setTimeout(r, 5)); return steps(k); },
    state: () => ({obs: current && current.obs, broken, running, status: $('status').textContent, fps, perFrame, history: history.length}),
    obsIndex: OBS,
    ask,
  };
  clampAll();
  applyPreset('clustered-epithelial', {start: false});
}
