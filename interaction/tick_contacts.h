// A tick's contacts as the collision pass leaves them: the runs its fields wrote, in field order, never merged into
// one list. A tick's contacts are megabytes (2 MB for 400 fields x 25 colliders); copying them into one list was a
// twelfth of the 2-thread tick, and the GPU upload copies them once more anyway, so that upload is the one copy.
#pragma once

#include "shared/gpu_layout.h"

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace sward {

// Contacts sorted by plant index, at most one per plant, as non-empty runs in order. Shares ownership of the
// buffers the runs lie in: it stays valid and unchanged after the pass that made it runs again.
class TickContacts {
public:
    using Run = std::span<const gpu::PlantContact>;

    TickContacts() = default;
    // Contacts made elsewhere (tests, tools), already sorted by plant: one run holding a copy of them.
    explicit TickContacts(std::vector<gpu::PlantContact> contacts);
    // Runs lying in buffers that `owner` keeps alive; empty runs are dropped.
    TickContacts(std::shared_ptr<const void> owner, std::vector<Run> runs);

    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    std::span<const Run> runs() const { return runs_; }
    // Every contact in order, into out (size() of them): the upload's one copy.
    void copyTo(std::span<gpu::PlantContact> out) const;
    // A contiguous copy, for tests and tools that index the contacts.
    std::vector<gpu::PlantContact> flatten() const;

private:
    std::shared_ptr<const void> owner_;
    std::vector<Run> runs_;
    size_t size_ = 0;
};

} // namespace sward
