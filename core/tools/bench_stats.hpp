// Small figures shared by gesturecam-bench's measurements and tables: wall time, medians
// and means that are NaN on no data, and fixed-point text that prints NaN as "n/a".
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace gc::tools {

using BenchClock = std::chrono::steady_clock;

double ms_since(BenchClock::time_point t0);
double median(std::vector<double> v);
double mean(const std::vector<double>& v);
std::string fixed(double v, int decimals);

}  // namespace gc::tools
