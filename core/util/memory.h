// Memory for large arrays that are written once and read often (light-tree nodes): no
// initialisation that the writer will overwrite, and huge pages where the kernel offers them.
#pragma once
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace sst {

// Asks the kernel to back the whole 2 MiB pages inside [p, p + bytes) with huge pages, before the
// array is first written: one page fault per 2 MiB instead of one per 4 KiB, which on this
// project's virtual machines costs more than filling the memory. A hint only: no effect where
// transparent huge pages are off or unsupported, or for arrays under 2 MiB.
void advise_huge_pages(void* p, size_t bytes);

// Returns the free memory of every malloc arena to the kernel (glibc's malloc_trim; nothing
// elsewhere): after many small buffers are freed at once, so that they do not count in the peak
// resident memory of what follows.
void release_free_memory();

// std::allocator whose value-less construct() default-initialises: resize() of a vector of
// trivial elements then leaves them unwritten, for a parallel writer to fill (and to touch the
// pages first on the thread that uses them).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A vector of trivial elements whose resize() writes nothing.
template <class T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;

// v resized to n elements, unwritten, for a writer that writes every one: storage kept from an
// earlier call is reused (a build per frame allocates nothing). With `huge_pages`, new storage goes
// on huge pages where offered (advise_huge_pages), before anything touches it. Not for what is
// read on every sample: light-tree nodes on huge pages made rtslc's and the hybrid's sampling 3-5%
// slower on this project's VM, though their single-frame build 36 -> 15 ms faster.
template <class T>
void resize_uninitialized(UninitializedVector<T>& v, size_t n, bool huge_pages) {
  if (n > v.capacity()) {
    v = {};  // nothing to copy: the old elements are not kept
    v.reserve(n);
    if (huge_pages) advise_huge_pages(v.data(), n * sizeof(T));
  }
  v.resize(n);
}

}  // namespace sst
