// runBake: orchestration only. Geometry comes from bake_geometry.cpp, light from slot_lighting.cpp, tracing
// from the IrradianceTracer, outputs from bake_outputs.cpp.
#include "gusuku_bake/bake_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include <nlohmann/json.hpp>

#include "bake_outputs.h"
#include "gusuku/atomic_file.h"
#include "gusuku_bake/bake_checkpoint.h"
#include "gusuku_bake/bake_geometry.h"
#include "gusuku_bake/bake_progress.h"
#include "gusuku_bake/content_hash.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/slot_lighting.h"

namespace gusuku::bake {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Everything that changes the traced sums: the inputs' bytes, the settings, and the tracer's own code.
uint64_t bakeInputHash(const SiteConfig& site, uint32_t samples, const BakeOptions& options) {
    ContentHash hash;
    hash.addString(kBakeSetFormat).addFile(site.file).addFile(site.building.path).addFile(site.sunny_sky.path);
    if (site.sfm_mesh) hash.addFile(site.sfm_mesh->path);
    if (site.overcast_sky) hash.addFile(site.overcast_sky->path);
    // The sky-sampling threshold picks the tracer's method per sky: a checkpoint from another method must not
    // be resumed, or the result would differ from an uninterrupted bake.
    hash.addValue(samples).addValue(options.max_texture_size).addValue(tracerCodeHash())
        .addValue(kSkyNextEventRelativeVarianceThreshold);
    return hash.value();
}

struct PointSet {
    std::string name;                  ///< "building", "ground_with", "ground_without"
    std::vector<QueryPointGpu> points;
    uint32_t skip_flags = 0;
};

std::vector<QueryPointGpu> buildingQueryPoints(const BakeGeometry& geometry) {
    std::vector<QueryPointGpu> points;
    points.reserve(geometry.texels.size());
    for (const LightmapTexel& texel : geometry.texels)
        points.push_back({glm::vec4(texel.position, 1.0f), glm::vec4(texel.shading_normal, 0.0f)});
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
          checkpoint_dir_(checkpoint_dir) {}

    /// Traces one set to `samples`; returns its sums, or nothing when stopped.
    std::optional<std::vector<glm::vec4>> trace(const std::string& slot_name, const PointSet& set,
                                                const TracePass& pass, uint32_t samples) {
        const std::string label = slot_name + " " + set.name;
        const std::string checkpoint_path = checkpoint_dir_ + "/" + slot_name + "." + set.name + ".bin";
        PointAccumulator accumulator = tracer_.createAccumulator(set.points);
        const uint32_t point_count = uint32_t(set.points.size());
        if (auto checkpoint = readMatchingCheckpoint(checkpoint_path, input_hash_, point_count)) {
            const uint32_t resumed = std::min(checkpoint->samples_done, samples);
            tracer_.restoreSums(accumulator, checkpoint->sums, resumed);
            progress_.addResumedWork(double(resumed) * point_count);
        }
        auto last_checkpoint = Clock::now();
        while (accumulator.samples_done < samples) {
            const uint32_t chunk = std::min(chunk_samples_, samples - accumulator.samples_done);
            const auto start = Clock::now();
            const uint64_t rays = tracer_.addSamples(accumulator, chunk, pass);
            const double seconds = std::max(secondsSince(start), 1e-4);
            trace_seconds_ += seconds;
            progress_.advance(label, accumulator.samples_done, samples, double(chunk) * point_count, rays);
            // Size the next chunk so a dispatch takes about target_chunk_seconds.
            const double wanted = double(chunk) * options_.target_chunk_seconds / seconds;
            chunk_samples_ = uint32_t(std::clamp(wanted, 1.0, 64.0));
            const bool stop = options_.should_stop && options_.should_stop();
            if (stop || accumulator.samples_done >= samples || secondsSince(last_checkpoint) > 2.0) {
                writeCheckpoint(checkpoint_path, {input_hash_, accumulator.samples_done, tracer_.readSums(accumulator)});
                last_checkpoint = Clock::now();
            }
            if (stop && accumulator.samples_done < samples) return std::nullopt;
        }
        if (point_count > 0 && !std::filesystem::exists(checkpoint_path))
            writeCheckpoint(checkpoint_path, {input_hash_, accumulator.samples_done, tracer_.readSums(accumulator)});
        return tracer_.readSums(accumulator);
    }

    double traceSeconds() const { return trace_seconds_; }

private:
    IrradianceTracer& tracer_;
    BakeProgress& progress_;
    const BakeOptions& options_;
    uint64_t input_hash_;
    std::string checkpoint_dir_;
    uint32_t chunk_samples_ = 1;
    double trace_seconds_ = 0.0;
};

std::optional<uint64_t> manifestInputHash(const std::string& manifest_path) {
    std::ifstream file(manifest_path);
    if (!file) return std::nullopt;
    try {
        const nlohmann::json manifest = nlohmann::json::parse(file);
        return std::stoull(manifest.at("input_hash").get<std::string>(), nullptr, 16);
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

}  // namespace

BakeReport runBake(VulkanContext& context, const SiteConfig& site, const BakeOptions& options) {
    const auto wall_start = Clock::now();
    BakeReport report;
    const uint32_t samples = uint32_t(options.samples_override > 0 ? options.samples_override
                                                                   : site.bake.samples_per_texel);
    report.samples_per_point = samples;
    const uint64_t input_hash = bakeInputHash(site, samples, options);
    report.manifest_path = options.output_dir + "/manifest.json";
    if (!options.force && manifestInputHash(report.manifest_path) == input_hash) {
        report.completed = true;
        report.up_to_date = true;
        return report;
    }

    // Light first: the lowest baked sun sizes the ground grid.
    const PreparedSky sunny = prepareSky(site.sunny_sky);
    std::optional<PreparedSky> overcast;
    if (site.overcast_sky) overcast = prepareSky(*site.overcast_sky);
    std::vector<SlotLighting> slots;
    double lowest_sun_elevation = -1.0;
    for (const BakeSlot& slot : site.bake.slots) {
        slots.push_back(lightSlot(site, slot, sunny, overcast ? &*overcast : nullptr));
        if (slots.back().sun.present) {
            const double elevation = slots.back().sun_position.apparent_elevation_deg;
            lowest_sun_elevation = lowest_sun_elevation < 0.0 ? elevation : std::min(lowest_sun_elevation, elevation);
        }
        for (const std::string& warning : slots.back().warnings) report.warnings.push_back(warning);
    }

    BakeGeometry geometry = prepareBakeGeometry(site, lowest_sun_elevation, options.max_texture_size);
    report.warnings.insert(report.warnings.end(), geometry.warnings.begin(), geometry.warnings.end());
    report.lightmap_resolution = geometry.lightmap_resolution;
    for (const std::string& warning : report.warnings) std::fprintf(stderr, "gusuku-bake: warning: %s\n", warning.c_str());

    const std::vector<PointSet> sets = {
        {"building", buildingQueryPoints(geometry), 0u},
        {"ground_with", groundQueryPoints(geometry), 0u},
        {"ground_without", groundQueryPoints(geometry), kTriangleFlagBuilding},
    };
    report.building_texels = sets[0].points.size();
    report.ground_cells = sets[1].points.size();

    double total_work = 0.0;
    for (const PointSet& set : sets) total_work += double(set.points.size()) * samples * double(slots.size());
    BakeProgress progress(total_work, options.show_progress);
    const std::string checkpoint_dir = options.output_dir + "/.checkpoint";
    std::filesystem::create_directories(checkpoint_dir);

    IrradianceTracer tracer(context, geometry.scene, sunny.tables, options.max_texture_size);
    SetTracer set_tracer(tracer, progress, options, input_hash, checkpoint_dir);
    BakeOutputWriter writer(options.output_dir, geometry, samples, options.denoise);
    writer.writeGeometry();
    for (const SlotLighting& lighting : slots) {
        tracer.setSky(lighting.sky->tables);
        TracePass pass;
        pass.max_bounces = uint32_t(site.bake.max_bounces);
        pass.seed = site.bake.seed;
        pass.sun = lighting.sun;
        std::vector<std::vector<glm::vec4>> sums;
        for (const PointSet& set : sets) {
            pass.skip_flags = set.skip_flags;
            auto set_sums = set_tracer.trace(lighting.slot.name, set, pass, samples);
            if (!set_sums) {
                progress.finish();
                report.rays_traced = progress.raysTraced();
                report.trace_seconds = set_tracer.traceSeconds();
                report.wall_seconds = secondsSince(wall_start);
                report.resumed_fraction = progress.resumedFraction();
                return report;  // completed = false: checkpoints hold everything done so far
            }
            sums.push_back(std::move(*set_sums));
        }
        writer.writeSlot(lighting, sums[0], sums[1], sums[2]);
    }
    progress.finish();
    report.rays_traced = progress.raysTraced();
    report.trace_seconds = set_tracer.traceSeconds();
    report.wall_seconds = secondsSince(wall_start);
    report.resumed_fraction = progress.resumedFraction();
    writer.writeManifest(site, input_hash, report);
    std::filesystem::remove_all(checkpoint_dir);
    report.completed = true;
    return report;
}

}  // namespace gusuku::bake
