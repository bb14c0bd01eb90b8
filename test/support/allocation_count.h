#pragma once

namespace sphere_contact_estimator::test
{
/// Counts every heap allocation of the process (malloc, calloc, realloc, the aligned ones, and so operator new and
/// Eigen's) made while one lives. allocation_count.cpp replaces the C library's allocator entry points in the
/// executable it is linked into (glibc's own __libc_* do the work): link it into a test binary of its own. Not under
/// the sanitizers, which replace the same entry points: there counting() is false.
class AllocationCount
{
public:
  AllocationCount();
  ~AllocationCount();
  AllocationCount(const AllocationCount&) = delete;
  AllocationCount& operator=(const AllocationCount&) = delete;
  /// Allocations since construction.
  long count() const;
  /// Whether this build replaces the allocator's entry points (glibc, no sanitizer).
  static bool enabled();
  /// Whether the count sees an allocation (a vector's storage): where enabled(), a test fails without it.
  static bool counting();

private:
  long start_;
};
}  // namespace sphere_contact_estimator::test

/// In a gtest body: skips where the allocator is not this package's to count (the sanitizers'), and fails where it
/// should be counted and an allocation is not seen.
#define SCE_REQUIRE_ALLOCATION_COUNT()                                                                               \
  do                                                                                                                 \
  {                                                                                                                  \
    if (!::sphere_contact_estimator::test::AllocationCount::enabled())                                               \
      GTEST_SKIP() << "the allocator is the sanitizer's here: allocations are not counted";                          \
    ASSERT_TRUE(::sphere_contact_estimator::test::AllocationCount::counting())                                       \
        << "the allocation count does not see an allocation";                                                        \
  } while (false)
