// The head client holds the commands not yet sent while the rate limit keeps them back. A
// newer command takes an older one's place only where the head ends the same as after both
// in turn: a vergence stop left out of the next pan/tilt command must still go out.
#pragma once

#include "headctl/head_backend.hpp"

#include <deque>
#include <optional>

namespace gc::headctl {

// One command doing what `earlier` then `next` do, when there is one: velocity after
// velocity, or absolute after absolute, with `next`'s values and `earlier`'s for the axes
// `next` does not name. Nullopt for any other pair.
std::optional<HeadCommand> merge_commands(const HeadCommand& earlier, const HeadCommand& next);

// Whether `next`, sent after `earlier`, leaves nothing of it: a stop, home or preset recall
// after any motion; a move that names every axis `earlier` names, unless `next` is relative
// (it starts from where `earlier` leaves the head). A saved preset is never undone.
bool undoes(const HeadCommand& next, const HeadCommand& earlier);

// Adds `next` to the commands waiting to be sent, oldest first: merged into the newest when
// they merge, else after dropping those it undoes. At most `max_waiting` wait; beyond that
// the oldest goes. Returns how many commands were merged away or dropped.
int queue_command(std::deque<HeadCommand>& waiting, const HeadCommand& next, std::size_t max_waiting);

}  // namespace gc::headctl
