#include "scenario/scenario.h"

#include "mesh/winding.h"
#include "scenario/pose_conf.h"

#include "mesh/error.h"
#include "mesh/input_path.h"
#include "mesh/io.h"
#include "mesh/remesh.h"
#include "mesh/small_file.h"
#include "scenario/detail/ct_acquisition.h"
#include "scenario/detail/partial_scan.h"
#include "scenario/detail/scenario_options.h"
#include "scenario/detail/toml_reader.h"
#include "scenario/pair_truth.h"
#include "volume/acquisition.h"
#include "volume/load.h"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

namespace glint {

namespace fs = std::filesystem;
using detail::read_analysis_sections;
using detail::TableReader;
using detail::validate_analysis_sections;

namespace {

Vec3d vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

fs::path resolve_mesh(TableReader& r, const std::string& key, const std::string& text,
                      const fs::path& scenario_dir, const fs::path& data_root, bool& needs_root) {
    const fs::path p(text);
    if (p.is_absolute()) return p;
    const fs::path local = scenario_dir / p;
    // A path that exists, or that this user may not reach, is the scenario's own: a data
    // root is tried only for what is missing beside the scenario.
    if (check_path(local).reach != PathReach::Missing) return local;
    if (!data_root.empty()) {
        needs_root = true;
        return data_root / p;
    }
    needs_root = true;
    (void)r;
    (void)key;
    return local;
}

// The surface keys of a [reference] / [examined] volume (volume/surface.h).
void read_surface_options(TableReader& r, SurfaceOptions& o) {
    if (auto v = r.optional<double>("iso", "a number (the volume's units)")) o.iso = *v;
    if (auto v = r.optional<std::string>(
            "surface_roi", "a string (sphere:x,y,z,r or box:x0,y0,z0,x1,y1,z1, mm)")) {
        try {
            o.roi = parse_roi(*v);
        } catch (const InputError& e) {
            r.fail(r.get("surface_roi"), "surface_roi", e.what());
        }
    }
    if (auto v = r.optional<bool>("largest", "a boolean")) o.largest = *v;
    if (auto v = r.numbers("surface_seed", 3, 3)) o.seed = vec3(*v);
    if (auto v = r.integer("smooth", 0, 100000)) o.smooth_iterations = static_cast<int>(*v);
    if (auto v = r.optional<double>("passband", "a number in (0, 2)")) o.passband = *v;
    if (auto v = r.optional<double>("edge", "a number (mm)")) o.edge_mm = *v;
    if (auto v = r.optional<double>("tolerance", "a number (mm)")) o.tolerance_mm = *v;
    if (!o.iso && !o.any()) return;
    try {
        if (o.iso) o.validate();
    } catch (const OptionError& e) {
        r.fail(r.get(e.key()), e.key(), e.what());
    }
}

SurfaceSource read_surface(TableReader& r, const fs::path& scenario_dir, const fs::path& data_root,
                           bool required) {
    SurfaceSource s;
    const auto phantom =
        r.optional<std::string>("phantom", "a string (sphere, ellipsoid, torus, condyle)");
    const auto mesh = r.optional<std::string>("mesh", "a string (a mesh or volume file path)");
    if (phantom && mesh) r.fail(r.get("mesh"), "mesh", "give either phantom or mesh, not both");
    if (mesh) {
        s.mesh_as_written = *mesh;
        s.mesh = resolve_mesh(r, "mesh", *mesh, scenario_dir, data_root, s.needs_data_root);
    }
    read_surface_options(r, s.surface);
    if (required) {
        if (auto v = r.optional<bool>("scan_as_ct", "true or false")) s.scan_as_ct = *v;
        if (s.scan_as_ct && mesh && is_volume_path(s.mesh))
            r.fail(r.get("scan_as_ct"), "scan_as_ct",
                   "scans a mesh or phantom as CT; \"" + *mesh + "\" is a volume already");
        if (auto v = r.numbers("ct_values", 2, 2)) {
            if (!s.scan_as_ct) r.fail(r.get("ct_values"), "ct_values", "needs scan_as_ct = true");
            if (!std::isfinite((*v)[0]) || !std::isfinite((*v)[1]) || (*v)[0] == (*v)[1])
                r.fail(r.get("ct_values"), "ct_values",
                       "expected [outside, inside]: two different finite values");
            s.ct_background = static_cast<float>((*v)[0]);
            s.ct_object = static_cast<float>((*v)[1]);
        }
        // The surface is cut from the scan at the middle of the two values unless iso is given.
        if (s.scan_as_ct && !s.surface.iso) s.surface.iso = 0.5 * (s.ct_background + s.ct_object);
    } else if (r.get("scan_as_ct") || r.get("ct_values")) {
        r.fail(r.get(r.get("scan_as_ct") ? "scan_as_ct" : "ct_values"),
               r.get("scan_as_ct") ? "scan_as_ct" : "ct_values",
               "belongs in [reference]: both scans image the reference's solid");
    }
    s.cut = detail::read_scan_cut(r);
    if (required) s.crop_ball = detail::read_crop_ball(r);
    else if (r.get("crop_ball"))
        r.fail(r.get("crop_ball"), "crop_ball",
               "crops the reference ([reference] crop_ball); an examined scan is cut with "
               "keep_side");
    // A derived examined scan (no mesh of its own) may take its own field of view: surface_roi.
    SurfaceOptions others = s.surface;
    if (!required) others.roi.reset();
    if ((others.iso || others.any()) && !mesh && !s.scan_as_ct)
        r.fail(r.get(s.surface.iso ? "iso" : "largest"), s.surface.iso ? "iso" : "largest",
               "surface keys need a volume file: mesh = \"scan.nii.gz\"");
    const auto scheme = r.optional<std::string>("scheme", "a string (uv or ico)");
    const auto resolution = r.integer("resolution", 0, 1 << 20);
    const auto size = r.numbers("size", 1, 3);
    if (phantom || scheme || resolution || size) {
        if (mesh)
            r.fail(r.get("mesh"), "mesh",
                   "a mesh file takes no phantom keys (scheme, resolution, size)");
        PhantomOptions o;
        try {
            if (phantom) o.kind = parse_phantom_kind(*phantom);
            if (scheme) o.scheme = parse_scheme(*scheme);
        } catch (const InputError& e) {
            r.fail(r.get(phantom ? "phantom" : "scheme"), phantom ? "phantom" : "scheme", e.what());
        }
        if (resolution) o.resolution = static_cast<int>(*resolution);
        if (size) {
            if (size->size() == 2)
                r.fail(r.get("size"), "size", "expected 1 or 3 numbers, found 2");
            o.radii = size->size() == 1 ? Vec3d::Constant((*size)[0]) : vec3(*size);
            if ((o.radii.array() <= 0).any())
                r.fail(r.get("size"), "size", "every size must be > 0");
        }
        if (!phantom && required)
            r.fail(nullptr, "phantom", "missing: give phantom = \"…\" or mesh = \"…\"");
        s.phantom = o;
    }
    if (required && !s.phantom && s.mesh.empty())
        r.fail(nullptr, "phantom", "missing: give phantom = \"…\" or mesh = \"…\"");
    return s;
}

DamageSpec read_damage(TableReader& r) {
    DamageSpec d;
    const auto kind = r.optional<std::string>("kind", "a string");
    if (!kind) r.fail(nullptr, "kind", "missing: dent, bump, pit, groove, flatten, erosion");
    try {
        // Reuse the spec parser for the kind name so both spellings stay in one place.
        d = parse_damage_spec(*kind);
    } catch (const InputError& e) {
        r.fail(r.get("kind"), "kind", e.what());
    }
    if (auto c = r.numbers("center", 3, 3)) d.center = vec3(*c);
    if (auto v = r.positive("radius")) d.radius = *v;
    if (auto v = r.positive("depth")) d.depth = *v;
    if (auto v = r.positive("sigma")) d.sigma = *v;
    if (auto v = r.integer("seed", 0, 4294967295)) d.seed = static_cast<std::uint32_t>(*v);
    if (auto n = r.numbers("normal", 3, 3)) d.plane_normal = vec3(*n);
    if (const toml::node* p = r.get("path")) {
        const auto* arr = p->as_array();
        if (!arr) r.fail(p, "path", "expected an array of [x, y, z] points");
        for (const auto& e : *arr) {
            const auto* pt = e.as_array();
            if (!pt || pt->size() != 3) r.fail(p, "path", "expected an array of [x, y, z] points");
            Vec3d q;
            for (std::size_t i = 0; i < 3; ++i) {
                auto v = (*pt)[i].value<double>();
                if (!v) r.fail(p, "path", "expected numbers in each point");
                q[static_cast<Eigen::Index>(i)] = *v;
            }
            d.path.push_back(q);
        }
    }
    r.finish();
    return d;
}

// [examined] pivot / erode / erode_to: a longitudinal pair resampled from a volume reference.
void read_volume_edit(TableReader& r, Scenario& sc) {
    if (auto v = r.numbers("pivot", 3, 3)) sc.pivot = vec3(*v);
    const auto erode = r.numbers("erode", 4, 4);
    const auto erode_to = r.optional<double>("erode_to", "a number (the volume's units)");
    if (erode) {
        if (!((*erode)[3] > 0)) r.fail(r.get("erode"), "erode", "radius (4th number) must be > 0");
        sc.erosions.push_back({Vec3d((*erode)[0], (*erode)[1], (*erode)[2]), (*erode)[3],
                               static_cast<float>(erode_to.value_or(0.0))});
    }
    if (erode_to && !erode) r.fail(r.get("erode_to"), "erode_to", "needs erode = [x, y, z, r]");
    sc.resample_volume =
        erode || r.has("pivot") || sc.examined.acquisition.any() || sc.reference.acquisition.any();
    const bool volume_reference = sc.reference.scan_as_ct ||
                                  (!sc.reference.mesh.empty() && is_volume_path(sc.reference.mesh));
    if ((erode || r.has("pivot")) && !volume_reference)
        r.fail(r.get(erode ? "erode" : "pivot"), erode ? "erode" : "pivot",
               "needs a volume reference (mesh = \"scan.nii.gz\") or scan_as_ct = true");
}

// [examined] truth_pose_conf / truth_pose_entry: a scan's ground-truth pose from a Stanford
// .conf file (scenario/pose_conf.h); it replaces pose as the truth the fit is scored against.
void read_conf_truth(TableReader& r, const fs::path& dir, const fs::path& data_root, Scenario& sc) {
    const auto conf = r.optional<std::string>("truth_pose_conf", "a string (a .conf file)");
    const auto entry = r.optional<std::string>("truth_pose_entry", "a string (a scan's name)");
    if (!conf && !entry) return;
    if (!conf || !entry)
        r.fail(r.get(conf ? "truth_pose_conf" : "truth_pose_entry"),
               conf ? "truth_pose_conf" : "truth_pose_entry",
               "needs both truth_pose_conf and truth_pose_entry");
    if (r.has("pose")) r.fail(r.get("pose"), "pose", "give pose or truth_pose_conf, not both");
    sc.truth_pose_conf = resolve_mesh(r, "truth_pose_conf", *conf, dir, data_root,
                                      sc.truth_pose_conf_needs_data_root);
    sc.truth_pose_entry = *entry;
    std::error_code ec;  // a missing file is reported with the data, as a mesh is
    if (fs::exists(sc.truth_pose_conf, ec))  // examined = pose · reference
        sc.pose = read_conf_pose(sc.truth_pose_conf, *entry).inverse();
}

Rigid read_pose(TableReader& r) {
    const toml::node* node = r.get("pose");
    if (!node) return Rigid::Identity();
    try {
        if (auto s = node->value<std::string>()) return parse_pose_spec(*s);
        if (const auto* arr = node->as_array()) {
            std::ostringstream text;
            for (std::size_t i = 0; i < arr->size(); ++i) {
                auto v = (*arr)[i].value<double>();
                if (!v) r.fail(node, "pose", "expected 6 numbers [rx, ry, rz, tx, ty, tz]");
                text << (i ? "," : "") << *v;
            }
            return parse_pose_spec(text.str());
        }
    } catch (const InputError& e) {
        r.fail(node, "pose", e.what());
    }
    r.fail(node, "pose",
           "expected [rx, ry, rz, tx, ty, tz] (degrees, mesh units) or a pose string");
}

void read_examined(TableReader& r, const fs::path& dir, const fs::path& data_root, Scenario& sc) {
    sc.examined = read_surface(r, dir, data_root, false);
    sc.examined_derived = sc.examined.mesh.empty();
    sc.pose = read_pose(r);
    if (auto v = r.optional<double>("noise", "a number (σ, mesh units)")) {
        if (!(*v >= 0)) r.fail(r.get("noise"), "noise", "must be ≥ 0");
        sc.noise_sigma = *v;
    }
    if (auto v = r.integer("noise_seed", 0, 4294967295))
        sc.noise_seed = static_cast<std::uint32_t>(*v);
    if (auto m = r.optional<std::string>("truth_mask", "a string (a .npy file)")) {
        bool needs = false;
        sc.truth_mask = resolve_mesh(r, "truth_mask", *m, dir, data_root, needs);
    }
    read_conf_truth(r, dir, data_root, sc);
    sc.examined.acquisition = detail::read_acquisition(
        r,
        sc.reference.scan_as_ct ||
            (!sc.reference.mesh.empty() && is_volume_path(sc.reference.mesh)),
        sc.reference.scan_as_ct ? &sc.reference.acquisition : nullptr);
    read_volume_edit(r, sc);
    if (sc.reference.crop_ball && (!sc.examined_derived || sc.resample_volume))
        throw InputError("scenario \"" + sc.file.string() +
                         "\": [reference] crop_ball crops the reference after the examined "
                         "surface was derived from the whole mesh; expected an examined surface "
                         "derived from a reference mesh (no examined mesh, no volume edit)");
    if (sc.examined.cut && !sc.examined_derived)
        r.fail(r.get("keep_side"), "keep_side",
               "cuts an examined surface derived from the reference");
    if (sc.noise_sigma > 0 && sc.resample_volume)
        r.fail(r.get("noise"), "noise",
               "a resampled examined volume (pivot, erode) takes no mesh noise");
    sc.remesh = r.positive("remesh");
    if (auto v = r.integer("remesh_iterations", 1, 100000)) {
        if (*v < 1) r.fail(r.get("remesh_iterations"), "remesh_iterations", "must be ≥ 1");
        sc.remesh_iterations = static_cast<int>(*v);
    }
    if (auto v = r.optional<bool>("shuffle", "true or false")) sc.shuffle = *v;
    if (auto v = r.optional<bool>("reverse_winding", "true or false")) sc.reverse_winding = *v;
    if (sc.reverse_winding && !sc.examined_derived)
        r.fail(r.get("reverse_winding"), "reverse_winding",
               "turns an examined surface derived from the reference");
    if (auto v = r.positive("scale")) {
        if (!sc.examined_derived)
            r.fail(r.get("scale"), "scale",
                   "scales an examined surface derived from the reference");
        sc.examined_scale = *v;
    }
    if (auto v = r.optional<bool>("as_mesh_files", "true or false")) sc.as_mesh_files = *v;
    if (sc.as_mesh_files && !sc.resample_volume && !sc.reference.acquisition.any())
        r.fail(r.get("as_mesh_files"), "as_mesh_files",
               "hands on the surfaces of a volume pair (a volume reference with pose, erode, "
               "voxel_size or volume_noise) as mesh files");
    if (auto v = r.integer("seed", 0, 4294967295)) sc.shuffle_seed = static_cast<std::uint32_t>(*v);
    if ((sc.remesh || sc.shuffle) && (!sc.examined_derived || sc.reference.phantom))
        r.fail(r.get(sc.remesh ? "remesh" : "shuffle"), sc.remesh ? "remesh" : "shuffle",
               "re-meshing and shuffling derive the examined surface from a reference mesh file");
    if (sc.examined.phantom && sc.reference.phantom) {
        // Re-tessellation of the reference phantom: same shape, other scheme/resolution.
        PhantomOptions o = *sc.reference.phantom;
        const auto& e = *sc.examined.phantom;
        if (r.has("phantom") && e.kind != o.kind)
            r.fail(r.get("phantom"), "phantom",
                   "an examined phantom must be the reference's shape (re-tessellation)");
        o.scheme = r.has("scheme") ? e.scheme : o.scheme;
        o.resolution = r.has("resolution") ? e.resolution : o.resolution;
        o.radii = r.has("size") ? e.radii : o.radii;
        sc.examined.phantom = o;
    } else if (sc.examined.phantom && !sc.reference.phantom) {
        r.fail(nullptr, "scheme", "re-tessellation needs a phantom reference");
    }
    r.finish();
}

void read_expect(TableReader& r, ScenarioExpect& x) {
    auto e = [&](const char* key, std::optional<double>& out) {
        out = r.optional<double>(key, "a number");
    };
    auto count = [&](const char* key, std::optional<std::size_t>& out) {
        if (auto v = r.optional<std::int64_t>(key, "an integer ≥ 0")) {
            if (*v < 0) r.fail(r.get(key), key, "must be ≥ 0");
            out = static_cast<std::size_t>(*v);
        }
    };
    count("regions", x.regions);
    count("min_regions", x.min_regions);
    count("max_regions", x.max_regions);
    count("max_false_regions", x.max_false_regions);
    count("max_close_region_vertices", x.max_close_region_vertices);
    e("min_iou", x.min_iou);
    e("min_f1", x.min_f1);
    e("min_precision", x.min_precision);
    e("min_recall", x.min_recall);
    e("max_rotation_error_deg", x.max_rotation_error_deg);
    e("max_translation_error", x.max_translation_error);
    e("max_scale_error", x.max_scale_error);
    if (auto v = r.optional<std::string>("warning", "a string (text a warning contains)"))
        x.warning = *v;
    e("max_centroid_error", x.max_centroid_error);
    e("min_coverage", x.min_coverage);
    e("min_region_shape_change", x.min_region_shape_change);
    if (auto v = r.positive("region_min_true_distance")) x.region_min_true_distance = *v;
    if (auto v = r.optional<bool>("all_damages_detected", "true or false"))
        x.all_damages_detected = *v;
    for (const char* key : {"kind", "every_kind"})
        if (auto v = r.optional<std::string>(key, "a string (dent, bump or missing surface)")) {
            if (*v != "dent" && *v != "bump" && *v != "missing surface")
                r.fail(r.get(key), key, "expected dent, bump or missing surface");
            (std::string(key) == "kind" ? x.kind : x.every_kind) = *v;
        }
    if (auto v = r.optional<std::string>(
            "first_kind", "a string (surface gone, dent, bump or missing surface)")) {
        if (*v != "surface gone" && *v != "dent" && *v != "bump" && *v != "missing surface")
            r.fail(r.get("first_kind"), "first_kind",
                   "expected surface gone, dent, bump or missing surface");
        x.first_kind = *v;
    }
    e("min_first_area", x.min_first_area);
    e("max_first_area", x.max_first_area);
    e("min_first_volume_lost", x.min_first_volume_lost);
    e("max_p_value", x.max_p_value);
    if (x.max_p_value && !(*x.max_p_value > 0 && *x.max_p_value <= 1))
        r.fail(r.get("max_p_value"), "max_p_value", "expected a probability in (0, 1]");
    e("min_compared", x.min_compared);
    e("max_compared", x.max_compared);
    read_asymmetry_expect(r, x.asymmetry);
    r.finish();
}

// The scenario file parsed as TOML; a missing file, a folder or a syntax error named.
toml::table parse_scenario_file(const fs::path& file) {
    std::error_code ec;
    if (!reachable_input(file, "scenario \"" + file.string() + "\""))
        throw IoError("scenario \"" + file.string() + "\": no such file");
    if (fs::is_directory(file, ec))
        throw IoError("scenario \"" + file.string() + "\" is a directory, expected a .toml file");
    toml::table root;
    try {
        root = toml::parse(read_small_file(file, "scenario", std::size_t{1} << 20), file.string());
    } catch (const toml::parse_error& e) {
        std::ostringstream s;
        s << "scenario \"" << file.string() << "\" line " << e.source().begin.line << ": "
          << e.description();
        throw InputError(s.str());
    }
    return root;
}

// name (a plain folder name under -o), description and tags.
void read_identity(TableReader& top, const fs::path& file, Scenario& sc) {
    sc.name = top.optional<std::string>("name", "a string").value_or(file.stem().string());
    // The name is a folder under -o: a plain name, so a scenario never writes elsewhere.
    if (sc.name.empty() || sc.name == "." || sc.name == ".." ||
        sc.name.find_first_of(std::string("/\\\0", 3)) != std::string::npos) {
        // note: a NUL is shown as \x00: an error's what() is a C string, cut at the first NUL
        // (issue 52: a name "a\u0000b" gave the message `name: "a`).
        std::string shown;
        for (const char c : sc.name) shown += c == '\0' ? std::string("\\x00") : std::string(1, c);
        top.fail(
            top.get("name"), "name",
            "\"" + shown +
                "\": expected a plain folder name (not empty, no \"/\" or \"\\\", not \".\" or "
                "\"..\")");
    }
    sc.description = top.optional<std::string>("description", "a string").value_or("");
    if (const toml::node* tags = top.get("tags")) {
        const auto* arr = tags->as_array();
        if (!arr) top.fail(tags, "tags", "expected an array of strings");
        for (const auto& t : *arr) {
            auto s = t.value<std::string>();
            if (!s) top.fail(tags, "tags", "expected an array of strings");
            sc.tags.push_back(*s);
        }
    }
}

// [[damage]] tables: only on a derived examined surface, not on a resampled volume.
void read_damages(TableReader& top, const std::string& name, Scenario& sc) {
    const toml::node* dmg = top.get("damage");
    if (dmg == nullptr) return;
    const auto* arr = dmg->as_array();
    if (!arr || !arr->is_array_of_tables()) top.fail(dmg, "damage", "expected [[damage]] tables");
    for (std::size_t i = 0; i < arr->size(); ++i) {
        TableReader r(*(*arr)[i].as_table(), name, "damage[" + std::to_string(i) + "]");
        sc.damages.push_back(read_damage(r));
    }
    if (!sc.examined_derived)
        top.fail(dmg, "damage",
                 "damage applies to a derived examined surface, not to an examined mesh file");
    if (sc.resample_volume)
        top.fail(
            dmg, "damage",
            "a resampled examined volume takes erode = [x, y, z, r] in [examined], not [[damage]]");
}

}  // namespace

Scenario load_scenario(const fs::path& file, const fs::path& data_root) {
    const toml::table root = parse_scenario_file(file);
    Scenario sc;
    sc.file = file;
    const fs::path dir = file.parent_path();
    const std::string name = file.string();
    TableReader top(root, name, "");

    read_identity(top, file, sc);

    auto table = [&](const std::string& key, bool required) -> const toml::table* {
        const toml::node* node = top.get(key);
        if (!node) {
            if (required) top.fail(nullptr, key, "missing section [" + key + "]");
            return nullptr;
        }
        const auto* t = node->as_table();
        if (!t)
            top.fail(node, key,
                     "expected a section [" + key + "], found " + TableReader::type_name(*node));
        return t;
    };

    {
        TableReader r(*table("reference", true), name, "reference");
        sc.reference = read_surface(r, dir, data_root, true);
        sc.reference.acquisition = detail::read_acquisition(
            r, sc.reference.scan_as_ct ||
                   (!sc.reference.mesh.empty() && is_volume_path(sc.reference.mesh)));
        if (sc.reference.scan_as_ct && !sc.reference.acquisition.voxel_size)
            r.fail(r.get("scan_as_ct"), "scan_as_ct",
                   "needs voxel_size = [x, y, z] (mm), the scan's voxels");
        r.finish();
    }
    if (const auto* t = table("examined", false)) {
        TableReader r(*t, name, "examined");
        read_examined(r, dir, data_root, sc);
    } else if (sc.reference.scan_as_ct) {
        sc.examined.acquisition = detail::inherited(sc.reference.acquisition);
        sc.resample_volume = true;
    }
    if (sc.reference.scan_as_ct && !sc.examined_derived)
        throw InputError("scenario \"" + sc.file.string() +
                         "\": [reference] scan_as_ct makes both scans from the reference's solid; "
                         "expected no examined mesh of its own");
    read_damages(top, name, sc);
    read_analysis_sections(top, dir, sc.analysis);
    detail::read_export_section(top, dir, sc.exports);
    if (const auto* t = table("expect", false)) {
        TableReader r(*t, name, "expect");
        read_expect(r, sc.expect);
    }
    if (const auto* t = table("baseline", false)) {
        TableReader r(*t, name, "baseline");
        sc.baseline_distance = r.positive("distance_threshold");
        r.finish();
    }
    read_asymmetry_scenario(top, sc);
    top.finish();
    validate_analysis_sections(root, name, sc.analysis);
    return sc;
}

namespace {

// The derived examined surface: the reference (or its re-tessellated phantom, or its CGAL
// remesh), damaged, then noise, then the pose. Truth on the reference, by the distance rule
// (scenario/pair_truth.h) for mesh files, by the displacement rule for phantoms.
void derive_examined(const Scenario& sc, ScenarioMeshes& out) {
    const bool from_file = !sc.reference.phantom;
    if (sc.examined.phantom) {
        out.examined = make_phantom(*sc.examined.phantom);
    } else if (sc.remesh) {
        const EdgeStats edges = edge_stats(out.reference);
        out.examined =
            remesh_isotropic(out.reference, {*sc.remesh * edges.median, sc.remesh_iterations});
        std::ostringstream note;
        note << "examined: reference remeshed at " << *sc.remesh << "× its median edge ("
             << edges.median << " → " << edge_stats(out.examined).median << "), "
             << out.examined.vertex_count() << " vertices";
        out.notes.push_back(note.str());
    } else {
        out.examined = out.reference;
    }
    if (sc.shuffle) shuffle_mesh(out.examined, sc.shuffle_seed);
    if (!sc.damages.empty()) apply_damage(out.examined, sc.damages);
    if (from_file) {
        // The damaged surface before noise and motion is what the truth is measured against.
        Mesh footprint = out.reference;
        if (!sc.damages.empty()) apply_damage(footprint, sc.damages);
        const std::vector<std::int32_t> labels =
            footprint.labels.empty() ? std::vector<std::int32_t>(out.reference.vertex_count(), 0)
                                     : footprint.labels;
        PairTruth truth = distance_truth(out.reference, out.examined, labels, sc.damages);
        out.truth = std::move(truth.damaged);
        out.truth_damage = std::move(truth.damage_id);
        out.true_distance = vertex_distances(out.reference, out.examined);
    } else if (!sc.damages.empty()) {
        Mesh truth_mesh = out.reference;
        apply_damage(truth_mesh, sc.damages);
        out.truth.resize(truth_mesh.vertex_count());
        for (std::size_t v = 0; v < out.truth.size(); ++v) out.truth[v] = truth_mesh.labels[v] != 0;
        out.truth_damage = truth_mesh.labels;
    } else {
        out.truth.assign(out.reference.vertex_count(), 0);
    }
    if (sc.examined.cut)  // the truth stays that of the whole surface
        out.notes.push_back(detail::cut_scan(out.examined, *sc.examined.cut, "examined"));
    if (sc.noise_sigma > 0) {
        DamageSpec noise;
        noise.kind = DamageKind::Noise;
        noise.sigma = sc.noise_sigma;
        noise.seed = sc.noise_seed;
        apply_damage(out.examined, {noise});  // labels and gt_displacement of the damages are kept
    }
    if (sc.reverse_winding) {
        // As some STL exporters write a surface: every triangle wound the other way, the same
        // geometry inside out (issue 53).
        reverse_winding(out.examined);
        out.notes.push_back("examined: every triangle's winding reversed (inside out)");
    }
    transform_mesh(out.examined, sc.pose);
    // Scaled after the pose: examined = k·pose(x) ⇒ reference x = pose⁻¹((1/k)·examined), the
    // form of a fitted similarity (the rigid motion after a scale about the origin).
    if (sc.examined_scale != 1.0) {
        for (auto& p : out.examined.positions) p *= static_cast<float>(sc.examined_scale);
        out.true_examined_scale = 1.0 / sc.examined_scale;
        char note[120];
        std::snprintf(note, sizeof note, "examined: scaled by %g about the origin after the pose",
                      sc.examined_scale);
        out.notes.emplace_back(note);
    }
    out.true_reference_from_examined = sc.pose.inverse();
    out.has_truth_pose = true;
}

// A longitudinal pair from one volume: the reference's surface, and the surface of the volume
// resampled under the known motion with the erosions; truth = reference vertices inside a ball.
ScenarioMeshes build_volume_pair(const Scenario& sc) {
    ScenarioMeshes out;
    if (!sc.reference.surface.iso)
        throw InputError("scenario \"" + sc.file.string() + "\": reference volume \"" +
                         sc.reference.mesh_as_written + "\" needs iso = VALUE in [reference]");
    VolumeEdit edit;
    edit.moved_from_original = motion_about(sc.pose, sc.pivot);
    edit.erosions = sc.erosions;
    // Each scan from the noiseless object (a volume, or a solid scanned as CT), with its own
    // noise, blur and voxel size.
    // The examined scan is cut as the reference was, or to its own field of view (its
    // surface_roi, in its own frame: where that scanner saw).
    SurfaceOptions examined_surface = sc.reference.surface;
    if (sc.examined.surface.roi) examined_surface.roi = sc.examined.surface.roi;
    // The truth of an erosion comes from the same two scans without their noise (erosion_truth):
    // what the scanners would show of it, blur and partial volume included. Each scan is made
    // noiseless, its noise added after (apply_scanner adds it last: the same values).
    Mesh quiet_reference, quiet_examined;
    double coarsest = 0.0;
    const auto add_noise = [](Volume& v, const Acquisition& a) {
        if (a.noise > 0) apply_scanner(v, {0.0, a.noise, a.noise_correlation, a.noise_seed});
    };
    const auto scan_pair = [&](const auto& scan) {
        Volume r = scan(VolumeEdit{}, sc.reference.acquisition);
        Volume e = scan(edit, sc.examined.acquisition);
        if (!sc.erosions.empty()) {
            quiet_reference = extract_surface(r, sc.reference.surface).mesh;
            quiet_examined = extract_surface(e, examined_surface).mesh;
            transform_mesh(quiet_examined, edit.moved_from_original.inverse());
            coarsest = std::max(r.geometry.spacing.maxCoeff(), e.geometry.spacing.maxCoeff());
        }
        add_noise(r, sc.reference.acquisition);
        add_noise(e, sc.examined.acquisition);
        out.reference = extract_surface(r, sc.reference.surface).mesh;
        out.examined = extract_surface(e, examined_surface).mesh;
    };
    if (sc.reference.scan_as_ct) {
        const Mesh object = sc.reference.phantom ? make_phantom(*sc.reference.phantom)
                                                 : load_surface(sc.reference.mesh, {}).mesh;
        const float outside = sc.reference.ct_background, inside = sc.reference.ct_object;
        scan_pair([&](const VolumeEdit& e, const Acquisition& a) {
            return detail::acquire(object, e, a, outside, inside, true);
        });
    } else {
        const Volume volume = read_volume(sc.reference.mesh);
        scan_pair([&](const VolumeEdit& e, const Acquisition& a) {
            return detail::acquire(volume, e, a, true);
        });
    }
    detail::cut_pair(sc, out, edit.moved_from_original);
    if (sc.as_mesh_files) {
        // What an STL/PLY export of each segmentation keeps: positions (as float) and triangles.
        for (Mesh* m : {&out.reference, &out.examined}) {
            m->voxel_axes.reset();
            m->field_of_view = {};
            m->faint.clear();
        }
        out.notes.push_back(
            "both surfaces handed on as mesh files: no grid, field of view or contrast flags");
    }
    // note: the reach, half a voxel beyond a ball: the erosion's partial-volume ramp (a voxel
    // wide, centred on the ball's surface). Farther out the noiseless scans differ by their
    // sampling alone: on CThead's 2 mm slices under the 4° motion their terraces stand up to
    // a millimetre apart, and a reach of two voxels labelled three times the erosion's
    // vertices (recall of the volume-edit pair 0.93 → 0.30 with the same region).
    out.truth = erosion_truth(out.reference, quiet_reference, quiet_examined, sc.erosions,
                              0.5 * coarsest, kErosionLabelVoxels * coarsest)
                    .damaged;
    out.true_reference_from_examined = edit.moved_from_original.inverse();
    out.has_truth_pose = true;
    out.notes.push_back(std::string(sc.reference.scan_as_ct
                                        ? "both scans: CT of the reference's solid, the examined "
                                          "one under the known motion with "
                                        : "examined: the reference volume resampled under the "
                                          "known motion with ") +
                        std::to_string(sc.erosions.size()) + " erosion(s); reference scan " +
                        detail::describe(sc.reference.acquisition) + ", examined scan " +
                        detail::describe(sc.examined.acquisition));
    return out;
}

}  // namespace

ScenarioMeshes build_scenario_meshes(const Scenario& sc) {
    if (sc.examined_derived && (sc.resample_volume || sc.reference.acquisition.any())) {
        if (!sc.reference.phantom &&
            !reachable_input(sc.reference.mesh,
                             "scenario \"" + sc.file.string() + "\": reference volume"))
            throw IoError("scenario \"" + sc.file.string() + "\": reference volume \"" +
                          sc.reference.mesh_as_written + "\" not found (looked at \"" +
                          sc.reference.mesh.string() + "\"" +
                          (sc.reference.needs_data_root ? "; give --data-root or GLINT_DATA" : "") +
                          ")");
        return build_volume_pair(sc);
    }
    ScenarioMeshes out;
    auto load = [&](const SurfaceSource& s, const std::string& role) {
        if (s.phantom) return make_phantom(*s.phantom);
        if (!reachable_input(s.mesh, "scenario \"" + sc.file.string() + "\": " + role + " mesh"))
            throw IoError("scenario \"" + sc.file.string() + "\": " + role + " mesh \"" +
                          s.mesh_as_written + "\" not found (looked at \"" + s.mesh.string() +
                          "\"" + (s.needs_data_root ? "; give --data-root or GLINT_DATA" : "") +
                          ")");
        // An examined volume without its own surface keys is cut as the reference was.
        const bool inherit = &s == &sc.examined && is_volume_path(s.mesh) && !s.surface.iso;
        return load_surface(s.mesh, inherit ? sc.reference.surface : s.surface).mesh;
    };
    out.reference = load(sc.reference, "reference");
    if (sc.reference.cut)
        out.notes.push_back(detail::cut_scan(out.reference, *sc.reference.cut, "reference"));
    if (sc.examined_derived) {
        if (sc.examined.surface.roi)
            throw InputError("scenario \"" + sc.file.string() +
                             "\": surface_roi in [examined] is the field of view of a scan "
                             "resampled from the reference's volume, expected pose, voxel_size, "
                             "volume_noise or erode in [examined] on a volume reference (or give "
                             "the examined its own mesh, or cut it with keep_side)");
        derive_examined(sc, out);
        if (sc.reference.crop_ball)
            out.notes.push_back(detail::crop_reference(out, *sc.reference.crop_ball));
        return out;
    }
    out.examined = load(sc.examined, "examined");
    if (!sc.truth_mask.empty()) {
        out.truth = read_npy_mask(sc.truth_mask);
        if (out.truth.size() != out.reference.vertex_count())
            throw InputError("scenario \"" + sc.file.string() + "\": truth mask has " +
                             std::to_string(out.truth.size()) + " values, the reference has " +
                             std::to_string(out.reference.vertex_count()) + " vertices");
    }
    if (!sc.truth_pose_conf.empty() &&
        !reachable_input(sc.truth_pose_conf, "scenario \"" + sc.file.string() + "\": pose file"))
        throw IoError(
            "scenario \"" + sc.file.string() + "\": pose file \"" + sc.truth_pose_conf.string() +
            "\" not found" +
            (sc.truth_pose_conf_needs_data_root ? "; give --data-root or GLINT_DATA" : ""));
    out.has_truth_pose = sc.pose.matrix() != Rigid::Identity().matrix() ||
                         sc.analysis.fit.mode == FitMode::Truth || !sc.truth_pose_conf.empty();
    out.true_reference_from_examined = sc.pose.inverse();
    if (sc.expect.max_close_region_vertices) {
        // Two scans given in one frame (or with the stated pose): the true distance is to the
        // examined surface placed back with that pose.
        Mesh placed = out.examined;
        transform_mesh(placed, out.true_reference_from_examined);
        out.true_distance = vertex_distances(out.reference, placed);
    }
    return out;
}

}  // namespace glint
