#include "allocation_count.h"

// STL
#include <atomic>
#include <cerrno>
#include <cstddef>
#include <vector>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SCE_COUNT_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define SCE_COUNT_ALLOCATIONS 0
#endif
#endif
#if !defined(SCE_COUNT_ALLOCATIONS) && defined(__GLIBC__)
#define SCE_COUNT_ALLOCATIONS 1
#endif
#ifndef SCE_COUNT_ALLOCATIONS
#define SCE_COUNT_ALLOCATIONS 0
#endif

namespace
{
std::atomic<int> g_counting{ 0 };  // live AllocationCounts
std::atomic<long> g_allocations{ 0 };

inline void counted()
{
  if (g_counting.load(std::memory_order_relaxed) > 0)
    g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

#if SCE_COUNT_ALLOCATIONS
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t n)
{
  counted();
  return __libc_malloc(n);
}
void* calloc(std::size_t count, std::size_t n)
{
  counted();
  return __libc_calloc(count, n);
}
void* realloc(void* p, std::size_t n)
{
  counted();
  return __libc_realloc(p, n);
}
void* memalign(std::size_t alignment, std::size_t n)
{
  counted();
  return __libc_memalign(alignment, n);
}
void* aligned_alloc(std::size_t alignment, std::size_t n)
{
  counted();
  return __libc_memalign(alignment, n);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t n)
{
  counted();
  void* p = __libc_memalign(alignment, n);
  if (!p)
    return ENOMEM;
  *out = p;
  return 0;
}
void free(void* p)
{
  __libc_free(p);
}
}
#endif

namespace sphere_contact_estimator::test
{
AllocationCount::AllocationCount() : start_(g_allocations.load())
{
  ++g_counting;
}

AllocationCount::~AllocationCount()
{
  --g_counting;
}

long AllocationCount::count() const
{
  return g_allocations.load() - start_;
}

bool AllocationCount::enabled()
{
  return SCE_COUNT_ALLOCATIONS != 0;
}

bool AllocationCount::counting()
{
  long n;
  {
    const AllocationCount count;
    std::vector<double> v(1000, 1.0);
    n = count.count() + static_cast<long>(v[0] - 1.0);
  }
  return n == 1;
}
}  // namespace sphere_contact_estimator::test
