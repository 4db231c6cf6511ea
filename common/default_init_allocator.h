// An allocator for vectors that are sized and then filled: resize() default-initialises new elements, which leaves
// trivial types uninitialised where std::allocator would zero them first. The collision pass sizes a tick's merged
// contacts (megabytes) and fills them from several threads; zeroing them first cost as much as the copy.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>

namespace sward {

template <class T> class DefaultInitAllocator : public std::allocator<T> {
public:
    template <class U> struct rebind { using other = DefaultInitAllocator<U>; };
    using std::allocator<T>::allocator;

    template <class U> void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args> void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

} // namespace sward
