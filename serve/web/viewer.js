// The 3D view: skeletons drawn as bones (lines) and joints (points) at one frame, an orbit camera,
// a ground grid and each motion's root path on the ground. Uses the global THREE (three.min.js and
// OrbitControls.js from Debian's libjs-three). Positions are cm, Y up, as the server sends them.

const BACKGROUND = 0xf4f4f2;

// Joint colour by error: green at 0, yellow at half the bound, red at the bound and above.
export function errorColour(cm, bound) {
  const t = Math.min(Math.max(bound > 0 ? cm / bound : 0, 0), 1);
  return t < 0.5 ? [2 * t, 0.75, 0.1] : [1, 0.75 * (2 - 2 * t), 0.1];
}

export class SkeletonViewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setClearColor(BACKGROUND);
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(45, 1, 1, 1e5);
    this.camera.position.set(300, 250, 500);
    this.controls = new THREE.OrbitControls(this.camera, this.renderer.domElement);
    this.scene.add(new THREE.AmbientLight(0xffffff, 0.9));
    this.grid = new THREE.GridHelper(2000, 40, 0x999999, 0xcccccc);
    this.scene.add(this.grid);
    this.motions = [];
    this.frame = 0;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    const loop = () => {
      this.controls.update();
      this.renderer.render(this.scene, this.camera);
      requestAnimationFrame(loop);
    };
    loop();
  }

  resize() {
    const w = Math.max(this.container.clientWidth, 1), h = Math.max(this.container.clientHeight, 1);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  clear() {
    for (const m of this.motions) for (const o of m.objects) this.scene.remove(o);
    this.motions = [];
  }

  // motion: {joints: [{name, parent}], frames, positions: Float32Array(frames*J*3), colour: 0xrrggbb,
  //          offset: [x, y, z] (cm, drawn beside), errors?: Float32Array(frames*J), bound?: cm}
  add(motion) {
    const J = motion.joints.length;
    const bones = [];
    motion.joints.forEach((j, k) => { if (j.parent >= 0) bones.push(j.parent, k); });
    const lineGeometry = new THREE.BufferGeometry();
    lineGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(bones.length * 3), 3));
    const lines = new THREE.LineSegments(lineGeometry, new THREE.LineBasicMaterial({ color: motion.colour }));
    const pointGeometry = new THREE.BufferGeometry();
    pointGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(J * 3), 3));
    const colours = new Float32Array(J * 3);
    const base = new THREE.Color(motion.colour);
    for (let k = 0; k < J; ++k) colours.set([base.r, base.g, base.b], 3 * k);
    pointGeometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    const points = new THREE.Points(pointGeometry, new THREE.PointsMaterial({ size: 6, vertexColors: true }));
    // The root path on the ground (the lowest joint height of the whole motion).
    let floor = Infinity;
    for (let i = 1; i < motion.positions.length; i += 3) floor = Math.min(floor, motion.positions[i]);
    const path = new Float32Array(motion.frames * 3);
    for (let f = 0; f < motion.frames; ++f) {
      path[3 * f] = motion.positions[f * J * 3];
      path[3 * f + 1] = floor;
      path[3 * f + 2] = motion.positions[f * J * 3 + 2];
    }
    const pathGeometry = new THREE.BufferGeometry();
    pathGeometry.setAttribute('position', new THREE.BufferAttribute(path, 3));
    const rootPath = new THREE.Line(pathGeometry, new THREE.LineBasicMaterial({ color: motion.colour, opacity: 0.5, transparent: true }));
    const objects = [lines, points, rootPath];
    const offset = motion.offset || [0, 0, 0];
    for (const o of objects) { o.position.set(offset[0], offset[1], offset[2]); this.scene.add(o); }
    this.motions.push({ ...motion, bones, lines, points, objects, floor });
    this.show(this.frame);
  }

  // Frames the camera on the first motion: centred on its whole path, as close as the figure's size and
  // the path's length allow.
  frameAll() {
    if (!this.motions.length) return;
    const m = this.motions[0], p = m.positions, J = m.joints.length;
    const extent = (from, to) => {
      const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
      for (let i = from; i < to; i += 3)
        for (let k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], p[i + k]); hi[k] = Math.max(hi[k], p[i + k]); }
      return { lo, hi, size: Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) };
    };
    const all = extent(0, p.length), figure = extent(0, 3 * J);
    const lo = all.lo, hi = all.hi;
    const centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
    const size = Math.max(2.5 * figure.size, 0.7 * all.size, 100);
    this.controls.target.copy(centre);
    this.camera.position.set(centre.x + 0.9 * size, centre.y + 0.6 * size, centre.z + 1.4 * size);
    this.grid.position.y = this.motions[0].floor;
    this.controls.update();
  }

  show(frame) {
    this.frame = frame;
    for (const m of this.motions) {
      const J = m.joints.length;
      const f = Math.min(frame, m.frames - 1);
      const src = m.positions.subarray(f * J * 3, (f + 1) * J * 3);
      const pts = m.points.geometry.attributes.position;
      pts.array.set(src);
      pts.needsUpdate = true;
      const line = m.lines.geometry.attributes.position;
      for (let b = 0; b < m.bones.length; ++b) line.array.set(src.subarray(3 * m.bones[b], 3 * m.bones[b] + 3), 3 * b);
      line.needsUpdate = true;
      if (m.errors) {
        const c = m.points.geometry.attributes.color;
        for (let k = 0; k < J; ++k) c.array.set(errorColour(m.errors[f * J + k], m.bound), 3 * k);
        c.needsUpdate = true;
      }
      m.points.geometry.computeBoundingSphere();
      m.lines.geometry.computeBoundingSphere();
    }
  }
}
