// glint report page: the atlas in 3D, the regions, the evidence (report/report_html.h).
// Data: the JSON in #glint-data (report.json whole, the mesh and per-vertex fields as base64
// little-endian typed arrays, colour maps, pictures as data URIs, the live view's examined
// surface). three.js r111, its OrbitControls and the live view (live.js) are inlined before
// this script. With "#selftest" in the URL the page checks itself and writes a JSON verdict
// into #selftest-verdict.
(function () {
  "use strict";
  const DATA = JSON.parse(document.getElementById("glint-data").textContent);
  const REPORT = DATA.report;
  const UNIT = DATA.unit;
  const GREY = [0.6, 0.6, 0.6];
  const BACKGROUND = 0x2a2e36;
  const $ = (id) => document.getElementById(id);

  function bytes(b64) {
    const bin = atob(b64);
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; ++i) out[i] = bin.charCodeAt(i);
    return out;
  }
  const positions = new Float32Array(bytes(DATA.mesh.positions).buffer);
  const indices = new Uint32Array(bytes(DATA.mesh.indices).buffer);
  // A large mesh is shown decimated: the page's vertex v is vertex vertexIds[v] of the atlas files.
  const vertexIds = DATA.mesh.vertex_ids ? new Uint32Array(bytes(DATA.mesh.vertex_ids).buffer) : null;
  const atlasVertex = (v) => (vertexIds ? vertexIds[v] : v);
  const fields = DATA.fields.map((f) => Object.assign({}, f, { data: new Float32Array(bytes(f.values).buffer) }));
  const byName = {};
  fields.forEach((f) => { byName[f.name] = f; });
  const state = { field: fields[0], low: 0, high: 1, greyUnseen: true, zoom: 0, flying: null };

  function fmt(v, digits) {
    if (v === null || v === undefined || Number.isNaN(v)) return "—";
    if (typeof v !== "number") return String(v);
    const s = Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(2) : v.toPrecision(digits || 3);
    return String(Number(s)).replace("-", "\u2212");
  }
  function el(tag, attrs, text) {
    const e = document.createElement(tag);
    Object.keys(attrs || {}).forEach((k) => e.setAttribute(k, attrs[k]));
    if (text !== undefined) e.textContent = text;
    return e;
  }

  // ---- colours -------------------------------------------------------------------------------
  // Linear interpolation between equally spaced knots, as OpenImageIO's color_map with knots.
  function knotColour(knots, t) {
    const n = knots.length / 3;
    const x = Math.min(1, Math.max(0, t)) * (n - 1);
    const i = Math.min(n - 2, Math.floor(x));
    const f = x - i;
    return [0, 1, 2].map((c) => knots[3 * i + c] * (1 - f) + knots[3 * (i + 1) + c] * f);
  }
  function categoryColour(id) {
    if (id <= 0) return [0.82, 0.82, 0.82];
    const h = (id * 0.618033988749895) % 1;
    const c = new THREE.Color().setHSL(h, 0.7, 0.5);
    return [c.r, c.g, c.b];
  }
  function seenField(f) { return byName["seen_z" + (f.zoom >= 0 ? f.zoom : state.zoom)]; }
  // Where the decision compared nothing (decision/comparison.h: a border band, surface the
  // examined scan never reached, a scanner's dropout): its values mean nothing, as the
  // pictures' hatching says. A warm grey apart from unseen grey.
  const NOT_COMPARED = [0.80, 0.78, 0.70];  // report/detail/canvas.h kNotCompared
  function comparedField(f) { return byName["not_compared_z" + (f.zoom >= 0 ? f.zoom : state.zoom)]; }
  // The decision field, the signed shape change ("shape_change_mm"), is the first field
  // (report/atlas_fields.h); the page opens on it.
  const shapeField = fields.find((f) => f.name.startsWith("shape_change_")) || fields[0];
  function colourOf(f, v, low, high) {
    const x = f.data[v];
    if (Number.isNaN(x)) return GREY;
    if (f.kind === "category") return categoryColour(Math.round(x));
    if (f.kind === "binary") return x > 0.5 ? [0.42, 0.74, 0.45] : GREY;
    if (state.greyUnseen) {
      const s = seenField(f);
      if (s && s.data[v] < 0.5) return GREY;
      const c = comparedField(f);
      if (c && c.data[v] > 0.5) return NOT_COMPARED;
    }
    const t = high > low ? (x - low) / (high - low) : 0.5;
    return knotColour(f.kind === "signed" ? DATA.colormaps.diverging : DATA.colormaps.sequential, t);
  }

  // ---- scene ---------------------------------------------------------------------------------
  const canvas = $("view3d");
  const renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(BACKGROUND);
  const center = new THREE.Vector3().fromArray(DATA.mesh.center);
  const radius = Math.max(DATA.mesh.radius, 1e-9);
  const camera = new THREE.PerspectiveCamera(35, 1, radius * 0.01, radius * 100);
  // Up as the pictures draw it (report.json "orientation": superior in a patient space, else +z
  // or --up); the page first looks from the front, turned left and raised, as atlas.png does.
  const ORIENT = REPORT.orientation || { up: [0, 0, 1], front: [1, 0, 0] };
  const UP = new THREE.Vector3().fromArray(ORIENT.up), FRONT = new THREE.Vector3().fromArray(ORIENT.front);
  camera.up.copy(UP);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(indices, 1));
  // The vertex normals the sweep rendered (int16 scaled by 32767), else made here.
  if (DATA.mesh.normals) {
    const n16 = new Int16Array(bytes(DATA.mesh.normals).buffer), normals = new Float32Array(n16.length);
    for (let i = 0; i < n16.length; ++i) normals[i] = n16[i] / 32767;
    geometry.setAttribute("normal", new THREE.BufferAttribute(normals, 3));
  } else {
    geometry.computeVertexNormals();
  }
  const colours = new Float32Array(positions.length);
  geometry.setAttribute("color", new THREE.BufferAttribute(colours, 3));
  // Pushed back a little in depth: the region outlines lie on the surface (overlays.js).
  const surfaceOptions = { vertexColors: THREE.VertexColors, side: THREE.DoubleSide, polygonOffset: true,
                           polygonOffsetFactor: 1, polygonOffsetUnits: 1 };
  const litMaterial = new THREE.MeshLambertMaterial(surfaceOptions);
  const flatMaterial = new THREE.MeshBasicMaterial(surfaceOptions);
  const mesh = new THREE.Mesh(geometry, litMaterial);
  scene.add(mesh);
  scene.add(new THREE.AmbientLight(0xffffff, 0.32));
  // A headlight from the upper left behind the viewer, as the pictures' light.
  const headlight = new THREE.DirectionalLight(0xffffff, 0.72);
  headlight.position.set(-0.3, 0.4, 0.866);
  camera.add(headlight);
  camera.add(headlight.target);
  scene.add(camera);
  const controls = new THREE.OrbitControls(camera, canvas);
  controls.screenSpacePanning = true;
  controls.target.copy(center);
  let renderPending = false;
  let overlays = null;  // outlines, region labels, pick marker (overlays.js)
  function renderNow() {
    if (overlays) overlays.update();
    renderer.render(scene, camera);
  }
  function requestRender() {
    if (renderPending) return;
    renderPending = true;
    requestAnimationFrame(() => { renderPending = false; renderNow(); });
  }
  controls.addEventListener("change", requestRender);
  function resize() {
    const w = Math.max(1, canvas.clientWidth), h = Math.max(1, canvas.clientHeight);
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    requestRender();
  }
  window.addEventListener("resize", resize);

  function dirFromAzEl(azDeg, elDeg) {
    const a = (azDeg * Math.PI) / 180, e = (Math.max(-89, Math.min(89, elDeg)) * Math.PI) / 180;
    return new THREE.Vector3(Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e));
  }
  function fitDistance(extent) { return extent / Math.sin((camera.fov * Math.PI) / 360); }
  function resetView() {
    controls.target.copy(center);
    const a = (-60 * Math.PI) / 180, e = (25 * Math.PI) / 180;
    const side = new THREE.Vector3().crossVectors(UP, FRONT);
    const dir = FRONT.clone().multiplyScalar(Math.cos(e) * Math.cos(a))
      .addScaledVector(side, Math.cos(e) * Math.sin(a)).addScaledVector(UP, Math.sin(e));
    camera.position.copy(center).addScaledVector(dir, fitDistance(radius * 1.05));
    controls.update();
    requestRender();
  }
  // Moves target and camera to new places over `ms` milliseconds (eased).
  function flyTo(target, position, ms) {
    const t0 = performance.now();
    const fromTarget = controls.target.clone(), fromPosition = camera.position.clone();
    return new Promise((resolve) => {
      function step(now) {
        const s = Math.min(1, (now - t0) / ms);
        const e = s * s * (3 - 2 * s);
        controls.target.lerpVectors(fromTarget, target, e);
        camera.position.lerpVectors(fromPosition, position, e);
        controls.update();
        renderNow();
        if (s < 1) requestAnimationFrame(step);
        else resolve();
      }
      requestAnimationFrame(step);
    });
  }

  // ---- fields, range, legend -----------------------------------------------------------------
  function recolour() {
    const f = state.field;
    for (let v = 0; v < f.data.length; ++v) {
      const c = colourOf(f, v, state.low, state.high);
      colours[3 * v] = c[0]; colours[3 * v + 1] = c[1]; colours[3 * v + 2] = c[2];
    }
    geometry.attributes.color.needsUpdate = true;
    drawLegend();
    requestRender();
  }
  function selectField(name) {
    state.field = byName[name] || fields[0];
    $("field").value = state.field.name;
    state.low = state.field.range[0];
    state.high = state.field.range[1];
    $("range-low").value = fmt(state.low, 4).replace("\u2212", "-");
    $("range-high").value = fmt(state.high, 4).replace("\u2212", "-");
    const continuous = state.field.kind === "signed" || state.field.kind === "sequential";
    $("range-label").style.visibility = continuous ? "visible" : "hidden";
    recolour();
  }
  function drawLegend() {
    const f = state.field, bar = $("legend-bar"), ctx = bar.getContext("2d"), ticks = $("legend-ticks");
    ticks.innerHTML = "";
    const h = bar.height;
    const put = (y, text) => { const s = el("span", {}, text); s.style.top = y + "px"; ticks.appendChild(s); };
    if (f.kind === "category" || f.kind === "binary") {
      // (at most 12 rows: "no region" and the first regions; the rest keep their colours)
      const n = f.kind === "binary" ? 2 : Math.min(12, Math.max(1, Math.round(f.range[1]) + 1));
      for (let i = 0; i < n; ++i) {
        const c = f.kind === "binary" ? (i === 0 ? [0.42, 0.74, 0.45] : GREY) : categoryColour(i);
        ctx.fillStyle = "rgb(" + c.map((x) => Math.round(255 * x)).join(",") + ")";
        ctx.fillRect(0, (i * h) / n, bar.width, h / n + 1);
        put(((i + 0.5) * h) / n, f.kind === "binary" ? (i === 0 ? "seen" : "unseen") : i === 0 ? "no region" : "region " + i);
      }
      return;
    }
    for (let y = 0; y < h; ++y) {
      const x = state.high - ((state.high - state.low) * y) / (h - 1);
      const t = state.high > state.low ? (x - state.low) / (state.high - state.low) : 0.5;
      const c = knotColour(f.kind === "signed" ? DATA.colormaps.diverging : DATA.colormaps.sequential, t);
      ctx.fillStyle = "rgb(" + c.map((v) => Math.round(255 * v)).join(",") + ")";
      ctx.fillRect(0, y, bar.width, 1);
    }
    for (let k = 0; k <= 4; ++k) {
      const x = state.high - ((state.high - state.low) * k) / 4;
      put((k * (h - 1)) / 4, (x > 0 && f.kind === "signed" ? "+" : "") + fmt(x) + (k === 0 && f.unit ? " " + f.unit : ""));
    }
    // glint asymmetry: the fields give this side against the mirrored other side
    const mirror = !!REPORT.asymmetry;
    if (f.kind === "signed") {
      put(-14, mirror ? "more than the mirror" : "gain (bump)");
      put(h + 12, mirror ? "less than the mirror" : "loss (dent)");
    }
  }

  // ---- picking -------------------------------------------------------------------------------
  const raycaster = new THREE.Raycaster();
  // The vertex nearest to the surface point under client pixel (x, y), or -1.
  function vertexAt(clientX, clientY) {
    const r = canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    const hits = raycaster.intersectObject(mesh);
    if (!hits.length) return -1;
    const h = hits[0], p = new THREE.Vector3();
    let best = -1, bestD = Infinity;
    [h.face.a, h.face.b, h.face.c].forEach((v) => {
      const d = p.fromArray(positions, 3 * v).distanceToSquared(h.point);
      if (d < bestD) { bestD = d; best = v; }
    });
    return best;
  }
  function showVertex(v) {
    const box = $("pick");
    box.innerHTML = "";
    if (v < 0) { box.textContent = "No surface there."; return; }
    const p = new THREE.Vector3().fromArray(positions, 3 * v);
    const t = el("table");
    const row = (k, val) => { const tr = el("tr"); tr.appendChild(el("td", {}, k)); tr.appendChild(el("td", {}, val)); t.appendChild(tr); };
    row("vertex " + atlasVertex(v), "(" + [p.x, p.y, p.z].map((x) => fmt(x, 5)).join(", ") + ") " + UNIT);
    fields.forEach((f) => {
      const x = f.data[v];
      row(f.label, Number.isNaN(x) ? "unseen" : fmt(x, 4) + (f.unit ? " " + f.unit : ""));
    });
    box.appendChild(t);
    overlays.placeMarker(p);
    requestRender();
  }
  let downAt = null;
  canvas.addEventListener("pointerdown", (e) => { downAt = [e.clientX, e.clientY]; });
  canvas.addEventListener("pointerup", (e) => {
    if (downAt && Math.hypot(e.clientX - downAt[0], e.clientY - downAt[1]) < 4) showVertex(vertexAt(e.clientX, e.clientY));
    downAt = null;
  });

  // ---- regions -------------------------------------------------------------------------------
  function regionsOf(z) { return (REPORT.zooms[z] && REPORT.zooms[z].regions) || []; }
  // The direction a region faces: the mean of its vertices' normals; when they cancel out, its
  // best view's direction (the sweep's view that saw its strongest deviation).
  function regionFacing(r) {
    const ids = byName["region_id_z" + state.zoom], normal = geometry.attributes.normal.array;
    const sum = new THREE.Vector3();
    let count = 0;
    if (ids)
      for (let v = 0; v < ids.data.length; ++v)
        if (ids.data[v] === r.id) { sum.x += normal[3 * v]; sum.y += normal[3 * v + 1]; sum.z += normal[3 * v + 2]; ++count; }
    if (count && sum.length() > 0.2 * count) return sum.normalize();
    if (r.best_view_azimuth_deg !== undefined) return dirFromAzEl(r.best_view_azimuth_deg, r.best_view_elevation_deg);
    return camera.position.clone().sub(controls.target).normalize();
  }
  function flyToRegion(r) {
    const target = new THREE.Vector3().fromArray(r.centroid);
    const extent = Math.max(Math.sqrt(Math.max(r.area, 0)) * 1.5, radius * 0.12);
    const position = target.clone().addScaledVector(regionFacing(r), fitDistance(extent));
    showBestView(r);
    return flyTo(target, position, 700);
  }
  function showBestView(r) {
    const img = $("best-view-img"), cap = $("best-view-caption");
    const uri = DATA.images.best_views[String(r.best_view)];
    if (uri) {
      img.src = uri;
      img.style.display = "block";
      // views/ exists only when the run wrote per-view pictures (--views; issue 51).
      const views = ((REPORT.analysis || {}).exports || {}).views === true;
      cap.textContent = "region " + r.id + ": best view " + viewName(r.best_view) + " (azimuth " + fmt(r.best_view_azimuth_deg) +
        "°, elevation " + fmt(r.best_view_elevation_deg) + "°)" + (views ? "; views/ holds every view" : "");
    } else {
      img.style.display = "none";
      const drawn = ((REPORT.analysis || {}).exports || {}).pictures !== false;
      cap.textContent = "region " + r.id + (drawn ? ": no picture of its best view is embedded (only the strongest regions' are)"
                                                 : ": no pictures were drawn (this run was made with --no-pictures)");
    }
  }
  // The view's name as its files are named (views/<name>.png), and its direction.
  function viewName(index) {
    const name = (DATA.view_names || [])[index];
    return name === undefined ? "view " + index : name;
  }
  function selectRegion(r, row) {
    document.querySelectorAll("#regions tbody tr").forEach((x) => x.classList.remove("selected"));
    row.classList.add("selected");
    // in the live view: the region's best view, as the sweep took it
    if (live && live.shown && r.best_view >= 0) live.jumpToView(r.best_view);
    else state.lastFlight = flyToRegion(r);
  }
  // Under each region's numbers: the finding in one plain sentence (report.json's `finding`),
  // the view that saw it best with a button that goes there, and folded away the method's
  // figures: why the decision made it a region and its strongest metric.
  function evidenceRow(r, row, columns) {
    const tr = el("tr", { class: "evidence", "data-evidence": r.id });
    const td = el("td", { colspan: columns });
    td.appendChild(el("span", { class: "finding-text" }, r.finding ? r.finding : r.kind + " region"));
    // How strongly it stands out of the undamaged surface (null where none was stated).
    if (typeof r.z === "number" && typeof r.p_value === "number")
      td.appendChild(el("span", { class: "significance" }, "; " + fmt(r.z) + " spreads of the undamaged surface, family-wise p " +
                                                             (r.p_value < 1e-6 ? "< 1e-6" : r.p_value.toPrecision(2))));
    if (r.best_view >= 0) {
      td.appendChild(el("br"));
      td.appendChild(document.createTextNode("best view "));
      td.appendChild(el("span", { class: "viewname" }, viewName(r.best_view)));
      td.appendChild(document.createTextNode(" (azimuth " + fmt(r.best_view_azimuth_deg) + "°, elevation " +
                                             fmt(r.best_view_elevation_deg) + "°)"));
      const go = el("button", { type: "button", class: "go-best-view" }, "go there");
      go.addEventListener("click", (e) => { e.stopPropagation(); selectRegion(r, row); });
      td.appendChild(go);
    }
    const metric = REPORT.metric.name, mu = REPORT.metric.unit === "deg" ? "°" : " " + REPORT.metric.unit;
    const why = el("details", { class: "region-details" });
    why.appendChild(el("summary", {}, "details"));
    why.appendChild(el("span", { class: "evidence-text" }, r.evidence ? r.evidence : "no evidence recorded"));
    why.appendChild(el("br"));
    why.appendChild(document.createTextNode("strongest " + metric + " " + fmt(r["max_" + metric + "_" + REPORT.metric.unit]) + mu +
                                            " · " + r.vertices + " vertices"));
    td.appendChild(why);
    tr.appendChild(td);
    return tr;
  }
  // The regions' numbers in the run's unit: depth with one robust standard deviation of the
  // distance on the unchanged surface (report.json depth_uncertainty), area, volume and where
  // the region lies (its place: anatomical sides when the orientation is known).
  function buildRegions() {
    const z = state.zoom, head = document.querySelector("#regions thead"), body = document.querySelector("#regions tbody");
    head.innerHTML = "";
    body.innerHTML = "";
    const cols = ["id", "kind", "depth (" + UNIT + ")", "± (" + UNIT + ")", "area (" + UNIT + "²)", "volume (" + UNIT + "³)", "place"];
    const tr = el("tr");
    cols.forEach((c) => tr.appendChild(el("th", {}, c)));
    head.appendChild(tr);
    const regions = regionsOf(z);
    if (!regions.length) { const r = el("tr"); r.appendChild(el("td", { colspan: cols.length }, "no region at this zoom")); body.appendChild(r); }
    regions.forEach((r) => {
      const row = el("tr", { "data-region": r.id, class: "region" });
      const kind = r.kind === "missing surface" ? "missing" : r.kind;
      // (a missing-surface region has no depth or volume: null in report.json, "—" here; surface
      // gone has a height above its rim, not a depth measured between two surfaces: no ±)
      const plusMinus = r.peak_depth === null || r.surface_gone || r.depth_uncertainty === undefined ? "—" : fmt(r.depth_uncertainty);
      [r.id, r.surface_gone ? "surface gone" : r.kind, fmt(r.peak_depth), plusMinus, fmt(r.area), fmt(r.volume), r.place || "—"]
        .forEach((v, i) => row.appendChild(el("td", i === 1 ? { class: kind } : i === 6 ? { class: "place" } : {}, String(v))));
      row.addEventListener("click", () => selectRegion(r, row));
      body.appendChild(row);
      body.appendChild(evidenceRow(r, row, cols.length));
    });
    if (regions.length) showBestView(regions[0]);
  }

  let evidence = null;  // the banner, fit, floors, run and pictures (evidence.js)

  // ---- modes: the atlas, or the live view (live.js) ----------------------------------------------
  let live = null;
  function showMode(mode) {
    const isLive = mode === "live";
    $("atlas-mode").hidden = isLive;
    $("live-mode").hidden = !isLive;
    document.querySelector("main").classList.toggle("live", isLive);
    $("mode-atlas").classList.toggle("selected", !isLive);
    $("mode-live").classList.toggle("selected", isLive);
    if (isLive && live.available) live.show();
    if (!isLive) {
      if (live.available) live.hide();
      resize();
    }
  }
  function initLive() {
    $("mode-atlas").addEventListener("click", () => showMode("atlas"));
    $("mode-live").addEventListener("click", () => showMode("live"));
    live = window.glintLiveView({ DATA: DATA, $: $, el: el, fmt: fmt, knotColour: knotColour, positions: positions,
                                  indices: indices, BACKGROUND: BACKGROUND });
  }

  // ---- page ----------------------------------------------------------------------------------
  function init() {
    fields.forEach((f) => $("field").appendChild(el("option", { value: f.name }, f.label)));
    REPORT.zooms.forEach((z, k) => $("zoom").appendChild(el("option", { value: k }, "zoom " + k)));
    $("field").addEventListener("change", () => selectField($("field").value));
    $("zoom").addEventListener("change", () => {
      state.zoom = Number($("zoom").value);
      buildRegions();
      overlays.setZoom(state.zoom);
      recolour();
    });
    const readRange = () => { state.low = Number($("range-low").value); state.high = Number($("range-high").value); recolour(); };
    $("range-low").addEventListener("change", readRange);
    $("range-high").addEventListener("change", readRange);
    $("range-reset").addEventListener("click", () => selectField(state.field.name));
    $("grey-unseen").addEventListener("change", () => { state.greyUnseen = $("grey-unseen").checked; recolour(); });
    $("view-reset").addEventListener("click", resetView);
    // The share the decision compared (decision/comparison.h), and a one-view scan's dropouts.
    const comparedText = (z) => {
      const c = z.comparison;
      if (!c || c.compared_fraction >= 1) return "";
      const drops = c.dropouts && c.dropouts.count ? ", " + c.dropouts.count + " scanner dropout(s) of a one-view scan" : "";
      const thin = c.not_compared && c.not_compared.below_resolution && c.not_compared.below_resolution.share > 0
        ? ", " + fmt(100 * c.not_compared.below_resolution.share) + " % below the scans' resolution (thin plates, narrow gaps)" : "";
      return " · compared " + fmt(100 * c.compared_fraction) + " % of the reference" + drops + thin + " (warm grey: not compared)";
    };
    const z0 = REPORT.zooms[0] || { regions: [], coverage: 0 };
    const shown = DATA.mesh.shown ? " (shown decimated to " + DATA.mesh.shown.triangles + " triangles, within " +
      fmt(DATA.mesh.shown.error, 2) + " " + UNIT + "; regions whole)" : "";
    $("subtitle").textContent = DATA.mesh.vertices + " vertices, " + DATA.mesh.triangles + " triangles" + shown +
      " · lengths in " + UNIT +
      " · " + z0.regions.length + " region(s) at zoom 0 · coverage " + fmt(100 * z0.coverage) + " %" + comparedText(z0);
    selectField(shapeField.name);
    buildRegions();
    evidence = window.glintEvidence({ REPORT: REPORT, DATA: DATA, UNIT: UNIT, $: $, el: el, fmt: fmt });
    overlays = window.glintOverlays({ THREE: THREE, scene: scene, camera: camera, renderer: renderer, positions: positions,
                                      indices: indices, byName: byName, REPORT: REPORT, $: $, el: el, radius: radius });
    overlays.setZoom(state.zoom);
    try {
      initLive();
    } catch (e) {
      // the atlas stays usable whatever the live view met
      window.glintErrors.push("live view: " + (e && e.stack ? e.stack : e));
      live = { available: false, reason: "The live view failed to start: " + e };
    }
    resize();
    resetView();
    if (location.hash === "#selftest") window.glintSelftest().then(() => {});
  }

  // ---- self-test (#selftest) -----------------------------------------------------------------
  const nextFrame = () => new Promise((r) => requestAnimationFrame(() => r()));
  function screenOf(v, w, h) {
    const p = new THREE.Vector3().fromArray(positions, 3 * v).project(camera);
    return [((p.x + 1) / 2) * w, ((1 - p.y) / 2) * h];
  }
  // A pixel inside a large, visible, front-facing triangle of the most saturated colours (so
  // the colour check means something), with the colour the unlit mesh must show there: the
  // corners' colours interpolated at the surface point under the pixel centre. The pixel sits
  // at the triangle's centroid, so all its samples fall in that one triangle.
  function knownPixel(w, h) {
    const f = state.field, scored = [], cam = camera.position;
    const a = new THREE.Vector3(), b = new THREE.Vector3(), c = new THREE.Vector3(), n = new THREE.Vector3();
    for (let t = 0; t < indices.length / 3; ++t) {
      const v = [indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]];
      if (v.some((x) => Number.isNaN(f.data[x]))) continue;
      const s = v.map((x) => screenOf(x, w, h));
      const area = Math.abs((s[1][0] - s[0][0]) * (s[2][1] - s[0][1]) - (s[2][0] - s[0][0]) * (s[1][1] - s[0][1])) / 2;
      const x = (s[0][0] + s[1][0] + s[2][0]) / 3, y = (s[0][1] + s[1][1] + s[2][1]) / 3;
      if (area < 24 || x < 10 || y < 10 || x > w - 10 || y > h - 10) continue;
      a.fromArray(positions, 3 * v[0]); b.fromArray(positions, 3 * v[1]); c.fromArray(positions, 3 * v[2]);
      n.subVectors(c, b).cross(a.clone().sub(b)).normalize();
      const centroid = a.clone().add(b).add(c).divideScalar(3);
      if (Math.abs(n.dot(cam.clone().sub(centroid).normalize())) < 0.5) continue;
      const cols = v.map((x) => colourOf(f, x, state.low, state.high));
      const saturation = Math.min(...cols.map((q) => Math.max(...q) - Math.min(...q)));
      scored.push({ t: t, v: v, x: x, y: y, cols: cols, score: saturation });
    }
    scored.sort((p, q) => q.score - p.score);
    for (const s of scored.slice(0, 40)) {
      const xi = Math.floor(s.x), yi = Math.floor(s.y);
      raycaster.setFromCamera(new THREE.Vector2(((xi + 0.5) / w) * 2 - 1, -(((yi + 0.5) / h) * 2 - 1)), camera);
      const hit = raycaster.intersectObject(mesh)[0];
      if (!hit || hit.faceIndex !== s.t) continue;  // hidden behind other surface
      const tri = new THREE.Triangle(...s.v.map((x) => new THREE.Vector3().fromArray(positions, 3 * x)));
      const bw = tri.getBarycoord(hit.point, new THREE.Vector3()).toArray();
      const expected = [0, 1, 2].map((ch) => Math.round(255 * (bw[0] * s.cols[0][ch] + bw[1] * s.cols[1][ch] + bw[2] * s.cols[2][ch])));
      // the corner nearest the surface point, as picking chooses it
      const dist = s.v.map((x) => new THREE.Vector3().fromArray(positions, 3 * x).distanceTo(hit.point));
      const corner = dist.indexOf(Math.min(...dist));
      let spread = 0;
      for (let ch = 0; ch < 3; ++ch) spread = Math.max(spread, Math.max(...s.cols.map((q) => q[ch])) - Math.min(...s.cols.map((q) => q[ch])));
      return { xi: xi, yi: yi, expected: expected, vertex: s.v[corner], spread: spread };
    }
    return null;
  }
  // The unlit mesh's pixels (a pixel's colour is then the interpolated vertex colour).
  function readCanvas() {
    mesh.material = flatMaterial;
    overlays.setVisible(false);
    renderNow();
    const gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    mesh.material = litMaterial;
    overlays.setVisible(true);
    renderNow();
    return { w: w, h: h, px: px };
  }
  function checkCanvas(c) {
    const bg = new THREE.Color(BACKGROUND);
    let drawn = 0;
    for (let i = 0; i < c.w * c.h; ++i)
      if (Math.max(Math.abs(c.px[4 * i] - 255 * bg.r), Math.abs(c.px[4 * i + 1] - 255 * bg.g),
                   Math.abs(c.px[4 * i + 2] - 255 * bg.b)) > 8) ++drawn;
    return { width: c.w, height: c.h, drawn_fraction: drawn / (c.w * c.h), ok: drawn / (c.w * c.h) > 0.02 };
  }
  async function checkRegionClick() {
    const row = document.querySelector("#regions tbody tr[data-region]");
    if (!row) return { ok: true, skipped: "no region" };
    const region = regionsOf(state.zoom).find((x) => String(x.id) === row.getAttribute("data-region"));
    const centroid = new THREE.Vector3().fromArray(region.centroid);
    const before = camera.position.clone();
    const img = $("best-view-img");
    img.style.display = "none";  // the click must show it again
    img.removeAttribute("src");
    row.click();
    await state.lastFlight;
    const forward = new THREE.Vector3();
    camera.getWorldDirection(forward);
    const towards = centroid.clone().sub(camera.position).normalize();
    const shown = img.style.display === "block" && img.src.startsWith("data:image/png");
    const moved = before.distanceTo(camera.position), targetError = controls.target.distanceTo(centroid);
    return { region: region.id, moved: moved, distance_before: before.distanceTo(centroid),
             distance_after: camera.position.distanceTo(centroid), target_error: targetError,
             looking_at_centroid: forward.dot(towards), best_view_shown: shown,
             ok: moved > radius * 1e-3 && targetError < radius * 1e-6 + 1e-9 && forward.dot(towards) > 0.9999 &&
                 (shown || !DATA.images.best_views[String(region.best_view)]) };
  }
  function checkColourAndPick(c, verdict) {
    const k = knownPixel(c.w, c.h);
    if (!k) { verdict.checks.colour = { ok: false, why: "no large visible triangle" }; return; }
    const o = 4 * ((c.h - 1 - k.yi) * c.w + k.xi);
    const got = [c.px[o], c.px[o + 1], c.px[o + 2]];
    // note: 6 of 255 for rounding and blending; the rest for the colour change across the
    // pixel (a triangle of at least 24 px² spans its corners' spread over ≥ 6 px).
    const tolerance = 6 + 255 * 0.15 * k.spread;
    const diff = Math.max(...got.map((g, i) => Math.abs(g - k.expected[i])));
    const f = state.field;
    verdict.checks.colour = { field: f.name, vertex: atlasVertex(k.vertex), value: f.data[k.vertex],
                              vertex_colour: colourOf(f, k.vertex, state.low, state.high).map((x) => Math.round(255 * x)),
                              low: state.low, high: state.high, pixel: [k.xi, k.yi], expected: k.expected, got: got,
                              tolerance: tolerance, ok: diff <= tolerance };
    const r = canvas.getBoundingClientRect(), dpr = c.w / r.width;
    const picked = vertexAt(r.left + (k.xi + 0.5) / dpr, r.top + (k.yi + 0.5) / dpr);
    verdict.checks.pick = { vertex: picked, expected: k.vertex, ok: picked === k.vertex };
  }
  // The self-test: the canvas is drawn; a click on region row 1 flies there and shows its best
  // view; there (triangles large, colours strong) a pixel shows the colour its surface point
  // must have, and picking it gives its vertex; the live view draws its panes and its numbers
  // are the frames' (live.js selftest), or without WebGL2 it says why; no error happened on
  // the page; every region has an outline and a label, hidden from behind, and the pick marker
  // keeps its size on screen (overlays.js selftest).
  window.glintSelftest = async function () {
    const verdict = { ok: false, checks: {}, errors: [] };
    try {
      await nextFrame();
      selectField(shapeField.name);
      verdict.checks.canvas = checkCanvas(readCanvas());
      verdict.checks.region_click = await checkRegionClick();
      checkColourAndPick(readCanvas(), verdict);
      verdict.checks.overlays = overlays.selftest({
        regions: regionsOf(state.zoom), center: center, facingOf: regionFacing, render: renderNow,
        setCamera: (target, position) => { controls.target.copy(target); camera.position.copy(position); controls.update(); } });
      resetView();
      if (live.available) {
        showMode("live");
        verdict.checks.live = await live.selftest();
        showMode("atlas");
        await nextFrame();
      } else {
        verdict.checks.live = { available: false, message: live.reason, shown: !$("live-message").hidden, ok: !$("live-message").hidden };
      }
      verdict.checks.live.available = live.available;
    } catch (e) {
      window.glintErrors.push("selftest: " + (e && e.stack ? e.stack : e));
    }
    verdict.errors = window.glintErrors.slice();
    verdict.ok = verdict.errors.length === 0 && Object.keys(verdict.checks).length >= 6 &&
                 Object.values(verdict.checks).every((c) => c.ok);
    $("selftest-verdict").textContent = JSON.stringify(verdict);
    return verdict;
  };

  init();
})();
