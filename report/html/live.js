// glint report page, live view (report/report_html.h): the method itself on the reader's GPU.
//
// Both surfaces, the examined one fitted by the run (DATA.live.examined is already in the
// reference's coordinates), are rendered as glint's sweep renders them (render/frame.h,
// shaders/normal.frag) and compared as its sweep compares them (scanner/compare.h,
// scanner/metric.h), in WebGL2 through three.js:
//
//   reference ─▶ frame: s·W × s·H RGBA32F (unit interpolated vertex normal, linear depth)
//   examined  ─▶ frame: s·W × s·H RGBA32F                 │
//                     └──────────────┬────────────────────┘
//   compare: per output pixel, its s×s sub-samples averaged over the covered ones and
//            renormalised (the footprint averaging of DESIGN.md), then, where both frames
//            cover all of them: angle between the normals, the paper's mean |ΔR|,|ΔG|,|ΔB|
//            of the 8-bit normal colours, signed depth (reference − examined: a dent < 0)
//            ─▶ W × H RGBA32F (angle °, rgb, depth, state)
//   display: per pane, the resolved normal colour (0.5·n + 0.5), light reflection dot(n, l)
//            or reflection lines; the difference on glint's colour maps, grey below the
//            threshold.
//
// The sub-sample (i, j) of pixel (x, y) sits at (x + (i + 0.5)/s, y + (j + 0.5)/s) as in
// glint's frames: the s×-size target's pixel centres are exactly there. A sweep view is
// reproduced by its orthographic camera (scanner/plan.h planned_view): eye at
// target + 3·radius·direction(azimuth, elevation), up +z, half height size·footprint/2.
//
// window.glintLiveView(page) builds the mode into #live-mode and returns its interface
// (show, hide, measure, bench, selftest); it is also window.glintLive for tests.
(function () {
  "use strict";

  // Shaders. Three.js (r111, WebGL2) adds the version line's defines, precision, the matrices
  // and the attributes `position` and `normal`.
  const FRAME_VERTEX = `#version 300 es
out vec3 vNormal;
out float vDepth;
void main() {
  vNormal = normal;  // the model matrix is the identity: world normals, as glint's frames
  vec4 p = modelViewMatrix * vec4(position, 1.0);
  vDepth = -p.z;     // linear depth along the viewing axis, mesh units
  gl_Position = projectionMatrix * p;
}`;
  const FRAME_FRAGMENT = `#version 300 es
in vec3 vNormal;
in float vDepth;
layout(location = 0) out highp vec4 normalDepth;
void main() {
  // a zero interpolated normal (opposite vertex normals across a fold) stays zero
  float len = length(vNormal);
  normalDepth = vec4(len > 0.0 ? vNormal / len : vec3(0.0), vDepth);
}`;
  const QUAD_VERTEX = `#version 300 es
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }`;
  // The resolve of one output pixel: glint's Frame pixel (render/frame.h). A sub-sample is
  // covered when it holds a normal (the targets are cleared to zero).
  const RESOLVE = `
uniform int s;
struct Pixel { vec3 n; float depth; float coverage; };
Pixel resolve(highp sampler2D frame, ivec2 p) {
  vec3 sum = vec3(0.0);
  float depth = 0.0, hits = 0.0;
  for (int j = 0; j < s; ++j)
    for (int i = 0; i < s; ++i) {
      vec4 v = texelFetch(frame, p * s + ivec2(i, j), 0);
      if (dot(v.xyz, v.xyz) > 0.25) { sum += v.xyz; depth += v.w; hits += 1.0; }
    }
  Pixel r;
  r.coverage = hits / float(s * s);
  float len = length(sum);
  r.n = len > 0.0 ? sum / len : vec3(0.0);
  r.depth = hits > 0.0 ? depth / hits : 0.0;
  return r;
}`;
  const COMPARE_FRAGMENT = `#version 300 es
uniform highp sampler2D referenceFrame;
uniform highp sampler2D examinedFrame;
uniform float minCoverage;
layout(location = 0) out highp vec4 result;
${RESOLVE}
vec3 paperColour(vec3 n) { return floor(clamp(0.5 * n + 0.5, 0.0, 1.0) * 255.0 + 0.5); }
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  Pixel a = resolve(referenceFrame, p), b = resolve(examinedFrame, p);
  // state: 0 not compared, 1 compared, 2 reference only (surface missing), 3 examined only
  bool inA = a.coverage > 0.0, inB = b.coverage > 0.0;
  if (inA != inB) {
    float state = inA && a.coverage >= minCoverage ? 2.0 : inB && b.coverage >= minCoverage ? 3.0 : 0.0;
    result = vec4(0.0, 0.0, 0.0, state);
    return;
  }
  if (a.coverage < minCoverage || b.coverage < minCoverage || dot(a.n, a.n) == 0.0 || dot(b.n, b.n) == 0.0) {
    result = vec4(0.0);
    return;
  }
  // atan2(|a×b|, a·b): exact near 0°, where acos of a float loses digits
  float angle = degrees(atan(length(cross(a.n, b.n)), dot(a.n, b.n)));
  vec3 d = abs(paperColour(a.n) - paperColour(b.n));
  result = vec4(angle, (d.r + d.g + d.b) / 3.0, a.depth - b.depth, 1.0);
}`;
  const DISPLAY_FRAGMENT = `#version 300 es
uniform highp sampler2D referenceFrame;
uniform highp sampler2D examinedFrame;
uniform highp sampler2D difference;
uniform ivec2 origin;       // the pane's lower left corner in the canvas, device pixels
uniform int pane;           // 0 reference, 1 examined, 2 difference
uniform int shading;        // 0 normal colour, 1 light reflection, 2 reflection lines
uniform int metric;         // 0 angle, 1 rgb, 2 signed depth
uniform vec3 lightDir;      // world, towards the light
uniform vec3 viewDir;       // world, from the eye into the scene
uniform vec3 viewUp;        // world, the image's up
uniform float low, high, threshold;
uniform vec3 background;
uniform vec3 sequential[17];
uniform vec3 diverging[9];
layout(location = 0) out highp vec4 colour;
${RESOLVE}
vec3 knots17(float t) {
  float x = clamp(t, 0.0, 1.0) * 16.0;
  int i = min(15, int(floor(x)));
  return mix(sequential[i], sequential[i + 1], x - float(i));
}
vec3 knots9(float t) {
  float x = clamp(t, 0.0, 1.0) * 8.0;
  int i = min(7, int(floor(x)));
  return mix(diverging[i], diverging[i + 1], x - float(i));
}
vec3 shade(vec3 n) {
  if (shading == 1) return vec3(max(dot(n, lightDir), 0.0));
  if (shading == 2) {
    // reflection lines: the reflected view ray against a sky of horizontal stripes
    vec3 r = reflect(viewDir, n);
    return vec3(fract(6.0 * asin(clamp(dot(r, viewUp), -1.0, 1.0)) / 3.14159265) < 0.5 ? 0.92 : 0.08);
  }
  return 0.5 * n + 0.5;
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - origin;
  if (pane < 2) {
    Pixel px;
    if (pane == 0) px = resolve(referenceFrame, p); else px = resolve(examinedFrame, p);
    // partly covered pixels blend with the background, as an antialiased picture
    colour = vec4(mix(background, shade(px.n), px.coverage), 1.0);
    return;
  }
  vec4 d = texelFetch(difference, p, 0);
  Pixel ref = resolve(referenceFrame, p);
  vec3 grey = vec3(0.25 + 0.5 * max(dot(ref.n, lightDir), 0.0));
  vec3 c = mix(background, grey, ref.coverage);
  if (d.w == 1.0) {
    float v = metric == 0 ? d.x : metric == 1 ? d.y : d.z;
    if (abs(v) >= threshold)
      c = metric == 2 ? knots9((v - low) / (high - low)) : knots17((v - low) / (high - low));
  } else if (d.w == 2.0) {
    c = vec3(0.85, 0.85, 0.45);  // surface only in the reference: missing
  } else if (d.w == 3.0) {
    c = vec3(0.45, 0.85, 0.85);  // surface only in the examined
  }
  colour = vec4(c, 1.0);
}`;

  const METRICS = {
    angle: { index: 0, label: "angle between the normals", unit: "°", kind: "sequential", colourMax: 20 },
    rgb: { index: 1, label: "|RGB| difference (the paper's, 8-bit)", unit: " rgb", kind: "sequential", colourMax: 64 },
    depth: { index: 2, label: "signed depth (examined behind: dent)", unit: "", kind: "signed", colourMax: 1 },
  };
  const SHADINGS = { normal: 0, light: 1, zebra: 2 };
  // note: one frame target of 4096² RGBA32F holds 256 MB; two of them bound the averaging
  // at a size every WebGL2 device can allocate (the asked s is lowered, and the page says so).
  const MAX_TARGET_PIXELS = 4096 * 4096;

  function decode(b64, Type) {
    const bin = atob(b64);
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; ++i) out[i] = bin.charCodeAt(i);
    return new Type(out.buffer);
  }
  function dirFromAzEl(azDeg, elDeg) {
    const a = (azDeg * Math.PI) / 180, e = (elDeg * Math.PI) / 180;
    return new THREE.Vector3(Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e));
  }
  // The up hint of glint's look_at (mesh/geometry.cpp): +z, or x / y when looking along z.
  function upFor(forward) {
    const up = new THREE.Vector3(0, 0, 1);
    if (new THREE.Vector3().crossVectors(forward, up).length() >= 1e-6) return up;
    return Math.abs(forward.x) < 0.9 ? new THREE.Vector3(1, 0, 0) : new THREE.Vector3(0, 1, 0);
  }

  window.glintLiveView = function (page) {
    const DATA = page.DATA, REPORT = DATA.report, $ = page.$, el = page.el, fmt = page.fmt;
    const UNIT = DATA.unit;
    const LIVE = DATA.live;
    const plan = REPORT.plan;
    const target0 = new THREE.Vector3().fromArray(plan.target);
    const radius = plan.radius;
    const zooms = REPORT.zooms;
    const api = { available: false, reason: "", shown: false };
    window.glintLive = api;
    const message = $("live-message");
    function unavailable(text) {
      api.reason = text;
      message.textContent = text;
      message.hidden = false;
      $("live-viewer").classList.add("unavailable");
      $("live-stage").classList.add("unavailable");
      return api;
    }

    if (!LIVE) return unavailable("This report holds no examined surface (it was written without one), " +
                                  "so there is nothing to compare live. The atlas view has the run's results.");
    const canvas = $("live-canvas");
    const gl = canvas.getContext("webgl2", { antialias: false, alpha: false, depth: true, stencil: false,
                                             preserveDrawingBuffer: true, powerPreference: "high-performance" });
    if (!gl) return unavailable("The live view needs WebGL2, which this browser does not give the page " +
                                "(switched off, or an old browser or driver). The atlas view works without it.");
    if (!gl.getExtension("EXT_color_buffer_float"))
      return unavailable("The live view renders normals into float targets (WebGL2's EXT_color_buffer_float), " +
                         "which this browser does not offer. The atlas view works without it.");
    const renderer = new THREE.WebGLRenderer({ canvas: canvas, context: gl });
    renderer.setPixelRatio(1);  // every size below is in device pixels
    renderer.autoClear = false;
    const maxTexture = renderer.capabilities.maxTextureSize;

    // ---- surfaces -------------------------------------------------------------------------------
    function surface(positions, indices, normals) {
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.BufferAttribute(positions, 3));
      if (normals) g.setAttribute("normal", new THREE.BufferAttribute(normals, 3, true));
      else g.computeVertexNormals();  // a page from a reference without normals
      g.setIndex(new THREE.BufferAttribute(indices, 1));
      return g;
    }
    const frameMaterial = new THREE.ShaderMaterial({ vertexShader: FRAME_VERTEX, fragmentShader: FRAME_FRAGMENT,
                                                      side: THREE.DoubleSide });
    const referenceGeometry = surface(page.positions, page.indices,
                                      DATA.mesh.normals ? decode(DATA.mesh.normals, Int16Array) : null);
    const examinedGeometry = surface(decode(LIVE.examined.positions, Float32Array), decode(LIVE.examined.indices, Uint32Array),
                                     LIVE.examined.normals ? decode(LIVE.examined.normals, Int16Array) : null);
    const referenceScene = new THREE.Scene(), examinedScene = new THREE.Scene();
    referenceScene.add(new THREE.Mesh(referenceGeometry, frameMaterial));
    examinedScene.add(new THREE.Mesh(examinedGeometry, frameMaterial));
    const shownTriangles = [page.indices.length / 3, LIVE.examined.shown_triangles];
    // What the page's copies are of a large pair (report/report_html.h: each surface above the
    // budget is decimated, exact around the regions).
    const decimated = [[DATA.mesh.triangles, shownTriangles[0], DATA.mesh.shown && DATA.mesh.shown.error, "reference"],
                       [LIVE.examined.triangles, shownTriangles[1], LIVE.examined.error, "examined"]]
      .filter((x) => x[1] < x[0]).map((x) => ": " + x[3] + " of " + x[0] + ", within " + fmt(x[2], 2) + " " + UNIT).join(";");
    // A sphere holding both surfaces (for the interactive camera's depth range).
    const bounds = (() => {
      referenceGeometry.computeBoundingSphere();
      examinedGeometry.computeBoundingSphere();
      const a = referenceGeometry.boundingSphere, b = examinedGeometry.boundingSphere;
      const c = a.center.clone().add(b.center).multiplyScalar(0.5);
      return { center: c, radius: Math.max(a.radius + a.center.distanceTo(c), b.radius + b.center.distanceTo(c)) };
    })();

    // ---- targets and passes ---------------------------------------------------------------------
    function floatTarget(w, h, withDepth) {
      const t = new THREE.WebGLRenderTarget(w, h, { type: THREE.FloatType, format: THREE.RGBAFormat,
        minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter, generateMipmaps: false,
        depthBuffer: withDepth, stencilBuffer: false });
      if (withDepth) t.depthTexture = new THREE.DepthTexture(w, h, THREE.FloatType);  // 32-bit depth
      return t;
    }
    // A set of targets for one output size and averaging.
    function makeTargets(w, h, s) {
      return { w: w, h: h, s: s, reference: floatTarget(s * w, s * h, true), examined: floatTarget(s * w, s * h, true),
               difference: floatTarget(w, h, false) };
    }
    function disposeTargets(t) {
      if (!t) return;
      [t.reference, t.examined, t.difference].forEach((x) => {
        if (x.depthTexture) x.depthTexture.dispose();
        x.dispose();
      });
    }
    const quadCamera = new THREE.Camera();
    function quadPass(material) {
      const scene = new THREE.Scene();
      const quad = new THREE.Mesh(new THREE.PlaneBufferGeometry(2, 2), material);
      quad.frustumCulled = false;
      scene.add(quad);
      return scene;
    }
    const compareMaterial = new THREE.ShaderMaterial({
      vertexShader: QUAD_VERTEX, fragmentShader: COMPARE_FRAGMENT, depthTest: false, depthWrite: false,
      uniforms: { referenceFrame: { value: null }, examinedFrame: { value: null }, s: { value: 1 },
                  minCoverage: { value: LIVE.min_coverage } } });
    const displayMaterial = new THREE.ShaderMaterial({
      vertexShader: QUAD_VERTEX, fragmentShader: DISPLAY_FRAGMENT, depthTest: false, depthWrite: false,
      uniforms: { referenceFrame: { value: null }, examinedFrame: { value: null }, difference: { value: null },
                  s: { value: 1 }, origin: { value: [0, 0] }, pane: { value: 0 }, shading: { value: 0 },
                  metric: { value: 0 }, lightDir: { value: new THREE.Vector3() }, viewDir: { value: new THREE.Vector3() },
                  viewUp: { value: new THREE.Vector3() }, low: { value: 0 }, high: { value: 1 }, threshold: { value: 0 },
                  background: { value: new THREE.Color(page.BACKGROUND) },
                  sequential: { value: DATA.colormaps.sequential.slice() },
                  diverging: { value: DATA.colormaps.diverging.slice() } } });
    const compareScene = quadPass(compareMaterial), displayScene = quadPass(displayMaterial);

    // Renders both frames with `camera` into `t` and compares them.
    function renderFrames(t, camera) {
      renderer.setClearColor(0x000000, 0);
      renderer.setRenderTarget(t.reference);
      renderer.clear(true, true, false);
      renderer.render(referenceScene, camera);
      renderer.setRenderTarget(t.examined);
      renderer.clear(true, true, false);
      renderer.render(examinedScene, camera);
      compareMaterial.uniforms.referenceFrame.value = t.reference.texture;
      compareMaterial.uniforms.examinedFrame.value = t.examined.texture;
      compareMaterial.uniforms.s.value = t.s;
      renderer.setRenderTarget(t.difference);
      renderer.render(compareScene, quadCamera);
      renderer.setRenderTarget(null);
    }
    // The camera of a sweep view (scanner/plan.h planned_view) for an image of w × h pixels.
    function sweepCamera(azimuthDeg, elevationDeg, footprint, w, h, target) {
      const c = new THREE.OrthographicCamera(-0.5 * w * footprint, 0.5 * w * footprint, 0.5 * h * footprint,
                                             -0.5 * h * footprint, 1.0 * radius, 5.0 * radius);
      const dir = dirFromAzEl(azimuthDeg, elevationDeg);
      c.up.copy(upFor(dir.clone().negate()));
      c.position.copy(target || target0).addScaledVector(dir, 3.0 * radius);
      c.lookAt(target || target0);
      c.updateMatrixWorld();
      return c;
    }
    // Reads a W × H float target as rows top first (glint's frames' order).
    function readTopFirst(target) {
      const w = target.width, h = target.height, px = new Float32Array(4 * w * h), out = new Float32Array(4 * w * h);
      renderer.readRenderTargetPixels(target, 0, 0, w, h, px);
      for (let y = 0; y < h; ++y) out.set(px.subarray(4 * (h - 1 - y) * w, 4 * (h - y) * w), 4 * y * w);
      return out;
    }

    // ---- the interactive view ---------------------------------------------------------------------
    // the difference shown first: the run's metric, whose floors the run measured
    const state = { layout: "side", shading: "normal", metric: METRICS[REPORT.metric.name] ? REPORT.metric.name : "angle",
                    supersample: LIVE.supersample || 2,
                    threshold: null, high: null, spin: false, dirty: true, targets: null, panes: [], frames: [],
                    lastFrameMs: 0, stats: null };
    const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.01 * radius, 10 * radius);
    camera.up.set(0, 0, 1);
    const paneNames = ["reference", "examined", "difference"];
    const paneDivs = paneNames.map((n) => $("live-pane-" + n));
    const sharedTarget = target0.clone();
    const controls = paneDivs.map((div) => {
      const c = new THREE.OrbitControls(camera, div);
      c.screenSpacePanning = true;
      c.target = sharedTarget;  // one target for every pane: orbit, zoom and pan are shared
      c.minZoom = 1e-3;
      c.maxZoom = 1e5;
      c.addEventListener("change", () => { state.dirty = true; requestFrame(); });
      c.addEventListener("start", () => {
        camera.up.set(0, 0, 1);  // after a jump straight along z, orbit about +z again
        controls.forEach((o) => { o.autoRotate = false; });
        if (state.spin) controls[0].autoRotate = true;
      });
      return c;
    });

    function footprint() { return (camera.top - camera.bottom) / camera.zoom / Math.max(1, state.paneH); }
    function setFootprint(f) {
      camera.zoom = (camera.top - camera.bottom) / (f * Math.max(1, state.paneH));
      camera.updateProjectionMatrix();
    }
    function nearestZoom(f) {
      let best = 0;
      zooms.forEach((z, k) => { if (Math.abs(Math.log(f / z.footprint)) < Math.abs(Math.log(f / zooms[best].footprint))) best = k; });
      return best;
    }
    function lookFrom(azimuthDeg, elevationDeg, f, target) {
      sharedTarget.copy(target || target0);
      const dir = dirFromAzEl(azimuthDeg, elevationDeg);
      camera.up.copy(upFor(dir.clone().negate()));
      camera.position.copy(sharedTarget).addScaledVector(dir, 3.0 * radius);
      camera.lookAt(sharedTarget);
      setFootprint(f);
      state.dirty = true;
      requestFrame();
    }
    // The atlas view's direction, the framed sphere filling the pane's narrower side.
    function resetView() { lookFrom(-60, 25, (2.0 * radius * 1.05) / Math.max(1, Math.min(state.paneW, state.paneH))); }

    // Pane rectangles (device pixels, GL's lower-left origin) for the layout; every pane one size.
    function layout() {
      const dpr = window.devicePixelRatio || 1;
      const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), h = Math.max(1, Math.round(canvas.clientHeight * dpr));
      if (canvas.width !== w || canvas.height !== h) renderer.setSize(w, h, false);
      const gap = Math.round(4 * dpr);
      const shown = state.layout === "side" ? [0, 1, 2] : [paneNames.indexOf(state.layout)];
      const pw = Math.max(1, Math.floor((w - gap * (shown.length - 1)) / shown.length));
      const oldW = state.paneW, oldH = state.paneH, oldF = oldH ? footprint() : null;
      state.paneW = pw;
      state.paneH = h;
      state.panes = shown.map((p, i) => ({ pane: p, x: i * (pw + gap), y: 0, w: pw, h: h }));
      paneDivs.forEach((div, p) => {
        const k = shown.indexOf(p);
        div.hidden = k < 0;
        if (k >= 0) {
          div.style.left = (state.panes[k].x / dpr) + "px";
          div.style.width = (pw / dpr) + "px";
        }
      });
      const aspect = pw / h;
      camera.left = -radius * aspect;
      camera.right = radius * aspect;
      camera.top = radius;
      camera.bottom = -radius;
      if (oldF && (oldW !== pw || oldH !== h)) setFootprint(oldF);  // a resize keeps the zoom
      camera.updateProjectionMatrix();
      state.dirty = true;
    }
    // The averaging used: the asked s, lowered until both frame targets fit.
    function usedSupersample(w, h) {
      let s = state.supersample;
      while (s > 1 && (s * Math.max(w, h) > maxTexture || s * s * w * h > MAX_TARGET_PIXELS)) --s;
      return s;
    }

    function metricRange() {
      const m = METRICS[state.metric];
      const z = zooms[nearestZoom(footprint())] || {};
      let floor = null, floorText = "";
      if (state.metric === "depth") {
        const sf = z.shape_floor ? z.shape_floor.value : DATA.shape_scale.floor;
        if (sf > 0) { floor = sf; floorText = "floor " + fmt(sf) + " " + UNIT; }
      } else if (REPORT.metric.name === state.metric && z.normal_floor) {
        floor = z.normal_floor.value;
        floorText = "floor " + fmt(floor) + m.unit;
      }
      // the run's metric: five times its floor, so the floor (the default threshold) sits a fifth
      // up the scale, in colour against the grey below it; at most the per-view heat maps'
      // range (scanner/metric.h), which a metric the run did not use gets; the depth: the
      // pictures' range (report/pictures.h)
      const high = state.high !== null ? state.high : state.metric === "depth" ? DATA.shape_scale.limit
        : floor !== null ? Math.min(Math.max(5 * floor, 1e-6), m.colourMax) : m.colourMax;
      // no floor for this metric (the run measured another): the threshold starts at a tenth
      // of the range, and the legend says so
      const threshold = floor !== null ? floor : 0.1 * high;
      return { low: state.metric === "depth" ? -high : 0, high: high, floor: floor, floorText: floorText,
               threshold: threshold, zoom: zooms.indexOf(z) };
    }

    function display() {
      const t = state.targets, u = displayMaterial.uniforms, r = metricRange();
      u.referenceFrame.value = t.reference.texture;
      u.examinedFrame.value = t.examined.texture;
      u.difference.value = t.difference.texture;
      u.s.value = t.s;
      u.shading.value = SHADINGS[state.shading];
      u.metric.value = METRICS[state.metric].index;
      u.low.value = r.low;
      u.high.value = r.high;
      u.threshold.value = state.threshold !== null ? state.threshold : r.threshold;
      // a light from the viewer's upper left, as the pictures' (report/pictures.h)
      const right = new THREE.Vector3(), up = new THREE.Vector3(), back = new THREE.Vector3();
      camera.matrixWorld.extractBasis(right, up, back);
      u.lightDir.value.set(0, 0, 0).addScaledVector(right, -0.3).addScaledVector(up, 0.4).addScaledVector(back, 0.866).normalize();
      u.viewDir.value.copy(back).negate();
      u.viewUp.value.copy(up);
      renderer.setRenderTarget(null);
      renderer.setScissorTest(false);
      renderer.setViewport(0, 0, canvas.width, canvas.height);
      renderer.setClearColor(page.BACKGROUND, 1);
      renderer.clear(true, true, false);
      state.panes.forEach((p) => {
        u.pane.value = p.pane;
        u.origin.value = [p.x, p.y];
        renderer.setViewport(p.x, p.y, p.w, p.h);
        renderer.render(displayScene, quadCamera);
      });
      drawLegend(r);
    }

    let framePending = false;
    function requestFrame() {
      if (framePending || !api.shown) return;
      framePending = true;
      requestAnimationFrame(frame);
    }
    function frame() {
      framePending = false;
      if (!api.shown) return;
      const t0 = performance.now();
      if (state.spin) controls[0].update();
      if (state.dirty) {
        const s = usedSupersample(state.paneW, state.paneH);
        const t = state.targets;
        if (!t || t.w !== state.paneW || t.h !== state.paneH || t.s !== s) {
          disposeTargets(t);
          state.targets = makeTargets(state.paneW, state.paneH, s);
        }
        fitDepthRange();
        renderFrames(state.targets, camera);
        state.dirty = false;
        state.stats = null;
        scheduleStats();
      }
      display();
      timeOnGpu(t0);
      const now = performance.now();
      state.frames.push(now);
      while (state.frames.length && state.frames[0] < now - 1000) state.frames.shift();
      showReadout();
      if (state.spin) { state.dirty = true; requestFrame(); }
    }
    // How long a frame took until the GPU finished it: a fence after its commands, polled.
    // (One at a time; a frame submitted while one is pending is not timed.)
    let fence = null;
    function timeOnGpu(t0) {
      if (fence) return;
      fence = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
      gl.flush();
      const poll = () => {
        if (gl.getSyncParameter(fence, gl.SYNC_STATUS) !== gl.SIGNALED) { setTimeout(poll, 1); return; }
        gl.deleteSync(fence);
        fence = null;
        state.lastFrameMs = performance.now() - t0;
        showReadout();
      };
      setTimeout(poll, 0);
    }
    // Near and far planes around both surfaces wherever the camera is (an orthographic camera
    // may have its near plane behind the eye).
    function fitDepthRange() {
      camera.updateMatrixWorld();
      const back = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 2);
      const d = back.dot(camera.position.clone().sub(bounds.center));
      camera.near = d - 1.01 * bounds.radius;
      camera.far = d + 1.01 * bounds.radius;
      camera.updateProjectionMatrix();
    }

    // ---- read-outs ----------------------------------------------------------------------------------
    function showReadout() {
      const f = footprint(), t = state.targets, k = nearestZoom(f);
      const z = zooms[k];
      // The paper's zoom, "distance in pixels from the camera to the nearest surface": the
      // distance of a perspective camera (fov 0.5 rad, render/view.h) that shows this
      // footprint at the nearest surface, in pixels of f0 = 2·radius/height (ZoomKind::DistancePixels).
      const paperDistance = (f * state.paneH * state.paneH) / (4 * radius * Math.tan(0.25));
      const parts = [
        "<b>" + fmt(f, 3) + " " + UNIT + " per pixel</b>",
        "averaging s = " + t.s + (t.s !== state.supersample ? " (asked " + state.supersample + ": the frame targets would not fit)" : "") +
          ": " + t.s * t.s + " sub-samples " + fmt(f / t.s, 3) + " " + UNIT + " apart",
        "sweep zoom " + k + ": " + fmt(z.footprint, 3) + " " + UNIT + "/px (" + (f > z.footprint ? "×" + fmt(f / z.footprint, 2) + " coarser" : "×" + fmt(z.footprint / f, 2) + " finer") + ")",
        "paper distance ≈ " + fmt(paperDistance, 3) + " px",
      ];
      $("live-readout").innerHTML = parts.join(" · ");
      // frames per second only while frames follow each other (spin): then the browser paces
      // them by the GPU; at rest, the time the last frame took until the GPU finished it
      const fps = state.frames.length > 1 ? (1000 * (state.frames.length - 1)) / (state.frames[state.frames.length - 1] - state.frames[0]) : 0;
      $("live-fps").textContent = (state.spin && state.frames.length > 2 ? fmt(fps, 3) + " fps · " : "") + "last frame " +
        (state.lastFrameMs ? fmt(state.lastFrameMs, 3) + " ms" : "—") + " to the GPU's end · " + state.paneW + "×" + state.paneH +
        " px per pane · frames " +
        t.s * state.paneW + "×" + t.s * state.paneH + " · " + shownTriangles[0] + " + " + shownTriangles[1] + " triangles" +
        (decimated ? " (decimated" + decimated + ")" : "") +
        (state.measured ? " · measured " + state.measured : "");
    }
    let statsTimer = null;
    function scheduleStats() {
      clearTimeout(statsTimer);
      statsTimer = setTimeout(() => { if (api.shown && !state.spin) showStats(); }, 250);
    }
    // What the difference pane shows, counted: compared pixels, how many exceed the threshold,
    // the largest value (read back once the view rests, not every frame).
    function computeStats() {
      const d = readTopFirst(state.targets.difference), m = METRICS[state.metric].index;
      const r = metricRange(), thr = state.threshold !== null ? state.threshold : r.threshold;
      let compared = 0, over = 0, max = 0, missing = 0;
      for (let i = 0; i < d.length; i += 4) {
        if (d[i + 3] === 2) ++missing;
        if (d[i + 3] !== 1) continue;
        ++compared;
        const v = Math.abs(d[i + m]);
        if (v >= thr) ++over;
        if (v > max) max = v;
      }
      return { compared: compared, over: over, max: max, missing: missing, threshold: thr };
    }
    function showStats() {
      if (!state.targets) return;
      const st = (state.stats = computeStats()), m = METRICS[state.metric];
      const unit = state.metric === "depth" ? " " + UNIT : m.unit;
      $("live-threshold-text").textContent = "≥ " + fmt(st.threshold, 3) + unit + ": " + st.over + " of " + st.compared +
        " compared pixels (" + fmt(st.compared ? (100 * st.over) / st.compared : 0, 3) + " %); largest " + fmt(st.max, 3) + unit +
        (st.missing ? "; " + st.missing + " pixels of missing surface" : "");
    }
    function drawLegend(r) {
      const bar = $("live-legend-bar"), ctx = bar.getContext("2d"), ticks = $("live-legend-ticks"), h = bar.height;
      const m = METRICS[state.metric], signed = state.metric === "depth";
      const knots = signed ? DATA.colormaps.diverging : DATA.colormaps.sequential;
      const thr = state.threshold !== null ? state.threshold : r.threshold;
      for (let y = 0; y < h; ++y) {
        const x = r.high - ((r.high - r.low) * y) / (h - 1);
        const c = Math.abs(x) < thr ? [0.5, 0.5, 0.5] : page.knotColour(knots, (x - r.low) / (r.high - r.low));
        ctx.fillStyle = "rgb(" + c.map((v) => Math.round(255 * v)).join(",") + ")";
        ctx.fillRect(0, y, bar.width, 1);
      }
      ticks.innerHTML = "";
      const put = (y, text, cls) => { const sp = el("span", cls ? { class: cls } : {}, text); sp.style.top = y + "px"; ticks.appendChild(sp); };
      const unit = signed ? UNIT : m.unit.trim();
      for (let k = 0; k <= 4; ++k) {
        const x = r.high - ((r.high - r.low) * k) / 4;
        put((k * (h - 1)) / 4, (signed && x > 0 ? "+" : "") + fmt(x) + (k === 0 ? " " + unit : ""));
      }
      if (r.floor !== null) put(((r.high - r.floor) / (r.high - r.low)) * (h - 1), "◀ " + r.floorText + ", zoom " + r.zoom, "floor");
      else if (state.threshold === null) put(((r.high - r.threshold) / (r.high - r.low)) * (h - 1), "◀ no floor: the run measured " + REPORT.metric.name, "floor");
      if (signed) { put(-14, "gain (bump)"); put(h + 12, "loss (dent)"); }
      $("live-legend-title").textContent = m.label;
    }

    // ---- controls of the mode -----------------------------------------------------------------------
    function option(select, value, text) { select.appendChild(el("option", { value: value }, text)); }
    function buildControls() {
      [1, 2, 3, 4, 6, 8].forEach((s) => option($("live-supersample"), s, s + "×" + s + (s === LIVE.supersample ? " (the run's)" : "")));
      $("live-supersample").value = String(state.supersample);
      $("live-metric").value = state.metric;
      const go = $("live-goto");
      option(go, "", "— a view of the run —");
      zooms.forEach((z, k) => (z.regions || []).forEach((r) => {
        if (r.best_view >= 0) option(go, "region:" + k + ":" + r.id, "zoom " + k + ": region " + r.id + " (" + r.kind + "), its best view");
      }));
      REPORT.views.forEach((v) => option(go, "view:" + v.index, "zoom " + v.zoom + ": view " + v.index + ", azimuth " + fmt(v.azimuth_deg) +
        "°, elevation " + fmt(v.elevation_deg) + "° (max " + fmt(v.max_angle_deg) + "°)"));
      go.addEventListener("change", () => {
        const [kind, a, b] = go.value.split(":");
        if (kind === "view") jumpToView(Number(a));
        if (kind === "region") {
          const r = zooms[Number(a)].regions.find((x) => String(x.id) === b);
          if (r) jumpToView(r.best_view);
        }
      });
      $("live-layout").addEventListener("change", () => { state.layout = $("live-layout").value; layout(); requestFrame(); });
      $("live-shading").addEventListener("change", () => { state.shading = $("live-shading").value; requestFrame(); });
      $("live-metric").addEventListener("change", () => {
        state.metric = $("live-metric").value;
        state.threshold = null;
        state.high = null;
        syncThreshold();
        requestFrame();
        scheduleStats();
      });
      $("live-supersample").addEventListener("change", () => {
        state.supersample = Number($("live-supersample").value);
        state.dirty = true;
        requestFrame();
      });
      $("live-threshold").addEventListener("input", () => {
        state.threshold = Number($("live-threshold").value);
        requestFrame();
        scheduleStats();
      });
      $("live-threshold-floor").addEventListener("click", () => { state.threshold = null; syncThreshold(); requestFrame(); scheduleStats(); });
      $("live-high").addEventListener("change", () => {
        const v = Number($("live-high").value);
        if (v > 0) state.high = v;
        syncThreshold();
        requestFrame();
      });
      $("live-reset").addEventListener("click", resetView);
      $("live-spin").addEventListener("change", () => {
        state.spin = $("live-spin").checked;
        controls[0].autoRotate = state.spin;
        state.frames = [];
        if (state.spin) requestFrame(); else scheduleStats();
      });
      $("live-measure").addEventListener("click", () => {
        const b = api.bench({ width: state.paneW, height: state.paneH, frames: 10 });
        state.measured = fmt(b.fps, 3) + " fps over " + b.frames + " frames of " + b.width + "×" + b.height + " (s = " + b.supersample + ")";
        requestFrame();
      });
      paneDivs.forEach((div) => {
        let downAt = null;
        div.addEventListener("pointerdown", (e) => { downAt = [e.clientX, e.clientY]; });
        div.addEventListener("pointerup", (e) => {
          if (downAt && Math.hypot(e.clientX - downAt[0], e.clientY - downAt[1]) < 4) pick(div, e);
          downAt = null;
        });
      });
      window.addEventListener("resize", () => { if (api.shown) { layout(); requestFrame(); } });
    }
    function syncThreshold() {
      const r = metricRange(), slider = $("live-threshold");
      const top = state.metric === "depth" ? r.high : Math.max(r.high, METRICS[state.metric].colourMax);
      slider.min = 0;
      slider.max = top;
      slider.step = top / 400;
      slider.value = state.threshold !== null ? state.threshold : r.threshold;
      $("live-high").value = Number(fmt(r.high, 4).replace("\u2212", "-"));
    }
    function jumpToView(index) {
      const v = REPORT.views.find((x) => x.index === index);
      if (!v) return;
      lookFrom(v.azimuth_deg, v.elevation_deg, zooms[v.zoom].footprint);
      $("live-pick").textContent = "Sweep view " + v.index + " (zoom " + v.zoom + ", azimuth " + fmt(v.azimuth_deg) + "°, elevation " +
        fmt(v.elevation_deg) + "°) at its footprint " + fmt(zooms[v.zoom].footprint, 3) + " " + UNIT +
        "/px; glint measured there: max " + fmt(v.max_angle_deg) + "°, mean " + fmt(v.mean_angle_deg) + "° over " + v.compared + " pixels.";
    }
    // The values of the pixel under a click.
    function pick(div, e) {
      const r = div.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
      const x = Math.floor((e.clientX - r.left) * dpr), yTop = Math.floor((e.clientY - r.top) * dpr);
      const t = state.targets;
      if (!t || x < 0 || yTop < 0 || x >= t.w || yTop >= t.h) return;
      const px = new Float32Array(4);
      renderer.readRenderTargetPixels(t.difference, x, t.h - 1 - yTop, 1, 1, px);
      const states = ["not compared (no surface, or a pixel only partly covered)", "compared", "surface missing in the examined", "surface only in the examined"];
      $("live-pick").textContent = "pixel (" + x + ", " + yTop + "): " + states[px[3]] +
        (px[3] === 1 ? ": angle " + fmt(px[0], 4) + "°, |RGB| " + fmt(px[1], 4) + ", depth " + (px[2] > 0 ? "+" : "") + fmt(px[2], 4) + " " + UNIT : "");
    }

    // ---- the interface ------------------------------------------------------------------------------
    api.available = true;
    api.renderer = renderer;
    api.show = function () {
      api.shown = true;
      layout();
      if (!state.started) { state.started = true; resetView(); syncThreshold(); }
      state.dirty = true;
      requestFrame();
    };
    api.hide = function () { api.shown = false; state.spin = false; $("live-spin").checked = false; controls[0].autoRotate = false; };
    api.lookFrom = lookFrom;
    api.jumpToView = jumpToView;
    api.footprint = footprint;
    api.state = state;
    // Renders and compares one sweep view at its own size, as glint did, and returns the
    // compared values, top row first: {width, height, supersample, angle, rgb, depth, state}.
    // spec: {azimuth, elevation, footprint, width, height, supersample}.
    api.measure = function (spec) {
      const s = spec.supersample || LIVE.supersample || 2;
      const t = makeTargets(spec.width, spec.height, s);
      try {
        renderFrames(t, sweepCamera(spec.azimuth, spec.elevation, spec.footprint, spec.width, spec.height));
        const d = readTopFirst(t.difference), n = spec.width * spec.height;
        const out = { width: spec.width, height: spec.height, supersample: s, angle: [], rgb: [], depth: [], state: [] };
        for (let i = 0; i < n; ++i) {
          out.state.push(d[4 * i + 3]);
          const ok = d[4 * i + 3] === 1;
          out.angle.push(ok ? d[4 * i] : null);
          out.rgb.push(ok ? d[4 * i + 1] : null);
          out.depth.push(ok ? d[4 * i + 2] : null);
        }
        return out;
      } finally {
        disposeTargets(t);
      }
    };
    // Frames per second of the whole pipeline (both frames, the comparison and the display of
    // the difference) at width × height, the camera turning 1° a frame; the GPU is waited for
    // once at the end (a 1-pixel read), so frames overlap as they do on screen.
    api.bench = function (spec) {
      const w = spec.width || 1024, h = spec.height || 1024, frames = spec.frames || 20;
      const s = spec.supersample || usedSupersample(w, h);
      const t = makeTargets(w, h, s), out = new THREE.WebGLRenderTarget(w, h);
      const c = sweepCamera(30, 20, (2.0 * radius) / h, w, h);
      const px = new Uint8Array(4);
      try {
        renderFrames(t, c);  // the first frame compiles the shaders
        renderer.readRenderTargetPixels(t.difference, 0, 0, 1, 1, new Float32Array(4));
        const t0 = performance.now();
        for (let i = 0; i < frames; ++i) {
          const cc = sweepCamera(31 + i, 20, (2.0 * radius) / h, w, h);
          renderFrames(t, cc);
          const u = displayMaterial.uniforms;
          u.referenceFrame.value = t.reference.texture;
          u.examinedFrame.value = t.examined.texture;
          u.difference.value = t.difference.texture;
          u.s.value = s;
          u.pane.value = 2;
          u.origin.value = [0, 0];
          renderer.setRenderTarget(out);
          renderer.render(displayScene, quadCamera);
          renderer.setRenderTarget(null);
        }
        renderer.readRenderTargetPixels(out, 0, 0, 1, 1, px);
        const ms = performance.now() - t0;
        return { width: w, height: h, supersample: s, frames: frames, ms: ms, fps: (1000 * frames) / ms,
                 triangles: shownTriangles.slice() };
      } finally {
        disposeTargets(t);
        out.dispose();
        state.dirty = true;
      }
    };

    // The live view's self-test (report.js runs it under #selftest): the panes are drawn; a
    // reference pane pixel shows the normal colour of its resolved normal and a difference
    // pixel the angle between the two, both recomputed here from the frames' sub-samples.
    api.selftest = async function () {
      const next = () => new Promise((r) => requestAnimationFrame(() => r()));
      api.show();
      await next();
      await next();
      const t = state.targets, w = canvas.width, h = canvas.height;
      const px = new Uint8Array(4 * w * h);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
      const bg = new THREE.Color(page.BACKGROUND);
      const drawn = state.panes.map((p) => {
        let n = 0;
        for (let y = p.y; y < p.y + p.h; y += 2)
          for (let x = p.x; x < p.x + p.w; x += 2) {
            const o = 4 * (y * w + x);
            if (Math.max(Math.abs(px[o] - 255 * bg.r), Math.abs(px[o + 1] - 255 * bg.g), Math.abs(px[o + 2] - 255 * bg.b)) > 8) ++n;
          }
        return n / ((p.w * p.h) / 4);
      });
      // the sub-samples of pixel (x, y) of a frame (GL rows), resolved here
      const frameOf = (target) => {
        const a = new Float32Array(4 * target.width * target.height);
        renderer.readRenderTargetPixels(target, 0, 0, target.width, target.height, a);
        return a;
      };
      const refHi = frameOf(t.reference), exaHi = frameOf(t.examined), diff = frameOf(t.difference);
      const resolve = (hi, x, y) => {
        let sx = 0, sy = 0, sz = 0, hits = 0;
        for (let j = 0; j < t.s; ++j)
          for (let i = 0; i < t.s; ++i) {
            const o = 4 * ((t.s * y + j) * t.s * t.w + t.s * x + i);
            if (hi[o] * hi[o] + hi[o + 1] * hi[o + 1] + hi[o + 2] * hi[o + 2] > 0.25) { sx += hi[o]; sy += hi[o + 1]; sz += hi[o + 2]; ++hits; }
          }
        const len = Math.hypot(sx, sy, sz);
        return { n: len > 0 ? [sx / len, sy / len, sz / len] : [0, 0, 0], coverage: hits / (t.s * t.s) };
      };
      // the compared pixel nearest the pane's centre, and the one of the largest angle
      let centre = null, strongest = null;
      for (let y = 0; y < t.h; ++y)
        for (let x = 0; x < t.w; ++x) {
          const o = 4 * (y * t.w + x);
          if (diff[o + 3] !== 1) continue;
          const d2 = (x - t.w / 2) ** 2 + (y - t.h / 2) ** 2;
          if (!centre || d2 < centre.d2) centre = { x: x, y: y, d2: d2 };
          if (!strongest || diff[o] > strongest.angle) strongest = { x: x, y: y, angle: diff[o] };
        }
      const checks = { drawn: drawn, ok: drawn.every((f) => f > 0.02), pixels: [] };
      if (!centre) return Object.assign(checks, { ok: false, why: "no compared pixel" });
      const refPane = state.panes.find((p) => p.pane === 0);
      [centre, strongest].forEach((q) => {
        const a = resolve(refHi, q.x, q.y), b = resolve(exaHi, q.x, q.y);
        const dot = Math.min(1, Math.max(-1, a.n[0] * b.n[0] + a.n[1] * b.n[1] + a.n[2] * b.n[2]));
        const expectedAngle = (Math.acos(dot) * 180) / Math.PI;
        const gotAngle = diff[4 * (q.y * t.w + q.x)];
        const o = 4 * ((refPane.y + q.y) * w + refPane.x + q.x);
        const expectedColour = a.n.map((c) => Math.round(255 * (0.5 * c + 0.5)));
        const gotColour = [px[o], px[o + 1], px[o + 2]];
        // note: the angle from acos of float normals in JavaScript's doubles against the
        // shader's atan2: 0.05° covers float rounding near 0°; the colour, 8-bit rounding: 1 of 255.
        const ok = Math.abs(gotAngle - expectedAngle) < 0.05 && Math.max(...gotColour.map((c, i) => Math.abs(c - expectedColour[i]))) <= 1;
        checks.pixels.push({ pixel: [q.x, q.y], expected_angle: expectedAngle, angle: gotAngle, expected_colour: expectedColour,
                             colour: gotColour, ok: ok });
        checks.ok = checks.ok && ok;
      });
      checks.supersample = t.s;
      return checks;
    };

    buildControls();
    return api;
  };
})();
