// glint report page: what is drawn over the atlas in 3D (report/report_html.h): each region's
// outline on the surface, its id as a label at its place, and the pick marker. report.js calls
// window.glintOverlays(ctx) once and overlays.update() before every render.
//
//   outline  the boundary between a region's vertices and the others, traced through the
//            triangles whose corners differ (marching triangles on the region ids): a segment
//            between the midpoints of the two edges that change label, or from each edge's
//            midpoint to the centroid when all three corners differ. The surface is drawn
//            pushed back (polygon offset) so the lines lying on it win the depth test.
//   labels   the region id at the region's vertex nearest its centroid (a point on the
//            surface), placed in screen space every frame; dimmed when the surface hides that
//            point (the depth of the surface there, read from a depth render when the view
//            has settled), gone when it leaves the view.
//   marker   a ring round the picked point, facing the camera, of a fixed fraction of the
//            view's height at the point's distance: the same size on screen at any zoom, and
//            its hole leaves the picked place visible.
(function () {
  "use strict";

  const MARKER_FRACTION = 0.022;  // ring radius / view height (12 px of a 560 px view)
  const MARKER_HOLE = 0.55;       // inner radius / outer radius: the picked place shows through
  const SETTLE_MS = 120;          // occlusion is read when the view has not moved for this long

  window.glintOverlays = function (ctx) {
    const { THREE, scene, camera, renderer, positions, indices, byName, REPORT, $, el } = ctx;
    const radius = ctx.radius;
    const outline = new THREE.LineSegments(new THREE.BufferGeometry(),
                                           new THREE.LineBasicMaterial({ color: 0x101214 }));
    outline.renderOrder = 1;
    scene.add(outline);
    const labels = [];
    let segmentsByRegion = {};
    let zoom = 0;

    // ---- outlines ------------------------------------------------------------------------------
    function traceOutline(ids) {
      const out = [];
      const counts = {};
      const mid = (a, b) => [0, 1, 2].map((c) => 0.5 * (positions[3 * a + c] + positions[3 * b + c]));
      const count = (labelsOfTriangle, segments) => labelsOfTriangle.forEach((l) => {
        if (l > 0) counts[l] = (counts[l] || 0) + segments;
      });
      for (let t = 0; t < indices.length / 3; ++t) {
        const v = [indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]];
        const l = v.map((x) => Math.round(ids[x]));
        if (l[0] === l[1] && l[1] === l[2]) continue;
        const distinct = [...new Set(l)];
        if (distinct.length === 3) {
          const g = [0, 1, 2].map((c) => (positions[3 * v[0] + c] + positions[3 * v[1] + c] + positions[3 * v[2] + c]) / 3);
          [[0, 1], [1, 2], [2, 0]].forEach(([i, j]) => out.push(...mid(v[i], v[j]), ...g));
          count(distinct, 3);
          continue;
        }
        // two corners agree: the odd one's two edges change label
        const odd = l[0] === l[1] ? 2 : l[0] === l[2] ? 1 : 0;
        const others = [0, 1, 2].filter((i) => i !== odd);
        out.push(...mid(v[odd], v[others[0]]), ...mid(v[odd], v[others[1]]));
        count(distinct, 1);
      }
      return { points: new Float32Array(out), counts: counts };
    }

    // ---- labels --------------------------------------------------------------------------------
    // The region's vertex nearest its centroid: the label's place, on the surface.
    function anchorOf(ids, region) {
      const c = region.centroid;
      let best = -1, bestD = Infinity;
      for (let v = 0; v < ids.length; ++v) {
        if (Math.round(ids[v]) !== region.id) continue;
        const d = (positions[3 * v] - c[0]) ** 2 + (positions[3 * v + 1] - c[1]) ** 2 + (positions[3 * v + 2] - c[2]) ** 2;
        if (d < bestD) { bestD = d; best = v; }
      }
      return best < 0 ? new THREE.Vector3().fromArray(c) : new THREE.Vector3().fromArray(positions, 3 * best);
    }

    function setZoom(z) {
      zoom = z;
      const field = byName["region_id_z" + z];
      const ids = field ? field.data : new Float32Array(positions.length / 3);
      const traced = traceOutline(ids);
      outline.geometry.dispose();
      outline.geometry = new THREE.BufferGeometry();
      outline.geometry.setAttribute("position", new THREE.BufferAttribute(traced.points, 3));
      segmentsByRegion = traced.counts;
      const layer = $("region-labels");
      layer.innerHTML = "";
      labels.length = 0;
      ((REPORT.zooms[z] && REPORT.zooms[z].regions) || []).forEach((r) => {
        const div = el("div", { class: "region-label", "data-region": r.id }, String(r.id));
        layer.appendChild(div);
        labels.push({ id: r.id, anchor: anchorOf(ids, r), div: div, x: 0, y: 0, depth: 0, behind: false });
      });
      scheduleOcclusion();
    }

    // ---- marker --------------------------------------------------------------------------------
    const marker = new THREE.Group();
    const ringMaterial = (colour, opacity) => new THREE.MeshBasicMaterial({
      color: colour, transparent: true, opacity: opacity, depthTest: false, side: THREE.DoubleSide });
    marker.add(new THREE.Mesh(new THREE.RingBufferGeometry(MARKER_HOLE, 1.0, 48), ringMaterial(0xffe14d, 0.95)));
    marker.add(new THREE.Mesh(new THREE.RingBufferGeometry(1.0, 1.2, 48), ringMaterial(0x000000, 0.6)));
    marker.add(new THREE.Mesh(new THREE.RingBufferGeometry(MARKER_HOLE - 0.12, MARKER_HOLE, 48), ringMaterial(0x000000, 0.6)));
    marker.children.forEach((m) => { m.renderOrder = 10; });
    marker.visible = false;
    scene.add(marker);

    function viewHeightAt(point) {
      const distance = camera.position.distanceTo(point);
      return 2 * distance * Math.tan((camera.fov * Math.PI) / 360);
    }
    function placeMarker(point) {
      marker.userData.placed = true;
      marker.position.copy(point);
      marker.visible = true;
    }

    // ---- every frame ---------------------------------------------------------------------------
    function update() {
      camera.updateMatrixWorld();
      if (marker.visible) {
        marker.quaternion.copy(camera.quaternion);
        marker.scale.setScalar(MARKER_FRACTION * viewHeightAt(marker.position));
      }
      const w = renderer.domElement.clientWidth, h = renderer.domElement.clientHeight;
      labels.forEach((l) => {
        const p = l.anchor.clone().project(camera);
        const inside = p.z > -1 && p.z < 1 && Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1;
        l.x = ((p.x + 1) / 2) * w;
        l.y = ((1 - p.y) / 2) * h;
        l.div.style.left = l.x + "px";
        l.div.style.top = l.y + "px";
        l.div.classList.toggle("outside", !inside);
      });
      scheduleOcclusion();
    }

    // ---- occlusion: is the surface nearer than a label's point? ------------------------------
    const depthMaterial = new THREE.MeshDepthMaterial({ depthPacking: THREE.RGBADepthPacking, side: THREE.DoubleSide });
    const depthTarget = new THREE.WebGLRenderTarget(1, 1);
    let settleTimer = null;
    function scheduleOcclusion() {
      if (settleTimer) clearTimeout(settleTimer);
      settleTimer = setTimeout(() => { settleTimer = null; readOcclusion(); }, SETTLE_MS);
    }
    const viewDistance = (d) => (camera.near * camera.far) / (camera.far - d * (camera.far - camera.near));
    function readOcclusion() {
      if (!labels.length) return [];
      const size = renderer.getDrawingBufferSize(new THREE.Vector2());
      depthTarget.setSize(size.x, size.y);
      const shown = [outline.visible, marker.visible];
      outline.visible = false;
      marker.visible = false;
      // cleared to depth 1 (white packs to it): no surface there
      const background = scene.background, clear = renderer.getClearColor().clone(), alpha = renderer.getClearAlpha();
      scene.background = null;
      scene.overrideMaterial = depthMaterial;
      renderer.setClearColor(0xffffff, 1);
      renderer.setRenderTarget(depthTarget);
      renderer.render(scene, camera);
      renderer.setRenderTarget(null);
      renderer.setClearColor(clear, alpha);
      scene.overrideMaterial = null;
      scene.background = background;
      [outline.visible, marker.visible] = shown;
      const px = new Uint8Array(4), dpr = size.x / Math.max(1, renderer.domElement.clientWidth);
      // note: 2 % of the surface's radius: a grazing surface's depth changes within the pixel
      // by about that much; a hidden label sits at least a wall's thickness behind.
      const tolerance = 0.02 * radius;
      return labels.map((l) => {
        const x = Math.floor(l.x * dpr), y = size.y - 1 - Math.floor(l.y * dpr);
        if (x < 0 || y < 0 || x >= size.x || y >= size.y) return { id: l.id, behind: false, outside: true };
        renderer.readRenderTargetPixels(depthTarget, x, y, 1, 1, px);
        const packed = new THREE.Vector4(px[0], px[1], px[2], px[3]).divideScalar(255);
        // three.js' RGBA depth packing: depth = dot(rgba, (1/256³, 1/256², 1/256, 1)).
        const depth = packed.dot(new THREE.Vector4(1 / 16777216, 1 / 65536, 1 / 256, 1)) * (255 / 256);
        const surface = depth >= 0.9999 ? Infinity : viewDistance(depth);
        const own = -l.anchor.clone().applyMatrix4(camera.matrixWorldInverse).z;
        l.behind = surface < own - tolerance;
        l.div.classList.toggle("behind", l.behind);
        return { id: l.id, behind: l.behind, surface: surface, own: own };
      });
    }

    // Hidden while the self-test reads the surface's own colours.
    function setVisible(visible) {
      outline.visible = visible;
      marker.visible = visible && marker.userData.placed === true;
    }

    function markerState() {
      return { visible: marker.visible, world_radius: marker.scale.x, view_height: viewHeightAt(marker.position),
               hole_fraction: MARKER_HOLE, transparent: marker.children[0].material.transparent };
    }

    // ---- self-test ----------------------------------------------------------------------------
    // Every region has an outline and a label; a region's label is clear seen from the side the
    // region faces and dimmed from the opposite side (the surface between); the marker keeps its
    // size on screen when the camera moves twice as far, so its size in the world doubles.
    // env: { regions, center, facingOf(region), setCamera(target, position), render() }.
    function selftest(env) {
      const layer = $("region-labels");
      const perRegion = env.regions.map((r) => ({
        id: r.id, segments: segmentsByRegion[r.id] || 0,
        label: layer.querySelector('.region-label[data-region="' + r.id + '"]') !== null }));
      const out = { regions: perRegion, ok: perRegion.every((r) => r.segments >= 3 && r.label) };
      if (!env.regions.length) return out;
      const r = env.regions[0], label = labels.find((l) => l.id === r.id);
      const facing = env.facingOf(r), distance = 3 * radius;
      env.setCamera(label.anchor, label.anchor.clone().addScaledVector(facing, distance));
      env.render();
      const front = readOcclusion().find((o) => o.id === r.id);
      env.setCamera(env.center, env.center.clone().addScaledVector(facing, -distance));
      env.render();
      const back = readOcclusion().find((o) => o.id === r.id);
      out.occlusion = { region: r.id, front: front, back: back, ok: !front.behind && !front.outside && back.behind };
      env.setCamera(label.anchor, label.anchor.clone().addScaledVector(facing, distance));
      placeMarker(label.anchor);
      env.render();
      const near = Object.assign({ distance: camera.position.distanceTo(label.anchor) }, markerState());
      env.setCamera(label.anchor, label.anchor.clone().addScaledVector(facing, 2 * distance));
      env.render();
      const far = Object.assign({ distance: camera.position.distanceTo(label.anchor) }, markerState());
      const ratio = far.world_radius / near.world_radius, expected = far.distance / near.distance;
      out.marker = { near: near, far: far, ratio: ratio, expected: expected,
                     ok: Math.abs(ratio / expected - 1) < 1e-3 && Math.abs(near.world_radius / near.view_height - MARKER_FRACTION) < 1e-6 &&
                         near.hole_fraction >= 0.5 && near.transparent };
      out.ok = out.ok && out.occlusion.ok && out.marker.ok;
      return out;
    }

    return {
      selftest: selftest,
      setZoom: setZoom,
      update: update,
      placeMarker: placeMarker,
      setVisible: setVisible,
      readOcclusion: readOcclusion,
      // for the self-test
      outlineSegments: () => Object.assign({}, segmentsByRegion),
      labels: () => labels.map((l) => ({ id: l.id, x: l.x, y: l.y, behind: l.behind, anchor: l.anchor.toArray() })),
      marker: markerState,
      zoom: () => zoom,
    };
  };
})();
