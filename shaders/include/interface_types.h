// Lets one header declare binding numbers and push-constant blocks for GLSL and C++ at once, so a layout is
// written once (shaders/include/*_interface.h). GLSL includes it through GL_GOOGLE_include_directive, C++
// through the gusuku_shader_interface target.
//
// Rules for an interface block: scalar uint, int and float members, and vec4 and mat4 only at a 16-byte
// offset: std430 and C++ then agree on every offset, which the C++ side pins with static_assert. A vec3 only at
// a 16-byte offset and always followed by a scalar member (named for what it holds) that fills its last 4 bytes:
// std140 and std430 align a vec3 to 16 and pack a following scalar into its tail, which is where C++ puts it.
// (The C++ vec3 and vec4 are not alignas(16), so the struct's size is the GLSL block's size, not padded past it.)
#ifndef GUSUKU_INTERFACE_TYPES_H
#define GUSUKU_INTERFACE_TYPES_H

#ifdef __cplusplus
#include <cstdint>
namespace gusuku::shader_interface {
using uint = std::uint32_t;
struct vec3 {
    float components[3];
    float& operator[](int index) { return components[index]; }
    float operator[](int index) const { return components[index]; }
};
struct vec4 {
    float components[4];
    float& operator[](int index) { return components[index]; }
    float operator[](int index) const { return components[index]; }
};
/// Column-major, as GLSL's mat4 in std140 and std430 (four vec4 columns).
struct mat4 {
    float columns[4][4];
};
}  // namespace gusuku::shader_interface
// C++: a plain struct in gusuku::shader_interface; GLSL: the push-constant block named `instance`.
#define GUSUKU_PUSH_CONSTANTS_BEGIN(BlockName) namespace gusuku::shader_interface { struct BlockName {
#define GUSUKU_PUSH_CONSTANTS_END(BlockName, instance) }; }
// A uniform block (std140; with the rules above its offsets equal std430's and the C++ struct's).
#define GUSUKU_UNIFORM_BLOCK_BEGIN(BlockName, set_number, binding_number) \
    namespace gusuku::shader_interface { struct BlockName {
#define GUSUKU_UNIFORM_BLOCK_END(BlockName, instance) }; }
#else
#define GUSUKU_PUSH_CONSTANTS_BEGIN(BlockName) layout(push_constant) uniform BlockName {
#define GUSUKU_PUSH_CONSTANTS_END(BlockName, instance) } instance;
#define GUSUKU_UNIFORM_BLOCK_BEGIN(BlockName, set_number, binding_number) \
    layout(std140, set = set_number, binding = binding_number) uniform BlockName {
#define GUSUKU_UNIFORM_BLOCK_END(BlockName, instance) } instance;
#endif

#endif
