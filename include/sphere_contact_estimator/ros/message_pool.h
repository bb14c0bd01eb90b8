#pragma once

// STL
#include <cstddef>
#include <vector>

// Boost
#include <boost/make_shared.hpp>
#include <boost/shared_ptr.hpp>

namespace sphere_contact_estimator
{
/// Messages published by shared pointer without allocating per message. roscpp hands a published pointer to
/// the subscribers in the same process (a nodelet manager) without serialising or copying it, so a message
/// must not change once published: each is reused only when nobody else holds it any more (use_count 1).
/// The pool grows while subscribers hold every message it has, up to kMaxSize; past that (a consumer that
/// hoards messages) each publish gets a fresh one that the pool does not keep.
template <class M>
class MessagePool
{
public:
  static constexpr std::size_t kMaxSize = 64;

  explicit MessagePool(std::size_t initial = 4)
  {
    pool_.reserve(kMaxSize);
    for (std::size_t i = 0; i < initial; ++i)
      pool_.push_back(boost::make_shared<M>());
  }

  /// A message that nobody holds, with the contents it had (assign every field before publishing it).
  boost::shared_ptr<M> acquire()
  {
    for (std::size_t n = 0; n < pool_.size(); ++n)
    {
      next_ = (next_ + 1) % pool_.size();
      if (pool_[next_].use_count() == 1)
        return pool_[next_];
    }
    if (pool_.size() < kMaxSize)
    {
      pool_.push_back(boost::make_shared<M>());
      next_ = pool_.size() - 1;
      return pool_.back();
    }
    return boost::make_shared<M>();
  }

  std::size_t size() const { return pool_.size(); }

private:
  std::vector<boost::shared_ptr<M>> pool_;
  std::size_t next_ = 0;
};

}  // namespace sphere_contact_estimator
