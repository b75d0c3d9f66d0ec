// The superdex viewer (docs/viewer.md): plays the trajectory embedded in this page with three.js
// (the global THREE of vendor/three.min.js, with THREE.OrbitControls).
//
// Options in the URL's hash, for links and for the browser test (tests/viewer/):
//   #t=0.5                       start paused at t [s]
//   &camera=ex,ey,ez,tx,ty,tz    eye and target [m] (up is +z); default: the whole scene
//   &fov=40                      vertical field of view [deg]
//   &contacts=0&forces=0         hide (1: show) the contact samples / the contact force arrows;
//                                by default shown unless the scene has over 50 dynamic actors
//   &play=1&speed=2              start playing, at twice the simulated rate
//   &size=1000x600               a fixed view of that many CSS pixels (screenshots), the
//                                panels placed in it
// window.__setTime(t) shows time t; #viewer-status holds the page's state as JSON. A module
// script: run once the document is parsed, its names its own.
const timings = { scriptStart: performance.now() };  // [ms] since the navigation started
const data = JSON.parse(document.getElementById('superdex-data').textContent);
timings.dataParsed = performance.now();
const options = parseHash(window.location.hash);
const times = data.times;
const t0 = times[0];
const t1 = times[times.length - 1];
const palette = ['#e4572e', '#2e86ab', '#76b041', '#8e44ad', '#f3a712', '#17becf', '#c2185b'];
const staticColor = '#9aa3ad';
const energyColors = { kinetic: '#e4572e', gravity: '#2e86ab', contact: '#f3a712',
                       elastic: '#76b041', total: '#111111' };

function parseHash(text) {
  const out = {};
  for (const part of text.replace(/^#/, '').split('&')) {
    if (!part) continue;
    const eq = part.indexOf('=');
    out[decodeURIComponent(eq < 0 ? part : part.slice(0, eq))] =
        eq < 0 ? '1' : decodeURIComponent(part.slice(eq + 1));
  }
  return out;
}

// --- Frames: base64 little-endian Float32 blocks, decoded when first shown (a few kept).
const cache = new Map();
function decodeFloats(text) {
  if (!text) return new Float32Array(0);
  const bytes = atob(text);
  const buffer = new Uint8Array(bytes.length);
  for (let i = 0; i < bytes.length; ++i) buffer[i] = bytes.charCodeAt(i);
  return new Float32Array(buffer.buffer);
}
function block(kind, frame) {
  const key = kind + frame;
  let values = cache.get(key);
  if (!values) {
    values = decodeFloats(data.frames[frame][kind]);
    if (cache.size > 256) cache.delete(cache.keys().next().value);
    cache.set(key, values);
  }
  return values;
}
// The frames around time t: index i, i + 1 and the weight of i + 1.
function framesAt(t) {
  let lo = 0;
  let hi = times.length - 1;
  if (t <= times[0]) return [0, 0, 0];
  if (t >= times[hi]) return [hi, hi, 0];
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= t) lo = mid; else hi = mid;
  }
  return [lo, hi, (t - times[lo]) / (times[hi] - times[lo])];
}

// --- Renderer, scene, camera.
const stage = document.getElementById('stage');
const fixedSize = /^(\d+)x(\d+)$/.exec(options.size || '');
if (fixedSize) {
  stage.style.width = fixedSize[1] + 'px';
  stage.style.height = fixedSize[2] + 'px';
}
const canvas = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true,
                                           preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(stage.clientWidth, stage.clientHeight, false);
const scene = new THREE.Scene();
scene.background = new THREE.Color('#eef1f5');
scene.add(new THREE.HemisphereLight('#ffffff', '#8a8f99', 1.6));
const sun = new THREE.DirectionalLight('#ffffff', 1.6);
sun.position.set(0.4, -0.6, 1.0);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(Number(options.fov || 40),
                                           stage.clientWidth / stage.clientHeight, 1e-3, 1e3);
camera.up.set(0, 0, 1);

// --- Actors: spheres and boxes as instanced meshes (one draw per shape), meshes, planes as a
// patch, soft surfaces rebuilt per frame.
const actors = [];  // per actor: how it is drawn
const groups = new Map();
const colors = {};
let paletteNext = 0;

function groupColor(dynamic) {
  return dynamic ? palette[paletteNext++ % palette.length] : staticColor;
}
function material(color, dynamic) {
  return new THREE.MeshLambertMaterial({ color, transparent: !dynamic,
                                         opacity: dynamic ? 1 : 0.45, depthWrite: dynamic,
                                         side: THREE.DoubleSide });
}
function shapeGeometry(shape, count) {
  if (shape.type === 'sphere') {
    return count > 200 ? new THREE.SphereGeometry(shape.radius, 16, 10)  // piles: lighter
                       : new THREE.SphereGeometry(shape.radius, 32, 16);
  }
  const h = shape.half_extents;
  return new THREE.BoxGeometry(2 * h[0], 2 * h[1], 2 * h[2]);
}
function addInstanced(index, actor, shape) {
  const key = JSON.stringify([shape, actor.dynamic]);
  let group = groups.get(key);
  if (!group) {
    group = { shape, dynamic: actor.dynamic, color: groupColor(actor.dynamic), actors: [] };
    groups.set(key, group);
  }
  actors[index] = { kind: 'instance', group, slot: group.actors.length };
  group.actors.push(index);
  colors[actor.name] = group.color;
}
function meshGeometry(vertices, faces) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(vertices), 3));
  geometry.setIndex(faces);
  geometry.computeVertexNormals();
  return geometry;
}
function addObject(index, actor, object, kind) {
  scene.add(object);
  actors[index] = { kind, object };
  colors[actor.name] = '#' + object.material.color.getHexString();
}
function addSoft(index, actor, offset) {
  const nodes = actor.surface.nodes;
  const geometry = meshGeometry(new Float32Array(3 * nodes), actor.surface.faces);
  geometry.attributes.position.setUsage(THREE.DynamicDrawUsage);
  const mesh = new THREE.Mesh(geometry, material(palette[paletteNext++ % palette.length], true));
  addObject(index, actor, mesh, 'soft');
  actors[index].offset = offset;
  actors[index].nodes = nodes;
}
function buildActors() {
  let softOffset = 0;
  data.actors.forEach((actor, index) => {
    const shape = actor.shape || { type: 'sphere', radius: 0 };  // radius 0: a marker
    if (actor.surface) {
      addSoft(index, actor, softOffset);
      softOffset += 3 * actor.surface.nodes;
    } else if (shape.type === 'mesh') {
      const mesh = new THREE.Mesh(meshGeometry(shape.vertices, shape.faces),
                                  material(groupColor(actor.dynamic), actor.dynamic));
      addObject(index, actor, mesh, 'mesh');
    } else if (shape.type === 'plane') {
      actors[index] = { kind: 'plane', normal: shape.normal };
      colors[actor.name] = '#c3c9d2';
    } else {
      addInstanced(index, actor, shape);
    }
  });
}

// --- Scene bounds (over a sample of the frames), for the default camera and the planes.
// An actor's half extents in the world frame at orientation q: a box's rotated box, a
// sphere's radius, a mesh's farthest vertex.
function meshRadius(s) {
  let r = 0;
  for (let k = 0; k < s.vertices.length; k += 3)
    r = Math.max(r, Math.hypot(s.vertices[k], s.vertices[k + 1], s.vertices[k + 2]));
  return r;
}
function halfExtents(shape, q, radius, out) {
  if (!shape || shape.type === 'plane') return out.set(0, 0, 0);
  if (shape.type !== 'box') return out.setScalar(radius);
  const m = new THREE.Matrix4().makeRotationFromQuaternion(q).elements;
  const h = shape.half_extents;
  for (let r = 0; r < 3; ++r)
    out.setComponent(r, Math.abs(m[r]) * h[0] + Math.abs(m[4 + r]) * h[1] +
                        Math.abs(m[8 + r]) * h[2]);
  return out;
}
function sampledFrames() {
  const step = Math.max(1, Math.floor(times.length / 40));
  const out = [];
  for (let f = 0; f < times.length; f += step) out.push(f);
  if (out[out.length - 1] !== times.length - 1) out.push(times.length - 1);
  return out;
}
function sceneBounds() {
  const box = new THREE.Box3();
  const p = new THREE.Vector3();
  const h = new THREE.Vector3();
  const q = new THREE.Quaternion();
  const radii = data.actors.map((a) => (a.shape && a.shape.type === 'sphere' ? a.shape.radius
                                        : a.shape && a.shape.type === 'mesh' ? meshRadius(a.shape)
                                        : 0));
  for (const f of sampledFrames()) {
    const pose = block('pose', f);
    const surface = block('surface', f);
    data.actors.forEach((actor, i) => {
      if (actor.shape && actor.shape.type === 'plane') return;
      p.set(pose[7 * i], pose[7 * i + 1], pose[7 * i + 2]);
      if (!isFinite(p.x + p.y + p.z)) return;
      q.set(pose[7 * i + 3], pose[7 * i + 4], pose[7 * i + 5], pose[7 * i + 6]);
      halfExtents(actor.shape, q, radii[i], h);
      box.expandByPoint(p.clone().add(h));
      box.expandByPoint(p.clone().sub(h));
    });
    for (let k = 0; k + 2 < surface.length; k += 3)
      if (isFinite(surface[k])) box.expandByPoint(p.fromArray(surface, k));
  }
  if (box.isEmpty()) box.setFromCenterAndSize(new THREE.Vector3(), new THREE.Vector3(1, 1, 1));
  return box;
}

// Planes: a square patch with a grid, centred under the scene.
function buildPlanes(bounds) {
  const centre = bounds.getCenter(new THREE.Vector3());
  const size = 2.5 * Math.max(bounds.max.x - bounds.min.x, bounds.max.y - bounds.min.y,
                              bounds.max.z - bounds.min.z, 0.2);
  const pose0 = block('pose', 0);
  actors.forEach((a, i) => {
    if (a.kind !== 'plane') return;
    const origin = new THREE.Vector3(pose0[7 * i], pose0[7 * i + 1], pose0[7 * i + 2]);
    const q = new THREE.Quaternion(pose0[7 * i + 3], pose0[7 * i + 4], pose0[7 * i + 5],
                                   pose0[7 * i + 6]);
    const n = new THREE.Vector3().fromArray(a.normal).applyQuaternion(q).normalize();
    const at = centre.clone().sub(n.clone().multiplyScalar(n.dot(centre.clone().sub(origin))));
    const patch = new THREE.Group();
    const surface = new THREE.Mesh(new THREE.PlaneGeometry(size, size),
                                   new THREE.MeshLambertMaterial({ color: '#c3c9d2',
                                                                   side: THREE.DoubleSide }));
    const grid = new THREE.GridHelper(size, 20, '#8d95a1', '#a9b0ba');
    grid.rotation.x = Math.PI / 2;  // GridHelper lies in x-z; the patch in x-y
    grid.position.z = 1e-4 * size;
    patch.add(surface, grid);
    patch.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n);
    patch.position.copy(at);
    scene.add(patch);
  });
}

// One instanced mesh per shape; actors without a shape (older trajectories) as small markers.
function buildGroups(bounds) {
  const marker = { type: 'sphere', radius: 0.01 * bounds.getSize(new THREE.Vector3()).length() };
  for (const group of groups.values()) {
    const mesh = new THREE.InstancedMesh(shapeGeometry(group.shape.radius === 0 ? marker
                                                                                : group.shape,
                                                       group.actors.length),
                                         material(group.color, group.dynamic),
                                         group.actors.length);
    mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    mesh.frustumCulled = false;
    group.mesh = mesh;
    scene.add(mesh);
  }
}

// --- Poses at time t: positions interpolated linearly, orientations by normalized lerp.
const tmp = { p: new THREE.Vector3(), q: new THREE.Quaternion(), qb: new THREE.Quaternion(),
              m: new THREE.Matrix4(), s: new THREE.Vector3(1, 1, 1),
              zero: new THREE.Vector3(0, 0, 0) };
function pose(a, b, w, i) {
  const o = 7 * i;
  tmp.p.set(a[o] + w * (b[o] - a[o]), a[o + 1] + w * (b[o + 1] - a[o + 1]),
            a[o + 2] + w * (b[o + 2] - a[o + 2]));
  tmp.q.set(a[o + 3], a[o + 4], a[o + 5], a[o + 6]);
  tmp.qb.set(b[o + 3], b[o + 4], b[o + 5], b[o + 6]);
  if (tmp.q.dot(tmp.qb) < 0) tmp.qb.set(-tmp.qb.x, -tmp.qb.y, -tmp.qb.z, -tmp.qb.w);
  tmp.q.set(tmp.q.x + w * (tmp.qb.x - tmp.q.x), tmp.q.y + w * (tmp.qb.y - tmp.q.y),
            tmp.q.z + w * (tmp.qb.z - tmp.q.z), tmp.q.w + w * (tmp.qb.w - tmp.q.w)).normalize();
  return isFinite(tmp.p.x) && isFinite(tmp.p.y) && isFinite(tmp.p.z);
}
function updateSoft(actor, a, b, w) {
  const attribute = actor.object.geometry.attributes.position;
  const out = attribute.array;
  const visible = isFinite(a[actor.offset]) && isFinite(b[actor.offset]);
  actor.object.visible = visible;
  if (!visible) return;
  for (let k = 0; k < 3 * actor.nodes; ++k) {
    const j = actor.offset + k;
    out[k] = a[j] + w * (b[j] - a[j]);
  }
  attribute.needsUpdate = true;
  actor.object.geometry.computeVertexNormals();
  actor.object.geometry.computeBoundingSphere();
}
function updateActors(f) {
  const [i, j, w] = f;
  const a = block('pose', i);
  const b = block('pose', j);
  const sa = block('surface', i);
  const sb = block('surface', j);
  actors.forEach((actor, index) => {
    if (actor.kind === 'plane') return;
    if (actor.kind === 'soft') return updateSoft(actor, sa, sb, w);
    const shown = pose(a, b, w, index);
    if (actor.kind === 'instance') {
      tmp.m.compose(tmp.p, tmp.q, shown ? tmp.s : tmp.zero);
      actor.group.mesh.setMatrixAt(actor.slot, tmp.m);
    } else {
      actor.object.visible = shown;
      actor.object.position.copy(tmp.p);
      actor.object.quaternion.copy(tmp.q);
    }
  });
  for (const group of groups.values()) group.mesh.instanceMatrix.needsUpdate = true;
}

// --- Contacts: samples as points coloured by normal traction, the net force per actor pair as
// an arrow (lines), both drawn over the bodies. Every frame's are uploaded once, when first
// shown, into one buffer each; showing a frame is choosing its draw range.
const contacts = { points: null, arrows: null, sampleStart: null, arrowStart: null, size: 1 };
const arrowVertices = 10;  // the shaft and four lines of the head
function tractionColor(x, color) {
  return color.setHSL(0.66 * (1 - Math.min(1, Math.max(0, x))), 1, 0.5);
}
function lineGeometry(positions, colors) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  if (colors) geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
  return geometry;
}
// Decodes one block of every frame; returns them and the running start of each frame's items.
function allFrames(kind, stride) {
  const blocks = data.frames.map((f) => decodeFloats(f[kind]));
  const start = [0];
  for (const b of blocks) start.push(start[start.length - 1] + b.length / stride);
  return { blocks, start };
}
function loadSamples() {
  const { blocks, start } = allFrames('contacts', 4);  // per sample: position, normal traction
  const total = start[start.length - 1];
  const positions = new Float32Array(3 * total);
  const colors = new Float32Array(3 * total);
  const color = new THREE.Color();
  let s = 0;
  for (const b of blocks) {
    for (let k = 0; k < b.length; k += 4, ++s) {
      positions.set(b.subarray(k, k + 3), 3 * s);
      tractionColor(b[k + 3] / (data.max_traction || 1), color).toArray(colors, 3 * s);
    }
  }
  contacts.points.geometry.dispose();
  contacts.points.geometry = lineGeometry(positions, colors);
  contacts.sampleStart = start;
}
// An arrow from `from` along force f (scaled) into out at vertex v: shaft, then the head's
// four lines from the tip back around the shaft.
function writeArrow(out, v, from, f) {
  const length = f.length();
  const tip = from.clone().add(f);
  const head = Math.min(0.3 * length, 0.02 * contacts.size);
  const u = length > 0 ? f.clone().divideScalar(length) : new THREE.Vector3(0, 0, 1);
  const a = new THREE.Vector3(1, 0, 0).cross(u);
  if (a.lengthSq() < 1e-6) a.set(0, 1, 0).cross(u);
  a.normalize();
  const b = u.clone().cross(a);
  const base = tip.clone().addScaledVector(u, -head);
  const ends = [from, tip];
  for (const [w, sign] of [[a, 1], [a, -1], [b, 1], [b, -1]])
    ends.push(tip, base.clone().addScaledVector(w, 0.35 * head * sign));
  ends.forEach((p, k) => p.toArray(out, 3 * (v + k)));
}
function loadArrows() {
  const { blocks, start } = allFrames('forces', 6);  // per pair: point, net force
  const positions = new Float32Array(3 * arrowVertices * start[start.length - 1]);
  const scale = 0.25 * contacts.size / (data.max_pair_force || 1);
  const from = new THREE.Vector3();
  const f = new THREE.Vector3();
  let v = 0;
  for (const b of blocks) {
    for (let k = 0; k < b.length; k += 6, v += arrowVertices)
      writeArrow(positions, v, from.fromArray(b, k), f.fromArray(b, k + 3).multiplyScalar(scale));
  }
  contacts.arrows.geometry.dispose();
  contacts.arrows.geometry = lineGeometry(positions);
  contacts.arrowStart = start;
}
function buildContacts(bounds) {
  contacts.size = bounds.getSize(new THREE.Vector3()).length();
  const overlay = { depthTest: false, depthWrite: false };
  contacts.points = new THREE.Points(new THREE.BufferGeometry(), new THREE.PointsMaterial(
      Object.assign({ size: 5, sizeAttenuation: false, vertexColors: true }, overlay)));
  contacts.arrows = new THREE.LineSegments(new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial(Object.assign({ color: '#1a1a1a' }, overlay)));
  for (const o of [contacts.points, contacts.arrows]) {
    o.renderOrder = 10;
    o.frustumCulled = false;
    o.visible = false;
    scene.add(o);
  }
}
// Shows the samples and arrows of frame f (as the checkboxes say).
function showContacts(f) {
  const samples = ui.contacts.checked && data.contact_samples > 0;
  if (samples && !contacts.sampleStart) loadSamples();
  contacts.points.visible = samples;
  if (samples) {
    const start = contacts.sampleStart;
    contacts.points.geometry.setDrawRange(start[f], start[f + 1] - start[f]);
  }
  const arrows = ui.forces.checked && data.contact_samples > 0;
  if (arrows && !contacts.arrowStart) loadArrows();
  contacts.arrows.visible = arrows;
  if (arrows) {
    const start = contacts.arrowStart;
    contacts.arrows.geometry.setDrawRange(arrowVertices * start[f],
                                          arrowVertices * (start[f + 1] - start[f]));
  }
}

// --- The energy plot: the series drawn once, the cursor at the current time on top.
const plot = { canvas: document.getElementById('energy-plot'), background: null,
               rect: null, series: [] };
function plotRange() {
  let lo = Infinity;
  let hi = -Infinity;
  for (const name of Object.keys(energyColors)) {
    const values = (data.energy || {})[name] || [];
    if (values.every((v) => v === null || v === 0) && name !== 'total') continue;
    plot.series.push(name);
    for (const v of values) if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  }
  if (!(hi >= lo)) return null;
  const pad = 0.05 * Math.max(hi - lo, 1e-12);
  return [lo - pad, hi + pad];
}
function drawSeries(ctx, name, x, y) {
  ctx.strokeStyle = energyColors[name];
  ctx.lineWidth = name === 'total' ? 2 : 1.5;
  ctx.beginPath();
  let pen = false;
  data.energy[name].forEach((v, k) => {
    if (v === null) { pen = false; return; }
    if (pen) ctx.lineTo(x(times[k]), y(v)); else ctx.moveTo(x(times[k]), y(v));
    pen = true;
  });
  ctx.stroke();
}
function drawPlotBackground() {
  const c = plot.canvas;
  const ctx = c.getContext('2d');
  const r = plot.rect = { left: 56, top: 24, width: c.width - 66, height: c.height - 46 };
  ctx.fillStyle = '#ffffff';
  ctx.fillRect(0, 0, c.width, c.height);
  ctx.fillStyle = '#1d2430';
  ctx.font = '12px system-ui, sans-serif';
  ctx.fillText('energy [J]', 6, 15);
  const range = plotRange();
  if (!range) {
    ctx.fillText('no energies in this trajectory', r.left, r.top + r.height / 2);
  } else {
    const x = (t) => r.left + (t1 > t0 ? (t - t0) / (t1 - t0) : 0) * r.width;
    const y = (v) => r.top + (1 - (v - range[0]) / (range[1] - range[0])) * r.height;
    ctx.strokeStyle = '#c8cdd4';
    ctx.strokeRect(r.left, r.top, r.width, r.height);
    ctx.textAlign = 'right';
    ctx.fillText(range[1].toPrecision(3), r.left - 4, r.top + 8);
    ctx.fillText(range[0].toPrecision(3), r.left - 4, r.top + r.height);
    ctx.fillText(t1.toPrecision(3) + ' s', r.left + r.width, c.height - 6);
    ctx.textAlign = 'left';
    ctx.fillText(t0.toPrecision(3) + ' s', r.left, c.height - 6);
    plot.series.forEach((name, k) => {
      drawSeries(ctx, name, x, y);
      ctx.fillStyle = energyColors[name];
      ctx.fillText(name, 84 + 58 * k, 15);
    });
  }
  plot.background = ctx.getImageData(0, 0, c.width, c.height);
}
function drawPlotCursor(t) {
  const ctx = plot.canvas.getContext('2d');
  const r = plot.rect;
  ctx.putImageData(plot.background, 0, 0);
  const x = Math.round(r.left + (t1 > t0 ? (t - t0) / (t1 - t0) : 0) * r.width) + 0.5;
  ctx.strokeStyle = '#7b2cbf';
  ctx.lineWidth = 1;
  ctx.beginPath();
  ctx.moveTo(x, r.top);
  ctx.lineTo(x, r.top + r.height);
  ctx.stroke();
}

// --- The info panel: legend, traction scale, notes.
function swatchRow(color, label) {
  const row = document.createElement('div');
  row.className = 'row';
  const swatch = document.createElement('span');
  swatch.className = 'swatch';
  swatch.style.background = color;
  const text = document.createElement('span');
  text.textContent = label;
  row.append(swatch, text);
  return row;
}
function groupLabel(indices) {
  const names = indices.map((i) => data.actors[i].name);
  if (names.length === 1) return names[0];
  return names[0] + ' … ' + names[names.length - 1] + ' (' + names.length + ')';
}
function buildInfo() {
  document.title = data.title + ' · superdex';
  document.getElementById('title').textContent = data.title;
  const s = data.settings || {};
  document.getElementById('summary').textContent =
      data.actors.length + ' actors, ' + times.length + ' frames, t = ' + t0.toPrecision(3) +
      ' – ' + t1.toPrecision(4) + ' s' +
      (s.integrator ? ', ' + s.integrator : '');
  const legend = document.getElementById('legend');
  for (const group of groups.values())
    legend.append(swatchRow(group.color, groupLabel(group.actors)));
  actors.forEach((a, i) => {
    const name = data.actors[i].name;
    if (a.kind !== 'instance') legend.append(swatchRow(colors[name], name));
  });
  const contactLegend = document.getElementById('contact-legend');
  if (!data.contact_samples) {
    const note = document.createElement('div');
    note.className = 'note';
    note.textContent = 'No contact samples in this trajectory (run with --contacts, or ' +
                       'output.contacts in the scene file).';
    contactLegend.append(note);
    return;
  }
  const row = document.createElement('div');
  row.className = 'row';
  const bar = document.createElement('span');
  bar.id = 'traction-bar';
  bar.style.background = 'linear-gradient(to right, hsl(238,100%,50%), hsl(120,100%,50%), ' +
                         'hsl(60,100%,50%), hsl(0,100%,50%))';
  const label = document.createElement('span');
  label.textContent = 'normal traction 0 – ' + data.max_traction.toPrecision(3) + ' Pa';
  row.append(bar, label);
  const arrows = document.createElement('div');
  arrows.className = 'note';
  arrows.textContent = 'arrows: net contact force per actor pair, ' +
                       data.max_pair_force.toPrecision(3) + ' N = ' +
                       (0.25 * contacts.size).toPrecision(2) + ' m';
  contactLegend.append(row, arrows);
}

// --- Time, controls, rendering.
const ui = { play: document.getElementById('play'), slider: document.getElementById('slider'),
             time: document.getElementById('time'), speed: document.getElementById('speed'),
             contacts: document.getElementById('show-contacts'),
             forces: document.getElementById('show-forces') };
const state = { t: t0, playing: false, last: 0, frame: [0, 0, 0], ready: false };
function render() {
  renderer.render(scene, camera);
}
function setTime(t) {
  state.t = Math.min(t1, Math.max(t0, Number(t)));
  state.frame = framesAt(state.t);
  updateActors(state.frame);
  const nearest = state.frame[2] < 0.5 ? state.frame[0] : state.frame[1];
  showContacts(nearest);
  ui.slider.value = state.t;
  ui.time.textContent = 't = ' + state.t.toFixed(4) + ' s';
  drawPlotCursor(state.t);
  render();
  writeStatus();
}
function tick(now) {
  if (state.playing) {
    const elapsed = state.last ? (now - state.last) / 1000 : 0;
    let t = state.t + elapsed * Number(ui.speed.value);
    if (t > t1) t = t0 + (t - t1) % Math.max(t1 - t0, 1e-9);
    setTime(t);
  }
  state.last = now;
  window.requestAnimationFrame(tick);
}
function setPlaying(playing) {
  state.playing = playing;
  ui.play.textContent = playing ? 'pause' : 'play';
}
function wireControls(controls) {
  ui.slider.min = t0;
  ui.slider.max = t1;
  ui.slider.step = (t1 - t0) / 10000 || 'any';
  ui.play.addEventListener('click', () => setPlaying(!state.playing));
  ui.slider.addEventListener('input', () => { setPlaying(false); setTime(ui.slider.value); });
  ui.contacts.addEventListener('change', () => setTime(state.t));
  ui.forces.addEventListener('change', () => setTime(state.t));
  controls.addEventListener('change', render);
  window.addEventListener('resize', () => {
    camera.aspect = stage.clientWidth / stage.clientHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(stage.clientWidth, stage.clientHeight, false);
    render();
    writeStatus();
  });
  window.addEventListener('keydown', (e) => {
    if (e.key !== ' ' || e.target !== document.body) return;
    setPlaying(!state.playing);
    e.preventDefault();
  });
}
function placeCamera(bounds) {
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  const values = (options.camera || '').split(',').map(Number);
  if (values.length === 6 && values.every(isFinite)) {
    camera.position.set(values[0], values[1], values[2]);
    controls.target.set(values[3], values[4], values[5]);
  } else {
    const centre = bounds.getCenter(new THREE.Vector3());
    const radius = 0.5 * bounds.getSize(new THREE.Vector3()).length();
    const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov) / 2);
    controls.target.copy(centre);
    camera.position.copy(centre).add(new THREE.Vector3(0.55, -1, 0.6).normalize()
                                                                  .multiplyScalar(distance));
  }
  const reach = camera.position.distanceTo(controls.target) +
                bounds.getSize(new THREE.Vector3()).length();
  camera.near = reach / 2e4;
  camera.far = 10 * reach;
  camera.updateProjectionMatrix();
  controls.update();
  return controls;
}
function writeStatus() {
  const r = plot.canvas.getBoundingClientRect();
  document.getElementById('viewer-status').textContent = JSON.stringify({
    ready: state.ready, t: state.t, frames: state.frame, timings,
    width: stage.clientWidth, height: stage.clientHeight,
    camera: { position: camera.position.toArray(), fov: camera.fov, aspect: camera.aspect },
    drawCalls: renderer.info.render.calls, instancedGroups: groups.size,
    plot: { left: r.left + plot.rect.left, top: r.top + plot.rect.top,
            width: plot.rect.width, height: plot.rect.height, series: plot.series,
            colors: energyColors, cursor: '#7b2cbf' },
    colors });
}

function main() {
  buildActors();
  const bounds = sceneBounds();
  buildGroups(bounds);
  buildPlanes(bounds);
  buildContacts(bounds);
  buildInfo();
  drawPlotBackground();
  wireControls(placeCamera(bounds));
  // Many actors: the contacts and arrows would cover the bodies, so they start hidden.
  const many = data.actors.filter((a) => a.dynamic).length > 50;
  ui.contacts.checked = options.contacts !== undefined ? options.contacts !== '0' : !many;
  ui.forces.checked = options.forces !== undefined ? options.forces !== '0' : !many;
  if (options.speed) ui.speed.value = options.speed;
  timings.built = performance.now();
  setTime(options.t !== undefined ? Number(options.t) : t0);
  setPlaying(options.play === '1');
  state.ready = true;
  timings.firstFrame = performance.now();
  writeStatus();
  window.__setTime = setTime;
  window.__viewerReady = true;
  window.requestAnimationFrame(tick);
}

main();
