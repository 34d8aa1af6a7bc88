#pragma once
// The similarity transform (uniform scale, rotation, translation) that best maps one set of 3D points onto
// another in the least-squares sense: Horn's closed-form solution with unit quaternions (B. K. P. Horn, "Closed-
// form solution of absolute orientation using unit quaternions", JOSA A 4(4), 1987), with the least-squares
// scale of Umeyama (IEEE PAMI 13(4), 1991, eq. 42). `gusuku-bake georef` fits site.json's sfm_mesh transform
// with it from ground control points.

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace gusuku::bake {

/// to = scale * rotation * from + translation (site.json's sfm_mesh: p_enu = t + R (s p_model)).
struct SimilarityTransform {
    double scale = 1.0;
    std::array<double, 4> rotation_wxyz{1, 0, 0, 0};  ///< unit quaternion, w >= 0
    glm::dvec3 translation{0.0};
    glm::dmat3 rotation() const;  ///< the quaternion's matrix
    glm::dvec3 apply(const glm::dvec3& point) const { return scale * (rotation() * point) + translation; }
};

struct SimilarityFit {
    SimilarityTransform transform;
    std::vector<double> residuals_m;  ///< |transform(from[i]) - to[i]|, per point
    double rms_residual_m = 0.0;
    size_t worst_point = 0;           ///< index of the largest residual
};

/// Points that determine no unique similarity: fewer than three, all on one line, or a mirror image.
class DegeneratePoints : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The points' spread across their line, against their spread along it, below which they count as collinear:
/// the middle singular value of the centred points over the largest (a point 2 % of the set's length off the
/// line of the others). The third singular value may be zero: three points always lie on a plane, and that fixes
/// the rotation.
inline constexpr double kCollinearSingularValueRatio = 0.02;
/// A mirrored fit is decided when a mirror image of `from` (one axis negated) fits `to` with an RMS residual
/// below this fraction of the proper fit's: no rotation can then map the one set onto the other.
inline constexpr double kMirrorResidualRatio = 0.5;

/// The least-squares fit of `to` by a similarity of `from` (same length, paired by index). Throws
/// DegeneratePoints, its message saying what is wrong, for fewer than 3 pairs, `from` or `to` collinear
/// (kCollinearSingularValueRatio), or a mirrored pairing (kMirrorResidualRatio).
SimilarityFit fitSimilarity(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to);

/// The singular values of the centred points (the square roots of their scatter matrix's eigenvalues), largest
/// first.
std::array<double, 3> centredSingularValues(const std::vector<glm::dvec3>& points);

}  // namespace gusuku::bake
