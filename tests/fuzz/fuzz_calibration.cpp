// libFuzzer entry point for the calibration loader: arbitrary bytes as a calibration file
// (the YAML and XML subset of core/stereo/calibration_text.hpp). The loader may only ever
// answer with a calibration or a gc::CalibrationError, and in time linear in the input.
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
