#pragma once
// manifest.json of a bake set (docs/bakeset.md) to and from gusuku::BakeSetManifest. Part of gusuku_assets (the
// I/O stack: nlohmann json); the struct itself is in gusuku/formats/bakeset_manifest.h and needs none of it.

#include <string>

#include "gusuku/formats/bakeset_manifest.h"

namespace gusuku {

/// The manifest's text: pretty-printed JSON (2-space indent, members in name order, numbers in the shortest
/// form that reads back to the same double), ending in a newline. The format's fixed texts (frames, units,
/// channel meanings) are written with it. The same manifest always gives the same bytes.
/// Throws std::invalid_argument, naming the field as a JSON pointer, for a value the reader would refuse: a
/// non-finite number (JSON has none), a sun present without a position, or an overcast slot with a
/// position, a local time or a UTC time.
std::string bakeSetManifestJson(const BakeSetManifest& manifest);

/// One slot's manifest entry, exactly as bakeSetManifestJson writes it inside "slots" (compact, keys sorted): what
/// a partial set's slot_hash covers besides the slot's files.
std::string bakeSetSlotJson(const BakeSetSlot& slot);

/// Writes bakeSetManifestJson(manifest) to path atomically (gusuku/assets/atomic_file.h).
void writeBakeSetManifest(const std::string& path, const BakeSetManifest& manifest);

/// Reads a manifest written by bakeSetManifestJson. Every problem is an InputError(file, "/json/pointer",
/// problem): a "format" other than kBakeSetFormat, invalid JSON, a missing or unknown field, a wrong type, a
/// number that is not finite or out of its range (latitude outside [-90, 90], a cell size <= 0, a negative
/// irradiance, a direction that is not a unit vector, a count that is not a whole number >= 0), a sunny slot
/// without its time or sun position, an overcast slot with them, an input_hash that is not 16 hex digits, an
/// "input_paths" other than its fixed text, a "partial" whose slot is not the manifest's one slot or not among
/// its site_slots. Input paths are returned as written (see resolveBakeSetInputPath in gusuku/assets/bakeset_loader.h).
/// `file` names the text in messages.
BakeSetManifest parseBakeSetManifest(const std::string& file, const std::string& text);

/// Reads the file at path (InputError when it cannot be read) and parses it, naming it by path.
BakeSetManifest readBakeSetManifest(const std::string& path);

}  // namespace gusuku
