// The page of `breastfit serve`: open a scan of the workspace, place the 12 landmarks on it,
// fit the template (progress streamed, cancellable; a re-fit after moving a landmark is warm-started),
// look at the drawings, distances and warnings, export the output set. Coordinates are the
// server's: millimetres, the scan's frame (any orientation: the views use the body frame the
// server estimates).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);

// ---------- server ----------
async function api(method, path, body) {
  const res = await fetch(path, {
    method,
    headers: body !== undefined ? { 'Content-Type': 'application/json' } : {},
    body: body !== undefined ? JSON.stringify(body) : undefined,
  });
  const type = res.headers.get('Content-Type') || '';
  const data = type.startsWith('application/json') ? await res.json() : await res.arrayBuffer();
  return { status: res.status, data };
}

function showMessage(text, info = false) {
  const m = $('message');
  m.textContent = text;
  m.className = info ? 'info' : '';
  m.hidden = !text;
}

// ---------- 3D view ----------
const canvas = $('canvas');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xfbfbfb);
const camera = new THREE.PerspectiveCamera(30, 1, 1, 20000);
const controls = new OrbitControls(camera, canvas);
scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 1.6));
const headLight = new THREE.DirectionalLight(0xffffff, 1.4);
camera.add(headLight);
scene.add(camera);

const groups = { scan: new THREE.Group(), model: new THREE.Group(), drawings: new THREE.Group(), landmarks: new THREE.Group(),
  mapped: new THREE.Group() };
for (const g of Object.values(groups)) scene.add(g);

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);

let needsRender = true;
controls.addEventListener('change', () => { needsRender = true; });
function animate() {
  if (needsRender) { renderer.render(scene, camera); needsRender = false; }
  requestAnimationFrame(animate);
}

let scanMesh = null;      // the scan as shown and picked: shadedMesh or texturedMesh
let shadedMesh = null;
let texturedMesh = null;  // a textured OBJ's scan, or null
let scanBox = null;

// The standard views in the body frame (the fit's, else the scan's shape estimate): front looks at
// the patient's anterior, "right" at the patient's right side, oblique from the front-right.
let frame = null;
function viewDirection(name) {
  const L = new THREE.Vector3(...frame.left), P = new THREE.Vector3(...frame.posterior), S = new THREE.Vector3(...frame.superior);
  const d = { front: P.clone().negate(), right: L.clone().negate(), left: L.clone(),
    oblique: P.clone().negate().addScaledVector(L, -0.8).addScaledVector(S, 0.15),
    'oblique-left': P.clone().negate().addScaledVector(L, 0.8).addScaledVector(S, 0.15) }[name];
  return { dir: d.normalize(), up: S };
}

function setView(name) {
  if (!scanBox || !frame) return;
  const c = scanBox.getCenter(new THREE.Vector3());
  const size = scanBox.getSize(new THREE.Vector3()).length();
  const { dir, up } = viewDirection(name);
  camera.position.copy(c).addScaledVector(dir, size * 1.55);
  camera.up.copy(up);
  controls.target.copy(c);
  controls.update();
  camera.updateMatrixWorld();  // picking and projection use the new view before the next frame
  needsRender = true;
}

// ---------- state ----------
// suggested: name -> {confidence, method} of the landmarks "Suggest" placed and nobody has
// moved since (a moved one counts as checked by the user).
const state = {
  scanId: null, scanName: '', names: [], landmarks: {}, selected: null,
  result: null, job: null, moved: false, suggested: {},
};

// A suggested landmark below this confidence is marked for the user to check.
const LOW_CONFIDENCE = 0.5;
function lowConfidence(name) {
  const s = state.suggested[name];
  return !!s && s.confidence < LOW_CONFIDENCE;
}

function landmarkColour(name) {
  const check = state.result && state.result.landmark_checks[name];
  return (check && check.flagged) || lowConfidence(name) ? 0xe0a000 : 0xd71920;
}

function rebuildLandmarks() {
  groups.landmarks.clear();
  const r = scanBox ? scanBox.getSize(new THREE.Vector3()).length() * 0.006 : 3;
  for (const [name, p] of Object.entries(state.landmarks)) {
    const s = new THREE.Mesh(new THREE.SphereGeometry(name === state.selected ? r * 1.4 : r, 16, 12),
      new THREE.MeshBasicMaterial({ color: landmarkColour(name), depthTest: false }));
    s.renderOrder = 3;
    s.position.set(...p);
    s.userData.landmark = name;
    groups.landmarks.add(s);
  }
  // Placed vs fitted: error lines.
  if (state.result) {
    const pts = [];
    for (const m of state.result.model_landmarks) {
      const placed = state.landmarks[m.name];
      if (placed) pts.push(new THREE.Vector3(...placed), new THREE.Vector3(...m.position));
    }
    const lines = new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(pts),
      new THREE.LineBasicMaterial({ color: 0x111111, depthTest: false }));
    lines.renderOrder = 2;
    groups.landmarks.add(lines);
    for (const m of state.result.model_landmarks) {
      // The fitted model's landmark: a small blue disc drawn over the placed (red) one.
      const s = new THREE.Mesh(new THREE.SphereGeometry(r * 0.5, 12, 8),
        new THREE.MeshBasicMaterial({ color: 0x1565c0, depthTest: false }));
      s.renderOrder = 4;
      s.position.set(...m.position);
      groups.landmarks.add(s);
    }
  }
  rebuildLandmarkList();
  needsRender = true;
}

function rebuildLandmarkList() {
  const ol = $('landmarks');
  ol.innerHTML = '';
  for (const name of state.names) {
    const li = document.createElement('li');
    li.textContent = name;
    li.dataset.name = name;
    if (name === state.selected) li.classList.add('selected');
    if (state.landmarks[name]) li.classList.add('placed');
    const sug = state.suggested[name];
    if (sug) {
      const span = document.createElement('span');
      span.className = 'confidence';
      span.title = `suggested: ${sug.method}`;
      span.textContent = ` ${Math.round(100 * sug.confidence)} %` + (lowConfidence(name) ? ' — low: check it' : '');
      li.appendChild(span);
      if (lowConfidence(name)) li.classList.add('low');
    }
    const check = state.result && state.result.landmark_checks[name];
    if (check && check.flagged) {
      li.classList.add('flagged');
      const span = document.createElement('span');
      span.className = 'check';
      if (check.predicted_distance_mm > check.predicted_tolerance_mm)
        span.textContent = ` ${check.predicted_distance_mm.toFixed(1)} mm from where the others put it: check it`;
      else if (check.distance_mm > check.tolerance_mm)
        span.textContent = ` ${check.distance_mm.toFixed(1)} mm from the fit: check it`;
      else
        span.textContent = ` ${check.anatomy_distance_mm.toFixed(1)} mm from ${check.anatomy}: check it`;
      li.appendChild(span);
    }
    li.onclick = () => { state.selected = name; rebuildLandmarks(); };
    ol.appendChild(li);
  }
  const missing = state.names.filter((n) => !state.landmarks[n]);
  const low = state.names.filter(lowConfidence).length;
  $('landmark-hint').textContent = !state.scanId ? 'Open a scan first.'
    : missing.length ? `Suggest places all 12; or click a name, then click the scan to place it (${missing.length} to place). Drag a placed landmark to move it.`
    : low ? `All 12 placed; ${low} suggested with low confidence (orange): check them, drag to correct, then Fit.`
    : 'All 12 placed. Check them (drag one to move it), then Fit.';
  updateButtons();
}

function updateButtons() {
  const placed = Object.keys(state.landmarks).length;
  $('fit').disabled = !state.scanId || !!state.job || placed < 3;
  $('fit').textContent = state.result && state.result.usable ? 'Re-fit' : 'Fit';
  $('cancel').disabled = state.job !== 'fit';
  $('suggest').disabled = !state.scanId || !!state.job;
  $('cancel-suggest').disabled = state.job !== 'suggest';
  $('export').disabled = !state.result || !!state.job;
}

function selectNextUnplaced() {
  const next = state.names.find((n) => !state.landmarks[n]);
  state.selected = next || state.selected;
}

// ---------- scan ----------
async function refreshFiles() {
  const { status, data } = await api('GET', '/api/files');
  if (status !== 200) return showMessage(data.error);
  const dl = $('files');
  dl.innerHTML = '';
  for (const f of data.files) {
    const o = document.createElement('option');
    o.value = f;
    dl.appendChild(o);
  }
}

async function openScan(path) {
  showMessage('Opening ' + path + ' …', true);
  const { status, data } = await api('POST', '/api/scans', { path });
  if (status !== 200) return showMessage(data.error);
  const mesh = await api('GET', `/api/scans/${data.id}/mesh`);
  if (mesh.status !== 200) return showMessage(mesh.data.error);
  const buf = mesh.data;
  const header = new Uint32Array(buf, 0, 2);
  const nv = header[0], nf = header[1];
  const positions = new Float32Array(buf, 8, nv * 3);
  const faces = new Uint32Array(buf, 8 + nv * 12, nf * 3);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  g.setIndex(new THREE.BufferAttribute(faces, 1));
  g.computeVertexNormals();
  g.computeBoundingBox();
  groups.scan.clear();
  scanMesh = shadedMesh = new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: 0xe8c4a8, roughness: 0.8, side: THREE.DoubleSide }));
  texturedMesh = null;
  groups.scan.add(scanMesh);
  $('texture-toggle').hidden = !data.textured;
  scanBox = g.boundingBox.clone();
  frame = data.body_frame;
  Object.assign(state, { scanId: data.id, scanName: data.name, names: data.landmark_names, landmarks: {}, result: null,
    suggested: {} });
  selectNextUnplaced();
  groups.model.clear(); groups.drawings.clear();
  $('scan-info').textContent = `${data.name}: ${nv} points, ${nf} triangles, ${data.units}` +
    (data.warnings.length ? ' — ' + data.warnings.join('; ') : '');
  $('export-dir').value = 'fits/' + data.name.replace(/\.[^.\/]*$/, '').replace(/[\/]/g, '_');
  $('mrk-path').value = data.name.replace(/\.[^.\/]*$/, '') + '.landmarks.mrk.json';
  showResult(null);
  groups.mapped.clear();
  $('map-result').textContent = '';
  $('export-result').textContent = '';
  $('progress').textContent = '';
  refreshMapSources();
  rebuildLandmarks();
  resize();
  setView('front');
  showMessage('');
  if (data.textured) await loadTexture(data.id, positions, faces);
}

// A textured OBJ: every face corner gets its own vertex (one vertex may have several texture
// coordinates), drawn unlit (the photograph has its own light). Display only: picking uses the
// same triangles, the fit the scan as read.
async function loadTexture(id, positions, faces) {
  const uv = await api('GET', `/api/scans/${id}/uv`);
  if (uv.status !== 200) return showMessage(uv.data.error);
  let map;
  try {
    map = await new THREE.TextureLoader().loadAsync(`/api/scans/${id}/texture`);
  } catch (e) {
    return showMessage(`${state.scanName}: the browser cannot read its texture image; shown shaded`);
  }
  if (state.scanId !== id) return;  // another scan was opened meanwhile
  map.colorSpace = THREE.SRGBColorSpace;
  const pos = new Float32Array(faces.length * 3);
  for (let i = 0; i < faces.length; ++i) pos.set(positions.subarray(3 * faces[i], 3 * faces[i] + 3), 3 * i);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.setAttribute('uv', new THREE.BufferAttribute(new Float32Array(uv.data), 2));
  g.computeBoundingSphere();
  texturedMesh = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ map, side: THREE.DoubleSide }));
  groups.scan.add(texturedMesh);
  applyScanLook();
}

// The texture ↔ shading toggle.
function applyScanLook() {
  const textured = !!texturedMesh && $('show-texture').checked;
  if (texturedMesh) texturedMesh.visible = textured;
  if (shadedMesh) shadedMesh.visible = !textured;
  scanMesh = textured ? texturedMesh : shadedMesh;
  needsRender = true;
}

// ---------- picking ----------
const raycaster = new THREE.Raycaster();
function pointerNdc(ev) {
  const r = canvas.getBoundingClientRect();
  return new THREE.Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
}
function hitScan(ev) {
  if (!scanMesh) return null;
  raycaster.setFromCamera(pointerNdc(ev), camera);
  const hits = raycaster.intersectObject(scanMesh, false);
  return hits.length ? hits[0].point : null;
}
function hitLandmark(ev) {
  raycaster.setFromCamera(pointerNdc(ev), camera);
  const spheres = groups.landmarks.children.filter((o) => o.userData.landmark);
  const hits = raycaster.intersectObjects(spheres, false);
  return hits.length ? hits[0].object.userData.landmark : null;
}

let drag = null;  // {name, moved}
let down = null;  // pointer-down position (a click is a press without motion)
canvas.addEventListener('pointerdown', (ev) => {
  down = { x: ev.clientX, y: ev.clientY };
  const name = hitLandmark(ev);
  if (name) {
    drag = { name, moved: false };
    state.selected = name;
    controls.enabled = false;
    canvas.setPointerCapture(ev.pointerId);
  }
});
canvas.addEventListener('pointermove', (ev) => {
  if (!drag) return;
  const p = hitScan(ev);
  if (p) {
    state.landmarks[drag.name] = [p.x, p.y, p.z];
    delete state.suggested[drag.name];  // moved by the user: checked
    drag.moved = true;
    rebuildLandmarks();
  }
});
canvas.addEventListener('pointerup', (ev) => {
  const wasClick = down && Math.hypot(ev.clientX - down.x, ev.clientY - down.y) < 4;
  if (drag) {
    if (drag.moved) state.moved = true;
    drag = null;
    controls.enabled = true;
    rebuildLandmarks();
    return;
  }
  if (wasClick && state.selected && state.scanId) {
    const p = hitScan(ev);
    if (p) {
      if (state.landmarks[state.selected]) state.moved = true;
      state.landmarks[state.selected] = [p.x, p.y, p.z];
      delete state.suggested[state.selected];
      selectNextUnplaced();
      rebuildLandmarks();
    }
  }
});

// ---------- fit ----------
function landmarkList() {
  return Object.entries(state.landmarks).map(([name, position]) => ({ name, position }));
}

// Follows the scan's running job (fit or suggest) through the server's event stream until it
// ends; resolves to its final status (null when the connection was lost). `onResult` sees a
// re-fit's first result (the fitted model and drawings) while the job still runs.
function watchJob(onProgress, onResult = () => {}) {
  return new Promise((resolve) => {
    const events = new EventSource(`/api/scans/${state.scanId}/events`);
    events.addEventListener('progress', (e) => onProgress(JSON.parse(e.data)));
    events.addEventListener('result', (e) => onResult(JSON.parse(e.data)));
    events.addEventListener('end', (e) => { events.close(); resolve(JSON.parse(e.data)); });
    events.onerror = () => {
      events.close();
      showMessage('The connection to breastfit serve was lost (is it still running?): reload the page.');
      resolve(null);
    };
  });
}

async function fit() {
  const warm = !!(state.result && state.result.usable);
  const { status, data } = await api('POST', `/api/scans/${state.scanId}/fit`, { landmarks: landmarkList(), warm });
  if (status !== 202) return showMessage(data.error);
  showMessage('');
  state.job = 'fit';
  state.moved = false;
  updateButtons();
  $('progress').textContent = warm ? 'Re-fitting from the previous fit…' : 'Fitting…';
  const st = await watchJob((p) => { $('progress').textContent = `Fitting: stage ${p.stage || '…'}, iteration ${p.iterations}`; },
    (first) => {
      const r = first.result;
      state.firstShown = r.generation;
      $('progress').textContent = `Re-fit #${r.generation}: model and drawings in ${(r.surface_ms / 1000).toFixed(2)} s; ` +
        'checking the landmarks, distances and measurements…';
      showResult(r);
    });
  state.job = null;
  if (st && st.state === 'done') {
    const r = st.result;
    $('progress').textContent = `${r.warm ? 'Re-fit' : 'Fit'} #${r.generation} done in ${(r.server_ms / 1000).toFixed(2)} s` +
      (r.warm ? ` (model and drawings in ${(r.surface_ms / 1000).toFixed(2)} s)` : '. To correct a landmark: drag it, then Re-fit.');
    showResult(r);
    refreshMapSources();
  } else if (st) {
    $('progress').textContent = st.message;
    if (st.state === 'failed') showMessage(st.message);
  }
  updateButtons();
}

// "Suggest": the server finds the 12 landmarks on the scan (a landmark-free fit); they replace
// the placed ones, each with its confidence in the list, and stay editable.
async function suggest() {
  const { status, data } = await api('POST', `/api/scans/${state.scanId}/suggest`);
  if (status !== 202) return showMessage(data.error);
  state.job = 'suggest';
  updateButtons();
  showMessage('Finding the landmarks on the scan…', true);
  const st = await watchJob((p) => showMessage(`Finding the landmarks: stage ${p.stage || '…'}, iteration ${p.iterations}`, true));
  state.job = null;
  if (st && st.state === 'done') {
    const sug = st.suggestion;
    state.landmarks = {};
    state.suggested = {};
    for (const l of sug.landmarks) {
      state.landmarks[l.name] = l.position;
      state.suggested[l.name] = { confidence: l.confidence, method: l.method };
    }
    state.moved = true;
    const low = sug.landmarks.filter((l) => l.confidence < LOW_CONFIDENCE).length;
    showMessage(`${sug.landmarks.length} landmarks suggested in ${(sug.server_ms / 1000).toFixed(2)} s` +
      (low ? `; ${low} of low confidence (orange): check them` : '') + '. Check each one (drag to correct), then Fit.', true);
  } else if (st) {
    showMessage(st.message, st.state === 'cancelled');
  }
  rebuildLandmarks();
}

// Viridis-like 5-stop ramp (matches the CSS colour bar).
const ramp = [[0x44, 0x01, 0x54], [0x3b, 0x52, 0x8b], [0x21, 0x91, 0x8c], [0x5e, 0xc9, 0x62], [0xfd, 0xe7, 0x25]];
function rampColour(t) {
  t = Math.min(Math.max(t, 0), 1) * (ramp.length - 1);
  const i = Math.min(Math.floor(t), ramp.length - 2), f = t - i;
  return ramp[i].map((a, k) => (a + (ramp[i + 1][k] - a) * f) / 255);
}

function buildModel() {
  groups.model.clear();
  groups.scan.visible = true;
  $('colorbar').hidden = true;
  const r = state.result;
  if (!r || (!$('show-model').checked && !$('show-distance').checked)) { needsRender = true; return; }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(r.fitted.vertices), 3));
  g.setIndex(r.fitted.faces);
  g.computeVertexNormals();
  const distance = $('show-distance').checked && r.fitted.distances_mm.length > 0;  // a re-fit's first result has none yet
  groups.scan.visible = !distance;  // the coloured model in place of the scan (no z-fighting)
  if (distance) {
    // The report's scale: 0 to the 95th percentile rounded up (server's distance_scale_mm); grey
    // where the scan does not cover the model (null: holes, beyond the scanned area).
    const top = r.fitted.distance_scale_mm > 0 ? r.fitted.distance_scale_mm : 10;
    const c = new Float32Array(r.fitted.distances_mm.length * 3);
    r.fitted.distances_mm.forEach((d, i) => c.set(d === null ? [0.62, 0.62, 0.62] : rampColour(d / top), 3 * i));
    const fmt = (x) => String(Math.round(x * 100) / 100);
    const ticks = $('colorbar').querySelectorAll('.ticks span');
    ticks[0].textContent = '0'; ticks[1].textContent = fmt(top / 2); ticks[2].textContent = fmt(top) + ' mm';
    g.setAttribute('color', new THREE.BufferAttribute(c, 3));
  }
  const opacity = distance ? 1 : Number($('model-opacity').value);
  const m = new THREE.Mesh(g, new THREE.MeshStandardMaterial({
    color: distance ? 0xffffff : 0x8fa8c8, vertexColors: distance, transparent: opacity < 1, opacity,
    depthWrite: opacity >= 1, roughness: 0.7, side: THREE.DoubleSide,
    polygonOffset: true, polygonOffsetFactor: -1, polygonOffsetUnits: -4,  // in front where it touches the scan
  }));
  groups.model.add(m);
  $('colorbar').hidden = !distance;
  needsRender = true;
}

// A drawing as a tube (WebGL line width is 1 px everywhere); `scale` of the standard radius.
function addTube(group, d, scale, onTop = false) {
  const pts = [];
  for (let i = 0; i < d.points.length; i += 3) pts.push(new THREE.Vector3(d.points[i], d.points[i + 1], d.points[i + 2]));
  if (d.closed && pts.length) pts.push(pts[0]);
  if (pts.length < 2) return;
  const curve = new THREE.CatmullRomCurve3(pts, false, 'centripetal');
  const radius = (scanBox ? scanBox.getSize(new THREE.Vector3()).length() * 0.0022 : 1.5) * scale;
  const tube = new THREE.Mesh(new THREE.TubeGeometry(curve, Math.max(pts.length * 2, 16), radius, 6, false),
    new THREE.MeshBasicMaterial({ color: d.colour, depthTest: !onTop }));
  tube.renderOrder = onTop ? 2 : 1;
  group.add(tube);
}

function buildDrawings() {
  groups.drawings.clear();
  const r = state.result;
  $('legend').innerHTML = '';
  if (!r) return;
  for (const d of r.drawings) {
    addTube(groups.drawings, d, 1);
    const li = document.createElement('li');
    li.innerHTML = `<span class="swatch" style="background:${d.colour}"></span>${d.name}` +
      ` <span class="hint">${Math.round(100 * d.supported_fraction)} % on the scan</span>`;
    $('legend').appendChild(li);
  }
  groups.drawings.visible = $('show-drawings').checked;
  needsRender = true;
}

function fmt(v, unit, digits = 1) { return v === null || v === undefined ? '—' : `${Number(v).toFixed(digits)} ${unit}`; }

function showResult(r) {
  state.result = r;
  if (r && r.body_frame) frame = r.body_frame;
  const v = $('verdict');
  if (!r) {
    v.className = 'hint'; v.textContent = 'No fit yet.';
    $('warnings').innerHTML = ''; $('measurements').innerHTML = '';
    buildModel(); buildDrawings();
    return;
  }
  const implausible = r.usable && r.status === 'implausible';
  v.className = implausible ? 'implausible' : r.usable ? 'usable' : 'not-usable';
  v.textContent = implausible
    ? '⚠ Implausible fit: the shape is not that of an adult torso or does not follow the scan (see the warnings). ' +
      'Check the scan, its units and the landmarks before using the drawings.'
    : (r.usable ? '✓ ' : '✗ ') + r.verdict.charAt(0).toUpperCase() + r.verdict.slice(1) + '.' +
      (r.usable ? ' Check the drawings, then Export (4).' : ' Check the landmarks and Fit again.');
  $('warnings').innerHTML = '';
  for (const w of r.warnings) {
    const li = document.createElement('li');
    li.textContent = w;
    $('warnings').appendChild(li);
  }
  if (r.complete === false) {  // a re-fit's first result: the measurements follow
    $('measurements').innerHTML = '<tr><td>measuring…</td></tr>';
    buildModel();
    buildDrawings();
    rebuildLandmarks();
    return;
  }
  const b = r.breasts;
  const rows = [['', 'right', 'left']];
  const side = (s, k, unit, scale = 1) => (s && s[k] !== undefined && s[k] !== null ? fmt(s[k] * scale, unit) : '—');
  rows.push(['volume', side(b.right, 'volume_ml', 'ml'), side(b.left, 'volume_ml', 'ml')]);
  rows.push(['notch → nipple', side(b.right, 'notch_to_nipple_mm', 'mm'), side(b.left, 'notch_to_nipple_mm', 'mm')]);
  rows.push(['nipple → IMF', side(b.right, 'nipple_to_imf_mm', 'mm'), side(b.left, 'nipple_to_imf_mm', 'mm')]);
  rows.push(['inter-nipple', fmt(b.inter_nipple_mm, 'mm'), '']);
  $('measurements').innerHTML = rows.map((row, i) =>
    '<tr>' + row.map((c) => (i === 0 ? `<th>${c}</th>` : `<td>${c}</td>`)).join('') + '</tr>').join('');
  buildModel();
  buildDrawings();
  rebuildLandmarks();
}

// ---------- standing <-> supine ----------
async function refreshMapSources() {
  const { status, data } = await api('GET', '/api/scans');
  if (status !== 200) return;
  const sel = $('map-from');
  sel.innerHTML = '';
  for (const sc of data.scans.filter((x) => x.fitted && x.id !== state.scanId)) {
    const o = document.createElement('option');
    o.value = sc.id;
    o.textContent = sc.name;
    sel.appendChild(o);
  }
  $('map').disabled = !sel.options.length || !(state.result && state.result.usable);
}

async function mapFrom() {
  const { status, data } = await api('POST', `/api/scans/${state.scanId}/map`, { from: $('map-from').value });
  if (status !== 200) return showMessage(data.error);
  groups.mapped.clear();
  // Thin and light, over this scan's own drawings (which they should follow).
  for (const c of data.curves) {
    const light = '#' + new THREE.Color(c.colour).lerp(new THREE.Color(0xffffff), 0.55).getHexString();
    addTube(groups.mapped, { ...c, colour: light }, 0.45, true);
  }
  const low = data.curves.reduce((n, c) => n + c.confidence.low, 0);
  const all = data.curves.reduce((n, c) => n + c.confidence.high + c.confidence.medium + c.confidence.low, 0);
  $('map-result').textContent = `Mapped ${data.curves.length} drawings from ${data.from}` +
    (low ? ` (${low} of ${all} points of low confidence: off this scan or far from the fit)` : '') + '.';
  showMessage('');
  needsRender = true;
}

// ---------- landmarks files, export ----------
async function importLandmarks() {
  const { status, data } = await api('POST', `/api/scans/${state.scanId}/landmarks/import`, { path: $('mrk-path').value });
  if (status !== 200) return showMessage(data.error);
  for (const l of data.landmarks) { state.landmarks[l.name] = l.position; delete state.suggested[l.name]; }
  selectNextUnplaced();
  showMessage(data.warnings.length ? data.warnings.join('; ') : '');
  rebuildLandmarks();
}

async function postConfirmingOverwrite(path, body, what) {
  let res = await api('POST', path, body);
  if (res.status === 409 && res.data.exists && window.confirm(`${res.data.error}\n\nOverwrite ${what}?`))
    res = await api('POST', path, { ...body, overwrite: true });
  return res;
}

async function saveLandmarks() {
  const path = $('mrk-path').value;
  const res = await postConfirmingOverwrite(`/api/scans/${state.scanId}/landmarks/export`,
    { path, landmarks: landmarkList() }, path);
  if (res.status !== 200) return showMessage(res.data.error);
  showMessage('Saved ' + res.data.path, true);
  refreshFiles();
}

// The landmarks as a 3D Slicer .mrk.json, downloaded by the browser (made by the server's writer).
async function downloadLandmarks() {
  const name = $('mrk-path').value.split('/').pop() || 'landmarks.mrk.json';
  const res = await fetch(`/api/scans/${state.scanId}/landmarks/download`, {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ name, landmarks: landmarkList() }),
  });
  if (res.status !== 200) return showMessage((await res.json()).error);
  const a = document.createElement('a');
  a.href = URL.createObjectURL(await res.blob());
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 5000);
}

async function exportResult() {
  const dir = $('export-dir').value;
  const res = await postConfirmingOverwrite(`/api/scans/${state.scanId}/export`, { dir }, 'the outputs in ' + dir);
  if (res.status !== 200) return showMessage(res.data.error);
  const links = res.data.files.filter((f) => /drawings\.mrk\.json$|report\.html$/.test(f))
    .map((f) => `<a href="/api/download?path=${encodeURIComponent(f)}">${f.split('/').pop()}</a>`).join(' · ');
  $('export-result').innerHTML = `Written to ${res.data.dir} (${res.data.files.length} files). Download: ${links}`;
  showMessage('');
  refreshFiles();
}

// Uploads the chosen files into uploads/ (a textured OBJ with its .mtl and image: choose them
// together), then opens the scan among them.
async function upload(files) {
  let scan = null;
  for (const file of files) {
    const res = await fetch('/api/upload?name=' + encodeURIComponent('uploads/' + file.name), { method: 'POST', body: file });
    const data = await res.json();
    if (res.status !== 201) return showMessage(data.error);
    if (/\.(ply|obj|stl|vtk|vtp)$/i.test(data.path)) scan = data.path;
  }
  await refreshFiles();
  if (!scan) return showMessage(`Uploaded ${files.length} file(s); none is a scan (.ply .obj .stl .vtk .vtp).`, true);
  $('scan-path').value = scan;
  openScan(scan);
}

// ---------- wiring ----------
$('open-scan').onclick = () => openScan($('scan-path').value);
$('scan-path').addEventListener('keydown', (e) => { if (e.key === 'Enter') openScan($('scan-path').value); });
$('upload').onchange = (e) => e.target.files.length && upload([...e.target.files]);
$('fit').onclick = fit;
$('cancel').onclick = () => api('POST', `/api/scans/${state.scanId}/cancel`);
$('suggest').onclick = suggest;
$('cancel-suggest').onclick = () => api('POST', `/api/scans/${state.scanId}/cancel`);
$('import-mrk').onclick = importLandmarks;
$('export-mrk').onclick = saveLandmarks;
$('download-mrk').onclick = downloadLandmarks;
$('export').onclick = exportResult;
$('map').onclick = mapFrom;
$('show-texture').onchange = applyScanLook;
$('show-model').onchange = buildModel;
$('show-distance').onchange = buildModel;
$('model-opacity').oninput = buildModel;
$('show-drawings').onchange = () => { groups.drawings.visible = $('show-drawings').checked; needsRender = true; };
for (const b of document.querySelectorAll('#view-buttons button')) b.onclick = () => setView(b.dataset.view);

// A small hook for the browser test: screen positions of 3D points, and the page's state.
window.breastfitTest = {
  project(p) {
    camera.updateMatrixWorld();
    const v = new THREE.Vector3(...p).project(camera);
    const r = canvas.getBoundingClientRect();
    return { x: r.left + (v.x + 1) / 2 * r.width, y: r.top + (1 - v.y) / 2 * r.height };
  },
  state: () => ({ scanId: state.scanId, firstShown: state.firstShown, textured: !!texturedMesh && texturedMesh.visible, landmarks: state.landmarks, selected: state.selected, suggested: state.suggested,
    job: state.job, fitRunning: state.job === 'fit', result: state.result && { generation: state.result.generation, warm: state.result.warm,
      usable: state.result.usable, server_ms: state.result.server_ms, surface_ms: state.result.surface_ms,
      complete: state.result.complete, drawings: state.result.drawings.map((d) => ({ name: d.name, colour: d.colour })) } }),
  setView,
};

resize();
animate();
refreshFiles();
const initial = new URLSearchParams(location.search).get('scan');
if (initial) { $('scan-path').value = initial; openScan(initial); }
