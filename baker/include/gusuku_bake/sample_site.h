#pragma once
// The bundled sample site, generated in code so that a fresh clone can run the baker without external assets
// (`gusuku-bake sample DIR`): a terrain patch with a raised limestone terrace, stone steps and a low wall, as
// on a Ryukyu castle (gusuku) terrace; a small thatched house with an open doorway; a clear and an overcast
// analytic sky; and the site.json that ties them together.
//
// Frames: site meshes are built in the site's ENU frame (x east, y north, z up, metres, origin at the site
// reference). The house is built in its own model frame with the same axes (x right, y = the model's north,
// z up), origin at the centre of its base, doorway on the -y (south) side. Both are written as glTF Y-up.

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/maths/mesh.h"

namespace gusuku::bake::sample_site {

// ---- the place and the bake ----
inline constexpr const char* kSiteName = "Nakagusuku sample terrace";
inline constexpr double kLatitudeDeg = 26.2856;
inline constexpr double kLongitudeDeg = 127.8008;
inline constexpr double kHeightM = 160.0;
inline constexpr const char* kUtcOffset = "+09:00";
inline constexpr const char* kBakeDate = "2026-06-21";
/// The clock time at which the sunny sky photo's sun is placed (SPA position at the site on the bake date).
inline constexpr const char* kSunnyPhotoLocalTime = "12:00";

// Bake settings sized for a bake of about a minute on this project's 2-core lavapipe machine: lightmap texels
// at 8 texels/m plus the ground cells, 512 samples, up to 3 bounces, four slots (docs/measurements.md has the
// sample's rays, ray rate and `gusuku-bake converge` errors).
inline constexpr double kTexelsPerMetre = 8.0;
inline constexpr int kSamplesPerTexel = 512;
inline constexpr int kMaxBounces = 3;
inline constexpr int kSeed = 1;
inline constexpr double kGroundCellM = 0.5;

// ---- the terrain and terrace (ENU metres) ----
inline constexpr double kTerrainHalfSizeM = 20.0;  ///< the patch spans -20..20 m east and north
inline constexpr double kTerrainCellM = 1.0;
inline constexpr double kTerraceMinEastM = -8.0, kTerraceMaxEastM = 10.0;
inline constexpr double kTerraceMinNorthM = -4.0, kTerraceMaxNorthM = 12.0;
inline constexpr double kTerraceTopM = 1.5;  ///< flat top, height above the site reference
inline constexpr int kStepRisers = 5;        ///< risers from the ground to the terrace top (4 treads below it)
inline constexpr double kStepTreadM = 0.35;
inline constexpr double kStepWidthM = 3.0;
inline constexpr double kLowWallHeightM = 1.0;
inline constexpr double kLowWallThicknessM = 0.5;

// ---- the house (model frame) ----
inline constexpr double kHouseHalfWidthM = 3.0;   ///< exterior, along x: 6 m
inline constexpr double kHouseHalfDepthM = 2.5;   ///< exterior, along y: 5 m
inline constexpr double kWallThicknessM = 0.2;
inline constexpr double kWallHeightM = 2.4;       ///< exterior face, base to the roof's underside
inline constexpr double kFloorHeightM = 0.3;      ///< raised wooden floor, top surface
inline constexpr double kDoorWidthM = 0.9;
inline constexpr double kDoorTopM = 2.1;          ///< the doorway spans kFloorHeightM..kDoorTopM
inline constexpr double kEaveOverhangM = 0.6;
inline constexpr double kRoofPitchDeg = 45.0;     ///< hip roof
inline constexpr double kThatchThicknessM = 0.3;  ///< measured vertically

/// Where the house's origin stands (ENU) and its compass heading: on the terrace top, its doorway facing
/// 180 + heading degrees (south-south-west), towards the steps.
inline constexpr double kHouseEastM = 2.0, kHouseNorthM = 4.0;
inline constexpr double kHouseHeadingDeg = 12.0;

// ---- the skies ----
inline constexpr int kSkyWidth = 1024, kSkyHeight = 512;
inline constexpr double kSunnyNorthAzimuthInImageDeg = 180.0;  ///< north in the middle of the image
inline constexpr double kOvercastNorthAzimuthInImageDeg = 0.0;

/// Height of the natural ground (outside the terrace) at an ENU position: gentle undulation of +-0.6 m.
double naturalGroundHeight(double east_m, double north_m);

/// The stand-in for the photogrammetry mesh, in ENU: terrain, terrace, steps and low wall, textured
/// (grass/earth and limestone, uv0).
TriangleMesh buildSiteMesh();

/// The house in its model frame (see the file comment), textured (plaster, wood, thatch; uv0 only).
TriangleMesh buildHouseMesh();

/// The house origin's ENU position.
glm::dvec3 houseOriginEnu();

/// Unit ENU direction of the sunny photo's sun: NREL SPA at kSunnyPhotoLocalTime on kBakeDate at the site.
glm::dvec3 sunnyPhotoSunDirection();

/// Writes site.glb, building.glb, sky_sunny.hdr, sky_overcast.hdr and site.json (last) into `directory`
/// (created if missing), each file atomically, overwriting files of those names. Returns the paths written.
std::vector<std::string> writeSampleSite(const std::string& directory);

}  // namespace gusuku::bake::sample_site
