#pragma once

// STL
#include <memory>
#include <utility>

namespace sphere_contact_estimator
{
/// An owned object on the heap with value semantics (copied deeply, as C++26's std::indirect): lets a model hold a
/// private part whose type its public header only declares. Every special member of the holder that copies, moves or
/// destroys it must be defined where T is complete (the holder's .cpp, `= default` there).
template <class T>
class Indirect
{
public:
  template <class... Args>
  explicit Indirect(std::in_place_t, Args&&... args) : p_(std::make_unique<T>(std::forward<Args>(args)...))
  {
  }
  Indirect(const Indirect& other) : p_(std::make_unique<T>(*other.p_)) {}
  Indirect(Indirect&&) noexcept = default;
  Indirect& operator=(const Indirect& other)
  {
    if (this != &other)
      *p_ = *other.p_;
    return *this;
  }
  Indirect& operator=(Indirect&&) noexcept = default;
  ~Indirect() = default;

  T& operator*() { return *p_; }
  const T& operator*() const { return *p_; }
  T* operator->() { return p_.get(); }
  const T* operator->() const { return p_.get(); }

private:
  std::unique_ptr<T> p_;  // never null but after a move from it
};

}  // namespace sphere_contact_estimator
