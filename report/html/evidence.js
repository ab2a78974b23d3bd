// glint report page: the words around the atlas (report/report_html.h). The banner under the
// header (the verdict in one sentence, every warning of report.json by severity), the fit with
// its units, the floors per zoom, the run, atlas.png and the mosaics. report.js calls
// window.glintEvidence(ctx) once; ctx gives report.json (REPORT), the page's data (DATA), the
// length unit and the page's helpers ($, el, fmt).
(function () {
  "use strict";

  // How much a warning matters, by what it says (report.json keeps warnings as sentences):
  //   severe   the result cannot be read as it stands (no fit, no decision, surfaces swapped);
  //   info     how the run went, nothing to act on;
  //   caution  everything else: read the result with it in mind.
  const SEVERE = [/did not converge/, /no regions are reported/, /swapped\?/, /allowed by --allow-scale-mismatch/];
  const INFO = [/the evidence was read over a radius/, /back-face culling turned off/, /had no vertex normals/,
                /using Embree without starting Vulkan/];
  function severityOf(text) {
    if (SEVERE.some((p) => p.test(text))) return "severe";
    if (INFO.some((p) => p.test(text))) return "info";
    return "caution";
  }

  // Every warning report.json holds, once: the run's (the zooms' come prefixed "zoom k: ") and
  // the renderer's.
  function allWarnings(report) {
    const out = [];
    (report.warnings || []).forEach((w) => out.push(w));
    ((report.device && report.device.warnings) || []).forEach((w) => out.push("renderer: " + w));
    return out;
  }

  function plural(n, word) {
    if (word === "surface gone") return n + (n === 1 ? " surface gone" : " surfaces gone");
    return n + " " + word + (n === 1 ? "" : "s");
  }
  // A region's kind as the page says it: surface gone (a loss where the examined surface
  // covered around it, report.json surface_gone) apart from a dent.
  function kindOf(r) { return r.surface_gone ? "surface gone" : r.kind; }

  // "2 regions: 1 surface gone, 1 bump"; no region: why, in the words the rule left.
  function verdictOf(zoom) {
    const regions = zoom.regions || [];
    if (regions.length) {
      const kinds = [];
      regions.forEach((r) => { if (!kinds.includes(kindOf(r))) kinds.push(kindOf(r)); });
      const parts = kinds.map((k) => plural(regions.filter((r) => kindOf(r) === k).length, k));
      return { text: plural(regions.length, "region") + ": " + parts.join(", "), kind: "damage" };
    }
    const noScale = (zoom.warnings || []).some((w) => /no regions are reported/.test(w));
    if (noScale) return { text: "no regions: no quiet scale, see warnings", kind: "undecided" };
    return { text: "no damage found above the floors", kind: "clear" };
  }

  function buildBanner(ctx) {
    const { REPORT, $, el, fmt, UNIT } = ctx;
    const zooms = REPORT.zooms || [];
    const z0 = zooms[0] || { regions: [], warnings: [] };
    const verdict = verdictOf(z0);
    $("verdict").textContent = verdict.text;
    $("banner").className = verdict.kind;
    const detail = ["zoom 0" + (z0.footprint !== undefined ? " (" + fmt(z0.footprint) + " " + UNIT + " per pixel)" : "")];
    if (z0.coverage !== undefined) detail.push(fmt(100 * z0.coverage) + " % of the surface seen");
    zooms.slice(1).forEach((z, k) => detail.push("zoom " + (k + 1) + ": " + verdictOf(z).text));
    $("verdict-detail").textContent = detail.join(" · ");
    const list = $("warnings");
    allWarnings(REPORT).forEach((w) => list.appendChild(el("li", { class: severityOf(w) }, w)));
  }

  function kvTable(el, pairs) {
    const t = el("table", { class: "kv" });
    pairs.forEach(([k, v]) => { const tr = el("tr"); tr.appendChild(el("td", {}, k)); tr.appendChild(el("td", {}, v)); t.appendChild(tr); });
    return t;
  }
  function jsonDetails(el, summary, obj) {
    const d = el("details");
    d.appendChild(el("summary", {}, summary));
    d.appendChild(el("pre", { class: "json" }, JSON.stringify(obj, null, 2)));
    return d;
  }

  // How the examined surface was placed on the reference, in words a reader checks by eye.
  const FIT_MODES = { register: "register: fitted here (robust ICP)", file: "given: read from a fit file",
                      identity: "identity: taken as already aligned", truth: "given: the scenario's known transform" };
  function fitRows(ctx) {
    const { REPORT, fmt, UNIT } = ctx;
    const fit = REPORT.fit, rows = [];
    const mode = (REPORT.analysis && REPORT.analysis.registration && REPORT.analysis.registration.mode) || fit.mode;
    rows.push(["mode", FIT_MODES[mode] || String(mode)]);
    if (fit.reference_from_examined) rows.push(["moves", "the examined surface onto the reference (reference_from_examined)"]);
    if (fit.path) rows.push(["fit file", fit.path]);
    if (fit.rotation_deg !== undefined)
      rows.push(["rotation", fmt(fit.rotation_deg, 4) + " ° about (" + fit.rotation_axis.map((x) => fmt(x, 3)).join(", ") + ")"]);
    if (fit.translation) {
      const t = fit.translation, length = Math.hypot(t[0], t[1], t[2]);
      rows.push(["translation", "(" + t.map((x) => fmt(x, 4)).join(", ") + ") " + UNIT + ", length " + fmt(length, 4) + " " + UNIT]);
    }
    if (fit.rms !== undefined) rows.push(["RMS distance", fmt(fit.rms, 4) + " " + UNIT]);
    if (fit.iterations !== undefined) rows.push(["iterations", String(fit.iterations)]);
    if (fit.converged !== undefined)
      rows.push(["converged", (fit.converged ? "yes" : "no") + (fit.termination ? " (" + fit.termination + ")" : "")]);
    if (fit.inlier_fraction !== undefined) rows.push(["inliers", fmt(100 * fit.inlier_fraction) + " % of the samples"]);
    if (fit.overlap !== undefined) rows.push(["overlap", fmt(100 * fit.overlap) + " % of the samples"]);
    if (fit.note) rows.push(["note", fit.note]);
    return rows;
  }

  function floorText(fmt, f, unit) {
    if (!f) return "—";
    return fmt(f.value, 4) + " " + unit + (f.given ? " (given)" : "") + " — " + f.rule + (f.note ? " — " + f.note : "");
  }

  function buildFloors(ctx) {
    const { REPORT, DATA, $, el, fmt, UNIT } = ctx;
    const floors = $("floors"), mu = REPORT.metric.unit;
    REPORT.zooms.forEach((z, k) => {
      floors.appendChild(el("h3", {}, "zoom " + k + ": footprint " + fmt(z.footprint) + " " + UNIT + " per pixel"));
      floors.appendChild(kvTable(el, [
        ["rule", z.rule_text],
        ["normal floor", floorText(fmt, z.normal_floor, mu)],
        ["shape floor", z.shape_floor ? floorText(fmt, z.shape_floor, UNIT) : "— (normal rule)"],
        ["coverage", fmt(100 * z.coverage) + " % of the surface seen; unseen " + fmt(z.unseen.area) + " " + UNIT + "² in " +
          z.unseen.patches + " patch(es)"],
        ["regions", z.regions.length + " (" + z.damaged_vertices + " damaged vertices, " + z.dropped_small_groups +
          " small group(s) dropped)"],
        ["colour range of the pictures", "±" + fmt(DATA.shape_scale.limit) + " " + UNIT + " (" + DATA.shape_scale.source + ")"],
      ]));
    });
  }

  function buildFitAndRun(ctx) {
    const { REPORT, $, el, fmt } = ctx;
    const fit = $("fit");
    if (!REPORT.fit) fit.textContent = "no fit recorded";
    else {
      const table = kvTable(el, fitRows(ctx));
      table.id = "fit-table";
      fit.appendChild(table);
      fit.appendChild(jsonDetails(el, "the fit as report.json holds it (with the options that reproduce it)", REPORT.fit));
    }
    $("run").appendChild(kvTable(el, [
      ["units", REPORT.units.note],
      ["metric", REPORT.metric.description],
      ["device", REPORT.device.name + " (" + REPORT.device.backend + ")"],
      ["command", REPORT.command_line || "—"],
      ["total time", fmt(REPORT.timings_s.total) + " s"],
    ].concat(REPORT.inputs.map((i) => [i.role, (i.path || i.description || "") + (i.sha256 ? "  sha256 " + i.sha256 : "")]))));
    $("run").appendChild(el("p", { class: "note" }, "Warnings: in the banner at the top of the page."));
    $("run").appendChild(jsonDetails(el, "report.json", REPORT));
  }

  function buildPictures(ctx) {
    const { DATA, $, el } = ctx;
    const atlas = $("atlas-picture");
    if (DATA.images.atlas) atlas.src = DATA.images.atlas;
    else $("atlas-panel").hidden = true;
    // A run with --no-pictures drew none: the panels say so instead of standing empty.
    if (!DATA.images.mosaics.length) {
      $("mosaics").appendChild(el("p", { class: "note" },
        "No pictures: this run was made with --no-pictures (exports.pictures = false)."));
    }
    DATA.images.mosaics.forEach((uri, k) => {
      $("mosaics").appendChild(el("h3", {}, "zoom " + k));
      $("mosaics").appendChild(el("img", { src: uri, alt: "mosaic of zoom " + k }));
    });
  }

  window.glintEvidence = function (ctx) {
    buildBanner(ctx);
    buildFloors(ctx);
    buildFitAndRun(ctx);
    buildPictures(ctx);
    return { severityOf: severityOf, verdictOf: verdictOf, allWarnings: allWarnings };
  };
})();
