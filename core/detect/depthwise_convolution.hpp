// Depthwise convolution with 5x5 kernels for OpenCV DNN networks. OpenCV 4.6's fast
// depthwise path covers 3x3 kernels; a 5x5 one (one filter per channel) goes through its
// general grouped convolution, and in the hand models those layers took more than half of
// a network call (docs/adr/0036-depthwise-convolution.md).
#pragma once

#include <opencv2/dnn.hpp>

#include <functional>
#include <string>

namespace gc {

// Runs `make_network` with OpenCV DNN's convolution layer replaced by one that computes
// depthwise convolutions with 5x5 kernels (as many groups as input and output channels,
// one input, stride 1 or 2) itself and leaves every other convolution to OpenCV's layer.
// Layers `make_network` creates (OpenCV's importers create every layer while they read;
// Net::getLayer creates one added by hand) keep the replacement; the factory is restored
// when it returns or throws, so networks read elsewhere in the process are unaffected.
cv::dnn::Net with_depthwise_convolution(const std::function<cv::dnn::Net()>& make_network);

// cv::dnn::readNetFromONNX(path) under with_depthwise_convolution. The network's results
// equal OpenCV's up to the order in which floating-point products are summed. Throws
// cv::Exception as cv::dnn::readNetFromONNX does.
cv::dnn::Net read_onnx_with_depthwise_convolution(const std::string& path);

}  // namespace gc
