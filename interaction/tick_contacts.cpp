#include "interaction/tick_contacts.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace sward {

TickContacts::TickContacts(std::vector<gpu::PlantContact> contacts) {
    if (contacts.empty()) return;
    auto owned = std::make_shared<std::vector<gpu::PlantContact>>(std::move(contacts));
    runs_.push_back(*owned);
    size_ = owned->size();
    owner_ = std::move(owned);
}

TickContacts::TickContacts(std::shared_ptr<const void> owner, std::vector<Run> runs)
    : owner_(std::move(owner)), runs_(std::move(runs)) {
    std::erase_if(runs_, [](Run run) { return run.empty(); });
    for (Run run : runs_) size_ += run.size();
}

void TickContacts::copyTo(std::span<gpu::PlantContact> out) const {
    assert(out.size() == size_);
    auto at = out.begin();
    for (Run run : runs_) at = std::copy(run.begin(), run.end(), at);
}

std::vector<gpu::PlantContact> TickContacts::flatten() const {
    std::vector<gpu::PlantContact> contacts(size_);
    copyTo(contacts);
    return contacts;
}

} // namespace sward
