#pragma once
// The visitor poses the bench's site section measures from (gusuku-bench --views), and the sample site's frame
// times it compares a real model's frame with (--sample-results).
//
// --views is one line of named poses, separated by ';':  NAME:E,N,U:E,N,U[:FOV]  (the camera centre and the point
// at the image centre in site ENU metres, the horizontal field of view in degrees, default 60), e.g.
// "front:2,-5,3.2:2,3.5,3;corner:-5,-2.5,3.2:2,3.5,2.8". Names are 1-32 of a-z, 0-9, _ and unique.

#include <map>
#include <string>
#include <vector>

#include "truth_renderer.h"

namespace gusuku::bench {

struct NamedView {
    std::string name;
    BenchView view;
};

/// The poses of a --views value, in order. std::invalid_argument, one line naming --views, the pose (its number
/// and name) and what is wrong: a malformed number, a point without three coordinates, a field of view outside
/// (1, 170), a camera at its look-at point, a bad or repeated name, an empty list.
std::vector<NamedView> parseBenchViews(const std::string& text);

/// The proposed method's median 1280x720 frame time per view name, from a gusuku-bench results.json whose run
/// had the site section (results["site"]["views"][i]["name"], ["frame_1280x720"]["proposed_ms"]).
/// InputError naming the file and the JSON field when the file is missing, not JSON, or has no such section.
std::map<std::string, double> sampleFrameTimesFrom(const std::string& results_json);

}  // namespace gusuku::bench
