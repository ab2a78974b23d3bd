// A volume written as a DICOM CT series: one single-frame file per slice k, each a 3D ITK
// image of depth 1 so that GDCM records the slice's own position (ImagePositionPatient) and
// the in-plane axes (ImageOrientationPatient) from the geometry; the study, series and frame
// of reference UIDs are shared by all slices so readers group them into one series.
#include "mesh/error.h"
#include "volume/plugin/itk_side.h"

#include <gdcmTrace.h>
#include <itkGDCMImageIO.h>
#include <itkImage.h>
#include <itkImageFileWriter.h>
#include <itkMetaDataObject.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace glint::detail {

namespace fs = std::filesystem;

namespace {

using ShortSlice = itk::Image<short, 3>;

// A UID under the UUID-derived root 2.25 (DICOM PS3.5 B.2): "2.25." + a random integer.
std::string new_uid(std::mt19937_64& rng) { return "2.25." + std::to_string(rng() >> 1); }

ShortSlice::Pointer slice_image(const RawVolume& v, std::size_t k) {
    auto image = ShortSlice::New();
    ShortSlice::SizeType size;
    size[0] = v.size[0];
    size[1] = v.size[1];
    size[2] = 1;
    image->SetRegions(ShortSlice::RegionType(size));
    ShortSlice::SpacingType spacing;
    ShortSlice::PointType origin;
    ShortSlice::DirectionType direction;
    for (unsigned d = 0; d < 3; ++d) {
        spacing[d] = v.spacing[d];
        // The slice's first voxel: origin + direction · (0, 0, k · spacing_k).
        origin[d] = v.origin[d] + v.direction[3 * d + 2] * v.spacing[2] * static_cast<double>(k);
        for (unsigned c = 0; c < 3; ++c) direction[d][c] = v.direction[3 * d + c];
    }
    image->SetSpacing(spacing);
    image->SetOrigin(origin);
    image->SetDirection(direction);
    image->Allocate();
    short* out = image->GetBufferPointer();
    const std::size_t n = v.size[0] * v.size[1];
    const float* in = v.voxels.data() + k * n;
    for (std::size_t i = 0; i < n; ++i)
        out[i] = static_cast<short>(std::clamp(std::lround(in[i]), -32768L, 32767L));
    return image;
}

}  // namespace

namespace itk_side {

void write_dicom(const RawVolume& v, const fs::path& folder) {
    itk::Object::GlobalWarningDisplayOff();
    gdcm::Trace::WarningOff();  // library code never prints
    std::mt19937_64 rng(std::random_device{}());
    const std::string study = new_uid(rng), series = new_uid(rng), frame = new_uid(rng);
    for (std::size_t k = 0; k < v.size[2]; ++k) {
        auto io = itk::GDCMImageIO::New();
        io->KeepOriginalUIDOn();
        const ShortSlice::Pointer slice = slice_image(v, k);
        // note: ImageFileWriter hands the image's dictionary to the ImageIO.
        itk::MetaDataDictionary& dict = slice->GetMetaDataDictionary();
        auto set = [&](const char* tag, const std::string& value) {
            itk::EncapsulateMetaData<std::string>(dict, tag, value);
        };
        set("0008|0016", "1.2.840.10008.5.1.4.1.1.2");  // CT Image Storage
        set("0008|0018", new_uid(rng));
        set("0008|0060", "CT");
        set("0010|0010", "glint^test");
        set("0020|000d", study);
        set("0020|000e", series);
        set("0020|0052", frame);
        set("0020|0013", std::to_string(k + 1));
        set("0008|103e", "written by glint");
        char name[32];
        std::snprintf(name, sizeof name, "slice%04zu.dcm", k);
        auto writer = itk::ImageFileWriter<ShortSlice>::New();
        writer->SetImageIO(io);
        writer->SetFileName((folder / name).string());
        writer->SetInput(slice);
        try {
            writer->Update();
        } catch (const itk::ExceptionObject& e) {
            throw IoError("DICOM folder \"" + folder.string() + "\": cannot write " + name + ": " +
                          e.GetDescription());
        }
    }
}

}  // namespace itk_side
}  // namespace glint::detail
