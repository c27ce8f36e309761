#include "detect/depthwise_convolution.hpp"

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/dnn/all_layers.hpp>
#include <opencv2/dnn/layer.hpp>

#include <algorithm>
#include <mutex>
#include <vector>

namespace gc {

namespace {

// The geometry of one depthwise convolution, for one channel plane.
struct PlaneGeometry {
    int in_h = 0, in_w = 0, out_h = 0, out_w = 0;
    int kernel_h = 0, kernel_w = 0, stride_h = 1, stride_w = 1, dilation_h = 1, dilation_w = 1;
    int pad_top = 0, pad_left = 0;
};

// One channel plane with its zero border already in place (`padded`, `padded_w` floats a
// row, (out_w - 1) * S + K of them, so no tap of an output pixel reads past its row): every
// output pixel sums the same K x K taps. Four pixels of a row are summed at a time with
// OpenCV's universal intrinsics (SSE2 or NEON, whatever the build's flags), the rest of the
// row one by one.
template <int K, int S>
void convolve_padded(const float* __restrict padded, int padded_w, float* __restrict out, int out_h, int out_w,
                     const float* __restrict kernel, float bias)
{
    constexpr int kLanes = cv::v_float32x4::nlanes;
    cv::v_float32x4 weights[K * K];
    for (int t = 0; t < K * K; ++t) weights[t] = cv::v_setall_f32(kernel[t]);
    for (int oy = 0; oy < out_h; ++oy) {
        const float* __restrict top = padded + oy * S * padded_w;
        float* __restrict row = out + oy * out_w;
        int ox = 0;
        for (; ox + kLanes <= out_w; ox += kLanes) {
            cv::v_float32x4 sum = cv::v_setall_f32(bias);
            for (int ky = 0; ky < K; ++ky)
                for (int kx = 0; kx < K; ++kx) {
                    const float* from = top + ky * padded_w + ox * S + kx;
                    cv::v_float32x4 taps;
                    if constexpr (S == 1) {
                        taps = cv::v_load(from);
                    } else {
                        taps = cv::v_float32x4(from[0], from[S], from[2 * S], from[3 * S]);
                    }
                    sum = cv::v_fma(weights[ky * K + kx], taps, sum);
                }
            cv::v_store(row + ox, sum);
        }
        for (; ox < out_w; ++ox) {
            float sum = bias;
            for (int ky = 0; ky < K; ++ky)
                for (int kx = 0; kx < K; ++kx) sum += kernel[ky * K + kx] * top[ky * padded_w + ox * S + kx];
            row[ox] = sum;
        }
    }
}

// Copies one channel plane into `padded` with `g`'s zero border (and enough rows and
// columns past the far edge for the last output pixel's taps).
void pad_plane(const float* in, const PlaneGeometry& g, std::vector<float>& padded, int& padded_w)
{
    padded_w = (g.out_w - 1) * g.stride_w + g.kernel_w;
    const int padded_h = (g.out_h - 1) * g.stride_h + g.kernel_h;
    padded.assign(size_t(padded_w) * padded_h, 0.0f);
    for (int y = 0; y < g.in_h; ++y) {
        const int py = y + g.pad_top;
        if (py < 0 || py >= padded_h) continue;
        const int first = std::max(0, -g.pad_left), end = std::min(g.in_w, padded_w - g.pad_left);
        if (first < end)
            std::copy(in + y * g.in_w + first, in + y * g.in_w + end,
                      padded.begin() + py * padded_w + first + g.pad_left);
    }
}

// The 5x5 kernels and strides the hand models use run here; any other kernel (OpenCV's 3x3
// path is faster than this loop) or a dilated one is left to OpenCV's layer.
using PaddedConvolution = void (*)(const float*, int, float*, int, int, const float*, float);
PaddedConvolution unrolled_convolution(const PlaneGeometry& g)
{
    if (g.kernel_h != g.kernel_w || g.stride_h != g.stride_w || g.dilation_h != 1 || g.dilation_w != 1) return nullptr;
    if (g.kernel_h == 5 && g.stride_h == 1) return &convolve_padded<5, 1>;
    if (g.kernel_h == 5 && g.stride_h == 2) return &convolve_padded<5, 2>;
    return nullptr;
}

// OpenCV's convolution layer, except that a depthwise convolution is computed here.
// Everything else (shapes, other convolutions, fusing a following layer) is OpenCV's own
// layer's work; an activation fused into this one is applied on both paths.
class ConvolutionWithDepthwise final : public cv::dnn::Layer {
public:
    explicit ConvolutionWithDepthwise(const cv::dnn::LayerParams& params)
        : Layer(params), builtin_(cv::dnn::ConvolutionLayer::create(params))
    {
    }

    static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams& params)
    {
        return cv::makePtr<ConvolutionWithDepthwise>(params);
    }

    bool getMemoryShapes(const std::vector<cv::dnn::MatShape>& inputs, int required_outputs,
                         std::vector<cv::dnn::MatShape>& outputs,
                         std::vector<cv::dnn::MatShape>& internals) const override
    {
        return builtin_->getMemoryShapes(inputs, required_outputs, outputs, internals);
    }

    void finalize(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr) override
    {
        builtin_->finalize(inputs_arr, outputs_arr);
        std::vector<cv::Mat> inputs, outputs;
        inputs_arr.getMatVector(inputs);
        outputs_arr.getMatVector(outputs);
        convolution_ = nullptr;
        if (!is_depthwise(inputs, outputs)) return;
        const cv::Mat& in = inputs[0];
        const cv::Mat& out = outputs[0];
        geometry_ = {in.size[2],
                     in.size[3],
                     out.size[2],
                     out.size[3],
                     int(builtin_->kernel_size[0]),
                     int(builtin_->kernel_size[1]),
                     int(builtin_->strides[0]),
                     int(builtin_->strides[1]),
                     int(builtin_->dilations[0]),
                     int(builtin_->dilations[1]),
                     int(builtin_->pads_begin[0]),
                     int(builtin_->pads_begin[1])};
        convolution_ = unrolled_convolution(geometry_);
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays internals_arr) override
    {
        if (!convolution_) {
            builtin_->forward(inputs_arr, outputs_arr, internals_arr);
            return;
        }
        std::vector<cv::Mat> inputs, outputs;
        inputs_arr.getMatVector(inputs);
        outputs_arr.getMatVector(outputs);
        const cv::Mat& in = inputs[0];
        cv::Mat& out = outputs[0];
        const int channels = in.size[1];
        const int planes = in.size[0] * channels;
        const size_t in_plane = size_t(geometry_.in_h) * geometry_.in_w;
        const size_t out_plane = size_t(geometry_.out_h) * geometry_.out_w;
        const float* weights = blobs[0].ptr<float>();
        const float* bias = blobs.size() > 1 ? blobs[1].ptr<float>() : nullptr;
        const int taps = geometry_.kernel_h * geometry_.kernel_w;
        cv::parallel_for_(cv::Range(0, planes), [&](const cv::Range& range) {
            // One padded plane per thread, grown once to the largest plane.
            thread_local std::vector<float> padded;
            int padded_w = 0;
            for (int p = range.start; p < range.end; ++p) {
                const int c = p % channels;
                float* dst = out.ptr<float>() + p * out_plane;
                pad_plane(in.ptr<float>() + p * in_plane, geometry_, padded, padded_w);
                convolution_(padded.data(), padded_w, dst, geometry_.out_h, geometry_.out_w, weights + c * taps,
                             bias ? bias[c] : 0.0f);
                if (activation_) activation_->forwardSlice(dst, dst, int(out_plane), out_plane, c, c + 1);
            }
        });
    }

    bool setActivation(const cv::Ptr<cv::dnn::ActivationLayer>& layer) override
    {
        if (!builtin_->setActivation(layer)) return false;
        activation_ = layer;
        return true;
    }

    bool tryFuse(cv::Ptr<cv::dnn::Layer>& top) override { return !convolution_ && builtin_->tryFuse(top); }

private:
    // One 4-D float input, one filter of one input channel per output channel, as many
    // outputs as inputs, and a 2-D kernel.
    bool is_depthwise(const std::vector<cv::Mat>& inputs, const std::vector<cv::Mat>& outputs) const
    {
        if (inputs.size() != 1 || outputs.size() != 1 || blobs.empty()) return false;
        const cv::Mat& in = inputs[0];
        const cv::Mat& w = blobs[0];
        return in.dims == 4 && outputs[0].dims == 4 && in.type() == CV_32F && w.type() == CV_32F && w.dims == 4 &&
               w.size[1] == 1 && w.size[0] == in.size[1] && outputs[0].size[1] == in.size[1] &&
               builtin_->kernel_size.size() == 2 && in.isContinuous() && outputs[0].isContinuous() &&
               (blobs.size() == 1 || blobs[1].total() == size_t(in.size[1]));
    }

    cv::Ptr<cv::dnn::BaseConvolutionLayer> builtin_;
    cv::Ptr<cv::dnn::ActivationLayer> activation_;
    PaddedConvolution convolution_ = nullptr;  // null: OpenCV's layer computes this one
    PlaneGeometry geometry_;
};

}  // namespace

cv::dnn::Net with_depthwise_convolution(const std::function<cv::dnn::Net()>& make_network)
{
    // The factory is process-wide: the replacement is pushed for this call only and popped
    // again, so networks the host application reads keep OpenCV's layer.
    static std::mutex making;
    const std::lock_guard<std::mutex> lock(making);
    cv::dnn::LayerFactory::registerLayer("Convolution", &ConvolutionWithDepthwise::create);
    struct Unregister {
        ~Unregister() { cv::dnn::LayerFactory::unregisterLayer("Convolution"); }
    } unregister;
    return make_network();
}

cv::dnn::Net read_onnx_with_depthwise_convolution(const std::string& path)
{
    return with_depthwise_convolution([&] { return cv::dnn::readNetFromONNX(path); });
}

}  // namespace gc
