#pragma once

// Records written to and read from JSON objects through one table of their
// keys. A record type R provides, where argument-dependent lookup finds it,
//
//   forEachKey(R& or const R&, fn)   fn(key, member) for every key, in order
//
// and write() and read() go through that table: write() sets j[key] to
// encode(member), read() calls decode(j, key, member) in the table's order
// (so the first key that fails is the first of the table). Plain, the
// default, is nlohmann's own conversion, every key required on reading; a
// record with members that need another conversion passes
// Overloaded{its conversions..., Plain{}}.

#include <concepts>
#include <type_traits>

#include <nlohmann/json.hpp>

namespace lancer::json_keys {

// A record of type R or a const one: forEachKey(json_keys::Of<R> auto& r, auto&& fn)
// declares a table for both write() and read().
template <class T, class R>
concept Of = std::same_as<std::remove_const_t<T>, R>;

// One callable from several: Overloaded{[](const A&) {...}, Plain{}}.
template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
// clang 14 deduces no aggregate's template arguments (C++20's P1816 came in clang 17).
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

struct Plain {
  template <class T>
  nlohmann::json operator()(const T& member) const {
    return member;
  }
  template <class T>
  void operator()(const nlohmann::json& j, const char* key, T& member) const {
    member = j.at(key).template get<T>();
  }
};

template <class R, class Encode = Plain>
nlohmann::json write(const R& record, Encode encode = {}) {
  nlohmann::json j = nlohmann::json::object();
  forEachKey(record, [&](const char* key, const auto& member) { j[key] = encode(member); });
  return j;
}

template <class R, class Decode = Plain>
void read(const nlohmann::json& j, R& record, Decode decode = {}) {
  forEachKey(record, [&](const char* key, auto& member) { decode(j, key, member); });
}

}  // namespace lancer::json_keys
