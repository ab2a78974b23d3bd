#include "volume/plugin/vtk_filters.h"

#include <vtkBox.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkExtractPolyDataGeometry.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataConnectivityFilter.h>
#include <vtkSphere.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <cstdint>
#include <vector>

namespace glint::detail::vtk_filters {

namespace {
PluginSurface run_flying_edges(vtkImageData* image, double iso);
}  // namespace

std::size_t triangle_count(const PluginSurface& surface) {
    return surface.poly ? static_cast<std::size_t>(surface.poly->GetNumberOfPolys()) : 0;
}

PluginSurface contour(const Volume& volume, const VoxelCrop& crop, double iso) {
    const VolumeGeometry& g = volume.geometry;
    std::array<std::size_t, 3> n{};
    for (std::size_t d = 0; d < 3; ++d) n[d] = crop[1][d] - crop[0][d] + 1;
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2]));
    // note: index space (spacing 1, origin at the crop's first voxel); the physical mapping,
    // with its direction matrix, is applied afterwards (VTK 9.1's contour filters ignore an
    // image's direction matrix).
    image->SetOrigin(static_cast<double>(crop[0][0]), static_cast<double>(crop[0][1]),
                     static_cast<double>(crop[0][2]));
    image->SetSpacing(1, 1, 1);
    auto scalars = vtkSmartPointer<vtkFloatArray>::New();
    const auto count = static_cast<vtkIdType>(n[0] * n[1] * n[2]);
    if (n == g.size) {
        // The whole volume: VTK reads our buffer in place (save = 1: VTK never frees it; the
        // filter only reads, and the image dies with this function).
        scalars->SetArray(const_cast<float*>(volume.voxels.data()), count, 1);
        image->GetPointData()->SetScalars(scalars);
        return run_flying_edges(image, iso);
    }
    scalars->SetNumberOfTuples(count);
    float* dst = scalars->GetPointer(0);
    for (std::size_t k = 0; k < n[2]; ++k)
        for (std::size_t j = 0; j < n[1]; ++j) {
            const float* src =
                volume.voxels.data() + g.offset(crop[0][0], crop[0][1] + j, crop[0][2] + k);
            std::copy_n(src, n[0], dst + n[0] * (j + n[1] * k));
        }
    image->GetPointData()->SetScalars(scalars);
    return run_flying_edges(image, iso);
}

namespace {
PluginSurface run_flying_edges(vtkImageData* image, double iso) {
    auto fe = vtkSmartPointer<vtkFlyingEdges3D>::New();
    fe->SetInputData(image);
    fe->SetValue(0, iso);
    fe->ComputeNormalsOff();
    fe->ComputeGradientsOff();
    fe->ComputeScalarsOff();
    fe->Update();
    return {fe->GetOutput()};
}
}  // namespace

void to_physical(PluginSurface& surface, const VolumeGeometry& g) {
    auto& poly = surface.poly;
    const Eigen::Matrix3d m = g.direction * g.spacing.asDiagonal();
    auto transform = vtkSmartPointer<vtkTransform>::New();
    double e[16] = {
        m(0, 0), m(0, 1), m(0, 2), g.origin.x(), m(1, 0), m(1, 1), m(1, 2), g.origin.y(),
        m(2, 0), m(2, 1), m(2, 2), g.origin.z(), 0,       0,       0,       1};
    transform->SetMatrix(e);
    auto filter = vtkSmartPointer<vtkTransformPolyDataFilter>::New();
    filter->SetInputData(poly);
    filter->SetTransform(transform);
    filter->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
    filter->Update();
    poly = filter->GetOutput();
}

void keep_inside(PluginSurface& surface, const Roi& roi) {
    auto& poly = surface.poly;
    auto filter = vtkSmartPointer<vtkExtractPolyDataGeometry>::New();
    if (roi.shape == Roi::Shape::Sphere) {
        auto sphere = vtkSmartPointer<vtkSphere>::New();
        sphere->SetCenter(roi.center.x(), roi.center.y(), roi.center.z());
        sphere->SetRadius(roi.radius);
        filter->SetImplicitFunction(sphere);
    } else {
        auto box = vtkSmartPointer<vtkBox>::New();
        box->SetBounds(roi.min.x(), roi.max.x(), roi.min.y(), roi.max.y(), roi.min.z(),
                       roi.max.z());
        filter->SetImplicitFunction(box);
    }
    filter->SetInputData(poly);
    filter->ExtractInsideOn();
    filter->ExtractBoundaryCellsOff();  // a triangle with a corner outside is dropped
    filter->Update();
    poly = filter->GetOutput();
}

std::size_t keep_component(PluginSurface& surface, const Vec3d* seed) {
    auto& poly = surface.poly;
    auto filter = vtkSmartPointer<vtkPolyDataConnectivityFilter>::New();
    filter->SetInputData(poly);
    if (seed) {
        filter->SetExtractionModeToClosestPointRegion();
        filter->SetClosestPoint(seed->x(), seed->y(), seed->z());
    } else {
        filter->SetExtractionModeToLargestRegion();
    }
    filter->Update();
    poly = filter->GetOutput();
    return static_cast<std::size_t>(filter->GetNumberOfExtractedRegions());
}

void smooth(PluginSurface& surface, int iterations, double passband) {
    auto& poly = surface.poly;
    auto filter = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
    filter->SetInputData(poly);
    filter->SetNumberOfIterations(iterations);
    filter->SetPassBand(passband);
    filter->NormalizeCoordinatesOn();  // numerical stability (VTK's advice)
    filter->BoundarySmoothingOff();    // ROI cuts stay where they are
    filter->FeatureEdgeSmoothingOff();
    filter->NonManifoldSmoothingOn();
    filter->Update();
    poly = filter->GetOutput();
}

Mesh to_mesh(const PluginSurface& surface, bool flip) {
    const auto& poly = surface.poly;
    Mesh mesh;
    vtkPoints* points = poly->GetPoints();
    vtkCellArray* cells = poly->GetPolys();
    const auto np = static_cast<std::size_t>(poly->GetNumberOfPoints());
    std::vector<std::uint32_t> remap(np, UINT32_MAX);
    mesh.triangles.reserve(static_cast<std::size_t>(cells->GetNumberOfCells()));
    auto it = vtk::TakeSmartPointer(cells->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell()) {
        vtkIdType count = 0;
        const vtkIdType* ids = nullptr;
        it->GetCurrentCell(count, ids);
        if (count != 3) continue;  // flying edges writes triangles only
        Triangle t{};
        for (int c = 0; c < 3; ++c) {
            const auto id = static_cast<std::size_t>(ids[c]);
            if (remap[id] == UINT32_MAX) {
                remap[id] = static_cast<std::uint32_t>(mesh.positions.size());
                double p[3];
                points->GetPoint(static_cast<vtkIdType>(id), p);
                mesh.positions.emplace_back(static_cast<float>(p[0]), static_cast<float>(p[1]),
                                            static_cast<float>(p[2]));
            }
            t[static_cast<std::size_t>(c)] = remap[id];
        }
        if (flip) std::swap(t[1], t[2]);
        mesh.triangles.push_back(t);
    }
    return mesh;
}

}  // namespace glint::detail::vtk_filters
