// The output guard (issue 39, items 1, 2 and 9; gusuku_bake/output_guard.h): every command that writes refuses,
// before it writes anything, an output that is, holds or lies inside an input of the bake or any bake set or
// pack other than its own previous output, in one line naming the path, with exit 1; every set, pack and input
// is byte-identical afterwards. Its own previous output is still replaced, and a pack is written beside its
// folder and renamed into place, so a failure half-way leaves the old pack whole, manifest and all.
#include <sys/resource.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake_command.h"
#include "bake_process.h"
#include "gpu_test_support.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/site.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/runtime_pack.h"
#include "mini_site.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::CommandResult;
using gusuku::testing::runBakeCommand;

// Every file below `dir` (relative path -> bytes): the independent record that a refusal touched nothing.
std::map<std::string, std::string> filesBelow(const std::string& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        files[fs::relative(entry.path(), dir).string()] = bytes.str();
    }
    return files;
}

std::vector<std::string> namesIn(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// While it lives, files this process and its children write may not grow past `bytes` (a write past it fails with
// EFBIG), and SIGXFSZ is ignored so that the write fails instead of the process dying.
class FileSizeLimit {
public:
    explicit FileSizeLimit(size_t bytes) {
        getrlimit(RLIMIT_FSIZE, &previous_limit_);
        previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
        rlimit limit = previous_limit_;
        limit.rlim_cur = rlim_t(bytes);
        setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &previous_limit_);
        std::signal(SIGXFSZ, previous_handler_);
    }
    FileSizeLimit(const FileSizeLimit&) = delete;
    FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
    rlimit previous_limit_{};
    void (*previous_handler_)(int) = SIG_DFL;
};

// One refused command: exit 1, one line "gusuku-bake: error: OUT: FIELD: ..." holding `problem`, nothing on stdout.
void expectRefused(const CommandResult& result, const std::string& output, const std::string& field,
                   const std::string& problem) {
    const std::string prefix = "gusuku-bake: error: " + output + ": " + (field.empty() ? "" : field + ": ");
    EXPECT_EQ(result.exit_code, 1) << output;
    EXPECT_EQ(result.stderr_text.rfind(prefix, 0), 0u) << "expected '" << prefix << "...', got " << result.stderr_text;
    EXPECT_TRUE(contains(result.stderr_text, problem)) << "expected '" << problem << "' in " << result.stderr_text;
    EXPECT_EQ(std::count(result.stderr_text.begin(), result.stderr_text.end(), '\n'), 1) << result.stderr_text;
    EXPECT_TRUE(result.stdout_text.empty()) << result.stdout_text;
}

class OutputGuardTest : public testing::GpuTest {
protected:
    // The mini site baked once per binary (2 samples) with its pack, and a second set of the same site: each test
    // gets its own copy of all three (the set's input paths are relative, so the copy reads its own site).
    void SetUp() override {
        GpuTest::SetUp();
        if (baked_.empty()) {
            baked_ = testing::makeTemporaryDirectory("gusuku-guard-baked");
            testing::MiniSiteOptions site_options;
            site_options.samples_per_texel = 2;
            testing::writeMiniSite(baked_ + "/site", site_options);
            BakeOptions options;
            options.output_dir = baked_ + "/set";
            options.show_progress = false;
            ASSERT_TRUE(runBake(context(), loadSiteConfig(baked_ + "/site/site.json"), options).completed);
            const CommandResult packed = runBakeCommand({"pack", baked_ + "/set"}, baked_);
            ASSERT_EQ(packed.exit_code, 0) << packed.stderr_text;
            fs::copy(baked_ + "/set", baked_ + "/other", fs::copy_options::recursive);
        }
        dir_ = testing::makeTemporaryDirectory("gusuku-guard");
        fs::copy(baked_, dir_, fs::copy_options::recursive);
        set_ = dir_ + "/set";
        before_ = everything();
    }

    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir_);
        GpuTest::TearDown();
    }

    // The site, both sets and their packs, file by file.
    std::map<std::string, std::string> everything() const {
        std::map<std::string, std::string> files;
        for (const char* part : {"site", "set", "other"})
            for (const auto& [name, bytes] : filesBelow(dir_ + "/" + part)) files[std::string(part) + "/" + name] = bytes;
        return files;
    }

    void expectNothingChanged() const {
        const std::map<std::string, std::string> after = everything();
        EXPECT_EQ(after.size(), before_.size()) << "files were added or removed";
        for (const auto& [name, bytes] : before_) {
            const auto found = after.find(name);
            EXPECT_TRUE(found != after.end() && found->second == bytes) << name << " changed";
        }
    }

    static std::string baked_;
    std::string dir_, set_;
    std::map<std::string, std::string> before_;
};
std::string OutputGuardTest::baked_;

TEST_F(OutputGuardTest, PackOntoItsSetAnotherSetAnInputOrANonFolderIsRefusedAndEverySetStaysByteIdentical) {
    fs::create_directories(dir_ + "/nest/inner");
    fs::copy(set_, dir_ + "/nest/inner/set", fs::copy_options::recursive);
    std::ofstream(dir_ + "/a_file") << "not a folder";
    ASSERT_EQ(::mkfifo((dir_ + "/a_fifo").c_str(), 0644), 0);
    fs::create_directories(dir_ + "/notes");
    std::ofstream(dir_ + "/notes/todo.txt") << "a user's file";
    struct Case {
        std::string output, problem;
    };
    const std::vector<Case> cases = {
        {set_, "is the bake set " + set_},
        {set_ + "/", "is the bake set " + set_},
        {dir_ + "/other", "is the bake set"},
        {dir_ + "/other/pack", "lies inside the bake set"},
        {dir_ + "/other/pack/sub", "lies inside the runtime pack"},
        {set_ + "/sub", "lies inside the bake set " + set_},
        {dir_ + "/site", "holds " + dir_ + "/site/"},
        {dir_, "holds " + dir_ + "/site/"},
        {dir_ + "/nest", "holds the bake set"},
        {dir_ + "/a_file", "is a regular file, not a folder"},
        {dir_ + "/a_fifo", "is a FIFO (named pipe), not a folder"},
        {dir_ + "/notes", "holds files but is not a runtime pack"},
    };
    const std::map<std::string, std::string> nested_before = filesBelow(dir_ + "/nest");
    for (const Case& refused : cases)
        expectRefused(runBakeCommand({"pack", set_, "-o", refused.output}, dir_), refused.output, "-o", refused.problem);
    expectNothingChanged();
    EXPECT_EQ(filesBelow(dir_ + "/nest"), nested_before);
    EXPECT_EQ(namesIn(dir_ + "/notes"), std::vector<std::string>{"todo.txt"});
    EXPECT_EQ(testing::readTextFile(dir_ + "/a_file"), "not a folder");
    EXPECT_NO_THROW(loadBakeSet(set_));
    EXPECT_NO_THROW(loadBakeSet(dir_ + "/other"));
}

TEST_F(OutputGuardTest, ExportOverAnInputOrInsideAnySetOrPackIsRefused) {
    struct Case {
        std::string output, problem;
    };
    const std::vector<Case> cases = {
        {dir_ + "/site/building.glb", "is an input of the export"},
        {set_ + "/pack/x.glb", "lies inside the runtime pack"},
        {set_ + "/sub/x.glb", "lies inside the bake set " + set_},
        {dir_ + "/other/x.glb", "lies inside the bake set"},
    };
    for (const Case& refused : cases)
        expectRefused(runBakeCommand({"export", set_, "--slot", "cloudy", "-o", refused.output}, dir_),
                      refused.output, "", refused.problem);
    expectNothingChanged();
    const CommandResult beside = runBakeCommand({"export", set_, "--slot", "cloudy", "-o", dir_ + "/out/x.glb"}, dir_);
    EXPECT_EQ(beside.exit_code, 0) << beside.stderr_text;
    EXPECT_TRUE(fs::exists(dir_ + "/out/x.glb"));
}

TEST_F(OutputGuardTest, BakeOverAnotherSitesSetOrIntoAPackIsRefusedAndItsOwnSetIsStillItsOwn) {
    testing::MiniSiteOptions site_options;
    site_options.samples_per_texel = 2;
    const SiteConfig second_site = loadSiteConfig(testing::writeMiniSite(dir_ + "/second", site_options));
    struct Case {
        std::string output, problem;
    };
    const std::vector<Case> cases = {
        {set_, "is the bake set of " + fs::canonical(dir_ + "/site/site.json").string()},
        {set_ + "/pack", "is the runtime pack"},
        {set_ + "/sub", "lies inside the bake set"},
    };
    for (const Case& refused : cases) {
        BakeOptions options;
        options.output_dir = refused.output;
        options.show_progress = false;
        try {
            runBake(context(), second_site, options);
            ADD_FAILURE() << "baking the second site into " << refused.output << " was not refused";
        } catch (const InputError& error) {
            EXPECT_EQ(error.file(), refused.output);
            EXPECT_EQ(error.field(), "-o");
            EXPECT_TRUE(contains(error.problem(), refused.problem)) << error.what();
        }
    }
    expectNothingChanged();
    // The set's own site bakes into it as before: up to date, untouched.
    BakeOptions own;
    own.output_dir = set_;
    own.show_progress = false;
    const BakeReport report = runBake(context(), loadSiteConfig(dir_ + "/site/site.json"), own);
    EXPECT_TRUE(report.up_to_date);
    expectNothingChanged();
}

TEST_F(OutputGuardTest, RepackingIntoItsOwnPackReplacesItWhole) {
    const CommandResult again = runBakeCommand({"pack", set_}, dir_);
    ASSERT_EQ(again.exit_code, 0) << again.stderr_text;
    expectNothingChanged();  // the same set gives the same pack, byte for byte
    EXPECT_TRUE(runtimePackIsUpToDate(set_));

    // A pack elsewhere, packed again: replaced whole, so a file only the earlier pack had (a texture of an
    // earlier building, another --textures kind) is gone, and the pack is the set's own pack byte for byte.
    const std::string phone = dir_ + "/phone";
    ASSERT_EQ(runBakeCommand({"pack", set_, "-o", phone}, dir_).exit_code, 0);
    std::ofstream(phone + "/texture_7.ktx2") << "an earlier pack's texture";
    const CommandResult repacked = runBakeCommand({"pack", set_, "-o", phone}, dir_);
    ASSERT_EQ(repacked.exit_code, 0) << repacked.stderr_text;
    EXPECT_EQ(filesBelow(phone), filesBelow(set_ + "/pack"));
    for (const std::string& name : namesIn(dir_))
        EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name << ": a temporary folder was left";
    for (const std::string& name : namesIn(set_))
        EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name << ": a temporary folder was left";
}

TEST_F(OutputGuardTest, AFailureHalfWayThroughAPackLeavesTheOldPackWithItsManifest) {
    const std::string phone = dir_ + "/phone";
    ASSERT_EQ(runBakeCommand({"pack", set_, "-o", phone}, dir_).exit_code, 0);
    const std::map<std::string, std::string> phone_before = filesBelow(phone);
    size_t largest_file_bytes = 0, smallest_file_bytes = SIZE_MAX;
    for (const auto& [name, bytes] : phone_before) {
        largest_file_bytes = std::max(largest_file_bytes, bytes.size());
        smallest_file_bytes = std::min(smallest_file_bytes, bytes.size());
    }
    ASSERT_LT(smallest_file_bytes, largest_file_bytes) << "the pack's files must differ in size for the limit below";
    // A real write failure, with no hook in the product: the commands run with a file-size limit (RLIMIT_FSIZE,
    // which the shell and gusuku-bake inherit) that the pack's small files fit under and its larger lightmaps do
    // not, so a write fails with EFBIG part-way through the pack, as a full disk fails one. SIGXFSZ, whose default
    // action would kill the process instead, is ignored for the time (an ignored signal stays ignored across exec).
    CommandResult into_phone, into_own;
    {
        const FileSizeLimit limit(largest_file_bytes - 1);
        into_phone = runBakeCommand({"pack", set_, "-o", phone}, dir_);
        into_own = runBakeCommand({"pack", set_}, dir_);
    }
    EXPECT_EQ(into_phone.exit_code, 1);
    EXPECT_EQ(into_phone.stderr_text.rfind("gusuku-bake: error: " + phone + "/", 0), 0u) << into_phone.stderr_text;
    EXPECT_TRUE(contains(into_phone.stderr_text, "File too large")) << into_phone.stderr_text;
    EXPECT_EQ(into_own.exit_code, 1) << into_own.stderr_text;
    EXPECT_EQ(filesBelow(phone), phone_before);
    expectNothingChanged();
    EXPECT_TRUE(runtimePackIsUpToDate(set_));
    EXPECT_NO_THROW(loadBakeSet(set_));
    for (const std::string& name : namesIn(dir_))
        EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name << ": a temporary folder was left";
    for (const std::string& name : namesIn(set_))
        EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name << ": a temporary folder was left";
}

TEST_F(OutputGuardTest, AHundredThousandCharacterSlotIsCutInTheMessage) {
    const std::string slot(100000, 's');
    const CommandResult exported = runBakeCommand({"export", set_, "--slot", slot, "-o", dir_ + "/out/x.glb"}, dir_);
    EXPECT_EQ(exported.exit_code, 1);
    EXPECT_TRUE(contains(exported.stderr_text, "(100000 characters)")) << exported.stderr_text.substr(0, 300);
    EXPECT_LT(exported.stderr_text.size(), 400u);
    const CommandResult baked =
        runBakeCommand({"bake", dir_ + "/site/site.json", "-o", dir_ + "/partial", "--slot", slot, "--quiet"}, dir_);
    EXPECT_EQ(baked.exit_code, 1);
    EXPECT_TRUE(contains(baked.stderr_text, "(100000 characters)")) << baked.stderr_text.substr(0, 300);
    EXPECT_LT(baked.stderr_text.size(), 400u);
    expectNothingChanged();
}

// A writer that fails on a full disk (OpenEXR: "File output failed" about the temporary name, errno ENOSPC) is
// reported as a full disk naming the output and its folder, not the temporary file (a bake with 800 KB free
// did that; with a real 800 KB tmpfs the message is the same).
TEST(OutputGuard, AFullDiskIsNamedAsOneWithTheFolderItFills) {
    const std::string dir = testing::makeTemporaryDirectory("gusuku-guard-full");
    const std::string output = dir + "/building_noon.exr";
    std::string temporary;
    try {
        writeFileAtomicallyKeepingExtension(output, [&](const std::string& temporary_path) {
            temporary = temporary_path;
            std::ofstream(temporary_path) << "half an image";
            errno = ENOSPC;
            throw std::runtime_error("Failed to write pixel data to image file \"" + temporary_path +
                                     "\". File output failed.");
        });
        ADD_FAILURE() << "the failed write was not reported";
    } catch (const std::runtime_error& error) {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind(output + ": cannot write: No space left on device (the disk holding " + dir +
                                    " is full",
                                0),
                  0u)
            << message;
        EXPECT_FALSE(contains(message, ".tmp-")) << message;
    }
    EXPECT_FALSE(temporary.empty());
    EXPECT_FALSE(fs::exists(temporary)) << "the temporary file is removed";
    EXPECT_FALSE(fs::exists(output));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gusuku::bake
