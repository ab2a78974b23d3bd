#include "image/detail/image_plugin.h"

#include "mesh/error.h"

namespace glint::detail {

namespace {

// The Debian package of the library the plugin links (dpkg -S libOpenImageIO.so.2.4). Loading
// it takes 433 MB of address space (VmSize before and after, Debian 12): its libraries' mappings
// and four threads their initialisers start (log4cplus's pool), each with a stack and a malloc
// arena of its own.
constexpr PluginSpec kPlugin{"libglint_image_io.so", GLINT_IMAGE_IO_ENTRY,
                             "pictures and image files", "libopenimageio2.4",
                             std::size_t{480} << 20};

}  // namespace

void preload_image_io_plugin() {
    std::string error;
    if (find_plugin(kPlugin, error).empty()) throw IoError(error);
    static const bool started = [] {
        load_in_background([] {
            try {
                (void)image_io_plugin();
            } catch (...) {  // reported by the first use
            }
        });
        return true;
    }();
    (void)started;
}

const ImageIoTable& image_io_plugin() { return plugin_table<ImageIoTable>(kPlugin); }

}  // namespace glint::detail
