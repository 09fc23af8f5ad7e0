// render/viewer/viewer.js: the page `qmotion view` writes (docs/guide/view.md). It reads the
// data the command inlined, starts the kernel (WebAssembly, render/viewer/kernel_wasm.cpp),
// and draws with three.js: key poses, trajectories, the exact sweep, the moving object along
// t. Editing a pose interpolates again in the kernel with the file's method and redraws.
// window.qmotion is the page's interface for scripts and tests.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const data = JSON.parse(document.getElementById("qmotion-data").textContent);
const status = document.getElementById("status");

function base64Bytes(text) {
  const raw = atob(text.trim());
  const bytes = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; ++i) bytes[i] = raw.charCodeAt(i);
  return bytes;
}

function say(message, isError) {
  status.textContent = message;
  status.className = isError ? "error" : "";
}

// The kernel, and the motion it holds.
const kernel = await QMotionKernel({
  wasmBinary: base64Bytes(document.getElementById("qmotion-wasm").textContent),
});
const motion = data.motion;
let shown = motion.kind === "quaternion-spline"
  ? kernel.loadSpline(motion.scheme, motion.knots, motion.keys.flat(), motion.positions.flat(),
                      motion.tension, motion.control_quaternions.flat(), motion.control_positions.flat())
  : kernel.loadCurve(motion.basis, motion.degree, motion.knots, motion.control_points.flat());
if (shown.error) throw new Error(`${data.name}: ${shown.error}`);
const copyPoses = (list) => list.map((p) => ({ t: p.t, position: [...p.position], quaternion: [...p.quaternion] }));
const poses = copyPoses(data.poses);

// The scene, z up as in qmotion.
const canvas = document.getElementById("scene");
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xffffff);
const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, -1e6, 1e6);
camera.up.set(0, 0, 1);
const controls = new OrbitControls(camera, canvas);
scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.2);
sun.position.set(1, 2, 3);
scene.add(sun);

const layers = { keys: new THREE.Group(), paths: new THREE.Group(), sweep: new THREE.Group() };
for (const g of Object.values(layers)) scene.add(g);

function clear(group) {
  for (const child of [...group.children]) {
    group.remove(child);
    child.traverse((o) => {
      if (o.geometry) o.geometry.dispose();
      if (o.material) (o.material.map?.dispose(), o.material.dispose());
    });
  }
}

// The size of the scene, from the key positions and the moving points' trajectories.
const box = new THREE.Box3();
function extent() {
  const size = box.getSize(new THREE.Vector3()).length();
  return size > 0 ? size : 1;
}

function label(text, size) {
  const c = document.createElement("canvas");
  c.width = c.height = 64;
  const g = c.getContext("2d");
  g.font = "bold 44px sans-serif";
  g.textAlign = "center";
  g.textBaseline = "middle";
  g.fillStyle = "#1a1a1a";
  g.fillText(text, 32, 34);
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(c), depthTest: false }));
  sprite.scale.setScalar(size);
  return sprite;
}

function triad(size) {
  const g = new THREE.Group();
  const colours = [0xd62728, 0x2ca02c, 0x1f77b4];
  for (let axis = 0; axis < 3; ++axis) {
    const end = [0, 0, 0];
    end[axis] = size;
    const geometry = new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3(...end)]);
    g.add(new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: colours[axis] })));
  }
  return g;
}

function setPose(object, p) {
  object.position.set(p[0], p[1], p[2]);
  object.quaternion.set(p[4], p[5], p[6], p[3]);
}

const pathPoints = data.points.length ? data.points : [[0, 0, 0]];
const traceCount = () => Math.min(4000, Math.max(400, 8 * shown.segments + 1));

function drawKeys() {
  clear(layers.keys);
  const size = 0.06 * extent();
  poses.forEach((p, i) => {
    const key = triad(size);
    setPose(key, [...p.position, ...p.quaternion]);
    const tag = label(String(i), 0.5 * size);
    tag.position.set(p.position[0], p.position[1], p.position[2] + 0.45 * size);
    layers.keys.add(key, tag);
  });
}

function drawPaths() {
  clear(layers.paths);
  for (const x of pathPoints) {
    const values = kernel.trajectory(x[0], x[1], x[2], traceCount());
    if (values.error) throw new Error(values.error);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(values), 3));
    geometry.computeBoundingBox();
    box.union(geometry.boundingBox);
    layers.paths.add(new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0x1f4e9c })));
  }
}

// The exact sweep: each profile edge's NURBS surface, evaluated by the kernel on a grid.
function drawSweep() {
  clear(layers.sweep);
  if (!data.profile) return;
  const nt = Math.min(2000, Math.max(65, 4 * shown.segments + 1));
  for (const edge of data.profile) {
    // A straight edge (degree 1, one span) sweeps a ruled surface: straight along v.
    const spans = new Set(edge.knots).size - 1;
    const nv = edge.degree === 1 && spans === 1 ? 2 : Math.min(200, Math.max(9, 4 * edge.degree * spans + 1));
    const values = kernel.sweepEdge(edge.degree, edge.knots, edge.control_points.flat(), edge.weights, nt, nv);
    if (values.error) throw new Error(values.error);
    const index = new Uint32Array(6 * (nt - 1) * (nv - 1));
    let k = 0;
    for (let i = 0; i + 1 < nt; ++i)
      for (let j = 0; j + 1 < nv; ++j) {
        const a = i * nv + j;
        index.set([a, a + nv, a + 1, a + 1, a + nv, a + nv + 1], k);
        k += 6;
      }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(values), 3));
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    geometry.computeVertexNormals();
    const material = new THREE.MeshStandardMaterial({
      color: 0x9ab8d8, side: THREE.DoubleSide, transparent: true, opacity: 0.55, depthWrite: false,
      metalness: 0.05, roughness: 0.6,
    });
    layers.sweep.add(new THREE.Mesh(geometry, material));
  }
}

// The moving object: the body, else the profile, else a frame.
const mover = new THREE.Group();
scene.add(mover);
// A triangle mesh as the data carry it: positions (3 numbers a vertex) and indices.
function meshOf(m, material) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(m.positions), 3));
  geometry.setIndex(m.indices);
  geometry.computeVertexNormals();
  return new THREE.Mesh(geometry, material);
}
if (data.body)
  mover.add(meshOf(data.body, new THREE.MeshStandardMaterial({ color: 0xe08a3c, flatShading: true })));
// The body's swept volume (view --volume): the certified enclosing mesh, fixed, translucent.
const volume = new THREE.Group();
scene.add(volume);
if (data.volume)
  volume.add(meshOf(data.volume, new THREE.MeshStandardMaterial(
    { color: 0x4a7fb5, transparent: true, opacity: 0.35, depthWrite: false, side: THREE.DoubleSide })));
if (data.profile)
  for (const edge of data.profile) {
    const n = 64, points = [];
    const curve = kernel.curvePoints(edge.degree, edge.knots, edge.control_points.flat(), edge.weights, n);
    for (let i = 0; i < n; ++i) points.push(new THREE.Vector3(curve[3 * i], curve[3 * i + 1], curve[3 * i + 2]));
    const geometry = new THREE.BufferGeometry().setFromPoints(points);
    mover.add(new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0xc0392b })));
  }

// Time: a slider over [a, b], play and pause.
const slider = document.getElementById("t");
const tText = document.getElementById("t-value");
let playing = false, last = 0;
function showTime(t) {
  const p = kernel.evaluate(t);
  if (p.error) return say(p.error, true);
  setPose(mover, p);
  tText.textContent = `t = ${t.toPrecision(6)}`;
}
function sliderTime() {
  return shown.a + ((shown.b - shown.a) * Number(slider.value)) / Number(slider.max);
}
slider.addEventListener("input", () => showTime(sliderTime()));
document.getElementById("play").addEventListener("click", (e) => {
  playing = !playing;
  e.target.textContent = playing ? "Pause" : "Play";
});

// The view directions of `qmotion render`, looking at the scene's centre.
const views = { iso: [1, 1, 1], top: [0, 0, 1], front: [0, -1, 0], side: [1, 0, 0] };
function look(name) {
  const centre = box.getCenter(new THREE.Vector3());
  const d = new THREE.Vector3(...views[name]).normalize();
  camera.up.set(0, 0, 1);
  if (name === "top") camera.up.set(0, 1, 0);
  camera.position.copy(centre).addScaledVector(d, 4 * extent());
  controls.target.copy(centre);
  const w = canvas.clientWidth, h = canvas.clientHeight, half = 0.55 * extent();
  camera.left = (-half * w) / h;
  camera.right = (half * w) / h;
  camera.top = half;
  camera.bottom = -half;
  camera.zoom = 1;
  camera.updateProjectionMatrix();
  controls.update();
}
for (const name of Object.keys(views))
  document.getElementById(`view-${name}`).addEventListener("click", () => look(name));

// The poses, editable when the file records how it was made.
const table = document.getElementById("poses");
const degrees = 180 / Math.PI;
function eulerOf(q) {
  const e = new THREE.Euler().setFromQuaternion(new THREE.Quaternion(q[1], q[2], q[3], q[0]), "XYZ");
  return [e.x * degrees, e.y * degrees, e.z * degrees];
}
function redraw() {
  box.makeEmpty();
  for (const p of poses) box.expandByPoint(new THREE.Vector3(...p.position));
  drawPaths();
  drawKeys();
  drawSweep();
  showTime(sliderTime());
}
function edit(i, field, k, value) {
  const p = poses[i];
  if (!Number.isFinite(value)) return say(`pose ${i}: ${field} must be a number`, true);
  if (field === "position") p.position[k] = value;
  else {
    const angles = eulerOf(p.quaternion);
    angles[k] = value;
    const q = new THREE.Quaternion().setFromEuler(
      new THREE.Euler(angles[0] / degrees, angles[1] / degrees, angles[2] / degrees, "XYZ"));
    p.quaternion = [q.w, q.x, q.y, q.z];
  }
  const flat = poses.flatMap((x) => [x.t ?? NaN, ...x.position, ...x.quaternion]);
  const result = kernel.interpolate(flat, data.method);
  if (result.error) return say(`pose ${i}: ${result.error}`, true);
  shown = result;
  redraw();
  say(`interpolated again: ${data.method.form ?? data.method.scheme}, ${shown.segments} segments`, false);
}
poses.forEach((p, i) => {
  const row = table.insertRow();
  row.insertCell().textContent = String(i);
  const cells = [
    ["position", p.position],
    ["rotation", eulerOf(p.quaternion)],
  ];
  for (const [field, values] of cells)
    values.forEach((v, k) => {
      const input = document.createElement("input");
      input.type = "number";
      input.step = "any";
      input.value = String(Number(v.toPrecision(12)));
      input.id = `pose-${i}-${field}-${k}`;
      input.disabled = !data.method;
      input.addEventListener("change", () => edit(i, field, k, Number(input.value)));
      row.insertCell().appendChild(input);
    });
});
if (!data.method) say(`${data.name}: the file does not record how it was made, so its poses are shown, not edited`);

// Saving: the poses as edited, as a pose file, and the motion the page holds, as a motion
// file (docs/formats.md); `qmotion interpolate` and every other command read them back.
function posesDocument() {
  return { units: data.units, poses: poses.map((p) => Object.assign(p.t == null ? {} : { t: p.t },
    { position: [...p.position], rotation: { quaternion: [...p.quaternion] } })) };
}
function rows(flat, n) {
  const out = [];
  for (let i = 0; i + n <= flat.length; i += n) out.push(Array.from(flat.subarray(i, i + n)));
  return out;
}
function motionDocument() {
  const m = kernel.motionDocument();
  if (m.error) throw new Error(m.error);
  const doc = { type: m.type, units: data.units, param_range: Array.from(m.param_range),
                knots: Array.from(m.knots) };
  if (m.type === "q-motion")
    return Object.assign(doc, { basis: m.basis, degree: m.degree, control_points: rows(m.control_points, 8) });
  Object.assign(doc, { scheme: m.scheme, keys: rows(m.keys, 4), positions: rows(m.positions, 3) });
  if (m.scheme === "quintic") doc.tension = Array.from(m.tension);
  if (m.scheme === "kks")
    Object.assign(doc, { control_quaternions: rows(m.control_quaternions, 4),
                         control_positions: rows(m.control_positions, 3) });
  return doc;
}
function download(name, doc) {
  const url = URL.createObjectURL(new Blob([JSON.stringify(doc, null, 1) + "\n"], { type: "application/json" }));
  const a = Object.assign(document.createElement("a"), { href: url, download: name });
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}
const stem = data.name.replace(/^.*[\\/]/, "").replace(/\.[^.]*$/, "");
document.getElementById("save-poses").addEventListener("click", () => download(`${stem}-poses.json`, posesDocument()));
document.getElementById("save-motion").addEventListener("click", () => download(`${stem}-motion.json`, motionDocument()));

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  renderer.setSize(w, h, false);
  const half = camera.top;
  camera.left = (-half * w) / h;
  camera.right = (half * w) / h;
  camera.updateProjectionMatrix();
}
window.addEventListener("resize", resize);

redraw();
look("iso");
resize();
renderer.setAnimationLoop((now) => {
  if (playing) {
    const step = ((now - last) / 6000) * Number(slider.max);
    slider.value = String((Number(slider.value) + Math.max(step, 0)) % Number(slider.max));
    showTime(sliderTime());
  }
  last = now;
  controls.update();
  renderer.render(scene, camera);
});

window.qmotion = {
  evaluate: (t) => Array.from(kernel.evaluate(t)),
  range: () => [shown.a, shown.b],
  poses: () => copyPoses(poses),
  method: data.method,
  posesDocument,
  motionDocument,
  // The swept volume as drawn: its triangles, and its vertices as the GPU holds them.
  drawnVolume: () => volume.children.map((m) => ({
    triangles: m.geometry.index.count / 3, positions: Array.from(m.geometry.getAttribute("position").array),
  })),
  // Where the camera looks from (unit vector from the target) and its up direction.
  camera: () => ({ from: camera.position.clone().sub(controls.target).normalize().toArray(),
                   up: camera.up.toArray(), zoom: camera.zoom }),
  kernel, // the WebAssembly kernel itself (render/viewer/kernel_wasm.cpp)
  // The trajectories as drawn (3 numbers per vertex) and the points they trace.
  drawnPaths: () => layers.paths.children.map((line, i) => ({
    point: pathPoints[i], positions: Array.from(line.geometry.getAttribute("position").array),
  })),
  interpolateAndSweep(flat) {
    const result = kernel.interpolate(flat, data.method);
    if (result.error) return result.error;
    shown = result;
    drawPaths();
    drawSweep();
    return null;
  },
  ready: true,
};
document.body.dataset.ready = "true";
