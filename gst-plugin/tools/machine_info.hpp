// What a benchmark ran on: core count, CPU model and load average (Linux /proc), so that the
// figures can be compared and a busy machine recognised.
#pragma once

#include <fstream>
#include <string>
#include <thread>

namespace gc::tools {

struct MachineInfo {
    unsigned cores = 0;
    std::string cpu_model = "unknown";
    double load_1min = -1.0;  // -1 when unknown
};

inline MachineInfo machine_info()
{
    MachineInfo m;
    m.cores = std::thread::hardware_concurrency();
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) == 0) {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos) {
                const std::size_t start = line.find_first_not_of(" \t", colon + 1);
                if (start != std::string::npos) m.cpu_model = line.substr(start);
            }
            break;
        }
    }
    std::ifstream loadavg("/proc/loadavg");
    double load = 0.0;
    if (loadavg >> load) m.load_1min = load;
    return m;
}

}  // namespace gc::tools
