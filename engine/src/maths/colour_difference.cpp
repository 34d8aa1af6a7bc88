// CIEDE2000 (gusuku/maths/colour.h), following Sharma, Wu and Dalal (2005) step by step; their equation numbers are in
// the comments. Angles stay in radians throughout (their published values were computed so too), which also
// decides the rounding on the 180-degree boundary that their pairs 13-16 straddle.
#include <cmath>
#include <numbers>

#include "gusuku/maths/colour.h"

namespace gusuku {

namespace {


template <typename T> T radians(T degrees) { return degrees * std::numbers::pi_v<T> / T(180); }

// x^7 by multiplication: defined at 0 and the same operations in colour.glsl (GLSL's pow is exp2(y log2 x)).
template <typename T> T seventhPower(T x) {
    const T x2 = x * x;
    return x2 * x2 * x2 * x;
}

// Hue angle in [0, 2 pi); 0 for the achromatic a' = b' = 0 (eq. 4, note).
template <typename T> T hueAngle(T b, T a_prime) {
    if (b == T(0) && a_prime == T(0)) return T(0);
    const T h = std::atan2(b, a_prime);
    return h < T(0) ? h + T(2) * std::numbers::pi_v<T> : h;
}

template <typename T> T ciede2000T(const glm::vec<3, T>& lab1, const glm::vec<3, T>& lab2) {
    const T two_pi = T(2) * std::numbers::pi_v<T>;
    // 1. a' and C', h' (eqs. 2-7).
    const T c1 = std::sqrt(lab1.y * lab1.y + lab1.z * lab1.z);
    const T c2 = std::sqrt(lab2.y * lab2.y + lab2.z * lab2.z);
    const T c_mean = (c1 + c2) / T(2);
    const T c_mean7 = seventhPower(c_mean);
    const T pow25_7 = T(6103515625);  // 25^7
    const T g = T(0.5) * (T(1) - std::sqrt(c_mean7 / (c_mean7 + pow25_7)));
    const T a1p = (T(1) + g) * lab1.y;
    const T a2p = (T(1) + g) * lab2.y;
    const T c1p = std::sqrt(a1p * a1p + lab1.z * lab1.z);
    const T c2p = std::sqrt(a2p * a2p + lab2.z * lab2.z);
    const T h1p = hueAngle(lab1.z, a1p);
    const T h2p = hueAngle(lab2.z, a2p);

    // 2. Delta L', Delta C', Delta H' (eqs. 8-11).
    const T delta_lp = lab2.x - lab1.x;
    const T delta_cp = c2p - c1p;
    const T chroma_product = c1p * c2p;
    T delta_hp = T(0);
    if (chroma_product != T(0)) {
        delta_hp = h2p - h1p;
        if (delta_hp > std::numbers::pi_v<T>) delta_hp -= two_pi;
        else if (delta_hp < -std::numbers::pi_v<T>) delta_hp += two_pi;
    }
    const T delta_big_hp = T(2) * std::sqrt(chroma_product) * std::sin(delta_hp / T(2));

    // 3. Means, weights and rotation (eqs. 12-17).
    const T l_mean = (lab1.x + lab2.x) / T(2);
    const T cp_mean = (c1p + c2p) / T(2);
    T hp_mean = h1p + h2p;
    if (chroma_product != T(0)) {
        if (std::fabs(h1p - h2p) <= std::numbers::pi_v<T>) hp_mean /= T(2);
        else if (hp_mean < two_pi) hp_mean = (hp_mean + two_pi) / T(2);
        else hp_mean = (hp_mean - two_pi) / T(2);
    }
    const T t = T(1) - T(0.17) * std::cos(hp_mean - radians(T(30))) + T(0.24) * std::cos(T(2) * hp_mean) +
                T(0.32) * std::cos(T(3) * hp_mean + radians(T(6))) -
                T(0.20) * std::cos(T(4) * hp_mean - radians(T(63)));
    const T hue_from_275 = (hp_mean - radians(T(275))) / radians(T(25));
    const T delta_theta = radians(T(30)) * std::exp(-hue_from_275 * hue_from_275);
    const T cp_mean7 = seventhPower(cp_mean);
    const T r_c = T(2) * std::sqrt(cp_mean7 / (cp_mean7 + pow25_7));
    const T l_from_50_sq = (l_mean - T(50)) * (l_mean - T(50));
    const T s_l = T(1) + T(0.015) * l_from_50_sq / std::sqrt(T(20) + l_from_50_sq);
    const T s_c = T(1) + T(0.045) * cp_mean;
    const T s_h = T(1) + T(0.015) * cp_mean * t;
    const T r_t = -std::sin(T(2) * delta_theta) * r_c;

    const T lightness = delta_lp / s_l;  // kL = 1
    const T chroma = delta_cp / s_c;     // kC = 1
    const T hue = delta_big_hp / s_h;    // kH = 1
    return std::sqrt(lightness * lightness + chroma * chroma + hue * hue + r_t * chroma * hue);
}

}  // namespace

double ciede2000(const glm::dvec3& lab1, const glm::dvec3& lab2) { return ciede2000T(lab1, lab2); }
float ciede2000(const glm::vec3& lab1, const glm::vec3& lab2) { return ciede2000T(lab1, lab2); }

}  // namespace gusuku
