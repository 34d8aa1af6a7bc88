// gusuku-bake georef: the similarity fit (gusuku_bake/similarity_fit.h) against a known transform, its refusals,
// the GCP reader (gusuku_bake/ground_control.h) through GeographicLib's own forward conversions, and the command.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/UTMUPS.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_command.h"
#include "gusuku/assets/site.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/ground_control.h"
#include "gusuku_bake/similarity_fit.h"

namespace {

using gusuku::bake::SimilarityTransform;

constexpr double kPi = 3.14159265358979323846;
const gusuku::GeodeticPoint kOrigin{26.2856, 127.8008, 160.0};  // Nakagusuku, the sample site

// The known transform: scale 0.37, 130 degrees about the tilted axis (1, 2, 3), a translation of tens of metres.
SimilarityTransform knownTransform() {
    const glm::dvec3 axis = glm::normalize(glm::dvec3(1, 2, 3));
    const double half_angle = 0.5 * 130.0 * kPi / 180.0;
    SimilarityTransform transform;
    transform.scale = 0.37;
    transform.rotation_wxyz = {std::cos(half_angle), std::sin(half_angle) * axis.x, std::sin(half_angle) * axis.y,
                               std::sin(half_angle) * axis.z};
    transform.translation = {12.5, -40.2, 3.1};
    return transform;
}

// Six mesh points about 100 units (37 m) apart, not on one plane.
std::vector<glm::dvec3> meshPoints() {
    return {{0, 0, 0}, {100, 5, -3}, {-20, 90, 10}, {60, 70, 40}, {-80, -40, 25}, {30, -90, -15}};
}

std::vector<glm::dvec3> mapped(const SimilarityTransform& transform, const std::vector<glm::dvec3>& points) {
    std::vector<glm::dvec3> result;
    for (const glm::dvec3& point : points) result.push_back(transform.apply(point));
    return result;
}

// The angle of the rotation taking one to the other, in degrees (from the quaternions' dot product).
double rotationDifferenceDeg(const SimilarityTransform& a, const SimilarityTransform& b) {
    double dot = 0.0;
    for (int k = 0; k < 4; ++k) dot += a.rotation_wxyz[k] * b.rotation_wxyz[k];
    return 2.0 * std::acos(std::min(1.0, std::abs(dot))) * 180.0 / kPi;
}

std::string refusal(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to) {
    try {
        gusuku::bake::fitSimilarity(from, to);
    } catch (const gusuku::bake::DegeneratePoints& error) {
        return error.what();
    }
    return "";
}

std::string readError(const std::string& text) {
    try {
        gusuku::bake::readGroundControlPoints("gcps.csv", text, kOrigin, std::nullopt);
    } catch (const gusuku::InputError& error) {
        return error.what();
    }
    return "";
}

}  // namespace

TEST(Georef, ExactPointsFitWithNoResidual) {
    const SimilarityTransform truth = knownTransform();
    const gusuku::bake::SimilarityFit fit = gusuku::bake::fitSimilarity(meshPoints(), mapped(truth, meshPoints()));
    EXPECT_NEAR(fit.transform.scale, truth.scale, 1e-12);
    EXPECT_LT(rotationDifferenceDeg(fit.transform, truth), 1e-6);
    EXPECT_LT(glm::length(fit.transform.translation - truth.translation), 1e-9);
    for (const double residual : fit.residuals_m) EXPECT_LT(residual, 1e-6);

    // The fields mean to site.json's reader what they mean to the fit: its sfm_mesh transform maps the mesh points
    // onto the survey.
    gusuku::SfmMeshConfig config;
    config.scale = fit.transform.scale;
    config.rotation_wxyz = fit.transform.rotation_wxyz;
    config.translation_enu_m = fit.transform.translation;
    const std::vector<glm::dvec3> surveyed = mapped(truth, meshPoints());
    for (size_t k = 0; k < surveyed.size(); ++k)
        EXPECT_LT(glm::length(glm::dvec3(config.enuFromModel() * glm::dvec4(meshPoints()[k], 1.0)) - surveyed[k]), 1e-6);
}

TEST(Georef, NoisyPointsRecoverTheTransform) {
    const SimilarityTransform truth = knownTransform();
    std::vector<glm::dvec3> surveyed = mapped(truth, meshPoints());
    std::mt19937 generator(20261207);
    std::normal_distribution<double> noise_m(0.0, 0.01);  // 1 cm per axis, a good RTK survey
    for (glm::dvec3& point : surveyed) point += glm::dvec3(noise_m(generator), noise_m(generator), noise_m(generator));
    const gusuku::bake::SimilarityFit fit = gusuku::bake::fitSimilarity(meshPoints(), surveyed);
    EXPECT_NEAR(fit.transform.scale / truth.scale, 1.0, 1e-3);
    EXPECT_LT(rotationDifferenceDeg(fit.transform, truth), 0.05);
    // 1 cm per axis is 1.7 cm in 3D; the fit absorbs 7 of the 18 degrees of freedom.
    EXPECT_GT(fit.rms_residual_m, 0.003);
    EXPECT_LT(fit.rms_residual_m, 0.025);
}

TEST(Georef, DegeneratePointsAreRefused) {
    const SimilarityTransform truth = knownTransform();
    const std::vector<glm::dvec3> two = {{0, 0, 0}, {10, 0, 0}};
    EXPECT_NE(refusal(two, mapped(truth, two)).find("2 points given"), std::string::npos);

    // On one line to within 0.1 % of their length (a mesh's rounding).
    const std::vector<glm::dvec3> line = {{0, 0, 0}, {10, 10, 0.01}, {20, 20, 0}, {30, 30.01, 0}};
    EXPECT_NE(refusal(line, mapped(truth, line)).find("the mesh positions lie on one line"), std::string::npos);

    // The same survey against a mesh with its z axis negated: a left-handed mesh.
    std::vector<glm::dvec3> mirrored = meshPoints();
    for (glm::dvec3& point : mirrored) point.z = -point.z;
    EXPECT_NE(refusal(mirrored, mapped(truth, meshPoints())).find("the mesh is mirrored"), std::string::npos);

    // Three points always lie on a plane: that is no refusal.
    const std::vector<glm::dvec3> triangle = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
    EXPECT_EQ(refusal(triangle, mapped(truth, triangle)), "");
}

TEST(Georef, LatitudeLongitudeFileRoundTripsThroughLocalCartesian) {
    const SimilarityTransform truth = knownTransform();
    const std::vector<glm::dvec3> enu = mapped(truth, meshPoints());
    const GeographicLib::LocalCartesian frame(kOrigin.latitude_deg, kOrigin.longitude_deg, kOrigin.height_m);
    std::string csv = "# survey of 2026-12-07\n" + std::string(gusuku::bake::kGeodeticControlHeader) + "\n\n";
    for (size_t k = 0; k < enu.size(); ++k) {
        double latitude = 0, longitude = 0, height = 0;
        frame.Reverse(enu[k].x, enu[k].y, enu[k].z, latitude, longitude, height);
        char row[256];
        std::snprintf(row, sizeof row, "p%zu, %.6f,%.6f,%.6f, %.11f,%.11f,%.5f\n", k, meshPoints()[k].x,
                      meshPoints()[k].y, meshPoints()[k].z, latitude, longitude, height);
        csv += row;
    }
    const std::vector<gusuku::bake::GroundControlPoint> points =
        gusuku::bake::readGroundControlPoints("gcps.csv", csv, kOrigin, std::nullopt);
    ASSERT_EQ(points.size(), enu.size());
    EXPECT_EQ(points[0].line, 4);
    for (size_t k = 0; k < enu.size(); ++k) EXPECT_LT(glm::length(points[k].enu_m - enu[k]), 1e-4) << k;
}

TEST(Georef, UtmGridFileRoundTripsThroughUtmUps) {
    const SimilarityTransform truth = knownTransform();
    const std::vector<glm::dvec3> enu = mapped(truth, meshPoints());
    const GeographicLib::LocalCartesian frame(kOrigin.latitude_deg, kOrigin.longitude_deg, kOrigin.height_m);
    std::string csv = std::string(gusuku::bake::kGridControlHeader) + "\n";
    for (size_t k = 0; k < enu.size(); ++k) {
        double latitude = 0, longitude = 0, height = 0, easting = 0, northing = 0, gamma = 0, k_scale = 0;
        frame.Reverse(enu[k].x, enu[k].y, enu[k].z, latitude, longitude, height);
        int zone = 0;
        bool north = false;
        GeographicLib::UTMUPS::Forward(latitude, longitude, zone, north, easting, northing, gamma, k_scale);
        ASSERT_EQ(zone, 52);  // Okinawa
        char row[256];
        std::snprintf(row, sizeof row, "p%zu,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f\n", k, meshPoints()[k].x,
                      meshPoints()[k].y, meshPoints()[k].z, easting, northing, height);
        csv += row;
    }
    const std::vector<gusuku::bake::GroundControlPoint> points =
        gusuku::bake::readGroundControlPoints("gcps.csv", csv, kOrigin, gusuku::UtmZone{52, true});
    for (size_t k = 0; k < enu.size(); ++k) EXPECT_LT(glm::length(points[k].enu_m - enu[k]), 1e-4) << k;
    EXPECT_NE(readError(csv).find("--utm-zone"), std::string::npos);
}

TEST(Georef, BadRowsAreNamedByLine) {
    const std::string header = std::string(gusuku::bake::kGeodeticControlHeader) + "\n";
    const std::string good = "a,0,0,0,26.2856,127.8008,160\n";
    EXPECT_NE(readError(header + good + "b,1,2,26.2857,127.8008,160\n").find("gcps.csv: line 3: has 6 columns"),
              std::string::npos);
    EXPECT_NE(readError(header + good + "b,1,2,3,200,127.8008,160\n")
                  .find("gcps.csv: line 3: latitude_deg: 200 is outside [-90, 90]"),
              std::string::npos);
    EXPECT_NE(readError(header + good + "b,1,NaN,3,26.2857,127.8008,160\n").find("gcps.csv: line 3: mesh_y:"),
              std::string::npos);
    EXPECT_NE(readError(header + good + "a,1,2,3,26.2857,127.8008,160\n").find("line 3: name: "), std::string::npos);
    EXPECT_NE(readError("name,x,y,z\n").find("gcps.csv: line 1: the header"), std::string::npos);
    EXPECT_NE(readError(header + good + "b,1,2,3,27.5,127.8008,160\n").find("km from the ENU origin"),
              std::string::npos);
}

// The command end to end: the fields it writes with -o are the known transform, and a point moved by 30 cm is
// refused by name with nothing written.
TEST(Georef, CommandWritesTheFieldsAndRefusesALargeResidual) {
    const std::filesystem::path scratch = std::filesystem::temp_directory_path() / "gusuku_test_georef";
    std::filesystem::remove_all(scratch);
    std::filesystem::create_directories(scratch);
    const SimilarityTransform truth = knownTransform();
    std::vector<glm::dvec3> enu = mapped(truth, meshPoints());
    const GeographicLib::LocalCartesian frame(kOrigin.latitude_deg, kOrigin.longitude_deg, kOrigin.height_m);
    const auto writeCsv = [&](const std::string& name) {
        std::ofstream file(scratch / name);
        file << gusuku::bake::kGeodeticControlHeader << "\n";
        for (size_t k = 0; k < enu.size(); ++k) {
            double latitude = 0, longitude = 0, height = 0;
            frame.Reverse(enu[k].x, enu[k].y, enu[k].z, latitude, longitude, height);
            char row[256];
            std::snprintf(row, sizeof row, "p%zu,%.6f,%.6f,%.6f,%.11f,%.11f,%.5f\n", k, meshPoints()[k].x,
                          meshPoints()[k].y, meshPoints()[k].z, latitude, longitude, height);
            file << row;
        }
        return (scratch / name).string();
    };
    const std::string origin = "--origin=26.2856,127.8008,160";
    const std::string output = (scratch / "sfm_mesh.json").string();
    const gusuku::testing::CommandResult good =
        gusuku::testing::runBakeCommand({"georef", writeCsv("good.csv"), origin, "-o", output}, scratch.string());
    ASSERT_EQ(good.exit_code, 0) << good.stderr_text;
    const nlohmann::json fields = nlohmann::json::parse(std::ifstream(output));
    // The file's 1e-6 of mesh units and 1e-11 degrees (1 um) limit the agreement to about 1e-8.
    EXPECT_NEAR(fields["scale"].get<double>(), truth.scale, 1e-7);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(fields["translation_enu_m"][k].get<double>(), truth.translation[k], 2e-4);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(fields["rotation_wxyz"][k].get<double>(), truth.rotation_wxyz[k], 1e-7);

    // --site takes the same origin from a site.json: the sample site's reference point is kOrigin.
    const std::string sample = (scratch / "sample").string();
    ASSERT_EQ(gusuku::testing::runBakeCommand({"sample", sample}, scratch.string()).exit_code, 0);
    const std::string from_site = (scratch / "from_site.json").string();
    const gusuku::testing::CommandResult site_run = gusuku::testing::runBakeCommand(
        {"georef", writeCsv("good.csv"), "--site", sample + "/site.json", "-o", from_site}, scratch.string());
    ASSERT_EQ(site_run.exit_code, 0) << site_run.stderr_text;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(from_site)), fields);

    enu[3].z += 0.30;
    std::filesystem::remove(output);
    const gusuku::testing::CommandResult bad =
        gusuku::testing::runBakeCommand({"georef", writeCsv("bad.csv"), origin, "-o", output}, scratch.string());
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.stderr_text.find("the residual of 'p3' (line 5)"), std::string::npos) << bad.stderr_text;
    EXPECT_FALSE(std::filesystem::exists(output));
    std::filesystem::remove_all(scratch);
}
