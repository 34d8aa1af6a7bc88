// `gusuku-bake converge` from the command line: the study's table and summary, the forced sky sampling it
// reports, and clear refusals of bad arguments.
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "gusuku/assets/image.h"

#include "bake_command.h"
#include "gpu_test_support.h"
#include "mini_site.h"

namespace {

using gusuku::testing::CommandResult;
using gusuku::testing::runBakeCommand;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class ConvergeCli : public ::testing::Test {
protected:
    void SetUp() override {
        directory_ = gusuku::testing::makeTemporaryDirectory("gusuku-converge-cli");
        site_path_ = gusuku::testing::writeMiniSite(directory_);
    }
    CommandResult converge(const std::vector<std::string>& options) {
        std::vector<std::string> args = {"converge", site_path_};
        args.insert(args.end(), options.begin(), options.end());
        return runBakeCommand(args, directory_);
    }
    std::string directory_;
    std::string site_path_;
};

TEST_F(ConvergeCli, PrintsTheCurveAndTheForcedSkySampling) {
    for (const auto& [option, name] : {std::pair<std::string, std::string>{"mis", "sky sampling: cosine + map (MIS)\n"},
                                       {"cosine", "sky sampling: cosine\n"}}) {
        const CommandResult result = converge(
            {"--slot", "cloudy", "--max-samples", "4", "--reference-samples", "8", "--sky-sampling", option});
        ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
        EXPECT_TRUE(contains(result.stdout_text, "slot cloudy,")) << result.stdout_text;
        EXPECT_TRUE(contains(result.stdout_text, name)) << result.stdout_text;
        EXPECT_TRUE(contains(result.stdout_text, "samples      rays   trace_s   rel_rms")) << result.stdout_text;
        EXPECT_TRUE(contains(result.stdout_text, "log-log slope:")) << result.stdout_text;
        EXPECT_TRUE(contains(result.stdout_text, "trace time to 5.0 % relative RMS:")) << result.stdout_text;
    }
}

// Exit codes as every gusuku-bake command (commands.h): 1 for a bad option value, 2 for bad usage.
TEST_F(ConvergeCli, BadArgumentsNameTheOption) {
    const CommandResult unknown_method = converge({"--sky-sampling", "sometimes"});
    EXPECT_EQ(unknown_method.exit_code, 1);
    EXPECT_TRUE(contains(unknown_method.stderr_text, "--sky-sampling: 'sometimes' is not auto, cosine or mis"))
        << unknown_method.stderr_text;

    const CommandResult zero_samples = converge({"--max-samples", "0"});
    EXPECT_EQ(zero_samples.exit_code, 1);
    EXPECT_EQ(zero_samples.stderr_text, "gusuku-bake converge: --max-samples: 0 is outside [1, 9999999]\n");

    const CommandResult target_one = converge({"--target-rms", "1"});
    EXPECT_EQ(target_one.exit_code, 1);
    EXPECT_EQ(target_one.stderr_text, "gusuku-bake converge: --target-rms: 1 is outside (0, 1)\n");

    const CommandResult missing_value = converge({"--slot"});
    EXPECT_EQ(missing_value.exit_code, 2);
    EXPECT_TRUE(contains(missing_value.stderr_text, "--slot: needs a value")) << missing_value.stderr_text;

    const CommandResult no_site = runBakeCommand({"converge"}, directory_);
    EXPECT_EQ(no_site.exit_code, 2);
    EXPECT_TRUE(contains(no_site.stderr_text, "needs SITE.json")) << no_site.stderr_text;
}

TEST_F(ConvergeCli, MaxSamplesAboveReferenceSamplesIsRefusedBeforeTracing) {
    const CommandResult result = converge({"--max-samples", "16", "--reference-samples", "8"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_TRUE(contains(result.stderr_text, "--max-samples 16 is above --reference-samples 8")) << result.stderr_text;
    EXPECT_FALSE(contains(result.stderr_text, "device")) << "refused before a device was opened: "
                                                         << result.stderr_text;
    EXPECT_TRUE(result.stdout_text.empty()) << result.stdout_text;

    const CommandResult defaults = converge({"--max-samples", "2048"});  // default reference: 1024
    EXPECT_EQ(defaults.exit_code, 2);
    EXPECT_TRUE(contains(defaults.stderr_text, "--max-samples 2048 is above --reference-samples 1024"))
        << defaults.stderr_text;
}

TEST_F(ConvergeCli, UnknownSlotIsAnErrorNamingIt) {
    const CommandResult result = converge({"--slot", "dusk", "--max-samples", "1", "--reference-samples", "1"});
    EXPECT_NE(result.exit_code, 0);
    EXPECT_TRUE(contains(result.stderr_text, "no slot named 'dusk'")) << result.stderr_text;
    EXPECT_TRUE(result.stdout_text.empty()) << result.stdout_text;
}

// --error-mask: the common_* columns hold the errors over the mask's texels only. A mask of every texel must give
// exactly the all-texel columns; a mask of the wrong size or shape is refused, naming the file.
TEST_F(ConvergeCli, ErrorMaskOfEveryTexelMatchesTheAllTexelColumns) {
    const auto writeMask = [&](const std::string& name, int width, int height) {
        gusuku::ImageRGBA mask;
        mask.width = width;
        mask.height = height;
        mask.texels.assign(size_t(width) * size_t(height) * 4, 1.0f);
        const std::string path = directory_ + "/" + name;
        gusuku::writePngSrgb(path, mask);
        return path;
    };
    const std::vector<std::string> study = {"--slot", "cloudy", "--max-samples", "4", "--reference-samples", "8"};
    const auto withMask = [&](const std::string& path) {
        std::vector<std::string> options = study;
        options.insert(options.end(), {"--error-mask", path});
        return converge(options);
    };

    const std::string not_square = writeMask("not_square.png", 4, 2);
    const CommandResult refused_shape = withMask(not_square);
    EXPECT_EQ(refused_shape.exit_code, 1);
    EXPECT_TRUE(contains(refused_shape.stderr_text, not_square + ": size: 4 x 2 is not square"))
        << refused_shape.stderr_text;

    const std::string one_texel = writeMask("one_texel.png", 1, 1);
    const CommandResult refused_size = withMask(one_texel);
    EXPECT_EQ(refused_size.exit_code, 1);
    std::smatch resolution;
    const std::regex lightmap_size("size: 1 texels is not the lightmap's ([0-9]+) x ([0-9]+)");
    ASSERT_TRUE(std::regex_search(refused_size.stderr_text, resolution, lightmap_size)) << refused_size.stderr_text;
    EXPECT_TRUE(contains(refused_size.stderr_text, one_texel)) << refused_size.stderr_text;
    EXPECT_TRUE(refused_size.stdout_text.empty()) << refused_size.stdout_text;

    const int side = std::stoi(resolution[1]);
    const CommandResult result = withMask(writeMask("every_texel.png", side, side));
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    // Every texel of the image: the lightmap's valid ones, and the padding between charts (not valid here).
    std::smatch counts;
    ASSERT_TRUE(std::regex_search(result.stdout_text, counts,
                                  std::regex("([0-9]+) texels valid here .*, ([0-9]+) more not valid here")))
        << result.stdout_text;
    EXPECT_GT(std::stoi(counts[1]), 0);
    EXPECT_EQ(std::stoi(counts[1]) + std::stoi(counts[2]), side * side) << result.stdout_text;
    std::istringstream lines(result.stdout_text);
    std::string line;
    int rows = 0;
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        double samples, rays, trace_s, rms, rms_denoised, denoise_s, scaled, corrected, denoised_corrected;
        double common_corrected, common_denoised_corrected;
        if (!(fields >> samples >> rays >> trace_s >> rms >> rms_denoised >> denoise_s >> scaled >> corrected >>
              denoised_corrected >> common_corrected >> common_denoised_corrected))
            continue;
        ++rows;
        EXPECT_DOUBLE_EQ(common_corrected, corrected) << line;
        EXPECT_DOUBLE_EQ(common_denoised_corrected, denoised_corrected) << line;
    }
    EXPECT_EQ(rows, 3) << "one row per sample count 1, 2, 4:\n" << result.stdout_text;
}

}  // namespace
