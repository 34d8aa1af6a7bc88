#pragma once
// The published layouts of the C API's versioned structs (gusuku.h, "Versions and struct sizes"): which
// struct_size values the library accepts for each struct and how many bytes of fields each one covers. Appending
// fields to a struct in gusuku.h means adding one line to its table here; the static_asserts below refuse a table
// that does not end at the struct's last field, or a new layout that would start inside an older one's padding.
// Not a public header: not installed.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <span>
#include <string>

#include "gusuku/runtime/gusuku.h"

namespace gusuku::c_api_detail {

/// One published layout: where the fields it added start, where its last field ends, and the struct's alignment
/// in it (its sizeof, what an app built against it sets struct_size to, is `end` rounded up to that).
struct StructLayout {
    size_t first_field_offset;
    size_t fields_end;
    size_t alignment;
    constexpr size_t size() const { return (fields_end + alignment - 1) / alignment * alignment; }
};

/// The layout whose added fields run from FIRST to LAST (a later version that raises the struct's alignment
/// writes the older layouts' alignment out instead of alignof).
#define GUSUKU_STRUCT_LAYOUT(TYPE, FIRST, LAST)                                                                 \
    ::gusuku::c_api_detail::StructLayout {                                                                      \
        offsetof(TYPE, FIRST), offsetof(TYPE, LAST) + sizeof(TYPE::LAST), alignof(TYPE)                         \
    }

/// Each versioned struct's name, direction and layouts, oldest first (index k: API version k; 0 is gusuku 0.1.0's
/// fields behind struct_size).
template <typename Struct>
struct StructLayouts;

template <>
struct StructLayouts<gusuku_vulkan_device> {
    static constexpr const char* name = "gusuku_vulkan_device";
    static constexpr bool library_writes = false;
    static constexpr StructLayout layouts[] = {
        GUSUKU_STRUCT_LAYOUT(gusuku_vulkan_device, instance, queue_family_index),
        GUSUKU_STRUCT_LAYOUT(gusuku_vulkan_device, instance_api_version, instance_api_version),
    };
};

template <>
struct StructLayouts<gusuku_bakeset_desc> {
    static constexpr const char* name = "gusuku_bakeset_desc";
    static constexpr bool library_writes = false;
    static constexpr StructLayout layouts[] = {
        GUSUKU_STRUCT_LAYOUT(gusuku_bakeset_desc, latitude_deg, slot_count),
        GUSUKU_STRUCT_LAYOUT(gusuku_bakeset_desc, ground_albedo, ground_albedo),
        GUSUKU_STRUCT_LAYOUT(gusuku_bakeset_desc, material_alpha_cutoffs, material_alpha_cutoffs),
    };
};

/// A gusuku_runtime_options layout of before API version 6, whose fields were all 4-byte aligned.
#define GUSUKU_RUNTIME_OPTIONS_LAYOUT_ALIGN4(FIRST, LAST)                                                                     \
    ::gusuku::c_api_detail::StructLayout {                                                                      \
        offsetof(gusuku_runtime_options, FIRST),                                                                \
            offsetof(gusuku_runtime_options, LAST) + sizeof(gusuku_runtime_options::LAST), 4                    \
    }

template <>
struct StructLayouts<gusuku_runtime_options> {
    static constexpr const char* name = "gusuku_runtime_options";
    static constexpr bool library_writes = false;
    static constexpr StructLayout layouts[] = {
        // API version 6's conversion handle raised the struct's alignment to 8: the older layouts had 4.
        GUSUKU_RUNTIME_OPTIONS_LAYOUT_ALIGN4(frame_width, direct_only_shadow_darkening),
        GUSUKU_RUNTIME_OPTIONS_LAYOUT_ALIGN4(shadow_sun_step_deg, max_anisotropy),
        GUSUKU_RUNTIME_OPTIONS_LAYOUT_ALIGN4(lightmap_format, texture_compression_astc_hdr),
        GUSUKU_RUNTIME_OPTIONS_LAYOUT_ALIGN4(texture_compression_astc_ldr, texture_compression_astc_ldr),
        GUSUKU_STRUCT_LAYOUT(gusuku_runtime_options, camera_ycbcr_image, camera_ycbcr_conversion),
    };
};

template <>
struct StructLayouts<gusuku_frame_input> {
    static constexpr const char* name = "gusuku_frame_input";
    static constexpr bool library_writes = false;
    static constexpr StructLayout layouts[] = {
        GUSUKU_STRUCT_LAYOUT(gusuku_frame_input, camera_rgba8, flags),
        GUSUKU_STRUCT_LAYOUT(gusuku_frame_input, camera_luma, signal_values),
        GUSUKU_STRUCT_LAYOUT(gusuku_frame_input, sun_scale, sun_scale),  // new in API version 4
    };
};

template <>
struct StructLayouts<gusuku_frame_info> {
    static constexpr const char* name = "gusuku_frame_info";
    static constexpr bool library_writes = true;
    static constexpr StructLayout layouts[] = {
        GUSUKU_STRUCT_LAYOUT(gusuku_frame_info, sun_azimuth_deg, overcast_weight),
        GUSUKU_STRUCT_LAYOUT(gusuku_frame_info, ground_quads_drawn, ground_quads_total),
    };
};

template <>
struct StructLayouts<gusuku_pass_timings> {
    static constexpr const char* name = "gusuku_pass_timings";
    static constexpr bool library_writes = true;
    static constexpr StructLayout layouts[] = {
        GUSUKU_STRUCT_LAYOUT(gusuku_pass_timings, upload_ms, total_ms),  // new in API version 1
    };
};

/// A struct's table is sound: it ends at the struct's last field, and each layout's fields begin after the
/// previous layout's (for a struct the app fills, after its tail padding too, which an older app leaves unset).
template <typename Struct>
constexpr bool layoutsAreSound() {
    const auto& layouts = StructLayouts<Struct>::layouts;
    const size_t count = std::size(layouts);
    if (layouts[count - 1].size() != sizeof(Struct)) return false;
    for (size_t k = 1; k < count; ++k) {
        const size_t older_end = StructLayouts<Struct>::library_writes ? layouts[k - 1].fields_end
                                                                       : layouts[k - 1].size();
        if (layouts[k].first_field_offset < older_end) return false;
    }
    return true;
}

static_assert(layoutsAreSound<gusuku_vulkan_device>(), "gusuku_vulkan_device: fix its layouts table");
static_assert(layoutsAreSound<gusuku_bakeset_desc>(), "gusuku_bakeset_desc: fix its layouts table");
static_assert(layoutsAreSound<gusuku_runtime_options>(), "gusuku_runtime_options: fix its layouts table");
static_assert(layoutsAreSound<gusuku_frame_input>(),
              "gusuku_frame_input: its layouts table must name its last field, and fields appended to it must "
              "start past the previous layout's sizeof (add a uint32_t pad first where that one ends short)");
static_assert(layoutsAreSound<gusuku_frame_info>(), "gusuku_frame_info: fix its layouts table");
static_assert(layoutsAreSound<gusuku_pass_timings>(), "gusuku_pass_timings: fix its layouts table");

/// "ARGUMENT.struct_size: N is not ..." when struct_size is no published layout's size (the accepted ones
/// listed); otherwise "" and the bytes of that layout's fields in `field_bytes`.
std::string findSizeProblem(uint32_t struct_size, const char* argument, const char* struct_name,
                            std::span<const StructLayout> layouts, size_t& field_bytes);

/// The struct_size at the start of an app's struct, read without assuming the app's struct is as large as ours.
inline uint32_t structSizeOf(const void* given) {
    uint32_t struct_size = 0;
    std::memcpy(&struct_size, given, sizeof struct_size);
    return struct_size;
}

/// Copies the fields of the layout the app's struct_size names over `full` (which holds today's defaults), so
/// the fields of later layouts keep them; "" or the size problem (nothing copied).
template <typename Struct>
std::string readSized(const Struct* given, const char* argument, Struct& full) {
    size_t field_bytes = 0;
    std::string problem = findSizeProblem(structSizeOf(given), argument, StructLayouts<Struct>::name,
                                          StructLayouts<Struct>::layouts, field_bytes);
    if (problem.empty()) std::memcpy(static_cast<void*>(&full), given, field_bytes);
    return problem;
}

/// The size problem of an app's struct the library will fill ("" for none), and the bytes it may write.
template <typename Struct>
std::string findSizeProblem(const Struct* given, const char* argument, size_t& field_bytes) {
    return findSizeProblem(structSizeOf(given), argument, StructLayouts<Struct>::name, StructLayouts<Struct>::layouts,
                           field_bytes);
}

/// Writes `full`'s fields of the layout given->struct_size names (checked before with findSizeProblem, which
/// gave field_bytes) into the app's struct, its struct_size kept.
template <typename Struct>
void writeSized(Struct full, Struct* given, size_t field_bytes) {
    full.struct_size = structSizeOf(given);
    std::memcpy(static_cast<void*>(given), &full, field_bytes);
}

}  // namespace gusuku::c_api_detail
