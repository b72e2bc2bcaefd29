// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_HUGE_PAGE_ALLOCATOR_H
#define CGAL_EXT_INTERNAL_HUGE_PAGE_ALLOCATOR_H

/// \file Huge_page_allocator.h
/// An allocator that asks Linux for transparent huge pages for large arrays
/// read at random places (the cell array of the segment walk).

#include <cstddef>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace CGAL_ext {
namespace internal {

/// Standard allocator whose allocations of 2 MiB or more are aligned to 2
/// MiB and, on Linux, advised as transparent huge pages
/// (`madvise(MADV_HUGEPAGE)`) before they are first touched. A walk
/// through a mesh much larger than the cache reads a few bytes at each of
/// many pages; with 4 KiB pages nearly every read also misses the TLB, whose
/// page walks are costly on virtual machines. With 2 MiB pages the TLB covers
/// the arrays of a million-cell mesh (on a virtual machine, only if the host
/// maps the guest's memory with huge pages too; otherwise each page walk is
/// still shorter). Where the kernel gives no huge pages
/// (THP set to `never`, other systems), it is a plain aligned allocation:
/// the advice is only a hint and its failure is ignored. (A large block is
/// normally fresh from the system; if the C library reuses memory already
/// touched, the kernel may still gather it into huge pages later.) Memory: at most 2
/// MiB of rounding per large allocation. Cost: the first touch of a huge
/// page zeroes 2 MiB at once, and where the kernel compacts memory to find
/// huge pages (its THP `defrag` setting), that touch may wait for it.
///
/// \tparam T the element type
template <class T>
struct Huge_page_allocator {
  /// Element type.
  using value_type = T;
  /// Size from which allocations are huge-page aligned.
  static constexpr std::size_t huge_page = std::size_t(2) << 20;
  static_assert(alignof(T) <= huge_page, "Huge_page_allocator: alignment above 2 MiB");

  Huge_page_allocator() noexcept = default;
  /// Conversion from the allocator of another type (stateless).
  template <class U>
  Huge_page_allocator(const Huge_page_allocator<U>&) noexcept {}

  /// Storage for `n` elements.
  /// \param n the number of elements
  /// \throws std::bad_alloc if there is no memory
  T* allocate(std::size_t n) {
    if (n > (std::size_t(-1) - huge_page) / sizeof(T)) throw std::bad_alloc(); // (the rounding below must not wrap)
    const std::size_t bytes = n * sizeof(T);
    if (bytes < huge_page) {
      // (the records are over-aligned: plain operator new only guarantees
      // __STDCPP_DEFAULT_NEW_ALIGNMENT__)
      if constexpr (over_aligned) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
      else return static_cast<T*>(::operator new(bytes));
    }
    const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
    void* p = ::operator new(rounded, std::align_val_t(huge_page));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    (void)madvise(p, rounded, MADV_HUGEPAGE);
#endif
    return static_cast<T*>(p);
  }
  /// Frees the storage of `allocate(n)`.
  /// \param p the storage
  /// \param n the number of elements it was allocated for
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) >= huge_page) ::operator delete(p, std::align_val_t(huge_page));
    else if constexpr (over_aligned) ::operator delete(p, std::align_val_t(alignof(T)));
    else ::operator delete(p);
  }
  /// All instances are interchangeable.
  template <class U>
  bool operator==(const Huge_page_allocator<U>&) const noexcept { return true; }
  /// All instances are interchangeable.
  template <class U>
  bool operator!=(const Huge_page_allocator<U>&) const noexcept { return false; }

private:
  static constexpr bool over_aligned = alignof(T) > __STDCPP_DEFAULT_NEW_ALIGNMENT__;
};

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_HUGE_PAGE_ALLOCATOR_H
