// The mocapdb page: clip browser, packed vs source, set explorer (docs/serve.md). The server's API is
// read-only GETs; motions come as a JSON header plus float32 positions (readMotion below).
import { SkeletonViewer } from './viewer.js';

const $ = (id) => document.getElementById(id);
// What the page shows, for people and for the browser tests.
const state = window.mocapdbState = { view: 'clips', clip: null, frames: 0, frame: 0, playing: true,
                                      packed: null, synth: null, sets: [], requests: 0, errors: [] };

function showError(message) {
  const box = $('error');
  box.textContent = message;
  box.hidden = false;
  state.errors.push(message);
}
function clearError() { $('error').hidden = true; }

async function fetchOk(path) {
  state.requests++;
  const reply = await fetch(path);
  if (!reply.ok) {
    let message = `${reply.status} ${reply.statusText}`;
    try { message = (await reply.json()).error || message; } catch (e) { /* not JSON */ }
    throw new Error(message);
  }
  return reply;
}
async function getJson(path) { return (await fetchOk(path)).json(); }

// u32 header length, JSON header, padding to 4 bytes, then float32 blocks.
async function readMotion(path) {
  const bytes = await (await fetchOk(path)).arrayBuffer();
  const n = new DataView(bytes).getUint32(0, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(bytes, 4, n)));
  const at = 4 + n + ((4 - (n % 4)) % 4);
  return { header, floats: new Float32Array(bytes, at, (bytes.byteLength - at) / 4) };
}

const viewer = new SkeletonViewer($('view3d'));

// The BVH link and its glTF twin (the same path with .glb).
function setDownloads(bvh) {
  $('download-bvh').href = bvh;
  $('download-glb').href = bvh.replace('.bvh?', '.glb?');
}

// ---- playback ----
let last = performance.now(), clock = 0;
function setFrames(frames, rate) {
  state.frames = frames;
  state.rate = rate;
  state.frame = 0;
  clock = 0;
  $('scrub').max = Math.max(frames - 1, 0);
  showFrame(0);
}
function showFrame(f) {
  state.frame = f;
  viewer.show(f);
  $('scrub').value = f;
  $('frame-label').textContent = `${f + 1} / ${state.frames}`;
  drawErrorPlot();
}
function tick(now) {
  const dt = (now - last) / 1000;
  last = now;
  if (state.playing && state.frames > 1) {
    clock += dt * Number($('speed').value);
    showFrame(Math.floor(clock * state.rate) % state.frames);
  }
  requestAnimationFrame(tick);
}
requestAnimationFrame(tick);
function setPlaying(on) {
  state.playing = on;
  $('play').textContent = on ? 'pause' : 'play';
}
$('play').onclick = () => setPlaying(!state.playing);
$('scrub').oninput = () => {
  setPlaying(false);
  clock = Number($('scrub').value) / (state.rate || 1);
  showFrame(Number($('scrub').value));
};

// ---- clips ----
let clips = [];
function renderClipList() {
  const filter = $('filter').value.toLowerCase();
  const list = $('clip-list');
  list.textContent = '';
  for (const c of clips) {
    if (filter && !c.id.toLowerCase().includes(filter)) continue;
    const li = document.createElement('li');
    li.dataset.id = c.id;
    li.textContent = c.id;
    const small = document.createElement('small');
    small.textContent = `${c.skeleton} · ${c.frames} frames · ${c.frame_rate} fps · ${c.duration_s.toFixed(2)} s`;
    li.appendChild(small);
    if (c.id === state.clip) li.classList.add('selected');
    li.onclick = () => chooseClip(c.id);
    list.appendChild(li);
  }
}
$('filter').oninput = renderClipList;

// Choices overlap (a view switch, a click, a new E): only the latest one's answer is drawn.
let clipTicket = 0;
async function chooseClip(id) {
  state.clip = id;
  renderClipList();
  const ticket = ++clipTicket;
  const latest = () => ticket === clipTicket;
  try {
    clearError();
    if (state.view === 'packed') await showPacked(id, latest);
    else await showClip(id, latest);
  } catch (e) {
    if (latest()) showError(`clip ${id}: ${e.message}`);
  }
}

async function showClip(id, latest) {
  const { header, floats } = await readMotion(`/api/clip?id=${encodeURIComponent(id)}`);
  if (!latest()) return;
  viewer.clear();
  viewer.add({ joints: header.joints, frames: header.frames, positions: floats, colour: 0x1565c0 });
  viewer.frameAll();
  state.packed = null;
  $('error-plot').hidden = true;
  setFrames(header.frames, header.frame_rate);
  $('info').textContent = `${id}: ${header.joints.length} joints (end sites included), ${header.frames} frames at ${header.frame_rate} fps`;
  setDownloads(`/api/clip.bvh?id=${encodeURIComponent(id)}`);
}

// The packed copy: the stored tier, or the clip packed alone in memory at a chosen E.
function fillPackedChoices(storedE) {
  const select = $('packed-e');
  select.textContent = '';
  if (storedE !== null) select.append(Object.assign(document.createElement('option'), { value: '', textContent: `the stored tier (${storedE} cm)` }));
  for (const e of [1, 0.5, 0.1, 0.03])
    select.append(Object.assign(document.createElement('option'), { value: String(e), textContent: `${e} cm, packed now` }));
  select.onchange = () => { if (state.clip) chooseClip(state.clip); };
}

async function showPacked(id, latest) {
  const e = $('packed-e').value;
  const { header, floats } = await readMotion(`/api/packed?id=${encodeURIComponent(id)}` + (e ? `&e=${e}` : ''));
  if (!latest()) return;
  const n = header.frames * header.joints.length;
  const source = floats.subarray(0, 3 * n), packed = floats.subarray(3 * n, 6 * n), errors = floats.subarray(6 * n, 7 * n);
  viewer.clear();
  viewer.add({ joints: header.joints, frames: header.frames, positions: source, colour: 0x9e9e9e });
  viewer.add({ joints: header.joints, frames: header.frames, positions: packed, colour: 0x1565c0, errors,
               bound: header.tier_max_error_cm });
  viewer.frameAll();
  const J = header.joints.length;
  const frameMax = new Float32Array(header.frames);
  for (let f = 0; f < header.frames; ++f) for (let k = 0; k < J; ++k) frameMax[f] = Math.max(frameMax[f], errors[f * J + k]);
  state.packed = { clip: id, max_cm: header.max_cm, rmse_cm: header.rmse_cm, frameMax, bound: header.tier_max_error_cm };
  $('error-plot').hidden = false;
  setFrames(header.frames, header.frame_rate);
  $('info').innerHTML = '';
  $('info').append(`${id} packed to ${header.tier_max_error_cm} cm${e ? ' in memory' : ''} (grey: source, blue: packed, joints coloured by error): max `,
                   Object.assign(document.createElement('b'), { id: 'packed-max', textContent: header.max_cm.toFixed(4) }),
                   ` cm (${header.worst_joint}, frame ${header.worst_frame}), RMSE ${header.rmse_cm.toFixed(4)} cm`);
  setDownloads(`/api/clip.bvh?id=${encodeURIComponent(id)}`);
}

function drawErrorPlot() {
  const p = state.packed, canvas = $('error-plot');
  if (!p || canvas.hidden) return;
  const g = canvas.getContext('2d'), w = canvas.width, h = canvas.height;
  g.clearRect(0, 0, w, h);
  const top = Math.max(p.bound, p.max_cm) || 1;
  g.strokeStyle = '#e57373';
  g.beginPath(); g.moveTo(0, h - (h - 12) * p.bound / top); g.lineTo(w, h - (h - 12) * p.bound / top); g.stroke();
  g.strokeStyle = '#1565c0';
  g.beginPath();
  for (let f = 0; f < p.frameMax.length; ++f) {
    const x = p.frameMax.length > 1 ? (w * f) / (p.frameMax.length - 1) : 0, y = h - (h - 12) * p.frameMax[f] / top;
    if (f === 0) g.moveTo(x, y); else g.lineTo(x, y);
  }
  g.stroke();
  const cx = p.frameMax.length > 1 ? (w * state.frame) / (p.frameMax.length - 1) : 0;
  g.strokeStyle = '#333'; g.beginPath(); g.moveTo(cx, 0); g.lineTo(cx, h); g.stroke();
  g.fillStyle = '#333';
  g.fillText(`max joint error per frame (cm); red: the bound ${p.bound} cm`, 4, 10);
}

// ---- sets ----
let set = null, request = null, pending = false, map = null;
function currentValues() { return [...document.querySelectorAll('#sliders input')].map((s) => Number(s.value)); }

async function loadSets() {
  const { sets } = await getJson('/api/sets');
  state.sets = sets;
  const select = $('set-select');
  select.textContent = '';
  for (const s of sets) select.append(Object.assign(document.createElement('option'), { value: s.name, textContent: `${s.name} (${s.samples} samples)` }));
  select.onchange = () => chooseSet(select.value);
  if (sets.length) await chooseSet(sets[0].name);
  else $('synth-note').textContent = 'This database has no motion set with control parameters.';
}

async function chooseSet(name) {
  set = state.sets.find((s) => s.name === name);
  const box = $('sliders');
  box.textContent = '';
  set.parameters.forEach((p, k) => {
    const span = (p.max - p.min) || 1;
    const label = document.createElement('label');
    const input = Object.assign(document.createElement('input'), { type: 'range', min: p.min - 0.5 * span, max: p.max + 0.5 * span,
                                                                     step: span / 200, value: (p.min + p.max) / 2 });
    input.dataset.param = p.name;
    input.oninput = () => { label.firstChild.textContent = `${p.name} ${Number(input.value).toFixed(2)} ${p.unit}`; requestSynthesis(); };
    label.append(`${p.name} ${Number(input.value).toFixed(2)} ${p.unit}`, input);
    box.appendChild(label);
    void k;
  });
  await loadMap();
  requestSynthesis();
}

async function loadMap() {
  map = null;
  if (!set || set.parameters.length < 1) return;
  try {
    map = await getJson(`/api/reliability?set=${encodeURIComponent(set.name)}&n=41&c=${currentValues().join(',')}`);
  } catch (e) { showError(`reliability map: ${e.message}`); }
  drawPad();
}

// One synthesis in flight at a time; the latest slider position wins.
function requestSynthesis() {
  request = currentValues();
  drawPad();
  if (!pending) runSynthesis();
}
async function runSynthesis() {
  pending = true;
  while (request) {
    const c = request;
    request = null;
    try {
      const { header, floats } = await readMotion(`/api/synth?set=${encodeURIComponent(set.name)}&c=${c.join(',')}`);
      clearError();
      showSynthesis(header, floats, c);
    } catch (e) { showError(`synthesis: ${e.message}`); }
  }
  pending = false;
}

function showSynthesis(header, floats, c) {
  viewer.clear();
  viewer.add({ joints: header.joints, frames: header.frames, positions: floats, colour: header.inside ? 0x2e7d32 : 0xc62828 });
  if (!state.synth || state.synth.set !== header.set) viewer.frameAll();
  let sum = 0;
  for (let i = 0; i < floats.length; ++i) sum += floats[i];
  state.synth = { set: header.set, c, reliability: header.reliability, inside: header.inside, checksum: sum, frames: header.frames };
  setFrames(header.frames, header.frame_rate);
  $('rho').textContent = header.reliability.toFixed(4);
  $('outside').hidden = header.inside;
  const body = document.querySelector('#params tbody');
  body.textContent = '';
  for (const p of header.parameters) {
    const row = body.insertRow();
    row.insertCell().textContent = `${p.name} ${p.unit ? '(' + p.unit + ')' : ''}`;
    row.insertCell().textContent = p.requested.toFixed(3);
    row.insertCell().textContent = p.measured === null ? '-' : p.measured.toFixed(3);
  }
  const w = header.warnings;
  $('synth-note').textContent = [w.low_reliability ? 'low reliability: the motion is extrapolated' : '', w.kernel_fit,
    w.regularized ? 'the kriging system was regularized' : ''].filter(Boolean).join('; ');
  $('info').textContent = `${header.set}: ${header.frames} frames (${header.duration_s.toFixed(2)} s), ${header.model} model, synthesized in ${(1e3 * header.seconds).toFixed(1)} ms`;
  setDownloads(`/api/synth.bvh?set=${encodeURIComponent(header.set)}&c=${c.join(',')}`);
}

// The pad: the first two parameters, rho shaded (white = 1, dark = 0), samples as dots, the request as a ring.
function padAxes() {
  const px = set.parameters[0], py = set.parameters[1] || set.parameters[0];
  const sx = document.querySelector('#sliders input'), inputs = document.querySelectorAll('#sliders input');
  const sy = inputs[1] || sx;
  return { px, py, sx, sy, one: set.parameters.length === 1 };
}
function drawPad() {
  const canvas = $('pad'), g = canvas.getContext('2d'), w = canvas.width, h = canvas.height;
  g.fillStyle = '#fff'; g.fillRect(0, 0, w, h);
  if (!set) return;
  const { sx, sy, one } = padAxes();
  const toX = (v) => ((v - sx.min) / (sx.max - sx.min)) * w, toY = (v) => h - ((v - sy.min) / (sy.max - sy.min)) * h;
  if (map) {
    const nx = map.x.count, ny = map.y.count;
    const cw = ((map.x.hi - map.x.lo) / Math.max(nx - 1, 1)) / (sx.max - sx.min) * w;
    const ch = one ? h : ((map.y.hi - map.y.lo) / Math.max(ny - 1, 1)) / (sy.max - sy.min) * h;
    for (let j = 0; j < ny; ++j) for (let i = 0; i < nx; ++i) {
      const rho = map.rho[j * nx + i], shade = Math.round(255 * (0.35 + 0.65 * rho));
      g.fillStyle = `rgb(${shade},${shade},${Math.min(255, shade + 20)})`;
      const x = map.x.lo + (i * (map.x.hi - map.x.lo)) / Math.max(nx - 1, 1);
      const y = one ? sy.min : map.y.lo + (j * (map.y.hi - map.y.lo)) / Math.max(ny - 1, 1);
      g.fillRect(toX(x) - cw / 2, one ? 0 : toY(y) - ch / 2, cw + 1, one ? h : ch + 1);
    }
  }
  g.fillStyle = '#263238';
  for (const v of set.values) { g.beginPath(); g.arc(toX(v[0]), one ? h / 2 : toY(v[1]), 3, 0, 2 * Math.PI); g.fill(); }
  const c = currentValues();
  g.strokeStyle = state.synth && !state.synth.inside ? '#c62828' : '#2e7d32';
  g.lineWidth = 2;
  g.beginPath(); g.arc(toX(c[0]), one ? h / 2 : toY(c[1]), 7, 0, 2 * Math.PI); g.stroke();
}
function padPick(event) {
  if (!set) return;
  const r = $('pad').getBoundingClientRect();
  const { sx, sy, one } = padAxes();
  sx.value = Number(sx.min) + ((event.clientX - r.left) / r.width) * (sx.max - sx.min);
  if (!one) sy.value = Number(sy.min) + (1 - (event.clientY - r.top) / r.height) * (sy.max - sy.min);
  sx.dispatchEvent(new Event('input'));
  if (!one) sy.dispatchEvent(new Event('input'));
}
$('pad').onpointerdown = (e) => { $('pad').setPointerCapture(e.pointerId); padPick(e); };
$('pad').onpointermove = (e) => { if (e.buttons) padPick(e); };
$('pad').onpointerup = () => loadMap();

// ---- views ----
for (const b of document.querySelectorAll('nav button')) {
  b.onclick = async () => {
    state.view = b.dataset.view;
    for (const o of document.querySelectorAll('nav button')) o.classList.toggle('active', o === b);
    for (const p of document.querySelectorAll('[data-panel]')) p.hidden = !p.dataset.panel.split(' ').includes(state.view);
    clearError();
    try {
      if (state.view === 'sets') { if (!state.sets.length) await loadSets(); else requestSynthesis(); }
      else if (state.clip) await chooseClip(state.clip);
    } catch (e) { showError(e.message); }
  };
}

(async () => {
  try {
    const list = await getJson('/api/clips');
    clips = list.clips;
    $('database').textContent = `${list.database}: ${clips.length} clips` +
      (list.packed_max_error_cm === null ? ', no packed tier' : `, packed to ${list.packed_max_error_cm} cm`);
    fillPackedChoices(list.packed_max_error_cm);
    renderClipList();
    if (clips.length) await chooseClip(clips[0].id);
  } catch (e) { showError(`cannot list the clips: ${e.message}`); }
})();
