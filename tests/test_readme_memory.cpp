// README.md's "Memory" requirement states the device memory the runtime holds for the sample at the default options
// and with msaa_samples 1. This test bakes the sample site (at a few samples a texel: the sample count changes no
// image's size, so not the memory), opens the runtime on it as gusuku-render does, and holds the README's figures to
// Runtime::deviceMemoryBytes within their rounding, so the README's claim is checked like code. The figures are
// lavapipe's (the README's machine): another device's alignments give other sizes, and the test skips there.

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/site.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/sample_site.h"

namespace gusuku {
namespace {

constexpr int kBakeSamples = 8;                   // the sizes depend on the site's texel density, not on this
constexpr double kReadmeRoundingMiB = 0.05 + 1e-9;  // the README gives one decimal

std::string readmePath() { return std::string(GUSUKU_GOLDEN_DIR) + "/../../README.md"; }

/// The "N.N MiB" figures of README.md's **Memory** bullet, in the order they appear.
std::vector<double> readmeMemoryMiB() {
    std::ifstream file(readmePath());
    std::stringstream text;
    text << file.rdbuf();
    const std::string readme = text.str();
    const size_t start = readme.find("- **Memory**");
    if (start == std::string::npos) return {};
    const size_t end = readme.find("\n- ", start + 1);  // the next bullet ends this one
    const std::string bullet = readme.substr(start, end == std::string::npos ? std::string::npos : end - start);
    std::vector<double> figures;
    const std::regex mebibytes(R"(([0-9]+\.[0-9]) MiB)");
    for (auto match = std::sregex_iterator(bullet.begin(), bullet.end(), mebibytes); match != std::sregex_iterator();
         ++match)
        figures.push_back(std::stod((*match)[1].str()));
    return figures;
}

class ReadmeMemory : public testing::GpuTest {
protected:
    double heldMiB(const BakeSetData& bake_set, uint32_t msaa_samples) {
        RuntimeOptions options;  // the defaults: 1280 x 720, two 1024^2 shadow maps, 4x multisampling
        options.msaa_samples = msaa_samples;
        const std::unique_ptr<Runtime> runtime = Runtime::open(context(), bake_set, options);
        return double(runtime->deviceMemoryBytes()) / double(1 << 20);
    }
};

TEST_F(ReadmeMemory, FiguresAreWhatTheRuntimeHoldsForTheSample) {
    if (context().deviceDescription().find("llvmpipe") == std::string::npos)
        GTEST_SKIP() << "README's memory figures are lavapipe's; this device is " << context().deviceDescription();
    const std::vector<double> stated = readmeMemoryMiB();
    ASSERT_EQ(stated.size(), 2u) << readmePath() << ": the **Memory** bullet should give two \"N.N MiB\" figures "
                                 << "(the defaults, then msaa_samples 1)";

    const std::string dir = testing::makeTemporaryDirectory("gusuku-readme-memory");
    bake::sample_site::writeSampleSite(dir + "/sample");
    bake::BakeOptions options;
    options.output_dir = dir + "/bakeset";
    options.samples_override = kBakeSamples;
    options.denoise = false;
    options.show_progress = false;
    ASSERT_TRUE(bake::runBake(context(), loadSiteConfig(dir + "/sample/site.json"), options).completed);
    const BakeSetData bake_set = loadBakeSet(options.output_dir);

    const RuntimeOptions defaults;
    ASSERT_EQ(defaults.frame_width, 1280u);  // what the README says the defaults are
    ASSERT_EQ(defaults.frame_height, 720u);
    ASSERT_EQ(defaults.shadow_map_size, 1024u);
    ASSERT_EQ(defaults.msaa_samples, 4u);
    const double at_defaults = heldMiB(bake_set, defaults.msaa_samples);
    const double single_sampled = heldMiB(bake_set, 1);
    EXPECT_NEAR(stated[0], at_defaults, kReadmeRoundingMiB) << "README.md's figure at the default options";
    EXPECT_NEAR(stated[1], single_sampled, kReadmeRoundingMiB) << "README.md's figure with msaa_samples 1";
}

}  // namespace
}  // namespace gusuku
