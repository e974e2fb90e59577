// SPDX-License-Identifier: MIT
// Presliding friction on the shared UR10e logs (../shared/realdata): identified on the 14-harmonic Fourier
// run (x_p chosen there), validated on joint-at-a-time runs where the other joints stand still holding
// friction. The Dahl model must cut the validation error that a memory-free model leaves (measured
// figures in docs/real-data.md). Skipped, with the reason, when the shared folder is absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "realdata.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;

std::string robot(const std::string& name, const std::string& friction) {
    const std::string path = (jacobid::test::scratch_directory() / name).string();
    std::ofstream(path) << "model: urdf\nurdf: " << (jacobid::test::realdata_dir() / "ur10e" / "ur10e.urdf").string()
                        << "\ngravity: [0, 0, -9.81]\nfriction: {coulomb: smooth, alpha: auto, offset: true" << friction << "}\nrotor_inertia: true\n";
    return path;
}

nlohmann::json validate(const std::string& robot_file, const std::string& log) {
    const fs::path ur = jacobid::test::realdata_dir() / "ur10e";
    const auto r = jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " identify --quiet --format json --robot " + robot_file +
                                              " --log-format " + (jacobid::test::log_formats_dir() / "ur10e.yaml").string() + " --in " +
                                              (ur / "identification" / "ur-20_02_19_14harm50sec.csv").string() + " --validate " +
                                              (ur / "validation" / log).string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out)["methods"]["jacobi"];
}

TEST(PreslidingRealData, DahlCutsTheWristValidationErrorOfTheUr10e) {
    REQUIRE_REALDATA();
    const std::string plain = robot("plain.yaml", ""), dahl = robot("dahl.yaml", ", presliding: dahl");
    for (const auto& [log, cut] : {std::pair{"ur-20_01_22-joint_5.csv", 0.30}, std::pair{"ur-20_01_22-joint_6.csv", 0.15}}) {
        const nlohmann::json before = validate(plain, log), after = validate(dahl, log);
        const double e0 = before["validation"]["relative_error"].get<double>(), e1 = after["validation"]["relative_error"].get<double>();
        EXPECT_LT(e1, (1.0 - cut) * e0) << log << ": " << e0 << " -> " << e1;
        // x_p chosen on the identification log, for the wrists in the presliding range the issue located.
        const nlohmann::json& joints = after["presliding_displacement"]["joints"];
        for (int j = 3; j < 6; ++j) {
            const double xp = joints[j]["displacement"].get<double>();
            EXPECT_TRUE(joints[j]["chosen"].get<bool>());
            EXPECT_GE(xp, 1e-4) << "joint " << j + 1;
            EXPECT_LE(xp, 1e-3) << "joint " << j + 1;
        }
    }
}

}  // namespace
