// Random numbers and direction sampling shared by the baker's tracer and (later) the bench's reference
// renderer. The generator is a counter-based PCG hash: every (seed, point, sample) triple starts its own
// stream, so a bake is deterministic and a resumed bake draws exactly the numbers an uninterrupted one would.
#ifndef GUSUKU_SAMPLING_GLSL
#define GUSUKU_SAMPLING_GLSL

const float kPi = 3.14159265358979;

uint pcgHash(uint value) {
    uint state = value * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rng { uint state; };

Rng rngForSample(uint seed, uint point_index, uint sample_index) {
    Rng rng;
    rng.state = pcgHash(seed ^ pcgHash(point_index ^ pcgHash(sample_index + 0x9e3779b9u)));
    return rng;
}

// Uniform in [0, 1): 24 high bits of the next PCG output.
float rngNext(inout Rng rng) {
    rng.state = rng.state * 747796405u + 2891336453u;
    uint word = ((rng.state >> ((rng.state >> 28u) + 4u)) ^ rng.state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8u) * (1.0 / 16777216.0);
}

vec2 rngNext2(inout Rng rng) { return vec2(rngNext(rng), rngNext(rng)); }

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
