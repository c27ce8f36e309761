// libFuzzer entry point for the calibration loader: arbitrary bytes as a calibration file
// (YAML, XML or JSON as cv::FileStorage reads them). The loader may only ever answer with
// a calibration or a gc::CalibrationError.
#include "stereo/calibration.hpp"
#include "stereo/calibration_io.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    const std::string content(reinterpret_cast<const char*>(data), size);
    try {
        const gc::StereoCalibration c = gc::parse_calibration(content, "fuzz-input");
        // Whatever loads must be usable: the checks that consumers rely on hold.
        gc::validate_calibration(c);
        gc::validate_calibration_size(c, c.image_size);
    } catch (const gc::CalibrationError&) {
        // Rejected with a message: the expected outcome for almost every input.
    }
    return 0;
}
