// The tools that time the runtime (gusuku-render, gusuku-bench) start from the runtime's own defaults
// (RuntimeOptions), so that every frame time they print, and every frame-time goal read from them, is the frame an
// app gets without setting anything (issue 44 item 5: the tools had asked for anisotropy 16 while the runtime's
// default is 1, which halved the proposed frame's extra cost on lavapipe and hid the ground ratio's).

#include <gtest/gtest.h>

#include "../bench/render/render_request.h"
#include "bench_run.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku {
namespace {

TEST(ToolDefaults, GusukuRenderAsksForTheRuntimesDefaults) {
    const RuntimeOptions runtime;
    const render_cli::RenderRequest render;
    EXPECT_EQ(render.max_anisotropy, runtime.max_anisotropy);
    EXPECT_EQ(render.msaa_samples, runtime.msaa_samples);
    EXPECT_EQ(render.width, runtime.frame_width);
    EXPECT_EQ(render.height, runtime.frame_height);
    EXPECT_FALSE(render.ground_change_threshold.has_value());  // unset: the runtime's own threshold
}

TEST(ToolDefaults, GusukuBenchAsksForTheRuntimesDefaults) {
    const RuntimeOptions runtime;
    const bench::Settings bench;
    EXPECT_EQ(bench.max_anisotropy, runtime.max_anisotropy);
    EXPECT_EQ(bench.msaa_samples, runtime.msaa_samples);
}

// The value the issue measured: the runtime's default is anisotropy off (an app must enable samplerAnisotropy on
// its device to ask for more), so the tools' frame times are read with it off.
TEST(ToolDefaults, TheRuntimesDefaultAnisotropyIsOff) { EXPECT_EQ(RuntimeOptions{}.max_anisotropy, 1.0f); }

}  // namespace
}  // namespace gusuku
