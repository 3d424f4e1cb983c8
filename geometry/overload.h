// Internal helper: build a visitor for std::visit from lambdas.
#pragma once

namespace kintsugi::geo::detail {

template <class... Fs>
struct Overload : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overload(Fs...) -> Overload<Fs...>;

}  // namespace kintsugi::geo::detail
