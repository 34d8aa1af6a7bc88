// What the bench ran on (see host_info.h).

#include "host_info.h"

#include <cstdlib>
#include <fstream>
#include <thread>

namespace gusuku::bench {

HostInfo describeHost(const std::string& device_description) {
    HostInfo info;
    info.device = device_description;
    info.cpu_model = "unknown";
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.rfind("model name", 0) == 0) {
            const size_t colon = line.find(':');
            if (colon != std::string::npos) info.cpu_model = line.substr(line.find_first_not_of(' ', colon + 1));
            break;
        }
    info.logical_cpus = std::thread::hardware_concurrency();
    info.lavapipe_threads = info.logical_cpus;
    if (const char* threads = std::getenv("LP_NUM_THREADS")) info.lavapipe_threads = unsigned(std::atoi(threads));
    return info;
}

}  // namespace gusuku::bench
