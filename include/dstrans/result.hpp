// A value or the reason there is none, for every call that can fail on bad input (after vk-bootstrap's
// Result<T>): no exceptions across the engine boundary, and the reason is always a sentence.
//
//   dstrans::result<int> parse(const std::string& s);
//   auto r = parse("12");
//   if (!r) std::fprintf(stderr, "%s\n", r.error().c_str());
//   else use(*r);
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace dstrans {

// The reason a call failed.
struct failure {
  std::string message;
};

template <class T>
class result {
 public:
  result(T value) : v_(std::move(value)) {}
  result(failure f) : v_(std::move(f)) {}

  explicit operator bool() const { return v_.index() == 0; }
  bool ok() const { return v_.index() == 0; }
  T& operator*() { return std::get<0>(v_); }
  const T& operator*() const { return std::get<0>(v_); }
  T* operator->() { return &std::get<0>(v_); }
  const T* operator->() const { return &std::get<0>(v_); }
  // The failure's sentence; empty when the call succeeded.
  const std::string& error() const {
    static const std::string none;
    return v_.index() == 1 ? std::get<1>(v_).message : none;
  }

 private:
  std::variant<T, failure> v_;
};

}  // namespace dstrans
