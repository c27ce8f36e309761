// The depthwise convolution that replaces OpenCV's for the hand models gives OpenCV's
// results, on small layers of every shape it takes and on both models, and leaves
// networks read without it alone.
#include "detect/depthwise_convolution.hpp"
#include "detect/model_files.hpp"

#include <gtest/gtest.h>

#include <opencv2/dnn/all_layers.hpp>

#include <string>
#include <vector>

namespace {

struct LayerShape {
    int channels, height, width, kernel, stride, pad;  // OpenCV pads both sides alike
    bool relu6;
};

// One convolution layer (and a ReLU6 the network fuses into it), its layers created at once.
cv::dnn::Net one_convolution(const LayerShape& s, const cv::Mat& weights, const cv::Mat& bias, int groups)
{
    cv::dnn::Net net;
    cv::dnn::LayerParams conv;
    conv.name = "conv";
    conv.type = "Convolution";
    conv.blobs = {weights, bias};
    conv.set("kernel_size", s.kernel);
    conv.set("stride", s.stride);
    conv.set("pad", s.pad);
    conv.set("num_output", s.channels);
    conv.set("group", groups);
    conv.set("bias_term", true);
    net.addLayerToPrev(conv.name, conv.type, conv);
    if (s.relu6) {
        cv::dnn::LayerParams relu;
        relu.set("min_value", 0.0f);
        relu.set("max_value", 6.0f);
        net.addLayerToPrev("relu6", "ReLU6", relu);
    }
    for (const std::string& name : net.getLayerNames()) net.getLayer(name);
    return net;
}

cv::Mat run(cv::dnn::Net& net, const cv::Mat& input)
{
    net.setInput(input);
    return net.forward().clone();
}

cv::Mat random_blob(std::vector<int> shape, float low, float high)
{
    cv::Mat blob(int(shape.size()), shape.data(), CV_32F);
    cv::randu(blob, low, high);
    return blob;
}

bool is_opencvs_convolution(cv::dnn::Net& net, const std::string& name)
{
    return dynamic_cast<cv::dnn::BaseConvolutionLayer*>(net.getLayer(name).get()) != nullptr;
}

TEST(DepthwiseConvolution, GivesOpenCVsResultsOnEveryShapeItTakes)
{
    cv::setRNGSeed(7);
    const LayerShape shapes[] = {
        {3, 13, 13, 5, 1, 2, false}, {8, 17, 9, 5, 1, 2, true},   {5, 16, 16, 5, 2, 1, true},
        {6, 15, 11, 5, 2, 0, false}, {4, 7, 3, 5, 1, 1, true},    {2, 30, 30, 5, 2, 2, false},
        {4, 10, 10, 3, 1, 1, true},  {3, 12, 12, 5, 1, 3, false},
    };
    for (const LayerShape& s : shapes) {
        SCOPED_TRACE("channels " + std::to_string(s.channels) + ", " + std::to_string(s.height) + "x" +
                     std::to_string(s.width) + ", kernel " + std::to_string(s.kernel) + ", stride " +
                     std::to_string(s.stride) + ", pad " + std::to_string(s.pad));
        const cv::Mat weights = random_blob({s.channels, 1, s.kernel, s.kernel}, -1.0f, 1.0f);
        const cv::Mat bias = random_blob({s.channels}, -0.5f, 0.5f);
        const cv::Mat input = random_blob({2, s.channels, s.height, s.width}, -3.0f, 3.0f);
        cv::dnn::Net opencv = one_convolution(s, weights, bias, s.channels);
        cv::dnn::Net ours =
            gc::with_depthwise_convolution([&] { return one_convolution(s, weights, bias, s.channels); });
        const cv::Mat expected = run(opencv, input);
        const cv::Mat got = run(ours, input);
        ASSERT_EQ(got.size, expected.size);
        EXPECT_LE(cv::norm(got, expected, cv::NORM_INF), 1e-4);
        if (s.relu6) {
            double low = 0, high = 0;
            cv::minMaxIdx(got, &low, &high);
            EXPECT_GE(low, 0.0);
            EXPECT_LE(high, 6.0);
        }
    }
}

// OpenCV folds a batch normalisation that follows a convolution into that layer's weights
// when the network is set up; a depthwise layer computed here must keep it.
TEST(DepthwiseConvolution, KeepsABatchNormalisationThatFollows)
{
    const LayerShape s{6, 12, 12, 5, 1, 2, false};
    const cv::Mat weights = random_blob({6, 1, 5, 5}, -1.0f, 1.0f);
    const cv::Mat bias = random_blob({6}, -0.5f, 0.5f);
    const cv::Mat input = random_blob({1, 6, 12, 12}, -1.0f, 1.0f);
    const auto with_batch_norm = [&] {
        cv::dnn::Net net = one_convolution(s, weights, bias, 6);
        cv::dnn::LayerParams norm;
        norm.blobs = {random_blob({6}, -1.0f, 1.0f), random_blob({6}, 0.5f, 2.0f), random_blob({6}, 0.5f, 2.0f),
                      random_blob({6}, -1.0f, 1.0f)};  // mean, variance, scale, shift
        norm.set("has_weight", true);
        norm.set("has_bias", true);
        norm.set("eps", 1e-5f);
        net.addLayerToPrev("norm", "BatchNorm", norm);
        for (const std::string& name : net.getLayerNames()) net.getLayer(name);
        return net;
    };
    cv::setRNGSeed(5);
    cv::dnn::Net opencv = with_batch_norm();
    cv::setRNGSeed(5);
    cv::dnn::Net ours = gc::with_depthwise_convolution(with_batch_norm);
    const cv::Mat expected = run(opencv, input);
    cv::dnn::Net plain = one_convolution(s, weights, bias, 6);
    EXPECT_GT(cv::norm(expected, run(plain, input), cv::NORM_INF), 0.1) << "the normalisation changes the output";
    EXPECT_LE(cv::norm(run(ours, input), expected, cv::NORM_INF), 1e-4);
}

TEST(DepthwiseConvolution, LeavesAGroupedConvolutionThatIsNotDepthwiseToOpenCV)
{
    const LayerShape s{4, 9, 9, 5, 1, 2, false};
    const cv::Mat weights = random_blob({4, 2, 5, 5}, -1.0f, 1.0f);  // two groups of two channels
    const cv::Mat bias = random_blob({4}, -0.5f, 0.5f);
    const cv::Mat input = random_blob({1, 4, 9, 9}, -1.0f, 1.0f);
    cv::dnn::Net opencv = one_convolution(s, weights, bias, 2);
    cv::dnn::Net ours = gc::with_depthwise_convolution([&] { return one_convolution(s, weights, bias, 2); });
    EXPECT_LE(cv::norm(run(ours, input), run(opencv, input), cv::NORM_INF), 1e-5);
}

TEST(DepthwiseConvolution, HandModelsGiveOpenCVsResultsAndOtherNetworksKeepOpenCVsLayer)
{
    cv::setRNGSeed(11);
    for (const auto& [file, side] : {std::pair<std::string, int>{"hand_landmark.onnx", 224},
                                     std::pair<std::string, int>{"palm_detection.onnx", 128}}) {
        SCOPED_TRACE(file);
        const std::string path = gc::find_model(file).string();
        cv::dnn::Net ours = gc::read_onnx_with_depthwise_convolution(path);
        cv::dnn::Net opencv = cv::dnn::readNetFromONNX(path);
        int replaced = 0;
        for (const std::string& name : ours.getLayerNames()) {
            if (ours.getLayer(name)->type != "Convolution") continue;
            replaced += !is_opencvs_convolution(ours, name);
            EXPECT_TRUE(is_opencvs_convolution(opencv, name)) << name << " read without the replacement";
        }
        EXPECT_GT(replaced, 0);
        const cv::Mat input = random_blob({1, 3, side, side}, 0.0f, 1.0f);
        const std::vector<std::string> outputs = opencv.getUnconnectedOutLayersNames();
        std::vector<cv::Mat> expected, got;
        opencv.setInput(input);
        opencv.forward(expected, outputs);
        ours.setInput(input);
        ours.forward(got, outputs);
        ASSERT_EQ(got.size(), expected.size());
        for (std::size_t i = 0; i < got.size(); ++i) {
            const double scale = std::max(1.0, cv::norm(expected[i], cv::NORM_INF));
            EXPECT_LE(cv::norm(got[i], expected[i], cv::NORM_INF), 1e-5 * scale) << outputs[i];
        }
    }
}

}  // namespace
