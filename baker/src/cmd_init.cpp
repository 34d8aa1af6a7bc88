// `gusuku-bake init DIR --lat --lon --height --utc-offset --date`: a starter site.json with comments and a checklist of
// what to measure on site (site_starter.h), for a site team starting from nothing but the README.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "commands.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/site.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"
#include "site_starter.h"

namespace gusuku::bake_cli {

namespace {

std::string range(const SiteValueRange& range) {
    char text[64];
    std::snprintf(text, sizeof text, "[%g, %g]", range.minimum, range.maximum);
    return text;
}

CommandHelp initHelp() {
    const SiteStarterPlace defaults;
    CommandHelp help;
    help.usage = "usage: gusuku-bake init DIR --lat DEG --lon DEG --height M --utc-offset +HH:MM --date YYYY-MM-DD "
                 "[options]";
    help.description =
        "Writes DIR/site.json, a starter whose comments say what each field is and how to measure it, and\n"
        "DIR/CHECKLIST.md, what to measure and photograph on site. The place and the day are options, not\n"
        "placeholders, so a starter never bakes wrong light silently. Then put your building, site mesh and sky\n"
        "photos beside it under the names it gives and run `gusuku-bake check DIR/site.json`.";
    help.options = {
        {"--lat", "", "DEG", "the reference point's latitude, north positive, " + range(kSiteLatitudeRangeDeg), ""},
        {"--lon", "", "DEG", "its longitude, east positive, " + range(kSiteLongitudeRangeDeg), ""},
        {"--height", "", "M",
         "its height above the WGS84 ellipsoid (what GNSS gives; not above sea level), metres, " +
             range(kSiteHeightRangeM),
         ""},
        {"--utc-offset", "", "+HH:MM", "the site's clock on the baked day, e.g. +09:00 or -04:00", ""},
        {"--date", "", "YYYY-MM-DD", "the day to bake, on the site's clock", ""},
        {"--name", "", "TEXT", "the site's name, shown in summaries", defaults.name},
        {"--force", "", "", "replace an existing site.json and CHECKLIST.md in DIR", ""},
    };
    help.notes = "Exit status: 0 written, 1 a bad value or an existing file, 2 bad usage.";
    return help;
}

bool twoDigits(const std::string& text, size_t at) {
    return text[at] >= '0' && text[at] <= '9' && text[at + 1] >= '0' && text[at + 1] <= '9';
}

// "+hh:mm" / "-hh:mm" within site.json's [-14:00, +14:00].
bool isUtcOffset(const std::string& text) {
    if (text.size() != 6 || (text[0] != '+' && text[0] != '-') || text[3] != ':' || !twoDigits(text, 1) ||
        !twoDigits(text, 4))
        return false;
    const int hours = std::stoi(text.substr(1, 2)), minutes = std::stoi(text.substr(4, 2));
    return minutes <= 59 && hours * 60 + minutes <= 14 * 60;
}

// "YYYY-MM-DD", a real calendar day.
bool isDate(const std::string& text) {
    if (text.size() != 10 || text[4] != '-' || text[7] != '-' || !twoDigits(text, 0) || !twoDigits(text, 2) ||
        !twoDigits(text, 5) || !twoDigits(text, 8))
        return false;
    const std::chrono::year_month_day day{std::chrono::year(std::stoi(text.substr(0, 4))),
                                          std::chrono::month(unsigned(std::stoi(text.substr(5, 2)))),
                                          std::chrono::day(unsigned(std::stoi(text.substr(8, 2))))};
    return day.ok();
}

}  // namespace

int runInitCommand(const std::vector<std::string>& args) {
    std::string directory;
    bool force = false;
    SiteStarterPlace place;
    const auto parse = [&](CommandLine& line) {
        const std::optional<double> latitude =
            line.number("--lat", kSiteLatitudeRangeDeg.minimum, kSiteLatitudeRangeDeg.maximum);
        const std::optional<double> longitude =
            line.number("--lon", kSiteLongitudeRangeDeg.minimum, kSiteLongitudeRangeDeg.maximum);
        const std::optional<double> height = line.number("--height", kSiteHeightRangeM.minimum, kSiteHeightRangeM.maximum);
        const std::optional<std::string> utc_offset = line.text("--utc-offset");
        const std::optional<std::string> date = line.text("--date");
        if (const std::optional<std::string> name = line.text("--name")) place.name = *name;
        force = line.flag("--force");
        const std::vector<std::string> directories = line.positionals();
        line.finish();
        if (directories.size() != 1) line.fail(directories.empty() ? "DIR is missing" : "more than one DIR given");
        directory = directories.front();
        // Each of the place's options is required: a default latitude or day would bake the wrong sun silently.
        for (const auto& [given, option] : {std::pair{latitude.has_value(), "--lat"}, {longitude.has_value(), "--lon"},
                                            {height.has_value(), "--height"}, {utc_offset.has_value(), "--utc-offset"},
                                            {date.has_value(), "--date"}})
            if (!given) line.fail(std::string(option) + " is missing (the starter takes the place and the day from it)");
        if (!isUtcOffset(*utc_offset))
            line.failValue("--utc-offset", "'" + *utc_offset + "' is not +HH:MM or -HH:MM within [-14:00, +14:00]");
        if (!isDate(*date)) line.failValue("--date", "'" + *date + "' is not a calendar day of the form YYYY-MM-DD");
        if (place.name.empty()) line.failValue("--name", "is empty");
        place.latitude_deg = *latitude;
        place.longitude_deg = *longitude;
        place.height_m = *height;
        place.utc_offset = *utc_offset;
        place.date = *date;
    };
    if (const std::optional<int> exit_code = readCommandLine("gusuku-bake init", args, initHelp(), true, parse))
        return *exit_code;

    namespace fs = std::filesystem;
    const fs::path folder(directory);
    const fs::path site_json = folder / "site.json", checklist = folder / "CHECKLIST.md";
    std::error_code error;
    if (fs::exists(folder, error) && !fs::is_directory(folder, error)) {
        std::fprintf(stderr, "gusuku-bake init: %s: exists and is not a folder\n", directory.c_str());
        return 1;
    }
    for (const fs::path& file : {site_json, checklist})
        if (!force && fs::exists(file, error)) {
            std::fprintf(stderr, "gusuku-bake init: %s: already exists; nothing written (--force replaces it)\n",
                         file.string().c_str());
            return 1;
        }
    fs::create_directories(folder, error);
    if (error) {
        std::fprintf(stderr, "gusuku-bake init: %s: cannot create the folder: %s\n", directory.c_str(),
                     error.message().c_str());
        return 1;
    }
    const std::string site_text = siteStarterJson(place), checklist_text = siteChecklist(place);
    writeBytesAtomically(site_json.string(), site_text.data(), site_text.size());
    writeBytesAtomically(checklist.string(), checklist_text.data(), checklist_text.size());
    std::printf("wrote %s and %s\n", site_json.string().c_str(), checklist.string().c_str());
    std::printf("next: put building.glb, site.glb, sky_sunny.hdr and sky_overcast.hdr beside them (or change the\n"
                "paths), then run: gusuku-bake check %s\n",
                site_json.string().c_str());
    return 0;
}

}  // namespace gusuku::bake_cli
