// A list that one thread appends to and another reads: what a test's peer or callback saw.
#pragma once

#include <mutex>
#include <vector>

namespace gc::headctl::testing {

template <class Item>
class SharedLog {
public:
    void add(const Item& item)
    {
        std::lock_guard lock(mutex_);
        items_.push_back(item);
    }
    std::vector<Item> items() const
    {
        std::lock_guard lock(mutex_);
        return items_;
    }

private:
    mutable std::mutex mutex_;
    std::vector<Item> items_;
};

}  // namespace gc::headctl::testing
