// footprint in the browser: the core (WebAssembly, web/src/exports.rs) renders the same camera
// in two modes, one per half of the canvas; this script only moves the camera, draws the
// pixels and shows the numbers.
//
// URL parameters (all optional): pitch=20 (the paper's view at that pitch; without it a map
// `serve --dem` was given opens in its overview), size=400x400, left=ps, right=as, seed, terrain=1024,
// and for tests: count=1 (count once the first frames are drawn), bench=N (fly N frames of the
// paper's path and report the times), still=1 (no animation loop). When the page has drawn,
// counted and benched what it was asked, <body data-ready="1"> carries data-hash0/1 (the
// frames' FNV-1a-64, as `footprint render` would hash them) and data-ms0/1.

const MODES = ['classic', 'ps', 'li', 'ss2', 'ss4', 'ss8', 'ss16', 'ss32', 'as', 'as-exact', 'as2'];
const FLIGHT_STEP_M = 0.5; // Sect. 5: 0.5 m forward per frame
const FLIGHT_FRAMES = 240;
const MOVE_M = 30; // W/S per frame, metres
const TURN_DEG = 1.5;

const params = new URLSearchParams(location.search);
const $ = (id) => document.getElementById(id);
const message = (text) => { $('message').textContent = text; };

const bytes = await (await fetch('footprint_web.wasm')).arrayBuffer();
const { instance } = await WebAssembly.instantiate(bytes, {});
const fp = instance.exports;

function text() {
  const view = new Uint8Array(fp.memory.buffer, fp.fp_message_ptr(), fp.fp_message_len());
  return new TextDecoder().decode(view);
}
function check(status, what) {
  if (status !== 0) {
    const e = text();
    message(what ? `${what}: ${e}` : e);
    return false;
  }
  return true;
}
function put(slot, data) {
  const ptr = fp.fp_buffer(slot, data.length);
  new Uint8Array(fp.memory.buffer, ptr, data.length).set(data);
}
function hex(v) {
  return BigInt.asUintN(64, v).toString(16).padStart(16, '0');
}

if (!check(fp.fp_init(), 'start')) throw new Error(text());

const canvas = $('canvas');
const ctx = canvas.getContext('2d');
const state = {
  dirty: true,
  counted: false,
  lastMove: 0,
  flying: 0,
  keys: new Set(),
  ms: [[], []],
  delivered: [], // when each of the last second's frames was on the canvas (performance.now())
};

// The page's rates. Frames delivered: how many frames (both halves drawn) reached the canvas
// in the last second, a count of timestamps, not 1000 / a render time, so a clock that stands
// still (headless virtual time) gives a number too; the page draws only when the camera moves,
// so at rest it is 0. A half's render time: the mean of its last 30 renders, '—' before the
// first. Nothing here divides by a time.
const RATE_WINDOW_MS = 1000;
function deliveredInLastSecond(stamps, now) {
  while (stamps.length > 0 && stamps[0] <= now - RATE_WINDOW_MS) stamps.shift();
  return stamps.length;
}
function meanMs(times) {
  if (times.length === 0) return '—';
  return (times.reduce((a, b) => a + b, 0) / times.length).toFixed(1);
}
function showDelivered(now) {
  $('delivered').textContent = deliveredInLastSecond(state.delivered, now).toLocaleString('en');
}

function size() {
  return [fp.fp_width(), fp.fp_height()];
}

function setMode(half, name) {
  put(4, new TextEncoder().encode(name));
  if (check(fp.fp_set_mode(half), `mode ${name}`)) {
    $(`mode-${half}`).value = name;
    $(`name-${half}`).textContent = name;
    state.ms[half] = [];
    state.dirty = true;
    state.counted = false;
  }
}

function paperView(pitch) {
  const [w, h] = params.has('size') ? params.get('size').split('x').map(Number) : size();
  if (check(fp.fp_paper_view(pitch, w, h), 'paper view')) {
    canvas.width = 2 * w;
    canvas.height = h;
    moved();
  }
}

// The map's overview: `footprint render`'s view of a map without view options (the map itself,
// from above its south edge), the page's view of a map the user picked.
function overview() {
  const [w, h] = params.has('size') ? params.get('size').split('x').map(Number) : size();
  if (check(fp.fp_overview(w, h), 'overview')) {
    canvas.width = 2 * w;
    canvas.height = h;
    $('pitch').value = fp.fp_param(4).toFixed(1);
    moved();
  }
}

function moved() {
  state.dirty = true;
  state.counted = false;
  state.lastMove = performance.now();
}

function setView(dx, dy, deye, dheading, dpitch) {
  const p = [0, 1, 2, 3, 4].map((i) => fp.fp_param(i));
  const status = fp.fp_set_view(p[0] + dx, p[1] + dy, p[2] + deye, p[3] + dheading, p[4] + dpitch);
  if (check(status, 'camera')) {
    $('pitch').value = (p[4] + dpitch).toFixed(1);
    moved();
  }
}

function forward(m) {
  if (check(fp.fp_forward(m), 'camera')) moved();
}

function draw() {
  const [w, h] = size();
  for (const half of [0, 1]) {
    const t0 = performance.now();
    if (!check(fp.fp_render(half), 'render')) return;
    const ms = performance.now() - t0;
    const times = state.ms[half];
    times.push(ms);
    if (times.length > 30) times.shift();
    const pixels = new Uint8ClampedArray(fp.memory.buffer, fp.fp_rgba_ptr(half), w * h * 4);
    ctx.putImageData(new ImageData(new Uint8ClampedArray(pixels), w, h), half * w, 0);
    $(`ms-${half}`).textContent = meanMs(times);
    $(`dy-${half}`).textContent = fp.fp_stat(half, 0).toFixed(3);
    $(`changed-${half}`).textContent = fp.fp_stat(half, 1).toLocaleString('en');
    $(`hash-${half}`).textContent = hex(fp.fp_hash(half));
    document.body.dataset[`hash${half}`] = hex(fp.fp_hash(half));
    for (const id of ['l', 'p', 'm', 'v', 'hits', 'coverage']) $(`${id}-${half}`).textContent = '…';
  }
  state.dirty = false;
  const now = performance.now();
  state.delivered.push(now);
  showDelivered(now);
  document.body.dataset.frames = Number(document.body.dataset.frames ?? 0) + 1;
}

function count() {
  const names = ['l', 'p', 'm', 'v', 'hits'];
  for (const half of [0, 1]) {
    if (!check(fp.fp_count(half), 'count')) return;
    names.forEach((id, k) => { $(`${id}-${half}`).textContent = fp.fp_stat(half, 2 + k).toLocaleString('en'); });
    $(`coverage-${half}`).textContent = fp.fp_stat(half, 7).toFixed(3);
  }
  state.counted = true;
}

function mapInfo() {
  fp.fp_map_info();
  $('map-info').textContent = text();
}

function tick(now) {
  const k = state.keys;
  const heading = fp.fp_param(3) * Math.PI / 180;
  const step = (k.has('w') ? 1 : 0) - (k.has('s') ? 1 : 0);
  if (step) setView(step * MOVE_M * Math.sin(heading), -step * MOVE_M * Math.cos(heading), 0, 0, 0);
  const turn = (k.has('d') ? 1 : 0) - (k.has('a') ? 1 : 0);
  if (turn) setView(0, 0, 0, turn * TURN_DEG, 0);
  const pitch = (k.has('ArrowDown') ? 1 : 0) - (k.has('ArrowUp') ? 1 : 0);
  if (pitch) setView(0, 0, 0, 0, pitch * 0.5);
  const rise = (k.has('PageUp') || k.has('ArrowRight') ? 1 : 0) - (k.has('PageDown') || k.has('ArrowLeft') ? 1 : 0);
  if (rise) setView(0, 0, rise * 10, 0, 0);
  if (state.flying > 0) {
    forward(FLIGHT_STEP_M);
    state.flying -= 1;
  }
  if (state.dirty) draw();
  else if (!state.counted && now - state.lastMove > 300) count();
  showDelivered(performance.now());
  requestAnimationFrame(tick);
}

// Controls.
for (const half of [0, 1]) {
  const select = $(`mode-${half}`);
  for (const m of MODES) select.add(new Option(m, m));
  select.addEventListener('change', () => setMode(half, select.value));
}
$('paper-view').addEventListener('click', () => paperView(Number($('pitch').value)));
$('overview').addEventListener('click', () => overview());
$('pitch').addEventListener('change', () => paperView(Number($('pitch').value)));
$('fly').addEventListener('click', () => {
  // Sect. 5: from the pitch-5° view, 0.5 m forward a frame.
  $('pitch').value = 5;
  paperView(5);
  state.flying = FLIGHT_FRAMES;
  for (const half of [0, 1]) state.ms[half] = [];
});
$('builtin').addEventListener('click', () => {
  if (check(fp.fp_load_builtin(Number(params.get('seed') ?? 1), Number(params.get('terrain') ?? 1024)), 'built-in terrain')) {
    message('');
    mapInfo();
    moved();
  }
});
window.addEventListener('keydown', (e) => {
  if (e.target.tagName === 'INPUT' || e.target.tagName === 'SELECT') return;
  const key = e.key.length === 1 ? e.key.toLowerCase() : e.key;
  if (['w', 'a', 's', 'd', 'ArrowUp', 'ArrowDown', 'ArrowLeft', 'ArrowRight', 'PageUp', 'PageDown'].includes(key)) {
    state.keys.add(key);
    e.preventDefault();
  }
});
window.addEventListener('keyup', (e) => {
  state.keys.delete(e.key.length === 1 ? e.key.toLowerCase() : e.key);
});
let drag = null;
canvas.addEventListener('pointerdown', (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
canvas.addEventListener('pointerup', () => { drag = null; });
canvas.addEventListener('pointermove', (e) => {
  if (!drag) return;
  const [dx, dy] = [e.clientX - drag[0], e.clientY - drag[1]];
  drag = [e.clientX, e.clientY];
  setView(0, 0, 0, dx * 0.2, dy * 0.1);
});

// Maps: a height map (.png, .asc, .hgt, .tif, .fpmap) and optionally its colour PNG, the height map
// first (two files dropped at once: the one named like a colour map, `color`/`colour`/`C1W`,
// is the colour map). Parsed in Rust by the CLI's readers: the same limits, the same one-line
// errors. The map opens in its overview, the view `footprint render --dem` takes of it.
async function loadFiles(files) {
  if (files.length === 0) return false;
  if (files.length > 2) {
    message('give one height map, or a height PNG and its colour PNG');
    return false;
  }
  const isColor = (f) => /colou?r|^c[\d_-]/i.test(f.name);
  let [height, color] = files;
  if (color && isColor(height) && !isColor(color) && !picked().includes(height)) [height, color] = [color, height];
  put(0, new Uint8Array(await height.arrayBuffer()));
  put(1, new TextEncoder().encode(height.name));
  if (color) {
    put(2, new Uint8Array(await color.arrayBuffer()));
    put(3, new TextEncoder().encode(color.name));
  }
  if (!check(fp.fp_load_files(color ? 1 : 0))) return false;
  message('');
  mapInfo();
  $('pitch').value = fp.fp_param(4).toFixed(1);
  moved();
  return true;
}
// The picker: a height map, and a colour PNG for it if one is chosen (before or after).
const picked = () => [...$('files').files, ...$('color-file').files];
$('files').addEventListener('change', () => loadFiles(picked()));
$('color-file').addEventListener('change', () => {
  if ($('files').files.length > 0) loadFiles(picked());
});
document.addEventListener('dragover', (e) => e.preventDefault());
document.addEventListener('drop', (e) => {
  e.preventDefault();
  loadFiles([...e.dataTransfer.files]);
});

// The map `footprint serve` was given: its files, or the built-in terrain's seed and side.
const served = await (await fetch('map.json')).json().catch(() => ({}));
let userMap = false;
if (served.height) {
  const fetchFile = async (f) => new File([await (await fetch(f.url)).arrayBuffer()], f.name);
  userMap = await loadFiles([await fetchFile(served.height), ...(served.color ? [await fetchFile(served.color)] : [])]);
} else if (served.terrain_size && (served.terrain_size !== 1024 || served.seed !== 1)) {
  check(fp.fp_load_builtin(served.seed, served.terrain_size), 'built-in terrain');
}

// The first frames, as the URL asks.
setMode(0, params.get('left') ?? 'ps');
setMode(1, params.get('right') ?? 'as');
// The built-in terrain opens in the paper's view (pitch 20° unless the URL says), a map
// `serve --dem` was given in its overview, as `footprint render` shows each.
if (userMap && !params.has('pitch')) {
  overview();
} else {
  $('pitch').value = params.get('pitch') ?? 20;
  paperView(Number($('pitch').value));
}
mapInfo();
draw();
if (params.has('count')) count();
const bench = Number(params.get('bench') ?? 0);
if (bench > 0) {
  // The paper's flight from here: `bench` frames, 0.5 m apart; min and median ms per half.
  for (const half of [0, 1]) state.ms[half] = [];
  const all = [[], []];
  for (let t = 0; t < bench; t++) {
    forward(FLIGHT_STEP_M);
    draw();
    for (const half of [0, 1]) all[half].push(state.ms[half].at(-1));
  }
  for (const half of [0, 1]) {
    const sorted = all[half].filter((t) => t !== undefined).sort((a, b) => a - b);
    if (sorted.length === 0) continue;
    document.body.dataset[`benchMin${half}`] = sorted[0].toFixed(2);
    document.body.dataset[`benchMedian${half}`] = sorted[Math.floor(sorted.length / 2)].toFixed(2);
  }
}
for (const half of [0, 1]) {
  // NaN if the frame could not be drawn (the message says why).
  document.body.dataset[`ms${half}`] = (state.ms[half].at(-1) ?? NaN).toFixed(2);
}
document.body.dataset.message = $('message').textContent;
document.body.dataset.ready = '1';
if (!params.has('still')) requestAnimationFrame(tick);
