// Counts every heap allocation of a program: replaces all global operator new and operator delete
// forms (plain, array, nothrow, aligned, sized) with versions that increment one counter and then
// use malloc/aligned_alloc/free. Used by the tests, rt_loop and the soak test to prove that the
// control path allocates nothing.
//
// This header DEFINES the replacement functions: include it in exactly one translation unit of an
// executable, and only in executables that are meant to count. Read the counter from anywhere with
// fuzzypid::support::allocation_count().
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace fuzzypid::support {

inline std::atomic<std::uint64_t> g_allocation_count{0};

// Allocations (successful or not) since the program started.
inline std::uint64_t allocation_count() noexcept {
  return g_allocation_count.load(std::memory_order_relaxed);
}

namespace detail {

inline void* counted_allocate(std::size_t size) noexcept {
  g_allocation_count.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}

inline void* counted_allocate(std::size_t size, std::align_val_t alignment) noexcept {
  g_allocation_count.fetch_add(1, std::memory_order_relaxed);
  const auto align = static_cast<std::size_t>(alignment);
  return std::aligned_alloc(align, ((size == 0 ? 1 : size) + align - 1) / align * align);
}

inline void* or_throw(void* p) {
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

// Out of line so that GCC does not pair an inlined free() with a visible operator new and warn
// (-Wmismatched-new-delete).
[[gnu::noinline]] inline void release(void* p) noexcept {
  std::free(p);
}

}  // namespace detail
}  // namespace fuzzypid::support

void* operator new(std::size_t size) {
  return fuzzypid::support::detail::or_throw(fuzzypid::support::detail::counted_allocate(size));
}
void* operator new[](std::size_t size) {
  return fuzzypid::support::detail::or_throw(fuzzypid::support::detail::counted_allocate(size));
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return fuzzypid::support::detail::counted_allocate(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return fuzzypid::support::detail::counted_allocate(size);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  return fuzzypid::support::detail::or_throw(
      fuzzypid::support::detail::counted_allocate(size, alignment));
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  return fuzzypid::support::detail::or_throw(
      fuzzypid::support::detail::counted_allocate(size, alignment));
}
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return fuzzypid::support::detail::counted_allocate(size, alignment);
}
void* operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return fuzzypid::support::detail::counted_allocate(size, alignment);
}

void operator delete(void* p) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete[](void* p) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete(void* p, std::size_t) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  fuzzypid::support::detail::release(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  fuzzypid::support::detail::release(p);
}
