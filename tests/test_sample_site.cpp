// The generated sample site: every file is there and loads through the project's own loaders, the transforms
// put things where they belong, the house is oriented, closed and open at its doorway, and it stands on the
// terrace. Geometry is checked with brute-force ray casts, independent of the baker's BVH.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sys/wait.h>
#include <filesystem>
#include <numbers>
#include <optional>
#include <random>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <gtest/gtest.h>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/sample_site.h"
#include "gpu_test_support.h"

namespace {

using namespace gusuku;
namespace ss = gusuku::bake::sample_site;

struct Hit {
    double distance;
    size_t triangle;
};

glm::dvec3 vertex(const TriangleMesh& mesh, size_t triangle, int corner) {
    return glm::dvec3(mesh.positions[mesh.indices[3 * triangle + size_t(corner)]]);
}

glm::dvec3 geometricNormal(const TriangleMesh& mesh, size_t triangle) {
    const glm::dvec3 a = vertex(mesh, triangle, 0), b = vertex(mesh, triangle, 1), c = vertex(mesh, triangle, 2);
    return glm::normalize(glm::cross(b - a, c - a));
}

// Moller-Trumbore against every triangle; both sides count.
std::optional<Hit> closestHit(const TriangleMesh& mesh, const glm::dvec3& origin, const glm::dvec3& direction) {
    std::optional<Hit> best;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::dvec3 a = vertex(mesh, t, 0), b = vertex(mesh, t, 1), c = vertex(mesh, t, 2);
        const glm::dvec3 e1 = b - a, e2 = c - a;
        const glm::dvec3 p = glm::cross(direction, e2);
        const double det = glm::dot(e1, p);
        if (std::abs(det) < 1e-14) continue;
        const glm::dvec3 s = origin - a;
        const double u = glm::dot(s, p) / det;
        if (u < 0.0 || u > 1.0) continue;
        const glm::dvec3 q = glm::cross(s, e1);
        const double v = glm::dot(direction, q) / det;
        if (v < 0.0 || u + v > 1.0) continue;
        const double distance = glm::dot(e2, q) / det;
        if (distance > 1e-9 && (!best || distance < best->distance)) best = Hit{distance, t};
    }
    return best;
}

glm::dvec3 transformPoint(const glm::dmat4& m, const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }
glm::dvec3 transformDirection(const glm::dmat4& m, const glm::dvec3& d) {
    return glm::normalize(glm::dvec3(m * glm::dvec4(d, 0.0)));
}

class SampleSite : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        directory_ = new std::string(gusuku::testing::makeTemporaryDirectory("sample_site"));
        written_ = new std::vector<std::string>(ss::writeSampleSite(*directory_));
        config_ = new SiteConfig(loadSiteConfig(*directory_ + "/site.json"));
        GltfLoadOptions site_options;
        site_options.enu_from_model = config_->sfm_mesh->enuFromModel();
        site_warnings_ = new std::vector<std::string>();
        site_mesh_ = new TriangleMesh(loadGltf(config_->sfm_mesh->path, site_options, site_warnings_));
        house_from_model_ = new glm::dmat4(config_->building.enuFromModel(config_->site.reference));
        GltfLoadOptions house_options;
        house_options.enu_from_model = *house_from_model_;
        house_ = new TriangleMesh(loadGltf(config_->building.path, house_options, site_warnings_));
    }

    // The house model's own frame (x right, y its north, z up) -> ENU, as loaded: the glTF Y-up axis change
    // is undone first, because the model was built in these axes and stored Y-up.
    static glm::dvec3 houseModelToEnu(const glm::dvec3& p) {
        return transformPoint(*house_from_model_ * glm::inverse(enuFromGltfYUp()), p);
    }
    static glm::dvec3 houseModelDirectionToEnu(const glm::dvec3& d) {
        return transformDirection(*house_from_model_ * glm::inverse(enuFromGltfYUp()), d);
    }

    static std::string* directory_;
    static std::vector<std::string>* written_;
    static SiteConfig* config_;
    static TriangleMesh* site_mesh_;
    static std::vector<std::string>* site_warnings_;  ///< from loading both meshes
    static TriangleMesh* house_;
    static glm::dmat4* house_from_model_;
};

std::string* SampleSite::directory_ = nullptr;
std::vector<std::string>* SampleSite::written_ = nullptr;
SiteConfig* SampleSite::config_ = nullptr;
TriangleMesh* SampleSite::site_mesh_ = nullptr;
std::vector<std::string>* SampleSite::site_warnings_ = nullptr;
TriangleMesh* SampleSite::house_ = nullptr;
glm::dmat4* SampleSite::house_from_model_ = nullptr;

TEST_F(SampleSite, WritesEveryFile) {
    EXPECT_EQ(written_->size(), 5u);
    for (const char* name : {"site.glb", "building.glb", "sky_sunny.hdr", "sky_overcast.hdr", "site.json"}) {
        const std::filesystem::path path = std::filesystem::path(*directory_) / name;
        EXPECT_TRUE(std::filesystem::is_regular_file(path)) << name;
        EXPECT_GT(std::filesystem::file_size(path), 100u) << name;
    }
    // Nothing else (no temporary files left behind by the atomic writes).
    size_t entries = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(*directory_)) ++entries;
    EXPECT_EQ(entries, 5u);
}

TEST_F(SampleSite, MeshesLoadWithoutWarnings) {
    for (const std::string& warning : *site_warnings_) ADD_FAILURE() << warning;
}

TEST_F(SampleSite, SiteJsonSaysWhatWasAsked) {
    EXPECT_EQ(config_->site.name, ss::kSiteName);
    EXPECT_DOUBLE_EQ(config_->site.reference.latitude_deg, 26.2856);
    EXPECT_DOUBLE_EQ(config_->site.reference.longitude_deg, 127.8008);
    EXPECT_EQ(config_->site.utc_offset_minutes, 9 * 60);
    ASSERT_TRUE(config_->sfm_mesh.has_value());
    EXPECT_NEAR(config_->sfm_mesh->rotation_wxyz[0], std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(config_->sfm_mesh->rotation_wxyz[1], std::sqrt(0.5), 1e-12);
    ASSERT_TRUE(config_->overcast_sky.has_value());
    EXPECT_EQ(config_->bake.date, "2026-06-21");
    EXPECT_EQ(config_->bake.samples_per_texel, ss::kSamplesPerTexel);
    EXPECT_DOUBLE_EQ(config_->bake.texels_per_metre, ss::kTexelsPerMetre);
    EXPECT_EQ(config_->bake.max_bounces, 3);
    EXPECT_DOUBLE_EQ(config_->bake.ground_cell_m, 0.5);
    // The default slots: three sunny and one overcast.
    EXPECT_EQ(config_->bake.slots.size(), 4u);
}

TEST_F(SampleSite, SiteMeshLandsInEnuThroughItsTransform) {
    // Written Y-up; site.json's rotation must bring it back: 40 m x 40 m horizontally, about 3 m tall.
    const Bounds3 bounds = meshBounds(*site_mesh_);
    EXPECT_NEAR(bounds.min.x, -20.0, 1e-3);
    EXPECT_NEAR(bounds.max.x, 20.0, 1e-3);
    EXPECT_NEAR(bounds.min.y, -20.0, 1e-3);
    EXPECT_NEAR(bounds.max.y, 20.0, 1e-3);
    EXPECT_GT(bounds.min.z, -1.5);
    EXPECT_LT(bounds.max.z, 3.0);
    EXPECT_GT(site_mesh_->triangleCount(), 1000u);
    EXPECT_LT(site_mesh_->triangleCount(), 10000u);
    // The terrace top is flat at 1.5 m; the ground outside follows naturalGroundHeight.
    const auto terrace = closestHit(*site_mesh_, {5.0, 8.0, 50.0}, {0.0, 0.0, -1.0});
    ASSERT_TRUE(terrace);
    EXPECT_NEAR(50.0 - terrace->distance, ss::kTerraceTopM, 1e-4);
    const auto ground = closestHit(*site_mesh_, {-15.0, -12.0, 50.0}, {0.0, 0.0, -1.0});
    ASSERT_TRUE(ground);
    EXPECT_NEAR(50.0 - ground->distance, ss::naturalGroundHeight(-15.0, -12.0), 0.05);
    // Textured, small textures, no lightmap coordinates.
    for (const ImageRGBA& texture : site_mesh_->textures) EXPECT_LE(std::max(texture.width, texture.height), 256);
    EXPECT_GE(site_mesh_->textures.size(), 2u);
}

TEST_F(SampleSite, HouseHasNoLightmapCoordinates) {
    EXPECT_FALSE(house_->has_uv1);
    const std::string bytes = readWholeFile(config_->building.path);
    EXPECT_EQ(bytes.find("TEXCOORD_1"), std::string::npos);
    EXPECT_NE(bytes.find("TEXCOORD_0"), std::string::npos);
    EXPECT_EQ(house_->textures.size(), 3u);
    for (const ImageRGBA& texture : house_->textures) EXPECT_LE(std::max(texture.width, texture.height), 256);
}

TEST_F(SampleSite, StoredNormalsAgreeWithWinding) {
    for (const TriangleMesh* mesh : {site_mesh_, house_}) {
        for (size_t t = 0; t < mesh->triangleCount(); ++t) {
            const glm::dvec3 normal = geometricNormal(*mesh, t);
            for (int corner = 0; corner < 3; ++corner) {
                const glm::dvec3 stored(mesh->normals[mesh->indices[3 * t + size_t(corner)]]);
                ASSERT_GT(glm::dot(normal, stored), 0.99) << "triangle " << t;
            }
        }
    }
}

TEST_F(SampleSite, HouseFacesPointOutOfTheSolid) {
    // From outside and from inside the room, the first surface a ray meets must face the ray (a front face):
    // that holds only if every exterior face points out and every interior face points into the room.
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const glm::dvec3 room = houseModelToEnu({0.8, 0.6, 1.2});
    const glm::dvec3 centre = houseModelToEnu({0.0, 0.0, 2.0});
    int outside_hits = 0;
    for (int i = 0; i < 300; ++i) {
        const double z = unit(random) * 0.9, phi = (2.0 * std::numbers::pi) * unit(random);
        const glm::dvec3 from = centre + 15.0 * glm::dvec3(std::sqrt(1 - z * z) * std::cos(phi),
                                                           std::sqrt(1 - z * z) * std::sin(phi), z);
        const glm::dvec3 target =
            centre + glm::dvec3(unit(random) * 4 - 2, unit(random) * 4 - 2, unit(random) * 3 - 1.5);
        const glm::dvec3 direction = glm::normalize(target - from);
        if (const auto hit = closestHit(*house_, from, direction)) {
            ++outside_hits;
            ASSERT_LT(glm::dot(direction, geometricNormal(*house_, hit->triangle)), 0.0) << "ray " << i;
        }
    }
    EXPECT_GT(outside_hits, 200);
    for (int i = 0; i < 300; ++i) {
        const double z = 2.0 * unit(random) - 1.0, phi = (2.0 * std::numbers::pi) * unit(random);
        const glm::dvec3 direction{std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z};
        const auto hit = closestHit(*house_, room, direction);
        if (!hit) continue;  // out through the doorway
        ASSERT_LT(glm::dot(direction, geometricNormal(*house_, hit->triangle)), 0.0) << "ray " << i;
    }
}

TEST_F(SampleSite, RoomIsClosedExceptTheDoorway) {
    // Every ray from inside the room that does not head for the doorway hits the house.
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const glm::dvec3 room_model{0.8, 0.6, 1.2};
    const glm::dvec3 room = houseModelToEnu(room_model);
    int escaped = 0;
    for (int i = 0; i < 400; ++i) {
        const double z = 2.0 * unit(random) - 1.0, phi = (2.0 * std::numbers::pi) * unit(random);
        const glm::dvec3 model_direction{std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z};
        const bool towards_front = model_direction.y < 0.0;
        const auto hit = closestHit(*house_, room, houseModelDirectionToEnu(model_direction));
        if (!hit) {
            ++escaped;
            EXPECT_TRUE(towards_front) << "escaped through the back, sides or roof: ray " << i;
        }
    }
    // Through the doorway (below the eaves' line of sight), rays from the room get out: it is open.
    for (double x = -0.35; x <= 0.35; x += 0.1)
        for (double z = 0.4; z <= 1.5; z += 0.1) {
            const glm::dvec3 door_point{x, -ss::kHouseHalfDepthM, z};
            EXPECT_FALSE(closestHit(*house_, room, houseModelDirectionToEnu(glm::normalize(door_point - room_model))))
                << "blocked towards the doorway at x " << x << " z " << z;
        }
}

TEST_F(SampleSite, DoorwayLetsARayIntoTheRoom) {
    const double door_centre_z = 0.5 * (ss::kFloorHeightM + ss::kDoorTopM);
    const glm::dvec3 from = houseModelToEnu({0.0, -ss::kHouseHalfDepthM - 2.0, door_centre_z});
    const glm::dvec3 through_door = houseModelToEnu({0.0, -ss::kHouseHalfDepthM, door_centre_z});
    const glm::dvec3 direction = glm::normalize(through_door - from);
    const auto hit = closestHit(*house_, from, direction);
    ASSERT_TRUE(hit);
    // It passes the front wall (2 m + wall thickness) and stops at the back wall's interior face.
    const double back_wall_distance = 2.0 + 2.0 * ss::kHouseHalfDepthM - ss::kWallThicknessM;
    EXPECT_NEAR(hit->distance, back_wall_distance, 1e-3);
    // Beside the doorway the same ray meets the front wall after 2 m.
    const glm::dvec3 beside = houseModelToEnu({1.5, -ss::kHouseHalfDepthM - 2.0, door_centre_z});
    const auto wall = closestHit(*house_, beside, direction);
    ASSERT_TRUE(wall);
    EXPECT_NEAR(wall->distance, 2.0, 1e-3);
    // Looking down through the doorway from above the threshold, at a slant, reaches the interior floor.
    const glm::dvec3 high = houseModelToEnu({0.0, -ss::kHouseHalfDepthM - 0.3, ss::kDoorTopM - 0.05});
    const glm::dvec3 floor_point = houseModelToEnu({0.0, 0.5, ss::kFloorHeightM});
    const auto floor_hit = closestHit(*house_, high, glm::normalize(floor_point - high));
    ASSERT_TRUE(floor_hit);
    EXPECT_NEAR(floor_hit->distance, glm::length(floor_point - high), 1e-3);
}

TEST_F(SampleSite, HouseStandsOnTheTerrace) {
    const Bounds3 bounds = meshBounds(*house_);
    // Footprint corners and centre: the terrain just below each is within 0.1 m of the house's base.
    for (const glm::dvec3& model : {glm::dvec3(0, 0, 0), glm::dvec3(-3, -2.5, 0), glm::dvec3(3, -2.5, 0),
                                    glm::dvec3(3, 2.5, 0), glm::dvec3(-3, 2.5, 0)}) {
        const glm::dvec3 base = houseModelToEnu(model);
        EXPECT_NEAR(base.z, bounds.min.z, 1e-4);
        const auto below = closestHit(*site_mesh_, base + glm::dvec3(0, 0, 30.0), {0.0, 0.0, -1.0});
        ASSERT_TRUE(below);
        EXPECT_NEAR(base.z + 30.0 - below->distance, base.z, 0.1);
    }
    // The whole roof, eaves included, is over the terrace and clear of the low wall.
    EXPECT_GT(bounds.min.x, ss::kTerraceMinEastM + ss::kLowWallThicknessM);
    EXPECT_LT(bounds.max.x, ss::kTerraceMaxEastM);
    EXPECT_GT(bounds.min.y, ss::kTerraceMinNorthM);
    EXPECT_LT(bounds.max.y, ss::kTerraceMaxNorthM - ss::kLowWallThicknessM);
    // Plausible size: a house about 6 x 5 m with a roof 4-6 m tall.
    EXPECT_GT(bounds.max.z - bounds.min.z, 4.0);
    EXPECT_LT(bounds.max.z - bounds.min.z, 6.5);
}

TEST_F(SampleSite, SkiesLoadAndTheSunIsWhereSpaPutsIt) {
    const ImageRGBA sunny = readRadianceMap(config_->sunny_sky.path);
    const ImageRGBA overcast = readRadianceMap(config_->overcast_sky->path);
    EXPECT_EQ(sunny.width, 1024);
    EXPECT_EQ(sunny.height, 512);
    EXPECT_EQ(overcast.width, 1024);
    EXPECT_EQ(overcast.height, 512);
    int bx = 0, by = 0;
    for (int y = 0; y < sunny.height; ++y)
        for (int x = 0; x < sunny.width; ++x)
            if (sunny.texel(x, y)[1] > sunny.texel(bx, by)[1]) {
                bx = x;
                by = y;
            }
    const glm::dvec3 brightest = equirectDirection((bx + 0.5) / sunny.width, (by + 0.5) / sunny.height,
                                                   config_->sunny_sky.north_azimuth_in_image_deg);
    const glm::dvec3 sun = ss::sunnyPhotoSunDirection();
    EXPECT_GT(sun.z, 0.9);  // near the zenith at noon at 26 deg N on the solstice
    EXPECT_LT(std::acos(std::fmin(1.0, glm::dot(brightest, sun))), 2.0 * std::numbers::pi / 512);
}

// Exit status of a shell command line (0 when it ran and succeeded).
int runCommand(const std::string& command_line) {
    const int status = std::system((command_line + " > /dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SampleCommand, RefusesANonEmptyFolderUnlessForced) {
    const std::string directory = gusuku::testing::makeTemporaryDirectory("sample_cli");
    const std::string keep = directory + "/notes.txt";
    std::ofstream(keep) << "mine";
    const std::string command = "'" + gusuku::testing::bakeExecutablePath() + "' sample '" + directory + "'";
    EXPECT_EQ(runCommand(command), 1);
    EXPECT_FALSE(std::filesystem::exists(directory + "/site.json"));
    EXPECT_EQ(runCommand(command + " --force"), 0);
    EXPECT_TRUE(std::filesystem::exists(directory + "/site.json"));
    EXPECT_TRUE(std::filesystem::exists(keep));  // --force writes beside other files, it does not clear them
    EXPECT_EQ(runCommand(command + " --bogus"), 2);
    // A fresh folder that does not exist yet is created.
    EXPECT_EQ(runCommand("'" + gusuku::testing::bakeExecutablePath() + "' sample '" + directory + "/new'"), 0);
    EXPECT_TRUE(std::filesystem::exists(directory + "/new/site.json"));
}

}  // namespace
