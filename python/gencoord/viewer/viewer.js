// SPDX-License-Identifier: BSD-3-Clause
// The viewer page's script (gencoord/viewer/page.py inlines it): plays the trajectory the page
// holds with three.js, with a time slider, speed, trails, an orbiting camera and a plot of the
// energy error or a coordinate with a cursor at the current time. `window.gencoordViewer`
// lets a program (the browser test) seek, play and read what is drawn where.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const COLOURS = [0x1f77b4, 0xd62728, 0x2ca02c, 0x9467bd, 0xff7f0e, 0x8c564b, 0xe377c2];
const TRAIL_SECONDS = 2.0;
const data = JSON.parse(document.getElementById("gencoord-data").textContent);
const model = data.scene;

function decode(text, Type) {
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  return new Type(bytes.buffer);
}

// --- the trajectory ---------------------------------------------------------------------
const times = decode(data.arrays.t, Float64Array);
// a model's run has an energy error and coordinates; a deformable run a mesh of springs
const energyError = data.energy ? decode(data.arrays.energy_error, Float32Array) : null;
// a dissipative model's work of its dampers and friction, drawn with its energy change
const work = data.arrays.work ? decode(data.arrays.work, Float32Array) : null;
const coordinates = data.arrays.q ? decode(data.arrays.q, Float32Array) : new Float32Array();
const frames = data.frames;
const numPoints = data.points.length;
const positions = new Float32Array(frames * numPoints * 3); // frames x points x 3, z = 0 in 2D
{
  const stored = decode(data.arrays.positions, Float32Array); // frames x points x dim
  const dim = model.dim;
  for (let k = 0; k < frames * numPoints; ++k) {
    for (let a = 0; a < dim; ++a) positions[3 * k + a] = stored[dim * k + a];
  }
}
const pointIndex = new Map(data.points.map((name, k) => [name, k]));
const t0 = times[0];
const t1 = times[frames - 1];

/** The frame i and weight w with times[i] <= time <= times[i + 1], w the share of i + 1. */
function locate(time) {
  if (time <= t0 || frames === 1) return [0, 0];
  if (time >= t1) return [frames - 1, 0];
  let lo = 0;
  let hi = frames - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= time) lo = mid;
    else hi = mid;
  }
  return [lo, (time - times[lo]) / (times[hi] - times[lo])];
}

const current = new Float32Array(numPoints * 3); // every point at the current time

function interpolate(time) {
  const [i, w] = locate(time);
  const a = i * numPoints * 3;
  const b = Math.min(i + 1, frames - 1) * numPoints * 3;
  for (let k = 0; k < numPoints * 3; ++k) {
    current[k] = (1 - w) * positions[a + k] + w * positions[b + k];
  }
}

/** A scene anchor ([[point, weight], ...]) at the current time. */
function anchorPosition(anchor, out) {
  out.set(0, 0, 0);
  for (const [name, weight] of anchor) {
    const k = pointIndex.get(name) * 3;
    out.x += weight * current[k];
    out.y += weight * current[k + 1];
    out.z += weight * current[k + 2];
  }
  return out;
}

function pointAt(name, out) {
  const k = pointIndex.get(name) * 3;
  return out.set(current[k], current[k + 1], current[k + 2]);
}

// --- extent and sizes -------------------------------------------------------------------
const box = new THREE.Box3();
{
  const p = new THREE.Vector3();
  for (let k = 0; k < frames * numPoints; ++k) {
    box.expandByPoint(p.fromArray(positions, 3 * k));
  }
}
const centre = box.getCenter(new THREE.Vector3());
const extent = Math.max(box.getSize(new THREE.Vector3()).length(), 0.2);
const radius0 = 0.03 * extent;
const is2d = model.dim === 2;
const up = new THREE.Vector3(...model.up, 0).setLength(1);
if (is2d) up.z = 0;

// --- the three.js scene -----------------------------------------------------------------
const view = document.getElementById("view");
/** Whether WebGL runs on a CPU renderer, where multisampling costs most of each frame. */
function softwareRenderer() {
  const gl = document.createElement("canvas").getContext("webgl2");
  const info = gl && gl.getExtension("WEBGL_debug_renderer_info");
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : "";
  if (gl) gl.getExtension("WEBGL_lose_context")?.loseContext();
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}

const renderer = new THREE.WebGLRenderer({ antialias: !softwareRenderer() });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const world = new THREE.Scene();
world.background = new THREE.Color(0xfafafa);
world.add(new THREE.AmbientLight(0xffffff, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.copy(up).multiplyScalar(2).add(new THREE.Vector3(1, 1, 1)).multiplyScalar(extent);
world.add(sun);

function material(colour, faded = false) {
  // flat colours in a plane (a picture of a 2D model), shading for depth in 3D
  const fading = faded ? { transparent: true, opacity: 0.45 } : {};
  return is2d
    ? new THREE.MeshBasicMaterial({ color: colour, ...fading })
    : new THREE.MeshStandardMaterial({ color: colour, roughness: 0.5, metalness: 0.1,
      ...fading });
}

const Y_AXIS = new THREE.Vector3(0, 1, 0);

function placeBetween(mesh, a, b) {
  const d = new THREE.Vector3().subVectors(b, a);
  const length = d.length();
  mesh.position.addVectors(a, b).multiplyScalar(0.5);
  if (length > 0) mesh.quaternion.setFromUnitVectors(Y_AXIS, d.divideScalar(length));
  mesh.scale.set(1, Math.max(length, 1e-9), 1);
}

const COIL_POINTS = 160;

/** A coil from a to b: a helix about the segment, fixed turns, ends straight. */
function drawCoil(entry) {
  const { a, b } = entry;
  const axis = new THREE.Vector3().subVectors(b, a);
  const length = axis.length() || 1e-9;
  axis.divideScalar(length);
  const side = new THREE.Vector3().crossVectors(axis, is2d ? new THREE.Vector3(0, 0, 1) : up);
  if (side.lengthSq() < 1e-12) side.set(1, 0, 0).cross(axis);
  side.normalize();
  const other = new THREE.Vector3().crossVectors(axis, side);
  const values = entry.coil.geometry.attributes.position.array;
  const turns = 10;
  const width = radius0 * 0.6;
  for (let k = 0; k < COIL_POINTS; ++k) {
    const s = k / (COIL_POINTS - 1);
    const along = a.clone().addScaledVector(axis, s * length);
    const inCoil = s > 0.1 && s < 0.9;
    const phase = 2 * Math.PI * turns * (s - 0.1) / 0.8;
    if (inCoil) {
      along.addScaledVector(side, width * Math.sin(phase));
      if (!is2d) along.addScaledVector(other, width * (Math.cos(phase) - 1) * 0.5);
    }
    along.toArray(values, 3 * k);
  }
  entry.coil.geometry.attributes.position.needsUpdate = true;
}

// The model's drawing: `prefix` names its points in the trajectory ("" for the model, the
// cross-check's "maximal:" for the penalty model drawn beside it, faded and moved by `shift`)
// A robot link's shapes (robot_geometry.py): boxes, cylinders and capsules along their z,
// spheres and triangle meshes, each posed by its row-major 4x4 in the body's (or the world's)
// axes; one group, so that the body's pose moves them all.
const Y_TO_Z = new THREE.Matrix4().makeRotationX(Math.PI / 2); // three.js's round shapes: y
function visualShapes(visuals, colour, faded) {
  const group = new THREE.Group();
  for (const visual of visuals) {
    let geometry;
    let turn = null;
    if (visual.kind === "box") {
      geometry = new THREE.BoxGeometry(...visual.size);
    } else if (visual.kind === "cylinder") {
      geometry = new THREE.CylinderGeometry(visual.radius, visual.radius, visual.length, 32);
      turn = Y_TO_Z;
    } else if (visual.kind === "capsule") {
      geometry = new THREE.CapsuleGeometry(visual.radius, visual.length, 8, 24);
      turn = Y_TO_Z;
    } else if (visual.kind === "sphere") {
      geometry = new THREE.SphereGeometry(visual.radius, 32, 16);
    } else if (visual.kind === "mesh") {
      geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position",
        new THREE.BufferAttribute(decode(visual.triangles, Float32Array), 3));
      geometry.computeVertexNormals();
    } else {
      continue;
    }
    const shape = new THREE.Mesh(geometry, material(colour, faded));
    if (visual.kind === "mesh") shape.material.side = THREE.DoubleSide;
    shape.matrixAutoUpdate = false;
    shape.matrix.set(...visual.pose);
    if (turn) shape.matrix.multiply(turn);
    group.add(shape);
  }
  return group;
}

function drawModel(prefix, faded, shift) {
  const masses = model.particles.map((p) => p.mass).filter((m) => m > 0);
  const heaviest = masses.length ? Math.max(...masses) : 1;
  const particles = model.particles.map((particle, k) => {
    const name = prefix + particle.name;
    const scale = particle.mass > 0 ? Math.max(0.5, Math.cbrt(particle.mass / heaviest)) : 1;
    const colour = COLOURS[k % COLOURS.length];
    const mesh = new THREE.Mesh(new THREE.SphereGeometry(radius0 * scale, 32, 16),
      material(colour, faded));
    mesh.renderOrder = 2; // over rods and trails
    world.add(mesh);
    return { name, mesh, colour };
  });

  const fixedPoints = model.fixed_points.map((name) => {
    const mesh = new THREE.Mesh(new THREE.BoxGeometry(radius0, radius0, radius0),
      material(0x333333, faded));
    world.add(mesh);
    return { name: prefix + "fixed:" + name, mesh };
  });

  const spindles = []; // a pivot holding a body's point, joined to the body's centre
  for (const pivot of model.pivots) {
    const mesh = new THREE.Mesh(new THREE.BoxGeometry(radius0, radius0, radius0),
      material(0x333333, faded));
    mesh.position.set(pivot.position[0], pivot.position[1], is2d ? 0 : pivot.position[2])
      .add(shift);
    world.add(mesh);
    if (pivot.body) {
      const rod = new THREE.Mesh(new THREE.CylinderGeometry(radius0 * 0.12, radius0 * 0.12, 1,
        8), material(0x555555, faded));
      world.add(rod);
      spindles.push({ rod, at: mesh.position, body: model.bodies.findIndex((b) => b.name
        === pivot.body) });
    }
  }

  // planes (normal . x = offset): in 2D a rail across the view, in 3D a translucent square;
  // both centred on the point of the plane nearest the motion's centre
  for (const plane of model.planes) {
    if (!plane.normal || plane.offset === null) continue; // moves with t: not drawn
    const normal = new THREE.Vector3(plane.normal[0], plane.normal[1], is2d ? 0 : plane.normal[2]);
    const scale = normal.lengthSq();
    if (!scale) continue;
    const nearest = centre.clone().addScaledVector(normal, (plane.offset - normal.dot(centre))
      / scale);
    normal.normalize();
    let mesh;
    if (is2d) {
      const along = new THREE.Vector3(-normal.y, normal.x, 0);
      mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius0 * 0.1, radius0 * 0.1, 1, 8),
        material(0xaaaaaa));
      placeBetween(mesh, nearest.clone().addScaledVector(along, -extent).add(shift),
        nearest.clone().addScaledVector(along, extent).add(shift));
    } else {
      mesh = new THREE.Mesh(new THREE.PlaneGeometry(2 * extent, 2 * extent),
        new THREE.MeshBasicMaterial({ color: 0x88aacc, transparent: true, opacity: 0.18,
          side: THREE.DoubleSide, depthWrite: false }));
      mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), normal);
      mesh.position.copy(nearest).add(shift);
    }
    world.add(mesh);
  }

  const links = model.links.map((declared) => {
    const rename = (anchor) => anchor.map(([column, weight]) => [prefix + column, weight]);
    const link = { ...declared, a: rename(declared.a), b: rename(declared.b) };
    const entry = { link, a: new THREE.Vector3(), b: new THREE.Vector3() };
    if (link.kind === "spring") {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position",
        new THREE.BufferAttribute(new Float32Array(COIL_POINTS * 3), 3));
      entry.coil = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0x555555,
        transparent: faded, opacity: faded ? 0.45 : 1 }));
      entry.coil.frustumCulled = false;
      world.add(entry.coil);
    } else if (link.kind === "pin") {
      entry.mesh = new THREE.Mesh(new THREE.SphereGeometry(radius0 * 0.4, 16, 8),
        material(0x333333, faded));
      world.add(entry.mesh);
    } else {
      const thickness = link.kind === "damper" ? 0.35 : 0.18;
      const geometry = new THREE.CylinderGeometry(radius0 * thickness, radius0 * thickness, 1,
        12);
      entry.mesh = new THREE.Mesh(geometry,
        material(link.kind === "damper" ? 0x999999 : 0x555555, faded));
      world.add(entry.mesh);
    }
    return entry;
  });

  // a body: its shape posed by p + R r, R and p from its point masses (x_k = p + R r_k)
  const bodies = model.bodies.map((body, k) => {
    const n = model.dim;
    const offsets = body.offsets.map((r) => new THREE.Vector3(r[0], r[1], n === 3 ? r[2] : 0));
    const differences = new THREE.Matrix3();
    const columns = [1, 2, 3].map((j) => (j <= n ? offsets[j].clone().sub(offsets[0])
      : new THREE.Vector3(0, 0, 1)));
    differences.set(columns[0].x, columns[1].x, columns[2].x,
      columns[0].y, columns[1].y, columns[2].y,
      columns[0].z, columns[1].z, columns[2].z);
    const inverse = differences.clone().invert();
    let geometry = null;
    const shape = new THREE.Matrix4();
    if (body.visuals) {
      // drawn below as the robot link's shapes, each with its own pose
    } else if (body.shape && body.shape.kind === "wheel") {
      // a disk about the axle at the wheel's centre (the cylinder's own axis is y)
      const { radius, width, axle, center } = body.shape;
      geometry = new THREE.CylinderGeometry(radius, radius, width, 48);
      shape.compose(new THREE.Vector3(...center),
        new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 1, 0),
          new THREE.Vector3(...axle)), new THREE.Vector3(1, 1, 1));
    } else if (body.shape && body.shape.kind === "ellipsoid") {
      geometry = new THREE.SphereGeometry(1, 48, 24);
      const [a, b, c] = body.shape.semi_axes;
      const axes = body.shape.axes; // rows: principal axes in body axes
      shape.set(axes[0][0] * a, axes[1][0] * b, axes[2][0] * c, 0,
        axes[0][1] * a, axes[1][1] * b, axes[2][1] * c, 0,
        axes[0][2] * a, axes[1][2] * b, axes[2][2] * c, 0,
        0, 0, 0, 1);
    } else {
      const r = body.shape ? body.shape.radius : radius0 * 2;
      geometry = new THREE.CircleGeometry(r, 48);
    }
    const colour = COLOURS[(k + particles.length) % COLOURS.length];
    const mesh = geometry ? new THREE.Mesh(geometry, material(colour, faded))
      : visualShapes(body.visuals, colour, faded);
    if (is2d) mesh.material.side = THREE.DoubleSide;
    mesh.matrixAutoUpdate = false;
    world.add(mesh);
    // the body's frame: its axes (x red, y green, z blue) at its centre of mass
    const reach = body.shape ? 1.4 * (body.shape.radius || Math.max(...body.shape.semi_axes))
      : radius0 * 3;
    const frame = new THREE.AxesHelper(reach);
    frame.matrixAutoUpdate = false;
    frame.renderOrder = 3;
    frame.material.depthTest = false; // seen through the body
    world.add(frame);
    return { name: body.name, points: body.points.map((name) => prefix + name), mesh, frame,
      shape, inverse, n };
  });
  // a robot's links welded to the world: their shapes, in world axes
  if (model.world_visuals) {
    const base = visualShapes(model.world_visuals, 0x888888, faded);
    base.position.copy(shift);
    world.add(base);
  }
  return { particles, fixedPoints, links, bodies, spindles };
}

const companionShift = new THREE.Vector3(...(data.companion_shift || [0, 0, 0]), 0);
if (is2d) companionShift.z = 0;
const drawings = [drawModel("", false, new THREE.Vector3())];
if (data.companion) drawings.push(drawModel(data.companion, true, companionShift));
const { particles } = drawings[0];

function poseBody(entry) {
  const { n } = entry;
  const points = entry.points.map((name) => pointAt(name, new THREE.Vector3()));
  const origin = points.reduce((sum, p) => sum.add(p), new THREE.Vector3())
    .divideScalar(points.length);
  const columns = [1, 2, 3].map((j) => (j <= n ? points[j].clone().sub(points[0])
    : new THREE.Vector3(0, 0, 1)));
  const spread = new THREE.Matrix3().set(columns[0].x, columns[1].x, columns[2].x,
    columns[0].y, columns[1].y, columns[2].y,
    columns[0].z, columns[1].z, columns[2].z);
  const rotation = spread.multiply(entry.inverse).elements; // column-major
  const pose = new THREE.Matrix4().set(rotation[0], rotation[3], rotation[6], origin.x,
    rotation[1], rotation[4], rotation[7], origin.y,
    rotation[2], rotation[5], rotation[8], origin.z,
    0, 0, 0, 1);
  entry.mesh.matrix.multiplyMatrices(pose, entry.shape);
  entry.frame.matrix.copy(pose);
  entry.centre = origin;
}

// trails: each particle's whole path in one line, drawn over the last TRAIL_SECONDS
const trails = particles.map(({ name, colour }) => {
  const k = pointIndex.get(name);
  const path = new Float32Array(frames * 3);
  for (let i = 0; i < frames; ++i) {
    path.set(positions.subarray((i * numPoints + k) * 3, (i * numPoints + k) * 3 + 3), 3 * i);
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(path, 3));
  const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({
    color: colour, transparent: true, opacity: 0.45 }));
  line.frustumCulled = false;
  world.add(line);
  return line;
});

// a deformable object: its nodes as dots and its intact springs as segments, both reading
// `current`; the springs come latest broken first, so those intact at t are a prefix
const mesh = data.arrays.spring_nodes ? (() => {
  const pairs = decode(data.arrays.spring_nodes, Int32Array);
  const brokenAt = decode(data.arrays.broken_at, Float64Array);
  const geometry = new THREE.BufferGeometry();
  const shared = new THREE.BufferAttribute(current, 3);
  geometry.setAttribute("position", shared);
  geometry.setIndex(new THREE.BufferAttribute(Uint32Array.from(pairs), 1));
  const springs = new THREE.LineSegments(geometry,
    new THREE.LineBasicMaterial({ color: 0x1f77b4 }));
  springs.frustumCulled = false;
  world.add(springs);
  const dots = new THREE.BufferGeometry();
  dots.setAttribute("position", shared);
  const nodes = new THREE.Points(dots, new THREE.PointsMaterial({ color: 0x222222, size: 3,
    sizeAttenuation: false }));
  nodes.frustumCulled = false;
  world.add(nodes);
  const intactAt = (time) => {
    let lo = 0;
    let hi = brokenAt.length; // brokenAt falls: the first index whose spring broke by `time`
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (brokenAt[mid] > time) lo = mid + 1;
      else hi = mid;
    }
    return lo;
  };
  return {
    intactAt,
    update(time) {
      shared.needsUpdate = true;
      geometry.setDrawRange(0, 2 * intactAt(time));
    },
    drawn: () => geometry.drawRange.count / 2,
  };
})() : null;

if (!is2d) {
  // the ground: a grid across the up axis, under the lowest point
  const low = Math.min(...[0, 1, 2, 3, 4, 5, 6, 7].map((c) => new THREE.Vector3(
    c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y,
    c & 4 ? box.max.z : box.min.z).dot(up)));
  const grid = new THREE.GridHelper(extent * 2, 20, 0xbbbbbb, 0xdddddd);
  grid.quaternion.setFromUnitVectors(Y_AXIS, up);
  grid.position.copy(centre).addScaledVector(up, low - centre.dot(up) - 0.05 * extent);
  world.add(grid);
}

// --- camera -----------------------------------------------------------------------------
const camera = new THREE.PerspectiveCamera(35, 1, extent * 1e-3, extent * 100);
camera.up.copy(is2d ? new THREE.Vector3(0, 1, 0) : up);
{
  // fit the motion: in 2D its box (at the view's aspect), in 3D its bounding sphere
  const halfAngle = THREE.MathUtils.degToRad(35 / 2);
  const size = box.getSize(new THREE.Vector3());
  const aspect = view.clientWidth / Math.max(view.clientHeight, 1);
  const distance = is2d
    ? 0.5 * Math.max(size.y, size.x / aspect, 0.2) * 1.25 / Math.tan(halfAngle)
    : 0.5 * extent * 1.1 / Math.sin(halfAngle);
  let direction = new THREE.Vector3(0, 0, 1);
  if (!is2d) {
    const side = new THREE.Vector3(1, 0, 0);
    if (Math.abs(side.dot(up)) > 0.9) side.set(0, 1, 0);
    side.addScaledVector(up, -side.dot(up)).normalize();
    const front = new THREE.Vector3().crossVectors(up, side);
    direction = side.multiplyScalar(0.55).addScaledVector(front, -0.75)
      .addScaledVector(up, 0.35).normalize();
  }
  camera.position.copy(centre).addScaledVector(direction, distance);
  camera.lookAt(centre);
}
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.copy(centre);
controls.update();

// --- the plot ---------------------------------------------------------------------------
const plotCanvas = document.getElementById("plot");
const seriesSelect = document.getElementById("series");
const nq = data.coordinates.length;
const series = data.energy
  ? [{ label: data.energy.label, values: energyError, reference: work }] : [];
data.coordinates.forEach((name, k) => {
  const values = new Float32Array(frames);
  for (let i = 0; i < frames; ++i) values[i] = coordinates[i * nq + k];
  series.push({ label: name, values });
});
if (mesh) {
  const values = new Float32Array(frames);
  for (let i = 0; i < frames; ++i) values[i] = mesh.intactAt(times[i]);
  series.push({ label: "springs intact", values });
}
series.forEach((s) => seriesSelect.add(new Option(s.values === energyError ? data.energy.name
  : s.label, seriesSelect.options.length)));
const PLOT_MARGIN = { left: 70, right: 14, top: 20, bottom: 22 };
let plotInfo = null; // null: the plot is to be drawn again (resize, another series)

function drawPlot() {
  const ratio = window.devicePixelRatio;
  const width = plotCanvas.clientWidth;
  const height = plotCanvas.clientHeight;
  plotCanvas.width = Math.round(width * ratio);
  plotCanvas.height = Math.round(height * ratio);
  const chosen = series[Number(seriesSelect.value) || 0];
  const { values, reference } = chosen;
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of reference ? [...values, ...reference] : values) {
    lo = Math.min(lo, v);
    hi = Math.max(hi, v);
  }
  if (!(hi > lo)) {
    const pad = Math.max(Math.abs(lo), 1e-16);
    lo -= pad;
    hi += pad;
  }
  const area = { left: PLOT_MARGIN.left, top: PLOT_MARGIN.top,
    width: width - PLOT_MARGIN.left - PLOT_MARGIN.right,
    height: height - PLOT_MARGIN.top - PLOT_MARGIN.bottom };
  const x = (t) => area.left + (t - t0) / Math.max(t1 - t0, 1e-300) * area.width;
  const y = (v) => area.top + (hi - v) / (hi - lo) * area.height;
  const context = plotCanvas.getContext("2d");
  context.setTransform(ratio, 0, 0, ratio, 0, 0);
  context.fillStyle = "#fff";
  context.fillRect(0, 0, width, height);
  context.strokeStyle = "#ccc";
  context.strokeRect(area.left, area.top, area.width, area.height);
  if (lo < 0 && hi > 0) {
    context.beginPath();
    context.moveTo(area.left, Math.round(y(0)) + 0.5);
    context.lineTo(area.left + area.width, Math.round(y(0)) + 0.5);
    context.stroke();
    context.textAlign = "right";
    context.fillStyle = "#222";
    context.font = "12px system-ui, sans-serif";
    context.fillText("0", area.left - 6, y(0) + 4);
  }
  context.fillStyle = "#222";
  context.font = "12px system-ui, sans-serif";
  context.textAlign = "left";
  context.fillText(chosen.label, area.left, 14);
  context.textAlign = "right";
  context.fillText(hi.toPrecision(3), area.left - 6, area.top + 10);
  context.fillText(lo.toPrecision(3), area.left - 6, area.top + area.height);
  context.textAlign = "left";
  context.fillText(`t = ${t0.toFixed(2)} s`, area.left, height - 6);
  context.textAlign = "right";
  context.fillText(`${t1.toFixed(2)} s`, area.left + area.width, height - 6);
  context.strokeStyle = "#1f77b4";
  context.beginPath();
  if (frames <= 2 * area.width) {
    // few frames: a line through every one
    for (let i = 0; i < frames; ++i) {
      if (i === 0) context.moveTo(x(times[i]), y(values[i]));
      else context.lineTo(x(times[i]), y(values[i]));
    }
  } else {
    // many: one vertical stroke per pixel column from its smallest to its largest value
    // (the previous column's last included, so the curve is continuous); every extreme
    // shows however many frames share a column
    let column = -1;
    let low = 0;
    let high = 0;
    const flush = () => {
      if (column < 0) return;
      context.moveTo(column + 0.5, y(high));
      context.lineTo(column + 0.5, y(low) + 1);
    };
    for (let i = 0; i < frames; ++i) {
      const c = Math.floor(x(times[i]));
      if (c !== column) {
        flush();
        column = c;
        const previous = i > 0 ? values[i - 1] : values[i];
        low = Math.min(values[i], previous);
        high = Math.max(values[i], previous);
      } else {
        low = Math.min(low, values[i]);
        high = Math.max(high, values[i]);
      }
    }
    flush();
  }
  context.stroke();
  if (reference) {
    // the work W dashed over E - E0: a sample a column, enough for a curve this smooth
    context.strokeStyle = "#d62728";
    context.setLineDash([6, 4]);
    context.beginPath();
    const step = Math.max(1, Math.floor(frames / area.width));
    for (let i = 0; i < frames; i += step) {
      if (i === 0) context.moveTo(x(times[i]), y(reference[i]));
      else context.lineTo(x(times[i]), y(reference[i]));
    }
    context.lineTo(x(times[frames - 1]), y(reference[frames - 1]));
    context.stroke();
    context.setLineDash([]);
  }
  let worst = 0;
  for (const v of values) worst = Math.max(worst, Math.abs(v));
  let balance = null; // max |E - E0 - W| where W is drawn
  if (reference) {
    balance = 0;
    for (let i = 0; i < frames; ++i) balance = Math.max(balance, Math.abs(values[i] - reference[i]));
  }
  const box = plotCanvas.getBoundingClientRect();
  plotInfo = { label: chosen.label, lo, hi, worst, balance, t0, t1,
    left: box.left + area.left, top: box.top + area.top,
    width: area.width, height: area.height };
  plotInfo.x = x;
}

// the cursor is an element over the plot, moved by a transform: the plot is drawn once, not
// every frame
const cursor = document.getElementById("cursor");

function drawCursor(time) {
  if (!plotInfo) {
    drawPlot();
    cursor.style.top = `${PLOT_MARGIN.top}px`;
    cursor.style.height = `${plotInfo.height}px`;
    cursor.style.display = "block";
  }
  cursor.style.transform = `translateX(${Math.round(plotInfo.x(time))}px)`;
}

seriesSelect.addEventListener("change", () => {
  plotInfo = null;
  render();
});

// --- playing ----------------------------------------------------------------------------
const slider = document.getElementById("slider");
const playButton = document.getElementById("play");
const speedSelect = document.getElementById("speed");
const trailsBox = document.getElementById("trails");
// bodies' frames: on by default, off for a robot (its links' drawing shows its joints)
const framesBox = document.getElementById("frames");
framesBox.checked = !model.bodies.some((body) => body.visuals);
document.getElementById("frames-label").hidden = model.bodies.length === 0;
const clock = document.getElementById("clock");
slider.min = t0;
slider.max = t1;
document.getElementById("title").innerHTML = `<b></b><br>${frames} frames`
  + (data.stride > 1 ? ` (every ${data.stride}th of ${data.rows})` : "")
  + (data.mesh ? `, ${numPoints} nodes, ${data.mesh.springs} springs`
    + ` (${data.mesh.broken} break)` : "")
  + (data.companion ? "<br>left: the reduced model; right, faded: the maximal penalty model"
    : "");
document.querySelector("#title b").textContent = model.name;

let time = t0;
let playing = false;
let lastTick = null;
const stats = { frames: 0, since: performance.now(), scriptMs: 0 };

function render() {
  const started = performance.now();
  interpolate(time);
  for (const { particles: spheres, fixedPoints, bodies, links, spindles } of drawings) {
    for (const { name, mesh } of spheres) pointAt(name, mesh.position);
    for (const { name, mesh } of fixedPoints) pointAt(name, mesh.position);
    for (const entry of bodies) {
      poseBody(entry);
      entry.frame.visible = framesBox.checked;
    }
    for (const { rod, at, body } of spindles) placeBetween(rod, at, bodies[body].centre);
    for (const entry of links) {
      anchorPosition(entry.link.a, entry.a);
      anchorPosition(entry.link.b, entry.b);
      if (entry.coil) drawCoil(entry);
      else if (entry.link.kind === "pin") entry.mesh.position.copy(entry.a);
      else placeBetween(entry.mesh, entry.a, entry.b);
    }
  }
  if (mesh) mesh.update(time);
  const [i] = locate(time);
  const first = locate(time - TRAIL_SECONDS)[0];
  for (const line of trails) {
    line.visible = trailsBox.checked;
    line.geometry.setDrawRange(first, i - first + 1);
  }
  renderer.render(world, camera);
  drawCursor(time);
  slider.value = time;
  clock.textContent = `t = ${time.toFixed(3)} s`;
  stats.frames += 1;
  stats.scriptMs += performance.now() - started;
}

function resize() {
  const width = view.clientWidth;
  const height = view.clientHeight;
  renderer.setSize(width, height);
  camera.aspect = width / Math.max(height, 1);
  camera.updateProjectionMatrix();
  plotInfo = null;
  render();
}

function setPlaying(on) {
  playing = on;
  if (playing && time >= t1) time = t0;
  playButton.textContent = playing ? "Pause" : "Play";
  lastTick = null;
}

function tick(now) {
  if (playing) {
    if (lastTick !== null) {
      time = Math.min(t1, time + (now - lastTick) / 1000 * Number(speedSelect.value));
      if (time >= t1) setPlaying(false);
    }
    lastTick = now;
    render();
  }
  requestAnimationFrame(tick);
}

playButton.addEventListener("click", () => setPlaying(!playing));
slider.addEventListener("input", () => {
  time = Number(slider.value);
  render();
});
trailsBox.addEventListener("change", render);
framesBox.addEventListener("change", render);
controls.addEventListener("change", () => {
  if (!playing) render();
});
window.addEventListener("resize", resize);
resize();
requestAnimationFrame(tick);

// --- the hook for programs (the browser test) -------------------------------------------
function toScreen(vector) {
  const box = renderer.domElement.getBoundingClientRect();
  const p = vector.clone().project(camera);
  return [box.left + (p.x + 1) / 2 * box.width, box.top + (1 - p.y) / 2 * box.height];
}

window.gencoordViewer = {
  t0, t1, frames, stride: data.stride,
  seek(to) {
    time = Math.min(t1, Math.max(t0, to));
    render();
    return time;
  },
  time: () => time,
  play() { setPlaying(true); },
  pause() { setPlaying(false); },
  playing: () => playing,
  setTrails(on) {
    trailsBox.checked = on;
    render();
  },
  /** Shows or hides the bodies' frames (their axes at the centre of mass). */
  setFrames(on) {
    framesBox.checked = on;
    render();
  },
  /** Screen position (CSS pixels in the page) of a point in model coordinates. */
  project: (x, y, z = 0) => toScreen(new THREE.Vector3(x, y, z)),
  /** Screen position of the sphere drawn for a particle. */
  particleOnScreen(name) {
    const particle = particles.find((p) => p.name === name);
    return particle ? toScreen(particle.mesh.position) : null;
  },
  particleColour(name) {
    const particle = particles.find((p) => p.name === name);
    const c = particle ? particle.colour : null; // sRGB, as the canvas shows it
    return particle ? [(c >> 16) & 255, (c >> 8) & 255, c & 255] : null;
  },
  /** Shows or hides a body's drawn shape (its frame stays); false for no such body. */
  showBody(name, on) {
    const body = drawings[0].bodies.find((b) => b.name === name);
    if (!body) return false;
    body.mesh.visible = on;
    render();
    return true;
  },
  plot: () => ({ ...plotInfo, x: undefined }),
  /** The springs of a deformable object drawn now (null for a model). */
  springsDrawn: () => (mesh ? mesh.drawn() : null),
  /** Frames drawn and milliseconds elapsed since resetStats(), and the milliseconds spent
   * in drawing them (the script's share: the rest is the browser's compositing). */
  stats: () => ({ frames: stats.frames, milliseconds: performance.now() - stats.since,
    scriptMilliseconds: stats.scriptMs }),
  resetStats() {
    stats.frames = 0;
    stats.since = performance.now();
    stats.scriptMs = 0;
  },
};
window.gencoordViewer.readyAt = performance.now(); // ms since the page began to load
window.gencoordViewer.ready = true;
