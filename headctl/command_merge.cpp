#include "headctl/command_merge.hpp"

namespace gc::headctl {

HeadCommand merge_commands(const HeadCommand& pending, const HeadCommand& next,
                           const std::array<bool, kAxisCount>& axes)
{
    HeadCommand merged = next;
    const bool same_kind = pending.kind == next.kind;
    for (Axis a : kAllAxes) {
        const bool named_before = pending.values.has(a), named_now = next.values.has(a);
        if (same_kind && (next.kind == CommandKind::Velocity || next.kind == CommandKind::Absolute)) {
            if (named_before && !named_now) merged.values.set(a, pending.values.get(a));
        } else if (same_kind && next.kind == CommandKind::Relative) {
            if (named_before) merged.values.set(a, pending.values.get(a) + (named_now ? next.values.get(a) : 0.0));
        } else if (pending.kind == CommandKind::Stop && next.kind == CommandKind::Velocity) {
            if (!named_now && axes[static_cast<std::size_t>(a)]) merged.values.set(a, 0.0);
        }
    }
    return merged;
}

}  // namespace gc::headctl
