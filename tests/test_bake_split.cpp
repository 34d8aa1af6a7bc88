// Bakes that split across machines (issue 11, item 8): the Kubernetes Indexed Job of deploy/kubernetes/ run here
// as separate processes. One `gusuku-bake bake --slot NAME` process per slot of a small site, then `gusuku-bake
// merge`, gives the bytes of a one-process bake of the same site (every file; the manifest's statistics, this
// run's rays and seconds, are the one field that may differ, and its rays must still add up). The merge
// refuses a missing slot, a slot given twice, partial sets of other inputs, shared files that differ, and a
// whole bake set, each with one FILE: FIELD: PROBLEM line and nothing written. A partial bake stopped and
// resumed gives the same bytes. A bake set stores its inputs' paths relative to itself, so a set moved with
// its inputs finds them, and an older manifest with absolute paths still loads.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_command.h"
#include "bake_process.h"
#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/bake_merge.h"
#include "gusuku_bake/content_hash.h"
#include "mini_site.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;
using gusuku::ImageEncoding;
using gusuku::ImageRGBA;
using gusuku::readImage;
using gusuku::writeExr;
using gusuku::testing::CommandResult;
using gusuku::testing::GpuTest;
using gusuku::testing::readTextFile;

constexpr double kProcessTimeoutSeconds = 300.0;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Relative path -> bytes, for every regular file under dir but the empty .lock (it only holds the flock).
std::map<std::string, std::string> filesUnder(const std::string& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file() && entry.path().filename() != ".lock")
            files[fs::relative(entry.path(), dir).string()] = readTextFile(entry.path().string());
    return files;
}

/// Every file byte for byte; the manifests byte for byte once `actual`'s statistics are set to `expected`'s
/// (the shared writer reproduces a manifest's bytes from what the reader got, test_bakeset_manifest.cpp).
void expectSameBakeSet(const std::string& expected_dir, const std::string& actual_dir) {
    const auto expected = filesUnder(expected_dir);
    const auto actual = filesUnder(actual_dir);
    std::vector<std::string> expected_names, actual_names;
    for (const auto& entry : expected) expected_names.push_back(entry.first);
    for (const auto& entry : actual) actual_names.push_back(entry.first);
    ASSERT_EQ(expected_names, actual_names);
    for (const auto& [name, bytes] : expected) {
        std::string other = actual.at(name);
        if (name == "manifest.json") {
            BakeSetManifest manifest = parseBakeSetManifest(actual_dir + "/" + name, other);
            manifest.statistics = parseBakeSetManifest(expected_dir + "/" + name, bytes).statistics;
            other = bakeSetManifestJson(manifest);
        }
        ASSERT_EQ(bytes.size(), other.size()) << name;
        const auto mismatch = std::mismatch(bytes.begin(), bytes.end(), other.begin());
        EXPECT_TRUE(mismatch.first == bytes.end())
            << name << ": first differing byte at offset " << (mismatch.first - bytes.begin());
    }
}

/// A small site (the mini site with an SfM mesh, so the occluder is one of the shared files) baked four ways,
/// once per test program, every bake its own process, all running at once as the Job's pods would: one partial
/// set per slot; the whole site; slots[1] from a byte copy of the site in another folder (a machine that mounts
/// it elsewhere); slots[1] from a copy whose site.json has another seed (other inputs).
struct SplitBakes {
    std::string dir;
    std::string site;
    std::vector<std::string> slots;
    std::vector<std::string> partials;  ///< dir/partials/<slot>
    std::string single;                 ///< dir/single: the one-process bake
    std::string mounted_partial;        ///< slots[1] of dir/mounted/site.json, the same bytes
    std::string foreign_partial;        ///< slots[1] of dir/changed/site.json, bake.seed + 1
};

/// Copies the site's files (not the bake sets) from `from` into the new folder `to`; returns its site.json.
std::string copySite(const std::string& from, const std::string& to) {
    fs::create_directories(to);
    for (const auto& entry : fs::directory_iterator(from))
        if (entry.is_regular_file() && entry.path().extension() != ".err")
            fs::copy(entry.path(), to / entry.path().filename());
    return to + "/site.json";
}

const SplitBakes& splitBakes() {
    static const SplitBakes bakes = [] {
        SplitBakes b;
        b.dir = gusuku::testing::makeTemporaryDirectory("gusuku-split");
        gusuku::testing::MiniSiteOptions options;
        options.samples_per_texel = 4;
        options.with_sfm_mesh = true;
        b.site = gusuku::testing::writeMiniSite(b.dir, options);
        for (const BakeSlot& slot : loadSiteConfig(b.site).bake.slots) b.slots.push_back(slot.name);
        b.single = b.dir + "/single";
        const std::string mounted_site = copySite(b.dir, b.dir + "/mounted");
        const std::string changed_site = copySite(b.dir, b.dir + "/changed");
        nlohmann::json changed = nlohmann::json::parse(readTextFile(changed_site));
        changed["bake"]["seed"] = changed["bake"].value("seed", 1) + 1;
        std::ofstream(changed_site, std::ios::trunc) << changed.dump(2);
        b.mounted_partial = b.dir + "/mounted_partials/" + b.slots.at(1);
        b.foreign_partial = b.dir + "/foreign/" + b.slots.at(1);
        std::vector<std::pair<std::string, pid_t>> runs;
        for (const std::string& slot : b.slots) {
            b.partials.push_back(b.dir + "/partials/" + slot);
            runs.push_back({slot, gusuku::testing::spawnBakeProcess(
                                      {"bake", b.site, "-o", b.partials.back(), "--slot", slot, "--quiet"}, "/dev/null",
                                      b.dir + "/" + slot + ".err")});
        }
        runs.push_back({"single", gusuku::testing::spawnBakeProcess({"bake", b.site, "-o", b.single, "--quiet"},
                                                                    "/dev/null", b.dir + "/single.err")});
        runs.push_back({"mounted", gusuku::testing::spawnBakeProcess(
                                       {"bake", mounted_site, "-o", b.mounted_partial, "--slot", b.slots.at(1), "--quiet"},
                                       "/dev/null", b.dir + "/mounted.err")});
        runs.push_back({"foreign", gusuku::testing::spawnBakeProcess(
                                       {"bake", changed_site, "-o", b.foreign_partial, "--slot", b.slots.at(1), "--quiet"},
                                       "/dev/null", b.dir + "/foreign.err")});
        for (const auto& [name, pid] : runs) {
            const int exit_code = gusuku::testing::waitBakeProcess(pid, kProcessTimeoutSeconds);
            EXPECT_EQ(exit_code, 0) << name << ": " << readTextFile(b.dir + "/" + name + ".err");
        }
        return b;
    }();
    return bakes;
}

class BakeSplitTest : public GpuTest {
protected:
    /// `gusuku-bake merge PARTIALS... -o out`.
    CommandResult merge(const std::vector<std::string>& partials, const std::string& out) {
        std::vector<std::string> args = {"merge"};
        args.insert(args.end(), partials.begin(), partials.end());
        args.insert(args.end(), {"-o", out});
        return gusuku::testing::runBakeCommand(args, scratch_);
    }

    /// A refused merge: exit 1, one line "gusuku-bake: error: FILE: FIELD: PROBLEM" naming file and field, and
    /// no output folder created.
    void expectRefused(const std::vector<std::string>& partials, const std::string& file, const std::string& field,
                       const std::string& problem_part) {
        const std::string out = scratch_ + "/refused";
        const CommandResult result = merge(partials, out);
        EXPECT_EQ(result.exit_code, 1) << result.stderr_text;
        const std::string prefix = "gusuku-bake: error: " + file + ": " + (field.empty() ? "" : field + ": ");
        EXPECT_EQ(result.stderr_text.rfind(prefix, 0), 0u) << result.stderr_text << "expected to start with " << prefix;
        EXPECT_TRUE(contains(result.stderr_text, problem_part)) << result.stderr_text;
        EXPECT_EQ(std::count(result.stderr_text.begin(), result.stderr_text.end(), '\n'), 1) << result.stderr_text;
        EXPECT_FALSE(fs::exists(out)) << "a refused merge must write nothing";
    }

    std::string scratch_ = gusuku::testing::makeTemporaryDirectory("gusuku-split-run");
};

TEST_F(BakeSplitTest, OneProcessPerSlotThenMergeWritesTheOneProcessBakeSet) {
    const SplitBakes& bakes = splitBakes();
    ASSERT_GE(bakes.slots.size(), 2u);

    // Each partial set: its slot's files and the shared ones, a manifest marked partial naming its slot.
    uint64_t partial_rays = 0;
    for (size_t i = 0; i < bakes.slots.size(); ++i) {
        SCOPED_TRACE(bakes.slots[i]);
        const BakeSetManifest manifest = readBakeSetManifest(bakes.partials[i] + "/manifest.json");
        ASSERT_TRUE(manifest.partial.has_value());
        EXPECT_EQ(manifest.partial->slot, bakes.slots[i]);
        EXPECT_EQ(manifest.partial->site_slots, bakes.slots);
        EXPECT_EQ(manifest.partial->slot_independent_hash, slotIndependentFilesHash(bakes.partials[i], manifest));
        ASSERT_EQ(manifest.slots.size(), 1u);
        EXPECT_TRUE(fs::exists(bakes.partials[i] + "/building_" + bakes.slots[i] + ".exr"));
        EXPECT_TRUE(fs::exists(bakes.partials[i] + "/occluder.glb"));
        for (const std::string& other : bakes.slots) {
            if (other == bakes.slots[i]) continue;
            EXPECT_FALSE(fs::exists(bakes.partials[i] + "/building_" + other + ".exr")) << other;
        }
        partial_rays += manifest.statistics.rays_traced;
        // A partial set is not a bake set the runtime can draw.
        try {
            loadBakeSet(bakes.partials[i]);
            ADD_FAILURE() << "a partial set must be refused by the loader";
        } catch (const InputError& error) {
            EXPECT_EQ(error.field(), "/partial");
            EXPECT_TRUE(contains(error.what(), "gusuku-bake merge")) << error.what();
        }
    }

    // Merged in the opposite order to the site's: the merge orders the slots as site.json does.
    std::vector<std::string> reversed(bakes.partials.rbegin(), bakes.partials.rend());
    const std::string merged = bakes.dir + "/merged";
    const CommandResult result = merge(reversed, merged);
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    EXPECT_TRUE(contains(result.stdout_text, std::to_string(bakes.slots.size()) + ", from")) << result.stdout_text;
    // merged sits beside single, so even the relative input paths ("../site.json") are the same text.
    expectSameBakeSet(bakes.single, merged);

    // The statistics: the work of all the machines. Every sample's rays are a pure function of its indices, so
    // the partial bakes traced exactly the rays of the one-process bake.
    const BakeSetManifest whole = readBakeSetManifest(merged + "/manifest.json");
    EXPECT_FALSE(whole.partial.has_value());
    EXPECT_EQ(whole.statistics.rays_traced, partial_rays);
    EXPECT_EQ(whole.statistics.rays_traced, readBakeSetManifest(bakes.single + "/manifest.json").statistics.rays_traced);
    const BakeSetData data = loadBakeSet(merged);
    EXPECT_EQ(data.slots.size(), bakes.slots.size());

    // A slot baked on a machine that sees the site at another place has the same input hash (inputs are named
    // relative to site.json's folder) and merges into the same bytes, the first set's input paths kept.
    const std::string merged_mounted = bakes.dir + "/merged_mounted";
    const CommandResult mounted = merge({bakes.partials[0], bakes.mounted_partial}, merged_mounted);
    ASSERT_EQ(mounted.exit_code, 0) << mounted.stderr_text;
    EXPECT_NE(readBakeSetManifest(bakes.mounted_partial + "/manifest.json").inputs[0].path,
              readBakeSetManifest(bakes.partials[1] + "/manifest.json").inputs[0].path);
    expectSameBakeSet(bakes.single, merged_mounted);

    // A second bake of the site into the merged folder has nothing to do: the merge wrote the whole bake's hash.
    const CommandResult rerun = gusuku::testing::runBakeCommand({"bake", bakes.site, "-o", merged}, scratch_);
    EXPECT_EQ(rerun.exit_code, 0) << rerun.stderr_text;
    EXPECT_TRUE(contains(rerun.stdout_text, "up to date")) << rerun.stdout_text;
}

TEST_F(BakeSplitTest, MergeRefusesMissingAndRepeatedSlotsOtherInputsAndChangedSharedFiles) {
    const SplitBakes& bakes = splitBakes();
    const std::string& first = bakes.partials.at(0);
    const std::string& second = bakes.partials.at(1);

    expectRefused({first}, first + "/manifest.json", "/partial/site_slots",
                  "slot \"" + bakes.slots[1] + "\" is in none of the 1 partial sets");
    expectRefused({first, second, first}, first + "/manifest.json", "/partial/slot",
                  "slot \"" + bakes.slots[0] + "\" is also the slot of");
    // The foreign partial's site.json differs (its seed): another input hash.
    expectRefused({first, bakes.foreign_partial}, bakes.foreign_partial + "/manifest.json", "/input_hash",
                  "the partial sets were baked from different inputs or settings");
    expectRefused({first, bakes.single}, bakes.single + "/manifest.json", "/partial",
                  "this is a whole bake set, not one slot's partial set");
    expectRefused({first, scratch_}, scratch_ + "/manifest.json", "", "file not found");

    // Shared files must be the ones the bake recorded, and the same in every set: the merge hashes them.
    const std::string tampered = scratch_ + "/tampered";
    fs::copy(second, tampered);
    std::string glb = readTextFile(tampered + "/building.glb");
    glb[glb.size() - 1] = char(glb[glb.size() - 1] ^ 1);
    fs::remove(tampered + "/building.glb");
    {
        std::ofstream file(tampered + "/building.glb", std::ios::binary);
        file << glb;
    }
    expectRefused({first, tampered}, tampered + "/manifest.json", "/partial/slot_independent_hash",
                  "they changed after the bake");
    // ... and a set whose manifest agrees with its changed files still differs from the first set's.
    BakeSetManifest manifest = readBakeSetManifest(tampered + "/manifest.json");
    manifest.partial->slot_independent_hash = slotIndependentFilesHash(tampered, manifest);
    writeBakeSetManifest(tampered + "/manifest.json", manifest);
    expectRefused({first, tampered}, tampered + "/manifest.json", "/partial/slot_independent_hash",
                  "the partial bakes disagree");

    // The output may not be one of the partial sets.
    const CommandResult into_partial = merge({first, second}, first);
    EXPECT_EQ(into_partial.exit_code, 1);
    EXPECT_EQ(into_partial.stderr_text.rfind("gusuku-bake: error: " + first + ": -o: is the partial set", 0), 0u)
        << into_partial.stderr_text;
    EXPECT_TRUE(readBakeSetManifest(first + "/manifest.json").partial.has_value()) << "the partial set is untouched";
}

// Each slot's own files are read and checked as the loader reads a bake set before anything is merged: a
// truncated, empty, resized or NaN lightmap used to merge with exit 0 into a set that then failed to load.
TEST_F(BakeSplitTest, MergeRefusesSlotFilesTheLoaderWouldRefuse) {
    const SplitBakes& bakes = splitBakes();
    const std::string& first = bakes.partials.at(0);
    const std::string& second = bakes.partials.at(1);
    const std::string lightmap = readBakeSetManifest(second + "/manifest.json").slots.at(0).building_irradiance;
    int variant = 0;
    // A copy of the second partial set with its lightmap changed by `change`; the merge must name that file.
    auto expectLightmapRefused = [&](const std::function<void(const std::string& path)>& change,
                                     const std::string& problem_part) {
        const std::string broken = scratch_ + "/broken" + std::to_string(variant++);
        fs::copy(second, broken);
        change(broken + "/" + lightmap);
        expectRefused({first, broken}, broken + "/" + lightmap, "", problem_part);
    };
    expectLightmapRefused([](const std::string& path) { fs::resize_file(path, fs::file_size(path) / 2); }, "");
    expectLightmapRefused([](const std::string& path) { fs::resize_file(path, 0); }, "");
    expectLightmapRefused(
        [](const std::string& path) {
            ImageRGBA image = readImage(path, ImageEncoding::Linear);
            image.texel(1, 2)[0] = std::numeric_limits<float>::quiet_NaN();
            writeExr(path, image, true);
        },
        "NaN");
    expectLightmapRefused(
        [](const std::string& path) {
            ImageRGBA image = readImage(path, ImageEncoding::Linear);
            ImageRGBA smaller;
            smaller.width = image.width - 1;
            smaller.height = image.height;
            smaller.texels.assign(size_t(smaller.width) * size_t(smaller.height) * 4, 1.0f);
            writeExr(path, smaller, true);
        },
        "texels");
}

// A partial set records the hash of its own slot (its manifest entry and files): an edited sun irradiance, which
// every reader accepts as a value, is refused because it is not what the bake wrote.
TEST_F(BakeSplitTest, MergeRefusesAnEditedSlotEntry) {
    const SplitBakes& bakes = splitBakes();
    const std::string& first = bakes.partials.at(0);
    const std::string& second = bakes.partials.at(1);
    const std::string edited = scratch_ + "/edited";
    fs::copy(second, edited);
    BakeSetManifest manifest = readBakeSetManifest(edited + "/manifest.json");
    ASSERT_TRUE(manifest.partial && manifest.partial->slot_hash) << "a partial set records its slot's hash";
    EXPECT_EQ(*manifest.partial->slot_hash, slotHash(second, manifest.slots.front()));
    manifest.slots.front().sun.present = manifest.slots.front().sky == gusuku::BakeSetSky::Sunny;
    manifest.slots.front().sun.irradiance_rgb = glm::dvec3(1e6);
    if (!manifest.slots.front().sun.present) manifest.slots.front().invalid_texels += 1;  // an overcast slot
    writeBakeSetManifest(edited + "/manifest.json", manifest);
    expectRefused({first, edited}, edited + "/manifest.json", "/partial/slot_hash", "it changed after the bake");
}

// An output folder that cannot be made (here under a regular file; a read-only file system alike) is one line
// naming it and the reason, not the library's "filesystem error: cannot create directories".
TEST_F(BakeSplitTest, MergeIntoAFolderThatCannotBeMadeSaysWhy) {
    const SplitBakes& bakes = splitBakes();
    const std::string file = scratch_ + "/a_file";
    std::ofstream(file) << "not a folder";
    std::vector<std::string> partials = bakes.partials;
    const CommandResult result = merge(partials, file + "/merged");
    EXPECT_EQ(result.exit_code, 1) << result.stderr_text;
    EXPECT_EQ(result.stderr_text,
              "gusuku-bake: error: " + file + "/merged: -o: cannot create the folder: Not a directory\n");
}

TEST_F(BakeSplitTest, SlotOptionNamesASlotOfTheSiteAndAFinishedPartialIsUpToDate) {
    const SplitBakes& bakes = splitBakes();
    const std::string out = scratch_ + "/unknown";
    const CommandResult unknown =
        gusuku::testing::runBakeCommand({"bake", bakes.site, "-o", out, "--slot", "dusk"}, scratch_);
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_EQ(unknown.stderr_text.rfind("gusuku-bake: error: " + bakes.site + ": /bake/slots: has no slot \"dusk\"", 0),
              0u)
        << unknown.stderr_text;
    EXPECT_TRUE(contains(unknown.stderr_text, bakes.slots[0] + ", " + bakes.slots[1])) << unknown.stderr_text;
    EXPECT_FALSE(fs::exists(out));

    // Rerunning a finished slot does nothing; a whole bake into that folder is not taken for done.
    const CommandResult again = gusuku::testing::runBakeCommand(
        {"bake", bakes.site, "-o", bakes.partials[0], "--slot", bakes.slots[0]}, scratch_);
    EXPECT_EQ(again.exit_code, 0) << again.stderr_text;
    EXPECT_TRUE(contains(again.stdout_text, "up to date")) << again.stdout_text;
    const std::string copy = bakes.dir + "/partial_copy";
    fs::copy(bakes.partials[0], copy);
    const CommandResult whole =
        gusuku::testing::runBakeCommand({"bake", bakes.site, "-o", copy, "--quiet"}, scratch_);
    EXPECT_EQ(whole.exit_code, 0) << whole.stderr_text;
    EXPECT_FALSE(contains(whole.stdout_text, "up to date")) << whole.stdout_text;
    expectSameBakeSet(bakes.single, copy);
}

TEST_F(BakeSplitTest, PartialBakeStoppedAndResumedWritesTheSameBytes) {
    const SplitBakes& bakes = splitBakes();
    const SiteConfig site = loadSiteConfig(bakes.site);
    BakeOptions options;
    options.show_progress = false;
    options.slot = bakes.slots.back();
    options.target_chunk_seconds = 1e-6;  // one sample per chunk, so the stop falls mid-set
    // Beside the partial baked by its own process, so even the manifests' relative input paths are the same.
    options.output_dir = bakes.dir + "/resumed/" + options.slot;
    int polls = 0;
    options.should_stop = [&polls] { return ++polls == 4; };
    const BakeReport stopped = runBake(context(), site, options);
    ASSERT_FALSE(stopped.completed);
    EXPECT_FALSE(fs::exists(options.output_dir + "/manifest.json"));
    options.should_stop = nullptr;
    const BakeReport resumed = runBake(context(), site, options);
    ASSERT_TRUE(resumed.completed);
    EXPECT_GT(resumed.resumed_fraction, 0.0);
    EXPECT_FALSE(fs::exists(options.output_dir + "/.checkpoint"));
    expectSameBakeSet(bakes.partials.back(), options.output_dir);
}

TEST_F(BakeSplitTest, BakeSetMovedWithItsInputsFindsThemAndAbsolutePathsStillLoad) {
    const SplitBakes& bakes = splitBakes();
    const BakeSetManifest manifest = readBakeSetManifest(bakes.single + "/manifest.json");
    EXPECT_TRUE(manifest.input_paths_relative_to_folder);
    ASSERT_FALSE(manifest.inputs.empty());
    EXPECT_EQ(manifest.inputs.front().role, "site");
    EXPECT_EQ(manifest.inputs.front().path, "../site.json");
    for (const BakeSetSlot& slot : manifest.slots) EXPECT_EQ(slot.sky_map.rfind("../", 0), 0u) << slot.sky_map;

    // Move the site and its bake set together to another machine's folder (another depth, another name), and
    // delete the originals, so nothing can be found at the old place.
    const std::string original = scratch_ + "/original";
    fs::create_directories(original);
    for (const auto& entry : fs::directory_iterator(bakes.dir))
        if (entry.is_regular_file()) fs::copy(entry.path(), original / entry.path().filename());
    fs::copy(bakes.single, original + "/single", fs::copy_options::recursive);
    const std::string moved = scratch_ + "/elsewhere/deeper/site copy";
    fs::create_directories(fs::path(moved).parent_path());
    fs::rename(original, moved);
    ASSERT_FALSE(fs::exists(original));

    const BakeSetData data = loadBakeSet(moved + "/single");
    EXPECT_EQ(data.slots.size(), bakes.slots.size());
    for (const BakeSetInput& input : data.manifest.inputs) {
        SCOPED_TRACE(input.role);
        const std::string path = resolveBakeSetInputPath(moved + "/single", data.manifest, input.path);
        EXPECT_EQ(fs::path(path).parent_path(), fs::weakly_canonical(moved)) << path;
        EXPECT_EQ(hashFileHex(path), input.fnv1a64);  // the very file the bake read
    }
    for (const BakeSetSlot& slot : data.manifest.slots)
        EXPECT_TRUE(fs::exists(resolveBakeSetInputPath(moved + "/single", data.manifest, slot.sky_map))) << slot.sky_map;

    // An older manifest: absolute paths, no "input_paths". It loads, and its paths are taken as they are.
    const std::string old_set = scratch_ + "/old";
    fs::copy(bakes.single, old_set, fs::copy_options::recursive);
    nlohmann::json json = nlohmann::json::parse(readTextFile(old_set + "/manifest.json"));
    json.erase("input_paths");
    for (auto& input : json["inputs"])
        input["path"] = (fs::path(moved) / fs::path(input["path"].get<std::string>()).filename()).string();
    for (auto& slot : json["slots"])
        slot["sky_map"] = (fs::path(moved) / fs::path(slot["sky_map"].get<std::string>()).filename()).string();
    {
        std::ofstream file(old_set + "/manifest.json", std::ios::binary);
        file << json.dump(2) << "\n";
    }
    const BakeSetData old_data = loadBakeSet(old_set);
    EXPECT_FALSE(old_data.manifest.input_paths_relative_to_folder);
    const std::string site_path = resolveBakeSetInputPath(old_set, old_data.manifest, old_data.manifest.inputs[0].path);
    EXPECT_EQ(site_path, moved + "/site.json");
    EXPECT_EQ(hashFileHex(site_path), old_data.manifest.inputs[0].fnv1a64);
    // Relative paths in an older manifest were relative to where its bake ran: left as they are.
    BakeSetManifest older = old_data.manifest;
    older.inputs[0].path = "out/sample/site.json";
    EXPECT_EQ(resolveBakeSetInputPath(old_set, older, older.inputs[0].path), "out/sample/site.json");
}

}  // namespace
}  // namespace gusuku::bake
