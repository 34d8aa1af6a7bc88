// Random numbers and direction sampling shared by the baker's tracer and (later) the bench's reference
// renderer. Every (seed, point, sample) triple has its own fixed numbers, so a bake is deterministic and a
// resumed bake draws exactly the numbers an uninterrupted one would.
//
// 2D draws (directions on the sky, the cosine lobe, the sun disc) come from a scrambled Sobol sequence:
// Sobol's first two dimensions, a (0,2)-sequence, so the first N samples of a point stratify the square; each
// 2D draw of a path (each bounce, each light) gets its own random scramble and its own shuffle of the sample
// index ("padding"), by hash-based nested uniform scrambling after Burley (2020, "Practical hash-based Owen
// scrambling"). Measured on the sample site: the error at a given sample count falls much faster than with
// independent random numbers. 1D draws (Russian roulette) use a counter-based PCG hash.
#ifndef GUSUKU_SAMPLING_GLSL
#define GUSUKU_SAMPLING_GLSL

#include "constants.glsl"

uint pcgHash(uint value) {
    uint state = value * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rng {
    uint state;         // PCG state for 1D draws
    uint point_seed;    // hash of (seed, point): the point's own scrambles
    uint sample_index;  // index into the point's Sobol sequence
    uint dimension;     // how many 2D draws this path has made
};

Rng rngForSample(uint seed, uint point_index, uint sample_index) {
    Rng rng;
    rng.point_seed = pcgHash(seed ^ pcgHash(point_index + 0x68bc21ebu));
    rng.sample_index = sample_index;
    rng.dimension = 0u;
    rng.state = pcgHash(rng.point_seed ^ pcgHash(sample_index + 0x9e3779b9u));
    return rng;
}

// Uniform in [0, 1): 24 high bits of the next PCG output.
float rngNext(inout Rng rng) {
    rng.state = rng.state * 747796405u + 2891336453u;
    uint word = ((rng.state >> ((rng.state >> 28u) + 4u)) ^ rng.state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8u) * (1.0 / 16777216.0);
}

// A hash that only moves bits towards the most significant end (Laine and Karras 2011): applied to a
// bit-reversed value it is a nested uniform (Owen) scramble.
uint laineKarrasPermutation(uint value, uint seed) {
    value += seed;
    value ^= value * 0x6c50b47cu;
    value ^= value * 0xb82f1e52u;
    value ^= value * 0xc7afe638u;
    value ^= value * 0x8d22f6e6u;
    return value;
}

uint nestedUniformScramble(uint value, uint seed) {
    return bitfieldReverse(laineKarrasPermutation(bitfieldReverse(value), seed));
}

// Sobol dimension 1 (dimension 0 is the bit reversal of the index): generator matrix by its recurrence.
uint sobolSecondDimension(uint index) {
    uint result = 0u;
    uint direction = 1u << 31u;
    for (; index != 0u; index >>= 1u, direction ^= direction >> 1u)
        if ((index & 1u) != 0u) result ^= direction;
    return result;
}

// The 2D draw of the current dimension at an index of the point's sequence; the dimension does not advance.
vec2 rngDraw2At(Rng rng, uint index) {
    uint pair_seed = pcgHash(rng.point_seed ^ pcgHash(rng.dimension + 0x2c1b3c6du));
    uint shuffled_index = nestedUniformScramble(index, pair_seed);
    uint x = nestedUniformScramble(bitfieldReverse(shuffled_index), pcgHash(pair_seed ^ 0xa511e9b3u));
    uint y = nestedUniformScramble(sobolSecondDimension(shuffled_index), pcgHash(pair_seed ^ 0x63d83595u));
    // 24 bits, so the result stays below 1 in float.
    return vec2(float(x >> 8u), float(y >> 8u)) * (1.0 / 16777216.0);
}

// Draw k of `count` (a power of two) for this sample: index sample * count + k of the current dimension's
// sequence, so the count draws of a sample are one aligned block of the scrambled Sobol sequence (stratified
// among themselves, and all samples' draws together one longer sequence). The caller advances rng.dimension
// once after the last.
vec2 rngNext2Split(Rng rng, uint k, uint count) { return rngDraw2At(rng, rng.sample_index * count + k); }

vec2 rngNext2(inout Rng rng) {
    vec2 draw = rngDraw2At(rng, rng.sample_index);
    rng.dimension++;
    return draw;
}

// Orthonormal basis around a unit normal (Duff et al. 2017, branchless).
void buildBasis(vec3 normal, out vec3 tangent, out vec3 bitangent) {
    float sign_z = normal.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sign_z + normal.z);
    float b = normal.x * normal.y * a;
    tangent = vec3(1.0 + sign_z * normal.x * normal.x * a, sign_z * b, -sign_z * normal.x);
    bitangent = vec3(b, sign_z + normal.y * normal.y * a, -normal.y);
}

// Cosine-weighted direction about `normal`; pdf over solid angle = cos / pi.
vec3 sampleCosineHemisphere(vec3 normal, vec2 xi) {
    float radius = sqrt(xi.x);
    float phi = 2.0 * kPi * xi.y;
    vec3 tangent, bitangent;
    buildBasis(normal, tangent, bitangent);
    float z = sqrt(max(0.0, 1.0 - xi.x));
    return normalize(tangent * (radius * cos(phi)) + bitangent * (radius * sin(phi)) + normal * z);
}

// Uniform direction inside a cone of half-angle acos(cos_max) about `axis`.
vec3 sampleCone(vec3 axis, float cos_max, vec2 xi) {
    float cos_theta = 1.0 - xi.x * (1.0 - cos_max);
    float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
    float phi = 2.0 * kPi * xi.y;
    vec3 tangent, bitangent;
    buildBasis(axis, tangent, bitangent);
    return normalize(tangent * (sin_theta * cos(phi)) + bitangent * (sin_theta * sin(phi)) + axis * cos_theta);
}

// Veach's power heuristic (beta = 2) for two strategies.
float powerHeuristic(float pdf_this, float pdf_other) {
    float a = pdf_this * pdf_this;
    float b = pdf_other * pdf_other;
    return a + b > 0.0 ? a / (a + b) : 0.0;
}

#endif
