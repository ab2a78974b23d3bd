#include "image/detail/image_plugin.h"

#include "mesh/error.h"

#include <future>

namespace glint::detail {

namespace {

// The Debian package of the library the plugin links (dpkg -S libOpenImageIO.so.2.4).
constexpr PluginSpec kPlugin{"libglint_image_io.so", GLINT_IMAGE_IO_ENTRY,
                             "pictures and image files", "libopenimageio2.4"};

}  // namespace

void preload_image_io_plugin() {
    std::string error;
    if (find_plugin(kPlugin, error).empty()) throw IoError(error);
    // note: the future's destructor (at exit) waits for a load still under way, so the
    // program never ends while another thread is inside dlopen.
    static std::future<void> loading = std::async(std::launch::async, [] {
        try {
            (void)image_io_plugin();
        } catch (...) {  // reported by the first use
        }
    });
}

const ImageIoTable& image_io_plugin() { return plugin_table<ImageIoTable>(kPlugin); }

}  // namespace glint::detail
