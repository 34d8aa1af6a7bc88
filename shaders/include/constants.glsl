// Mathematical constants shared by every shader chunk, defined once so that two chunks included into one shader
// never collide and never disagree. The C++ side uses std::numbers; each value here is the float the C++
// constant rounds to (float(std::numbers::pi) == 3.14159265358979323846f), so GLSL and C++ twins compute with
// the same bits. Self-contained: no bindings, no extensions.
#ifndef GUSUKU_CONSTANTS_GLSL
#define GUSUKU_CONSTANTS_GLSL

const float kPi = 3.14159265358979323846;

#endif  // GUSUKU_CONSTANTS_GLSL
