// The head client keeps one command not yet sent; a newer one takes its place. Taking its
// place must not lose what the older one asked of axes the newer one leaves alone: a
// vergence stopped by one velocity command and left out of the next would keep turning.
#pragma once

#include "headctl/head_backend.hpp"

#include <array>

namespace gc::headctl {

// The one command that leaves the head as `pending` then `next`, sent in turn, would:
// - velocity after velocity, or absolute after absolute: `next`'s values, and `pending`'s
//   for the axes `next` does not name;
// - relative after relative: the sum of both moves on each axis;
// - velocity after a stop: `next`, and velocity 0 for every other axis in `axes`;
// - anything else: `next` (a stop, a home or a preset decides for every axis, and commands
//   of different kinds cannot be made one).
HeadCommand merge_commands(const HeadCommand& pending, const HeadCommand& next,
                           const std::array<bool, kAxisCount>& axes);

}  // namespace gc::headctl
