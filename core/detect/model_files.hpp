// Where the learned hand models live, found without configuration, and loading them with
// errors that say which file is wrong and how.
#pragma once

#include <opencv2/dnn.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace gc {

// Environment variable that names the model folder, ahead of the built-in places.
inline constexpr const char* kModelDirEnv = "GESTURECAM_MODEL_DIR";

// The folders searched for a model, in order. An explicit folder (a property or a tool
// option), when not empty, is the only one: a folder the user named and got wrong must not
// be papered over by another copy. Otherwise GESTURECAM_MODEL_DIR alone when set, else the
// installed data folder, then the source tree's core/models (so runs from the build tree
// and the tests need no installation).
std::vector<std::filesystem::path> model_search_dirs(const std::filesystem::path& explicit_dir = {});

// The path of `file_name` in the first of model_search_dirs that holds it. Throws
// std::runtime_error naming the file and every folder searched when none does.
std::filesystem::path find_model(const std::string& file_name, const std::filesystem::path& explicit_dir = {});

// Reads an ONNX network and checks that it has the named outputs. Throws
// std::runtime_error naming `path` and what is wrong: missing, unreadable or not a network
// OpenCV can load, or a network without one of the outputs.
cv::dnn::Net load_onnx_model(const std::filesystem::path& path, const std::vector<std::string>& expected_outputs);

}  // namespace gc
