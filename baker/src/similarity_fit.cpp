// Horn's quaternion method (1987) for the rotation, Umeyama's least-squares scale, and a cyclic Jacobi
// eigen-solver for the small symmetric matrices both need (GLM has no eigen-solver or SVD).
#include "gusuku_bake/similarity_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>

namespace gusuku::bake {

namespace {

template <int N>
using Square = std::array<std::array<double, N>, N>;

// Eigenvalues and eigenvectors (vectors[k][i]: component k of the i-th vector) of the symmetric matrix a, by
// cyclic Jacobi rotations (Golub and Van Loan, Matrix Computations, 8.5): each rotation zeroes one off-diagonal
// entry; sweeps repeat until the off-diagonal part is negligible. Exact enough for 3x3 and 4x4 in a few sweeps.
template <int N>
void symmetricEigen(Square<N> a, std::array<double, N>& values, Square<N>& vectors) {
    for (int i = 0; i < N; ++i)
        for (int k = 0; k < N; ++k) vectors[i][k] = i == k ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 64; ++sweep) {
        double off_diagonal = 0.0, diagonal = 0.0;
        for (int p = 0; p < N; ++p) {
            diagonal += a[p][p] * a[p][p];
            for (int q = p + 1; q < N; ++q) off_diagonal += a[p][q] * a[p][q];
        }
        if (off_diagonal <= 1e-30 * diagonal || off_diagonal == 0.0) break;
        for (int p = 0; p < N; ++p)
            for (int q = p + 1; q < N; ++q) {
                if (a[p][q] == 0.0) continue;
                // The rotation's tangent that zeroes a[p][q]: the smaller root of t^2 + 2 theta t - 1 = 0.
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < N; ++k) {  // a = a J
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < N; ++k) {  // a = J^T a
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < N; ++k) {  // vectors = vectors J
                    const double vkp = vectors[k][p], vkq = vectors[k][q];
                    vectors[k][p] = c * vkp - s * vkq;
                    vectors[k][q] = s * vkp + c * vkq;
                }
            }
    }
    for (int i = 0; i < N; ++i) values[i] = a[i][i];
}

// A number with `decimals` digits after the point, for messages.
std::string fixed(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

glm::dvec3 centroid(const std::vector<glm::dvec3>& points) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& point : points) sum += point;
    return sum / double(points.size());
}

// The fit without the degeneracy checks: Horn's rotation of the centred points, Umeyama's scale, then the
// translation that maps centroid onto centroid.
SimilarityFit fitProper(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to) {
    const glm::dvec3 from_centre = centroid(from), to_centre = centroid(to);
    Square<3> s{};  // s[i][j] = sum of a_i b_j over the centred pairs (Horn's S_xy ...)
    double from_spread = 0.0;
    for (size_t n = 0; n < from.size(); ++n) {
        const glm::dvec3 a = from[n] - from_centre, b = to[n] - to_centre;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) s[i][j] += a[i] * b[j];
        from_spread += glm::dot(a, a);
    }
    // Horn's N (eq. 23 of the paper): the unit quaternion maximising sum b . (q a q*) is its eigenvector of the
    // largest eigenvalue.
    const double xx = s[0][0], xy = s[0][1], xz = s[0][2], yx = s[1][0], yy = s[1][1], yz = s[1][2], zx = s[2][0],
                 zy = s[2][1], zz = s[2][2];
    const Square<4> n = {{{xx + yy + zz, yz - zy, zx - xz, xy - yx},
                          {yz - zy, xx - yy - zz, xy + yx, zx + xz},
                          {zx - xz, xy + yx, -xx + yy - zz, yz + zy},
                          {xy - yx, zx + xz, yz + zy, -xx - yy + zz}}};
    std::array<double, 4> values{};
    Square<4> vectors{};
    symmetricEigen<4>(n, values, vectors);
    const int largest = int(std::max_element(values.begin(), values.end()) - values.begin());
    std::array<double, 4> q{vectors[0][largest], vectors[1][largest], vectors[2][largest], vectors[3][largest]};
    const double length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double sign = q[0] < 0 ? -1.0 : 1.0;  // q and -q are the same rotation; keep w >= 0
    for (double& component : q) component *= sign / length;

    SimilarityFit fit;
    fit.transform.rotation_wxyz = q;
    const glm::dmat3 rotation = fit.transform.rotation();
    // Umeyama's scale: the least-squares s for the rotation found, sum b . R a / sum |a|^2.
    double correlation = 0.0;
    for (size_t k = 0; k < from.size(); ++k)
        correlation += glm::dot(to[k] - to_centre, rotation * (from[k] - from_centre));
    fit.transform.scale = correlation / from_spread;
    fit.transform.translation = to_centre - fit.transform.scale * (rotation * from_centre);
    double sum_of_squares = 0.0;
    for (size_t k = 0; k < from.size(); ++k) {
        const double residual = glm::length(fit.transform.apply(from[k]) - to[k]);
        fit.residuals_m.push_back(residual);
        sum_of_squares += residual * residual;
    }
    fit.rms_residual_m = std::sqrt(sum_of_squares / double(from.size()));
    fit.worst_point = size_t(std::max_element(fit.residuals_m.begin(), fit.residuals_m.end()) -
                             fit.residuals_m.begin());
    return fit;
}

void requireNotCollinear(const std::vector<glm::dvec3>& points, const std::string& which) {
    const std::array<double, 3> singular = centredSingularValues(points);
    if (!(singular[0] > 0.0))
        throw DegeneratePoints("the " + which + " positions are all the same point; the points must span a triangle");
    if (singular[1] < kCollinearSingularValueRatio * singular[0])
        throw DegeneratePoints("the " + which + " positions lie on one line (spread across it " +
                               fixed(singular[1] / singular[0] * 100.0, 2) + " % of the spread along it, below " +
                               fixed(kCollinearSingularValueRatio * 100.0, 0) +
                               " %): a rotation about that line is not fixed; add a point away from the line");
}

}  // namespace

glm::dmat3 SimilarityTransform::rotation() const {
    const double w = rotation_wxyz[0], x = rotation_wxyz[1], y = rotation_wxyz[2], z = rotation_wxyz[3];
    glm::dmat3 matrix;  // column-major, as SfmMeshConfig::enuFromModel writes it
    matrix[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    matrix[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
    matrix[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
    return matrix;
}

std::array<double, 3> centredSingularValues(const std::vector<glm::dvec3>& points) {
    const glm::dvec3 centre = centroid(points);
    Square<3> scatter{};
    for (const glm::dvec3& point : points) {
        const glm::dvec3 d = point - centre;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) scatter[i][j] += d[i] * d[j];
    }
    std::array<double, 3> values{};
    Square<3> vectors{};
    symmetricEigen<3>(scatter, values, vectors);
    std::sort(values.begin(), values.end(), [](double a, double b) { return a > b; });
    for (double& value : values) value = std::sqrt(std::max(value, 0.0));
    return values;
}

SimilarityFit fitSimilarity(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to) {
    if (from.size() != to.size()) throw std::invalid_argument("fitSimilarity: the point lists differ in length");
    if (from.size() < 3)
        throw DegeneratePoints(std::to_string(from.size()) +
                               " points given; a scale, rotation and translation need at least 3, not on one line");
    requireNotCollinear(from, "mesh");
    requireNotCollinear(to, "surveyed");
    SimilarityFit fit = fitProper(from, to);
    // A mirror image of the mesh (one axis negated) that fits far better means no rotation maps mesh onto survey.
    std::vector<glm::dvec3> mirrored = from;
    for (glm::dvec3& point : mirrored) point.z = -point.z;
    const SimilarityFit mirror_fit = fitProper(mirrored, to);
    if (mirror_fit.rms_residual_m < kMirrorResidualRatio * fit.rms_residual_m)
        throw DegeneratePoints(
            "the mesh is mirrored: its mirror image fits the survey with an RMS residual of " +
            fixed(mirror_fit.rms_residual_m * 100.0, 2) + " cm against " +
            fixed(fit.rms_residual_m * 100.0, 2) +
            " cm for the best rotation; its axes are left-handed (flip one axis in the photogrammetry tool's export)");
    return fit;
}

}  // namespace gusuku::bake
