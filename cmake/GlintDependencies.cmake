# Every dependency comes from a Debian package (tools/setup installs them all).
# When one is missing, configure stops and names the package to install.

macro(glint_require found_var package)
  if(NOT ${found_var})
    message(FATAL_ERROR "glint: ${package} not found; install the Debian package '${package}' "
                        "(tools/setup installs everything)")
  endif()
endmacro()

find_package(Threads REQUIRED)
find_package(Eigen3 3.4 QUIET NO_MODULE)
glint_require(Eigen3_FOUND libeigen3-dev)
find_package(glm QUIET)
glint_require(glm_FOUND libglm-dev)
find_package(Vulkan QUIET)
glint_require(Vulkan_FOUND libvulkan-dev)
find_program(GLINT_GLSLANG glslangValidator)
glint_require(GLINT_GLSLANG glslang-tools)
find_package(embree 3 QUIET)
glint_require(embree_FOUND libembree-dev)
# oneTBB (libtbb-dev, which libembree-dev depends on): the render module's worker pool.
find_package(TBB QUIET)
glint_require(TBB_FOUND libtbb-dev)
find_package(Ceres QUIET)
glint_require(Ceres_FOUND libceres-dev)
find_package(OpenImageIO QUIET)
glint_require(OpenImageIO_FOUND libopenimageio-dev)
# note: Debian 12's OpenImageIO config lists /usr/include/opencv4 (and Python Imath bits) as
# interface paths although OIIO's public headers need neither; drop paths that do not exist
# rather than pulling in OpenCV's development package.
foreach(oiio_target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${oiio_target})
    get_target_property(oiio_dirs ${oiio_target} INTERFACE_INCLUDE_DIRECTORIES)
    if(oiio_dirs)
      set(oiio_kept)
      foreach(dir ${oiio_dirs})
        if(EXISTS "${dir}" OR dir MATCHES "^\\$<")
          list(APPEND oiio_kept "${dir}")
        endif()
      endforeach()
      set_target_properties(${oiio_target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${oiio_kept}")
    endif()
  endif()
endforeach()
# FreeType draws the pictures' text (report/detail/text.cpp): OpenImageIO 2.4's render_text
# decodes UTF-8 wrongly ("°" became "0"). libopenimageio-dev already depends on the package.
find_package(Freetype QUIET)
glint_require(FREETYPE_FOUND libfreetype-dev)
find_package(assimp QUIET)
glint_require(assimp_FOUND libassimp-dev)
find_package(meshoptimizer QUIET)
glint_require(meshoptimizer_FOUND libmeshoptimizer-dev)
# CGAL: isotropic remeshing of real surfaces (the re-tessellated pairs of the evaluation).
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
find_package(CGAL QUIET)
glint_require(CGAL_FOUND libcgal-dev)
# ITK reads the volumes (MetaImage, NIfTI, NRRD; DICOM through GDCM) with their geometry; VTK
# extracts the surface (flying edges, connectivity, windowed-sinc smoothing). Only the
# modules glint uses, so configuring pulls in none of VTK's rendering or Qt parts.
# note: ITK's package configuration looks for HDF5 with a C test program, so C is enabled.
enable_language(C)
# zlib reads a NIfTI header (.nii or .nii.gz) before ITK does (volume/detail/itk_io.cpp).
find_package(ZLIB QUIET)
glint_require(ZLIB_FOUND zlib1g-dev)
find_package(ITK 5 QUIET COMPONENTS ITKCommon ITKIOImageBase ITKIOMeta ITKIONIFTI ITKIONRRD ITKIOGDCM)
glint_require(ITK_FOUND libinsighttoolkit5-dev)
# GDCM itself (ITK's DICOM IO uses Debian's GDCM): only to silence its warning trace.
find_package(GDCM QUIET)
glint_require(GDCM_FOUND libgdcm-dev)
find_package(VTK 9 QUIET COMPONENTS CommonCore CommonDataModel CommonTransforms FiltersCore FiltersGeneral
             FiltersExtraction)
glint_require(VTK_FOUND libvtk9-dev)
set(GLINT_VTK_LIBRARIES VTK::CommonCore VTK::CommonDataModel VTK::CommonTransforms VTK::FiltersCore
    VTK::FiltersGeneral VTK::FiltersExtraction)
find_package(CLI11 QUIET)
glint_require(CLI11_FOUND libcli11-dev)
find_package(PkgConfig QUIET)
find_package(tomlplusplus QUIET)
if(NOT tomlplusplus_FOUND AND PkgConfig_FOUND)
  pkg_check_modules(tomlplusplus QUIET IMPORTED_TARGET tomlplusplus)
  if(tomlplusplus_FOUND)
    add_library(tomlplusplus::tomlplusplus ALIAS PkgConfig::tomlplusplus)
  endif()
endif()
glint_require(tomlplusplus_FOUND libtomlplusplus-dev)
find_package(OpenSSL QUIET)
glint_require(OPENSSL_FOUND libssl-dev)
find_package(nlohmann_json 3 QUIET)
glint_require(nlohmann_json_FOUND nlohmann-json3-dev)
if(GLINT_BUILD_TESTS)
  find_package(GTest QUIET)
  glint_require(GTest_FOUND libgtest-dev)
endif()
if(GLINT_BUILD_BENCH)
  find_package(benchmark QUIET)
  glint_require(benchmark_FOUND libbenchmark-dev)
endif()
# three.js (r111) and its OrbitControls from Debian's libjs-three: embedded into report.html at
# build time (report/CMakeLists.txt), never fetched from the network.
find_file(GLINT_THREE_JS three.min.js PATHS /usr/share/javascript/three NO_DEFAULT_PATH)
glint_require(GLINT_THREE_JS libjs-three)
find_file(GLINT_ORBIT_CONTROLS_JS OrbitControls.js PATHS /usr/share/javascript/three/examples/js/controls
          NO_DEFAULT_PATH)
glint_require(GLINT_ORBIT_CONTROLS_JS libjs-three)
