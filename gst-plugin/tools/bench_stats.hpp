// Small figures shared by gesturecam-bench's measurements and tables: wall time, medians
// and means that are NaN on no data, the angle between two directions, and fixed-point
// text that prints NaN as "n/a".
#pragma once

#include <opencv2/core.hpp>

#include <chrono>
#include <string>
#include <vector>

namespace gc::tools {

using BenchClock = std::chrono::steady_clock;

double ms_since(BenchClock::time_point t0);
// CPU time in ms, of the calling thread or of the whole process (every thread): what a
// measurement costs however busy the machine is, where wall time also counts the waits.
double thread_cpu_ms();
double process_cpu_ms();
double median(std::vector<double> v);
double mean(const std::vector<double>& v);
double angle_deg(const cv::Vec3d& a, const cv::Vec3d& b);
std::string fixed(double v, int decimals);

}  // namespace gc::tools
