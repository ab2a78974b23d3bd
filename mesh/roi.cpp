#include "mesh/roi.h"

#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/parse.h"

#include <algorithm>
#include <sstream>

namespace glint {

bool Roi::contains(std::size_t vertex, const Vec3d& p) const {
    if (shape == Shape::VertexMask) {
        GLINT_ASSERT(vertex < vertex_mask.size(), "ROI vertex mask does not cover the mesh");
        return vertex_mask[vertex] != 0;
    }
    return contains_point(p);
}

bool Roi::contains_point(const Vec3d& p) const {
    GLINT_ASSERT(shape != Shape::VertexMask, "a vertex mask ROI has no point test");
    if (shape == Shape::Sphere) return (p - center).norm() <= radius;
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
}

Roi parse_roi(const std::string& text) {
    const auto colon = text.find(':');
    const std::string kind = text.substr(0, colon);
    const std::string where = "ROI '" + text + "'";
    if (colon == std::string::npos)
        throw InputError(
            where +
            ": expected 'sphere:x,y,z,r', 'box:x0,y0,z0,x1,y1,z1' or 'mask:FILE.ply[:SCALAR]'");
    const std::string rest = text.substr(colon + 1);
    Roi roi;
    if (kind == "mask") {
        roi.shape = Roi::Shape::VertexMask;
        // FILE[:SCALAR]; a colon right after a drive letter or at the start is part of the name.
        const auto sep = rest.rfind(':');
        const bool named = sep != std::string::npos && sep > 1;
        roi.mask_file = named ? rest.substr(0, sep) : rest;
        roi.mask_property = named ? rest.substr(sep + 1) : "label";
        if (roi.mask_file.empty()) throw InputError(where + ": expected a mesh file after 'mask:'");
        if (roi.mask_property.empty())
            throw InputError(where + ": empty scalar name after the file");
        return roi;
    }
    const auto v = parse_number_list(rest, where);
    if (kind == "sphere") {
        if (v.size() != 4)
            throw InputError(where + ": sphere needs 4 numbers x,y,z,r, found " +
                             std::to_string(v.size()));
        roi.shape = Roi::Shape::Sphere;
        roi.center = {v[0], v[1], v[2]};
        roi.radius = v[3];
        if (!(roi.radius > 0)) throw InputError(where + ": radius must be > 0");
    } else if (kind == "box") {
        if (v.size() != 6)
            throw InputError(where + ": box needs 6 numbers, found " + std::to_string(v.size()));
        roi.shape = Roi::Shape::Box;
        roi.min = {v[0], v[1], v[2]};
        roi.max = {v[3], v[4], v[5]};
        if ((roi.max.array() <= roi.min.array()).any())
            throw InputError(where + ": box max must exceed min on every axis");
    } else {
        throw InputError(where + ": unknown shape '" + kind + "', expected sphere, box or mask");
    }
    return roi;
}

std::string to_string(const Roi& roi) {
    std::ostringstream s;
    s.precision(10);
    switch (roi.shape) {
        case Roi::Shape::Sphere:
            s << "sphere:" << roi.center.x() << ',' << roi.center.y() << ',' << roi.center.z()
              << ',' << roi.radius;
            break;
        case Roi::Shape::Box:
            s << "box:" << roi.min.x() << ',' << roi.min.y() << ',' << roi.min.z() << ','
              << roi.max.x() << ',' << roi.max.y() << ',' << roi.max.z();
            break;
        case Roi::Shape::VertexMask:
            s << "mask:" << roi.mask_file.string() << ':' << roi.mask_property;
            break;
    }
    return s.str();
}

void read_roi_mask(Roi& roi, std::size_t vertex_count) {
    GLINT_ASSERT(roi.shape == Roi::Shape::VertexMask, "read_roi_mask on a shape ROI");
    const std::string where = "ROI mask \"" + roi.mask_file.string() + "\"";
    LoadOptions keep;
    keep.weld = keep.drop_degenerate = keep.drop_unused = false;
    const LoadedMesh mask = load_mesh(roi.mask_file, keep);
    if (mask.mesh.vertex_count() != vertex_count)
        throw InputError(where + ": " + std::to_string(mask.mesh.vertex_count()) +
                         " vertices, the reference has " + std::to_string(vertex_count));
    roi.vertex_mask.clear();
    roi.vertex_mask.reserve(vertex_count);
    if (roi.mask_property == "label" && !mask.mesh.labels.empty()) {
        for (auto l : mask.mesh.labels) roi.vertex_mask.push_back(l != 0);
    } else if (const ScalarField* f = mask.mesh.find_scalar(roi.mask_property)) {
        for (float x : f->values) roi.vertex_mask.push_back(x != 0.0f);
    } else {
        throw InputError(
            where + ": no '" + roi.mask_property + "' property" +
            (roi.mask_property == "label" ? "; name a scalar as mask:FILE:SCALAR" : ""));
    }
    if (std::none_of(roi.vertex_mask.begin(), roi.vertex_mask.end(),
                     [](std::uint8_t m) { return m != 0; }))
        throw InputError(where + ": '" + roi.mask_property +
                         "' is zero on every vertex: the region is empty");
}

}  // namespace glint
