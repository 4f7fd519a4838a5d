// The 3D view: a 3D input's answer (`answer.space`: its stems, eight
// numbers a stem, and its layout's volumes) drawn with WebGL 2 on a
// canvas shown instead of the 2D preview. Orthographic, like `stlc render
// --view AZ,EL`: the camera starts at the answer's view (30,20, the CLI's
// default), dragging or the arrow keys orbit it, the wheel or + and -
// zoom, Fit or 0 resets both (orbit.js). The volumes are drawn translucent
// (meshes.js), the tree over them: each stem a band of its width (screen
// pixels for an .lsys, canvas units for a tree), one instance of a
// four-corner strip, so the page holds 32 bytes a stem, and 12 more for
// its colour (paint3d.js: a palette's, an S= ramp's, else the stroke).
// Leaves are triangles in their colour, lit on both sides, shown with the
// whole tree. Replay shows the stems up to a decision (a uniform: nothing
// is uploaded again).

import { byId } from './dom.js';
import { LEAF_FS, LEAF_VS, STEM_FS, STEM_VS, VOLUME_FS, VOLUME_VS, compile } from './gl3d.js';
import { volumeMesh } from './meshes.js';
import { orbit } from './orbit.js';
import { leafTriangles, rgb, stemColours } from './paint3d.js';

// The rows of the camera's rotation for `az`, `el` (degrees): right, down
// and forward, as render/view.rs projects (a point p is drawn at p.right,
// p.down, at depth p.forward).
export function camera(az, el) {
  const [a, e] = [az * Math.PI / 180, el * Math.PI / 180];
  const [ca, sa, ce, se] = [Math.cos(a), Math.sin(a), Math.cos(e), Math.sin(e)];
  return [[ca, 0, sa], [sa * se, ce, -ca * se], [-sa * ce, se, ca * ce]];
}

/**
 * @param {{onView?: function(number[]): void}} [options] `onView` is told
 *   the angles `[az, el]` each time the view is drawn (the header's mesh
 *   export shows them)
 */
export function createView3d({ onView } = {}) {
  const host = byId('view');
  const canvas = document.createElement('canvas');
  canvas.id = 'view3d';
  canvas.dataset.testid = 'view3d';
  canvas.tabIndex = 0;
  canvas.hidden = true;
  host.appendChild(canvas);
  const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true, premultipliedAlpha: false });
  const label = document.createElement('div');
  label.id = 'view3d-label';
  label.dataset.testid = 'view3d-label';
  label.hidden = true;
  host.appendChild(label);

  // The camera, the stems' box and what is drawn.
  // `moved`: turned or zoomed since the last fit (else a resize refits).
  const cam = { az: 30, el: 20, scale: 1, home: [30, 20], moved: false };
  let centre = [0, 0, 0];
  let range = 1;
  let points = new Float32Array(0);
  let count = 0;
  let upTo = Infinity;
  let pixelWidths = true;
  let leafCount = 0;
  let leafPos = new Float32Array(0);
  let lastDecision = 0;
  let background = [1, 1, 1];
  let volumes = [];
  let frame = 0;
  let fitted = false;
  let stemProg = null;
  let volumeProg = null;
  let stemVao = null;
  let stemBuf = null;
  let colourBuf = null;
  let leafProg = null;
  let leafVao = null;
  let leafBufs = [];

  if (gl) {
    stemProg = compile(gl, STEM_VS, STEM_FS);
    volumeProg = compile(gl, VOLUME_VS, VOLUME_FS);
    stemVao = gl.createVertexArray();
    gl.bindVertexArray(stemVao);
    const corners = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, corners);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([0, -1, 0, 1, 1, -1, 1, 1]), gl.STATIC_DRAW);
    gl.enableVertexAttribArray(stemProg.attr('corner'));
    gl.vertexAttribPointer(stemProg.attr('corner'), 2, gl.FLOAT, false, 0, 0);
    stemBuf = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, stemBuf);
    for (const [name, size, offset] of [['a', 3, 0], ['b', 3, 12], ['wd', 2, 24]]) {
      const at = stemProg.attr(name);
      gl.enableVertexAttribArray(at);
      gl.vertexAttribPointer(at, size, gl.FLOAT, false, 32, offset);
      gl.vertexAttribDivisor(at, 1);
    }
    colourBuf = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, colourBuf);
    gl.enableVertexAttribArray(stemProg.attr('col'));
    gl.vertexAttribPointer(stemProg.attr('col'), 3, gl.FLOAT, false, 0, 0);
    gl.vertexAttribDivisor(stemProg.attr('col'), 1);
    gl.bindVertexArray(null);
    leafProg = compile(gl, LEAF_VS, LEAF_FS);
    leafVao = gl.createVertexArray();
    gl.bindVertexArray(leafVao);
    leafBufs = ['position', 'normal', 'col'].map((name) => {
      const buf = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, buf);
      gl.enableVertexAttribArray(leafProg.attr(name));
      gl.vertexAttribPointer(leafProg.attr(name), 3, gl.FLOAT, false, 0, 0);
      return buf;
    });
    gl.bindVertexArray(null);
  } else {
    label.textContent = 'This browser has no WebGL 2: the 3D view cannot be shown (export a PNG instead).';
  }

  // Every point of the stems, the leaves and the volumes' corners: their box's centre
  // is what the camera turns about.
  function bounds() {
    const b = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
    const add = (x, y, z) => {
      b[0] = Math.min(b[0], x); b[1] = Math.min(b[1], y); b[2] = Math.min(b[2], z);
      b[3] = Math.max(b[3], x); b[4] = Math.max(b[4], y); b[5] = Math.max(b[5], z);
    };
    for (let i = 0; i < points.length; i += 8) {
      add(points[i], points[i + 1], points[i + 2]);
      add(points[i + 3], points[i + 4], points[i + 5]);
    }
    for (const pos of [leafPos, ...volumes.map((v) => v.pos)]) {
      for (let i = 0; i < pos.length; i += 3) add(pos[i], pos[i + 1], pos[i + 2]);
    }
    return b[0] > b[3] ? [0, 0, 0, 1, 1, 1] : b;
  }

  // The scale that fits everything in the canvas from the current angles.
  function fitScale() {
    const [r, d] = camera(cam.az, cam.el);
    let [mx, my] = [1e-9, 1e-9];
    const see = (x, y, z) => {
      const [px, py, pz] = [x - centre[0], y - centre[1], z - centre[2]];
      mx = Math.max(mx, Math.abs(px * r[0] + py * r[1] + pz * r[2]));
      my = Math.max(my, Math.abs(px * d[0] + py * d[1] + pz * d[2]));
    };
    for (let i = 0; i < points.length; i += 8) {
      see(points[i], points[i + 1], points[i + 2]);
      see(points[i + 3], points[i + 4], points[i + 5]);
    }
    for (const pos of [leafPos, ...volumes.map((v) => v.pos)]) {
      for (let i = 0; i < pos.length; i += 3) see(pos[i], pos[i + 1], pos[i + 2]);
    }
    const { width, height } = canvas;
    return 0.92 * Math.min(width / (2 * mx), height / (2 * my));
  }

  function resize() {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(canvas.clientWidth * dpr));
    const h = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== w || canvas.height !== h) {
      canvas.width = w;
      canvas.height = h;
      if (!fitted || !cam.moved) cam.scale = fitScale();
    }
  }

  function render() {
    frame = 0;
    if (!gl || canvas.hidden) return;
    resize();
    const dpr = window.devicePixelRatio || 1;
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(background[0], background[1], background[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const rot = new Float32Array(camera(cam.az, cam.el).flat());
    // Column-major: the rows above are the matrix's rows, so transpose.
    const setCommon = (p) => {
      gl.useProgram(p.prog);
      gl.uniformMatrix3fv(p.u.rot, true, rot);
      gl.uniform3fv(p.u.centre, centre);
      gl.uniform1f(p.u.scale, cam.scale);
      gl.uniform2f(p.u.viewport, canvas.width, canvas.height);
    };
    // The volumes, translucent, under the tree: no depth.
    gl.disable(gl.DEPTH_TEST);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    setCommon(volumeProg);
    for (const v of volumes) {
      gl.bindVertexArray(v.vao);
      gl.uniform4fv(volumeProg.u.colour, v.colour);
      gl.drawArrays(gl.TRIANGLES, 0, v.pos.length / 3);
    }
    gl.disable(gl.BLEND);
    // The tree, near over far.
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    setCommon(stemProg);
    // Pixel widths are CSS pixels, as in the 2D picture.
    gl.uniform1f(stemProg.u.pixelWidths, pixelWidths ? dpr : 0);
    gl.uniform1f(stemProg.u.upTo, upTo === Infinity ? 3.4e38 : upTo);
    gl.uniform1f(stemProg.u.range, range);
    gl.uniform3fv(stemProg.u.background, background);
    gl.bindVertexArray(stemVao);
    gl.drawArraysInstanced(gl.TRIANGLE_STRIP, 0, 4, count);
    // The leaves, with the whole tree (a replay's last step).
    if (leafCount && upTo >= lastDecision) {
      setCommon(leafProg);
      gl.uniform1f(leafProg.u.range, range);
      gl.bindVertexArray(leafVao);
      gl.drawArrays(gl.TRIANGLES, 0, leafCount);
    }
    gl.bindVertexArray(null);
    label.textContent = `view ${Math.round(cam.az)},${Math.round(cam.el)} · drag or arrow keys to turn, wheel or +/− to zoom, Fit or 0 to reset`;
    if (onView) onView(angles());
  }

  function redraw() {
    if (!frame) frame = requestAnimationFrame(render);
  }

  // The view's angles as the exports use them: tenths of a degree.
  function angles() {
    return [Math.round(cam.az * 10) / 10, Math.round(cam.el * 10) / 10];
  }

  function volumeVao(pos, nrm) {
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    for (const [name, data] of [['position', pos], ['normal', nrm]]) {
      const buf = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, buf);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
      const at = volumeProg.attr(name);
      gl.enableVertexAttribArray(at);
      gl.vertexAttribPointer(at, 3, gl.FLOAT, false, 0, 0);
    }
    gl.bindVertexArray(null);
    return vao;
  }

  // Shows `answer` (one with `space`); `refit`: the camera back home.
  function show(answer, refit) {
    const s = answer.space;
    canvas.hidden = false;
    label.hidden = false;
    canvas.classList.remove('stale');
    if (!gl) return;
    points = Float32Array.from(s.stems);
    count = points.length / 8;
    gl.bindBuffer(gl.ARRAY_BUFFER, stemBuf);
    gl.bufferData(gl.ARRAY_BUFFER, points, gl.STATIC_DRAW);
    pixelWidths = s.width_in_pixels;
    const stroke = rgb(answer.stroke, [0, 0, 0]);
    gl.bindBuffer(gl.ARRAY_BUFFER, colourBuf);
    gl.bufferData(gl.ARRAY_BUFFER, stemColours(s, stroke), gl.STATIC_DRAW);
    const leaves = leafTriangles(s, stroke);
    for (const [buf, data] of [[leafBufs[0], leaves.pos], [leafBufs[1], leaves.nrm], [leafBufs[2], leaves.col]]) {
      gl.bindBuffer(gl.ARRAY_BUFFER, buf);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
    }
    leafCount = leaves.count;
    leafPos = leaves.pos;
    lastDecision = s.decisions || 0;
    background = rgb(s.background, [1, 1, 1]);
    volumes.forEach((v) => gl.deleteVertexArray(v.vao));
    volumes = (s.volumes || []).map((v) => {
      const { pos, nrm } = volumeMesh(v, s.axis || [0, 0]);
      const c = rgb(v.color, [0, 0.5, 0]);
      // White carves: shown grey, fainter.
      const carve = c.every((x) => x > 0.99);
      return { pos, vao: volumeVao(pos, nrm), colour: carve ? [0.45, 0.45, 0.45, 0.12] : [...c, 0.22] };
    });
    // An edit keeps the camera (as the 2D view keeps its box); a new
    // file turns about its own centre, fitted.
    const b = bounds();
    if (refit || !fitted) centre = [(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2];
    const far = [0, 1, 2].map((i) => Math.max(Math.abs(b[i] - centre[i]), Math.abs(b[i + 3] - centre[i])));
    range = 1.01 * Math.max(1e-6, Math.hypot(...far));
    if (refit || !fitted) {
      cam.home = s.view.slice();
      reset();
    } else {
      redraw();
    }
  }

  // The camera at its first view, fitted.
  function reset() {
    [cam.az, cam.el] = cam.home;
    resize();
    cam.scale = fitScale();
    cam.moved = false;
    fitted = true;
    redraw();
  }

  function hide() {
    canvas.hidden = true;
    label.hidden = true;
  }

  orbit(canvas, cam, { redraw, zoom: (f) => zoom(f), reset: () => reset() });

  function zoom(factor) {
    cam.scale /= factor;
    cam.moved = true;
    redraw();
  }

  if (window.ResizeObserver) new ResizeObserver(redraw).observe(host);

  // Pixels that are not the background, read back from the canvas (for
  // tests and scripts): `count`, and a checksum of the whole picture.
  function pixels() {
    if (!gl) return { count: 0, sum: 0 };
    render();
    const { width, height } = canvas;
    const px = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const bg = background.map((x) => Math.round(x * 255));
    let n = 0;
    let sum = 0;
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - bg[0]) + Math.abs(px[i + 1] - bg[1]) + Math.abs(px[i + 2] - bg[2]) > 6) n++;
      sum = (sum * 31 + px[i] + 7 * px[i + 1] + 13 * px[i + 2]) % 1000000007;
    }
    return { count: n, sum, width, height };
  }

  return {
    element: canvas,
    show,
    hide,
    reset,
    zoom,
    // Replay: the stems of decisions up to `k` (Infinity: all).
    upTo(k) { upTo = k; redraw(); },
    stale() { canvas.classList.add('stale'); },
    angles,
    turn(az, el) { cam.az = az; cam.el = el; redraw(); },
    available: () => !!gl,
    pixels,
  };
}
