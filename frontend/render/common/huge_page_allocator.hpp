// An allocator for the large per-frame arrays of the host renderers: blocks
// of 4 MiB or more are aligned to 2 MiB and marked for transparent huge
// pages (madvise MADV_HUGEPAGE; Linux's default THP mode is "madvise"), so
// the first touch of such an array faults once per 2 MiB instead of once
// per 4 KiB page. On the default forest render that was 52,000 page faults
// and about 10% of the process's CPU time (docs/cpu-renderer.md, "Memory").
// Smaller blocks, and systems without madvise, take the ordinary allocator.
//
// resize() leaves trivially copyable elements uninitialized (their objects
// begin implicitly in the allocated memory) instead of zeroing them: the
// setup writes every element on the worker thread that owns it before
// anything reads it, so the pages are first touched in parallel and once,
// not zeroed by one thread first and written again by the workers.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace blurcull::frontend {

template <class T>
struct HugePageAllocator {
    using value_type = T;
    static constexpr std::size_t huge_page = std::size_t(2) << 20;
    static constexpr std::size_t threshold = std::size_t(4) << 20;

    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (bytes < threshold) return std::allocator<T>().allocate(n);
        const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
        void* p = std::aligned_alloc(huge_page, rounded);
        if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        madvise(p, rounded, MADV_HUGEPAGE);  // a hint: without THP it changes nothing
#endif
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < threshold)
            std::allocator<T>().deallocate(p, n);
        else
            std::free(p);
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        if constexpr (sizeof...(Args) == 0 && std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>)
            (void)p;  // left for the owner to write
        else
            ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    template <class U>
    bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
    template <class U>
    bool operator!=(const HugePageAllocator<U>&) const noexcept { return false; }
};

// A std::vector whose large buffers live on huge pages (and whose resize()
// leaves trivially copyable elements for the caller to write).
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace blurcull::frontend
