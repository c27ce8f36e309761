#include "headctl/command_merge.hpp"

#include <algorithm>

namespace gc::headctl {

std::optional<HeadCommand> merge_commands(const HeadCommand& earlier, const HeadCommand& next)
{
    const bool mergeable =
        earlier.kind == next.kind && (next.kind == CommandKind::Velocity || next.kind == CommandKind::Absolute);
    if (!mergeable) return std::nullopt;
    HeadCommand merged = next;
    for (Axis a : kAllAxes)
        if (earlier.values.has(a) && !next.values.has(a)) merged.values.set(a, earlier.values.get(a));
    return merged;
}

bool undoes(const HeadCommand& next, const HeadCommand& earlier)
{
    if (earlier.kind == CommandKind::SavePreset) return false;
    if (next.kind == CommandKind::Stop || next.kind == CommandKind::Home || next.kind == CommandKind::RecallPreset)
        return true;
    const bool earlier_names_axes = earlier.kind == CommandKind::Velocity || earlier.kind == CommandKind::Absolute ||
                                    earlier.kind == CommandKind::Relative;
    if (next.kind == CommandKind::Relative || next.kind == CommandKind::SavePreset || !earlier_names_axes) return false;
    return std::all_of(kAllAxes.begin(), kAllAxes.end(),
                       [&](Axis a) { return !earlier.values.has(a) || next.values.has(a); });
}

int queue_command(std::deque<HeadCommand>& waiting, const HeadCommand& next, std::size_t max_waiting)
{
    if (!waiting.empty())
        if (std::optional<HeadCommand> merged = merge_commands(waiting.back(), next)) {
            waiting.back() = *merged;
            return 1;
        }
    const std::size_t before = waiting.size();
    std::erase_if(waiting, [&](const HeadCommand& earlier) { return undoes(next, earlier); });
    int gone = int(before - waiting.size());
    waiting.push_back(next);
    for (; waiting.size() > max_waiting; ++gone) waiting.pop_front();
    return gone;
}

}  // namespace gc::headctl
