#include "tools/model_runs.hpp"

#include "tools/bench_stats.hpp"

#include "detect/depthwise_convolution.hpp"
#include "detect/dnn_input.hpp"
#include "detect/model_files.hpp"

#include <opencv2/dnn.hpp>

#include <algorithm>

namespace gc::tools {

namespace {

constexpr int kWarmUpCalls = 3;

struct TimedNet {
    cv::dnn::Net net;
    std::vector<std::string> outputs;
    std::vector<cv::Mat> results;
    std::vector<double> cpu_ms;

    void call(const cv::Mat& input, bool timed)
    {
        const double start = thread_cpu_ms();
        net.setInput(input);
        net.forward(results, outputs);
        if (timed) cpu_ms.push_back(thread_cpu_ms() - start);
    }
};

ModelTiming time_model(const std::string& file, int side, int calls)
{
    const std::string path = gc::find_model(file).string();
    TimedNet opencv{cv::dnn::readNetFromONNX(path), {}, {}, {}};
    TimedNet product{gc::read_onnx_with_depthwise_convolution(path), {}, {}, {}};
    opencv.outputs = product.outputs = opencv.net.getUnconnectedOutLayersNames();
    cv::Mat input = gc::make_square_blob(side);
    cv::RNG(1).fill(input, cv::RNG::UNIFORM, 0.0, 1.0);
    // Alternating calls share whatever else the machine does at the time.
    for (int i = 0; i < kWarmUpCalls + calls; ++i) {
        opencv.call(input, i >= kWarmUpCalls);
        product.call(input, i >= kWarmUpCalls);
    }
    ModelTiming t{file, side, calls, median(opencv.cpu_ms), median(product.cpu_ms), 0.0};
    for (std::size_t k = 0; k < opencv.results.size(); ++k)
        t.max_abs_diff = std::max(t.max_abs_diff, cv::norm(opencv.results[k], product.results[k], cv::NORM_INF));
    return t;
}

}  // namespace

std::vector<ModelTiming> measure_models(int calls)
{
    return {time_model("palm_detection.onnx", 128, calls), time_model("hand_landmark.onnx", 224, calls)};
}

}  // namespace gc::tools
