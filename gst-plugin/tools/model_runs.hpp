// gesturecam-bench's cost of one call of each learned model, as OpenCV DNN reads the
// network and with the depthwise convolution the product uses (docs/adr/0036), measured
// in the same run on the same input.
#pragma once

#include <string>
#include <vector>

namespace gc::tools {

struct ModelTiming {
    std::string model;          // file name
    int input_side = 0;         // the square input, pixels
    int calls = 0;              // timed calls per way, alternating
    double opencv_ms = 0.0;     // median thread CPU time of a call, OpenCV's layers
    double product_ms = 0.0;    // ... with the product's depthwise convolution
    double max_abs_diff = 0.0;  // largest difference between the two ways' outputs
};

// Both models, `calls` timed calls each way (one OpenCV thread, as the rest of the bench).
std::vector<ModelTiming> measure_models(int calls);

}  // namespace gc::tools
