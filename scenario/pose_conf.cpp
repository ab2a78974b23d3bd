#include "scenario/pose_conf.h"

#include "mesh/error.h"
#include "mesh/small_file.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace glint {

Rigid read_conf_pose(const std::filesystem::path& conf, const std::string& entry) {
    std::istringstream in(read_small_file(conf, "pose file"));
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        std::string keyword, file;
        if (!(words >> keyword) || keyword != "bmesh" || !(words >> file) || file != entry)
            continue;
        double t[3], q[4];
        const auto where = "pose file \"" + conf.string() + "\" line " + std::to_string(number);
        if (!(words >> t[0] >> t[1] >> t[2] >> q[0] >> q[1] >> q[2] >> q[3]))
            throw InputError(where + ": expected bmesh <file> tx ty tz qx qy qz qw, found \"" +
                             line + "\"");
        const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        bool finite = std::isfinite(norm);
        for (const double v : t) finite = finite && std::isfinite(v);
        if (!finite || std::abs(norm - 1.0) > 1e-3)
            throw InputError(where + ": the quaternion has norm " + std::to_string(norm) +
                             ", expected a unit quaternion of finite numbers");
        const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
        Rigid pose = Rigid::Identity();
        pose.linear() = rotation.normalized().toRotationMatrix().transpose();
        pose.translation() = Vec3d(t[0], t[1], t[2]);
        return pose;
    }
    throw InputError("pose file \"" + conf.string() + "\": no line \"bmesh " + entry +
                     " …\"; expected the scan's pose there");
}

}  // namespace glint
