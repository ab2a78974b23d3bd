// glint devices: the Vulkan devices glint sees, whether each is usable (and why not), which
// one a default Vulkan renderer picks, and what --backend auto would choose.
#include "mesh/error.h"
#include "mesh/json_text.h"
#include "render/renderer.h"
#include "tools/command.h"

#include <nlohmann/json.hpp>

#include <iomanip>
#include <iostream>

namespace glint::cli::devices_command {
namespace {

void run() {
    std::vector<DeviceInfo> devices;
    std::string vulkan_error;
    try {
        devices = list_devices();
    } catch (const DeviceError& e) {
        vulkan_error = e.what();
    }
    std::string reason;
    const Backend chosen = resolve_backend(RenderOptions{}, 1'000'000, &reason);
    if (global_flags().json) {
        nlohmann::json out = {{"devices", nlohmann::json::array()},
                              {"auto_backend", to_string(chosen)},
                              {"auto_reason", reason}};
        for (const auto& d : devices) {
            out["devices"].push_back({{"name", d.name},
                                      {"type", d.type},
                                      {"driver", d.driver},
                                      {"api_version", d.api_version_text},
                                      {"usable", d.is_usable},
                                      {"reason", d.reason},
                                      {"preferred", d.is_preferred},
                                      {"gpu_atlas", d.supports_gpu_atlas},
                                      {"gpu_atlas_reason", d.gpu_atlas_reason}});
        }
        if (!vulkan_error.empty()) out["vulkan_error"] = vulkan_error;
        std::cout << json_text(out, 2) << '\n';
    } else {
        if (!vulkan_error.empty()) std::cout << "Vulkan: " << vulkan_error << '\n';
        for (const auto& d : devices) {
            std::cout << (d.is_preferred ? "* " : "  ") << d.name << " [" << d.type << ", Vulkan "
                      << d.api_version_text << (d.driver.empty() ? "" : ", " + d.driver)
                      << "]: " << (d.is_usable ? "usable" : "not usable, " + d.reason)
                      << (!d.is_usable ? ""
                          : d.supports_gpu_atlas
                              ? "; compares on the device"
                              : "; compares on the CPU (" + d.gpu_atlas_reason + ")")
                      << '\n';
        }
        std::cout << "embree (CPU): usable\n";
        std::cout << "--backend auto: " << to_string(chosen) << " (" << reason << ")\n";
    }
    if (devices.empty() && !vulkan_error.empty()) throw DeviceError(vulkan_error);
}

void setup(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "devices", "List Vulkan devices, why any is unusable, and the auto backend");
    cmd->callback([] { run(); });
}

const CommandRegistrar registrar(45, setup);

}  // namespace
}  // namespace glint::cli::devices_command
