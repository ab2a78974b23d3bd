#include "render/view_list.h"

#include "mesh/error.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <sstream>

namespace glint {

namespace {

double item_number(const std::string& kv, std::size_t eq, const std::string& where) {
    double value = 0.0;
    try {
        std::size_t used = 0;
        value = std::stod(kv.substr(eq + 1), &used);
        if (used != kv.size() - eq - 1) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
        throw InputError(where + ": \"" + kv + "\", expected a number after '='");
    }
    if (!std::isfinite(value))
        throw InputError(where + ": \"" + kv + "\", expected a finite number");
    return value;
}

}  // namespace

ViewSpec parse_view_item(const std::string& item, const ViewSpec& base, const std::string& where) {
    ViewSpec spec = base;
    std::istringstream s(item);
    std::string kv;
    bool has_az = false;
    while (std::getline(s, kv, ',')) {
        const auto eq = kv.find('=');
        if (eq == std::string::npos)
            throw InputError(where + ": \"" + kv + "\", expected key=value");
        const std::string key = kv.substr(0, eq);
        const double value = item_number(kv, eq, where);
        if (key == "az") {
            spec.azimuth_deg = value;
            has_az = true;
        } else if (key == "el") {
            spec.elevation_deg = value;
        } else if (key == "fp") {
            spec.zoom = ZoomKind::Footprint;
            spec.zoom_value = value;
        } else if (key == "dist") {
            spec.zoom = ZoomKind::Distance;
            spec.zoom_value = value;
        } else {
            throw InputError(where + ": unknown key \"" + key + "\" (az, el, fp, dist)");
        }
    }
    if (!has_az) throw InputError(where + ": \"" + item + "\" has no az=");
    try {
        spec.validate();
    } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
    }
    return spec;
}

std::vector<ViewSpec> parse_view_list(const std::string& text, char separator, const ViewSpec& base,
                                      const std::string& source) {
    const bool lines = separator == '\n';
    std::vector<ViewSpec> specs;
    std::istringstream in(text);
    std::string item;
    std::size_t number = 0;
    while (std::getline(in, item, separator)) {
        ++number;
        if (lines) {
            if (const auto hash = item.find('#'); hash != std::string::npos) item.erase(hash);
            item.erase(0, item.find_first_not_of(" \t\r"));
            item.erase(item.find_last_not_of(" \t\r") + 1);
        }
        if (item.empty()) continue;
        if (specs.size() == kMaxListedViews)
            throw InputError(source + ": more than " + std::to_string(kMaxListedViews) +
                             " views (" + (lines ? "line " : "item ") + std::to_string(number) +
                             "), expected at most " + std::to_string(kMaxListedViews));
        const std::string where = lines ? source + " line " + std::to_string(number)
                                        : source + " item " + std::to_string(specs.size() + 1);
        specs.push_back(parse_view_item(item, base, where));
    }
    return specs;
}

std::string read_views_file(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) throw IoError("cannot read views file \"" + path + "\": " + std::strerror(errno));
    struct stat st {};
    const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    const auto size = static_cast<std::size_t>(regular ? st.st_size : 0);
    std::string text(regular && size <= kMaxViewsFileBytes ? size : 0, '\0');
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::read(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        done += static_cast<std::size_t>(n);
    }
    ::close(fd);
    if (!regular)
        throw InputError("views file \"" + path + "\": not a regular file, expected a text file");
    if (size > kMaxViewsFileBytes)
        throw InputError("views file \"" + path + "\": " + std::to_string(size) +
                         " bytes, expected at most 1 MiB");
    text.resize(done);
    return text;
}

}  // namespace glint
