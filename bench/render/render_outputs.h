#pragma once
// gusuku-render's outputs may never overwrite what it reads: a composite written onto a bake set's lightmap or
// onto the camera image would destroy the input (and the next render would fail on the wrong size), so every
// output is checked against every input, and against the other outputs, before anything is rendered.

#include <string>
#include <vector>

#include "render_request.h"

namespace gusuku::render_cli {

/// The files a render reads: every file in the bake set folder (the manifest and what it names), the camera
/// image unless it is "sample", and site.json when one is given (or resolved from the manifest, `site_json`).
std::vector<std::string> renderInputFiles(const RenderRequest& request, const std::string& site_json);

/// Throws InputError(output, option, "is an input of this render (...)") when an output (-o, --direct-only,
/// --camera-out) is, after resolving links and relative parts, one of `inputs` or the bake set folder itself,
/// or the same file as another output; then applies the output guard every writing command shares
/// (gusuku_bake/output_guard.h): no output inside a bake set or a runtime pack.
void refuseOutputsThatAreInputs(const RenderRequest& request, const std::vector<std::string>& inputs);

}  // namespace gusuku::render_cli
