// runBake: orchestration only. Geometry comes from bake_geometry.cpp, light from slot_lighting.cpp, tracing
// from the IrradianceTracer, outputs from bake_outputs.cpp.
#include "gusuku_bake/bake_job.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "bake_checkpoint.h"
#include "gusuku_bake/adaptive_sampling.h"
#include "gusuku_bake/lightmap_denoise.h"
#include "bake_geometry.h"
#include "bake_inputs.h"
#include "bake_outputs.h"
#include "bake_preflight.h"
#include "invalid_texel_reasons.h"
#include "gusuku_bake/content_hash.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/bake_folder_lock.h"
#include "gusuku_bake/bake_progress.h"
#include "gusuku_bake/dispatch_budget.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/output_guard.h"
#include "gusuku_bake/slot_lighting.h"
#include "gusuku_bake/trace_input_kind.h"

namespace gusuku::bake {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Everything that changes the traced sums: the bytes of every file the bake reads (a glTF's external buffers
// and textures included), the settings, and the tracer's own code. Checkpoints carry this hash. Files are named
// relative to site.json's folder, not as this run spelled them: the slots of one site baked on machines that
// mount it at different places (gusuku-bake merge) agree on the hash, and a partial set can prove its inputs.
uint64_t traceInputHash(const SiteConfig& site, const std::vector<std::string>& input_files, uint32_t samples,
                        const BakeOptions& options) {
    ContentHash hash;
    hash.addString(kBakeSetFormat);
    const std::string site_folder = std::filesystem::absolute(site.file).parent_path().string();
    for (const std::string& file : input_files)
        hash.addString(bakeSetRelativeInputPath(site_folder, file)).addFile(file);
    // The sky-sampling threshold picks the tracer's method per sky: a checkpoint from another method must not
    // be resumed, or the result would differ from an uninterrupted bake.
    hash.addString("texel footprints 1");  // texels traced over their footprints (lightmap_uv.h), not at centres
    // Version 2: a pilot of a quarter and the plan by sigma^kAdaptiveNoiseExponent (version 1's checkpoints hold
    // a pilot of half, which this plan must not resume).
    hash.addString(options.adaptive_sampling ? "adaptive sampling 2" : "uniform sampling");
    hash.addValue(samples).addValue(options.max_texture_size).addValue(tracerCodeHash())
        .addValue(options.building_texture_size)
        .addValue(kSkyNextEventRelativeVarianceThreshold);
    return hash.value();
}

// The manifest's hash: the traced sums' plus the settings that only change how they become files. The filter
// is not part of the checkpoint hash, so a bake resumed with or without --no-denoise reuses the traced sums.
uint64_t outputInputHash(uint64_t trace_hash, const BakeOptions& options) {
    return ContentHash().addValue(trace_hash).addValue(uint8_t(options.denoise ? 1 : 0)).value();
}

struct PointSet {
    std::string name;                  ///< "building", "ground_with", "ground_without"
    std::vector<QueryPointGpu> points;
    uint32_t skip_flags = 0;
    uint32_t samples_per_point = 0;    ///< 0: the bake's samples (the building's footprint slots take a share)
    bool adaptive = false;             ///< a pilot of a quarter, the rest where the noise is (traceAdaptively)
    uint32_t samples(uint32_t bake_samples) const { return samples_per_point ? samples_per_point : bake_samples; }
};

/// The three sets every slot traces (bakePointSets), named by what they feed: the building's lightmap and the
/// ground's two maps, whose ratio is the building's shadow on the ground.
struct BakePointSets {
    PointSet building;        ///< the building's texels over their footprints
    PointSet ground_with;     ///< the ground's cells, the building in the scene
    PointSet ground_without;  ///< the same cells, the building's triangles skipped

    /// The sets in the order they are traced (and checkpointed and shown in the progress line).
    std::array<const PointSet*, 3> inTraceOrder() const { return {&building, &ground_with, &ground_without}; }
};

// The building's texels spread over their footprints (lightmap_uv.h): every slot a point of its own.
std::vector<QueryPointGpu> buildingQueryPoints(const LightmapFootprint& footprint) {
    std::vector<QueryPointGpu> points;
    points.reserve(footprint.points.size());
    for (const LightmapFootprintPoint& point : footprint.points)
        points.push_back({glm::vec4(point.position, 1.0f), glm::vec4(point.shading_normal, 0.0f),
                          glm::vec4(point.geometric_normal, 0.0f)});
    return points;
}

std::vector<QueryPointGpu> groundQueryPoints(const BakeGeometry& geometry) {
    std::vector<QueryPointGpu> points;
    const GroundRegion& region = geometry.ground_region;
    for (int row = 0; row < region.rows; ++row)
        for (int column = 0; column < region.columns; ++column) {
            const GroundCell& cell = geometry.ground_cells[size_t(row) * size_t(region.columns) + size_t(column)];
            if (!cell.valid) continue;
            const glm::dvec2 centre = groundCellCentre(region, column, row);
            points.push_back({glm::vec4(float(centre.x), float(centre.y), cell.height_m, 1.0f),
                              glm::vec4(cell.normal, 0.0f)});
        }
    return points;
}

class SetTracer {
public:
    SetTracer(IrradianceTracer& tracer, BakeProgress& progress, const BakeOptions& options, uint64_t input_hash,
              const std::string& checkpoint_dir)
        : tracer_(tracer), progress_(progress), options_(options), input_hash_(input_hash),
          checkpoint_dir_(checkpoint_dir), budget_(options.target_chunk_seconds) {}

    /// A set's running sums and sums of squared luminance (PointAccumulator's).
    struct Sums {
        std::vector<glm::vec4> sums;
        std::vector<float> luminance_square_sums;
    };

    /// Traces one set to `samples`; returns its sums, or nothing when stopped. A stop request is polled
    /// before the set and after every dispatch (each about target_chunk_seconds, DispatchBudget), and is
    /// honoured even when that dispatch finished the set (with --samples 1 every set may be one dispatch): the
    /// set's sums are checkpointed first, a part-done pass included, so nothing is lost.
    std::optional<Sums> trace(const std::string& slot_name, const PointSet& set,
                                                const TracePass& pass, uint32_t samples) {
        if (stopRequested()) return std::nullopt;
        // An empty set (no ground cell over the ground) is done at once: there is nothing to trace or save.
        if (set.points.empty()) return Sums{};
        const std::string label = slot_name + " " + set.name;
        const std::string checkpoint_path = checkpoint_dir_ + "/" + slot_name + "." + set.name + ".bin";
        PointAccumulator accumulator = tracer_.createAccumulator(set.points);
        resume(accumulator, checkpoint_path, samples);
        auto last_checkpoint = Clock::now();
        std::optional<Sums> written;  // what the last checkpoint of this call wrote: the accumulator's sums then
        while (accumulator.samples_done < samples) {
            traceOneDispatch(accumulator, label, pass, samples);
            const bool stop = stopRequested();
            if (stop || accumulator.samples_done >= samples || secondsSince(last_checkpoint) > 2.0) {
                written = checkpoint(accumulator, checkpoint_path);
                last_checkpoint = Clock::now();
            }
            if (stop) return std::nullopt;
        }
        // The loop's last dispatch wrote the final sums; without one (resumed complete) they are read once here.
        if (!written) {
            if (std::filesystem::exists(checkpoint_path))
                written = Sums{tracer_.readSums(accumulator), tracer_.readLuminanceSquareSums(accumulator)};
            else
                written = checkpoint(accumulator, checkpoint_path);
        }
        if (stopRequested()) return std::nullopt;
        return written;
    }

    double traceSeconds() const { return trace_seconds_; }

    /// Sticky: a should_stop that answers true once (a signal flag, a test's counter) stops the whole bake.
    bool stopRequested() {
        stop_requested_ = stop_requested_ || (options_.should_stop && options_.should_stop());
        return stop_requested_;
    }

private:
    /// The set's checkpoint, if it matches, restored into the accumulator (a part-done pass only below `samples`).
    void resume(PointAccumulator& accumulator, const std::string& checkpoint_path, uint32_t samples) {
        const uint32_t point_count = accumulator.point_count;
        std::string ignored_checkpoint;
        if (auto checkpoint = readMatchingCheckpoint(checkpoint_path, input_hash_, point_count, &ignored_checkpoint)) {
            const uint32_t resumed = std::min(checkpoint->samples_done, samples);
            const uint32_t part_pass = resumed < samples ? checkpoint->points_with_next_sample : 0u;
            tracer_.restoreSums(accumulator, checkpoint->sums, checkpoint->luminance_square_sums, resumed, part_pass);
            progress_.addResumedWork(double(resumed) * point_count + double(part_pass));
        }
        if (!ignored_checkpoint.empty()) std::fprintf(stderr, "gusuku-bake: %s\n", ignored_checkpoint.c_str());
    }

    /// One dispatch as the budget sizes it: whole passes, or the next range of points of a pass.
    void traceOneDispatch(PointAccumulator& accumulator, const std::string& label, const TracePass& pass,
                          uint32_t samples) {
        const DispatchSize size =
            budget_.next(accumulator.point_count, accumulator.points_with_next_sample, samples - accumulator.samples_done);
        const auto start = Clock::now();
        const bool whole_passes = size.points == accumulator.point_count && accumulator.points_with_next_sample == 0;
        const uint64_t rays = whole_passes ? tracer_.addSamples(accumulator, size.samples, pass)
                                           : tracer_.addSampleToNextPoints(accumulator, size.points, pass);
        const double seconds = std::max(secondsSince(start), 1e-4);
        const double point_samples = double(size.samples) * double(size.points);
        trace_seconds_ += seconds;
        budget_.measured(point_samples, seconds);
        progress_.advance(label, accumulator.samples_done, samples, point_samples, rays, seconds);
    }

    /// The accumulator's sums written to the set's checkpoint; returns them.
    Sums checkpoint(const PointAccumulator& accumulator, const std::string& checkpoint_path) {
        Sums sums{tracer_.readSums(accumulator), tracer_.readLuminanceSquareSums(accumulator)};
        writeCheckpoint(checkpoint_path, {input_hash_, accumulator.samples_done, accumulator.points_with_next_sample,
                                          sums.sums, sums.luminance_square_sums});
        return sums;
    }

    IrradianceTracer& tracer_;
    BakeProgress& progress_;
    const BakeOptions& options_;
    uint64_t input_hash_;
    std::string checkpoint_dir_;
    DispatchBudget budget_;
    double trace_seconds_ = 0.0;
    bool stop_requested_ = false;
};

/// One slot's traced sums, a member per set of BakePointSets.
struct SlotSums {
    SetTracer::Sums building;
    SetTracer::Sums ground_with;
    SetTracer::Sums ground_without;
};

/// The building's set traced adaptively (adaptive_sampling.h): a pilot (adaptivePilotSamplesPerPoint), every
/// point alike (checkpointed as the set itself), then extra samples planned per texel from the pilot's noise,
/// traced as copies of the texels' footprint points in sets of their own ("building_extra", checkpointed like
/// any set; the plan follows from the pilot's sums, so a resumed bake plans the same copies), added to their
/// points and normalised so that every point reads as `samples` samples. Nothing when stopped.
std::optional<SetTracer::Sums> traceAdaptively(SetTracer& set_tracer, const std::string& slot_name, const PointSet& set,
                                               const LightmapFootprint& footprint, const TracePass& pass,
                                               uint32_t samples, size_t max_points) {
    const uint32_t pilot = adaptivePilotSamplesPerPoint(samples, footprint.pointsPerTexel());
    std::optional<SetTracer::Sums> pilot_sums = set_tracer.trace(slot_name, set, pass, pilot);
    if (!pilot_sums || set.points.empty()) return pilot_sums;
    SetSums all{std::move(pilot_sums->sums), std::move(pilot_sums->luminance_square_sums),
                std::vector<uint32_t>(set.points.size(), pilot)};
    const std::vector<float> texel_variance = texelLuminanceVarianceFromFootprint(
        footprint, all.sums, all.luminance_square_sums, pilot, kMaxBackfaceFraction);
    const bool finished = traceAdaptiveExtras(
        all, set.points, texel_variance, footprint.pointsPerTexel(), pilot, samples, max_points,
        [&](size_t batch, const std::vector<QueryPointGpu>& copies, std::vector<glm::vec4>& sums,
            std::vector<float>& square_sums) {
            const PointSet extra_set{set.name + "_extra" + (batch > 0 ? std::to_string(batch) : std::string()),
                                     copies, set.skip_flags, kAdaptiveSamplesPerCopy, false};
            std::optional<SetTracer::Sums> traced = set_tracer.trace(slot_name, extra_set, pass, kAdaptiveSamplesPerCopy);
            if (!traced) return false;
            sums = std::move(traced->sums);
            square_sums = std::move(traced->luminance_square_sums);
            return true;
        });
    if (!finished) return std::nullopt;
    return SetTracer::Sums{std::move(all.sums), std::move(all.luminance_square_sums)};
}

/// True when manifest_path is a finished bake of these inputs, of the same kind: the whole site (slot empty), or
/// the partial set of that one slot. Anything unreadable is not up to date.
bool manifestIsUpToDate(const std::string& manifest_path, uint64_t input_hash, const std::string& slot) {
    if (!std::filesystem::exists(manifest_path)) return false;
    try {
        const BakeSetManifest manifest = readBakeSetManifest(manifest_path);
        return manifest.input_hash == input_hash && (manifest.partial ? manifest.partial->slot : "") == slot;
    } catch (const std::exception&) {
        return false;
    }
}

/// The site's slots this run traces: all of them, or the one --slot names.
std::vector<const BakeSlot*> slotsToTrace(const SiteConfig& site, const std::string& only) {
    if (!only.empty()) requireSiteSlot(site, only);
    std::vector<const BakeSlot*> chosen;
    for (const BakeSlot& slot : site.bake.slots)
        if (only.empty() || slot.name == only) chosen.push_back(&slot);
    return chosen;
}

/// Every slot of the site lit (a partial bake lights them all too: it is cheap, no tracing, so its ground grid
/// and warnings are the whole bake's); their warnings join the report's. The slots point into sunny and overcast.
std::vector<SlotLighting> lightEverySlot(const SiteConfig& site, const PreparedSky& sunny,
                                         const std::optional<PreparedSky>& overcast, BakeReport& report) {
    std::vector<SlotLighting> slots;
    for (const BakeSlot& slot : site.bake.slots) {
        slots.push_back(lightSlot(site, slot, sunny, overcast ? &*overcast : nullptr));
        for (const std::string& warning : slots.back().warnings) report.warnings.push_back(warning);
    }
    return slots;
}

/// The bake's geometry, refused (before any file is written) when the building has no texel or a device buffer
/// would pass the device's limit; a site with no ground cell over the ground gets a warning instead.
BakeGeometry prepareCheckedGeometry(VulkanContext& context, const SiteConfig& site, const std::vector<SlotSun>& suns,
                                    const PreparedSky& sunny, const std::optional<PreparedSky>& overcast,
                                    const BakeOptions& options) {
    checkTraceDeviceLimits(context);  // before the geometry's minutes, not after
    // The lowest baked sun sizes the ground grid.
    const uint64_t storage_buffer_limit = storageBufferLimitBytes(context.properties().limits.maxStorageBufferRange);
    BakeGeometry geometry = prepareBakeGeometry(site, lowestSunElevationDeg(suns), options.max_texture_size,
                                                options.building_texture_size, storage_buffer_limit);
    refuseBuildingWithoutTexels(site, geometry);
    std::vector<std::pair<std::string, const SkySamplingTables*>> skies = {{"/skies/sunny/path", &sunny.tables}};
    if (overcast) skies.push_back({"/skies/overcast/path", &overcast->tables});
    const std::vector<InputError> too_large = deviceLimitProblems(
        site, bakeDeviceBuffers(site, geometry, skies, options.max_texture_size), storage_buffer_limit);
    if (!too_large.empty()) throw too_large.front();
    const std::string no_ground = emptyGroundReason(site, geometry);
    if (!no_ground.empty()) geometry.warnings.push_back(no_ground);
    return geometry;
}

/// The sets every slot traces: the building's footprint points (adaptively once a texel has the samples for a
/// pilot), the ground's cells with the building and without it.
BakePointSets bakePointSets(const LightmapFootprint& footprint, const BakeGeometry& geometry,
                            uint32_t samples_per_slot, bool adaptive_building) {
    return {
        {"building", buildingQueryPoints(footprint), 0u, samples_per_slot, adaptive_building},
        {"ground_with", groundQueryPoints(geometry), 0u},
        {"ground_without", groundQueryPoints(geometry), kTriangleFlagBuilding},
    };
}

/// The point-samples the whole run traces, for the progress line: every set over every traced slot.
double totalTraceWork(const BakePointSets& sets, uint32_t samples, size_t traced_slot_count) {
    double total_work = 0.0;
    for (const PointSet* set : sets.inTraceOrder())
        total_work += double(set->points.size()) * set->samples(samples) * double(traced_slot_count);
    return total_work;
}

TracePass slotTracePass(const SiteConfig& site, const SlotLighting& lighting) {
    TracePass pass;
    pass.max_bounces = uint32_t(site.bake.max_bounces);
    pass.seed = site.bake.seed;
    pass.sun = lighting.sun;
    return pass;
}

/// One slot's sets traced in order, each with its own skip flags; nothing when stopped.
std::optional<SlotSums> traceSlotSets(SetTracer& set_tracer, const SlotLighting& lighting, const BakePointSets& sets,
                                      const LightmapFootprint& footprint, TracePass pass, uint32_t samples,
                                      size_t max_trace_points) {
    SlotSums sums;
    const std::array<std::pair<const PointSet*, SetTracer::Sums*>, 3> sums_of_set = {{
        {&sets.building, &sums.building},
        {&sets.ground_with, &sums.ground_with},
        {&sets.ground_without, &sums.ground_without},
    }};
    for (const auto& [set, set_sums] : sums_of_set) {
        pass.skip_flags = set->skip_flags;
        auto traced = set->adaptive ? traceAdaptively(set_tracer, lighting.slot.name, *set, footprint, pass,
                                                      set->samples(samples), max_trace_points)
                                    : set_tracer.trace(lighting.slot.name, *set, pass, set->samples(samples));
        if (!traced) return std::nullopt;
        *set_sums = std::move(*traced);
    }
    return sums;
}

/// The run's tracing statistics into the report, whether it finished or was stopped.
void recordTraceStatistics(BakeReport& report, BakeProgress& progress, const SetTracer& set_tracer,
                           Clock::time_point wall_start) {
    progress.finish();
    report.rays_traced = progress.raysTraced();
    report.trace_seconds = set_tracer.traceSeconds();
    report.wall_seconds = secondsSince(wall_start);
    report.resumed_fraction = progress.resumedFraction();
}

}  // namespace

void requireSiteSlot(const SiteConfig& site, const std::string& slot) {
    std::string names;
    for (const BakeSlot& candidate : site.bake.slots) {
        if (candidate.name == slot) return;
        names += (names.empty() ? "" : ", ") + candidate.name;
    }
    // A long value is cut as every reader cuts one (quotedForMessage), so a 100 KB --slot never floods the line.
    const std::string shown_slot = slot.size() <= 80 ? "\"" + slot + "\"" : quotedForMessage(slot);
    throw InputError(site.file, "/bake/slots", "has no slot " + shown_slot + " (--slot); its slots: " + names);
}

BakeReport runBake(VulkanContext& context, const SiteConfig& site, const BakeOptions& options) {
    const auto wall_start = Clock::now();
    BakeReport report;
    const uint32_t samples = uint32_t(options.samples_override > 0 ? options.samples_override
                                                                   : site.bake.samples_per_texel);
    report.samples_per_point = samples;
    // Before anything is created or written: the output folder must not be, or hold, anything the bake reads,
    // nor be, hold or lie inside a bake set or pack other than this site's own earlier bake set.
    const std::vector<std::string> input_files = bakeInputFiles(site);
    OutputRequest output_request;
    output_request.output = options.output_dir;
    output_request.kind = OutputKind::kBakeSet;
    output_request.inputs = input_files;
    output_request.site_json = site.file;
    refuseUnsafeOutput(output_request);
    const std::vector<const BakeSlot*> traced_slots = slotsToTrace(site, options.slot);
    const uint64_t trace_hash = traceInputHash(site, input_files, samples, options);
    const uint64_t input_hash = outputInputHash(trace_hash, options);
    report.manifest_path = options.output_dir + "/manifest.json";

    const BakeFolderLock lock(options.output_dir);  // a second bake into this folder is refused here
    if (!options.force && manifestIsUpToDate(report.manifest_path, input_hash, options.slot)) {
        report.completed = true;
        report.up_to_date = true;
        return report;
    }

    // Everything that can refuse the bake comes before the first file is replaced. Light first: the lowest
    // baked sun sizes the ground grid.
    const std::vector<SlotSun> suns = slotSunPositions(site);
    const PreparedSky sunny = prepareSky(site.sunny_sky);
    std::optional<PreparedSky> overcast;
    if (site.overcast_sky) overcast = prepareSky(*site.overcast_sky);
    const std::vector<SlotLighting> slots = lightEverySlot(site, sunny, overcast, report);
    const BakeGeometry geometry = prepareCheckedGeometry(context, site, suns, sunny, overcast, options);
    report.warnings.insert(report.warnings.end(), geometry.warnings.begin(), geometry.warnings.end());
    report.lightmap_resolution = geometry.lightmap_resolution;
    for (const std::string& warning : report.warnings) std::fprintf(stderr, "gusuku-bake: warning: %s\n", warning.c_str());

    // Each texel's samples spread over its footprint: K slots of samples / K each (the same rays), folded back
    // into one sum per texel before the outputs.
    const size_t max_trace_points =
        storageBufferLimitBytes(context.properties().limits.maxStorageBufferRange) / sizeof(QueryPointGpu);
    const LightmapFootprint footprint = lightmapTexelFootprints(
        geometry.building, geometry.lightmap_resolution, geometry.texels,
        footprintGridSide(samples, geometry.texels.size(), max_trace_points), site.bake.seed);
    const uint32_t samples_per_slot = samples / uint32_t(footprint.pointsPerTexel());
    const BakePointSets sets = bakePointSets(footprint, geometry, samples_per_slot,
                                             options.adaptive_sampling && samples >= kMinAdaptiveSamples);
    report.building_texels = geometry.texels.size();
    report.ground_cells = sets.ground_with.points.size();

    BakeProgress progress(totalTraceWork(sets, samples, traced_slots.size()), options.show_progress);
    // The old manifest goes before the first file of this bake replaces one of its files: a bake set with a
    // manifest is then always the complete, matching one, even if this bake is interrupted or fails.
    std::filesystem::remove(report.manifest_path);
    const std::string checkpoint_dir = options.output_dir + "/.checkpoint";
    std::filesystem::create_directories(checkpoint_dir);

    IrradianceTracer tracer(context, geometry.scene, sunny.tables, options.max_texture_size);
    report.alpha_tested_triangles = tracer.alphaTestedTriangleCount();
    for (uint32_t flags : geometry.scene.triangle_flags)
        report.masked_triangles += (flags & kTriangleFlagAlphaMasked) != 0 ? 1u : 0u;
    SetTracer set_tracer(tracer, progress, options, trace_hash, checkpoint_dir);
    BakeOutputWriter writer(options.output_dir, geometry, samples, options.denoise);
    writer.writeGeometry();
    InvalidTexelAccounting invalid_accounting(geometry, &footprint);
    for (const SlotLighting& lighting : slots) {
        if (!options.slot.empty() && lighting.slot.name != options.slot) continue;
        tracer.setSky(lighting.sky->tables);
        const std::optional<SlotSums> sums = traceSlotSets(
            set_tracer, lighting, sets, footprint, slotTracePass(site, lighting), samples, max_trace_points);
        if (!sums) {
            recordTraceStatistics(report, progress, set_tracer, wall_start);
            return report;  // completed = false: checkpoints hold everything done so far
        }
        const SetTracer::Sums& building = sums->building;
        const std::vector<glm::vec4> texel_sums =
            texelSumsFromFootprint(footprint, building.sums, samples_per_slot, kMaxBackfaceFraction);
        report.invalid_texels.push_back(invalid_accounting.count(lighting.slot.name, texel_sums, samples));
        writer.writeSlot(lighting, texel_sums,
                         texelLuminanceVarianceFromFootprint(footprint, building.sums, building.luminance_square_sums,
                                                             samples_per_slot, kMaxBackfaceFraction),
                         sums->ground_with.sums, sums->ground_without.sums);
    }
    recordTraceStatistics(report, progress, set_tracer, wall_start);
    std::optional<BakeSetPartial> partial;
    if (!options.slot.empty()) {
        partial = BakeSetPartial{options.slot, {}, writer.slotIndependentHash()};
        for (const BakeSlot& slot : site.bake.slots) partial->site_slots.push_back(slot.name);
    }
    writer.writeManifest(site, input_hash, report, partial);
    std::filesystem::remove_all(checkpoint_dir);
    report.completed = true;
    return report;
}

}  // namespace gusuku::bake
