// The checks of what a scene is asked to render: its configuration, a head pose and a hand
// pose, each refused with std::invalid_argument naming what is wrong.
#pragma once

#include "sim/scene.hpp"

#include <string>

namespace gc::sim {

// Throws std::invalid_argument(message) unless `ok`.
void require_valid(bool ok, const std::string& message);
// A number as the messages show it.
std::string number_text(double v);

void validate(const SceneConfig& c);
void validate(const HeadPose& h);
void validate(const HandPose& p);

}  // namespace gc::sim
