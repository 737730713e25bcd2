#pragma once
// A closed family of kinds (materials, lights, ...) held in a std::variant:
// every kind is a type with a `static constexpr std::string_view kName`, the
// name scene files use. These helpers turn a name into a kind without a
// hand-kept list of names or a switch, so the variant's alternative list is
// the one place a kind is registered, and std::visit makes the compiler check
// that every operation handles every kind.

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

namespace strahl {

// The names of the family's kinds, in the variant's order.
template <typename Family>
constexpr auto kindNames() {
    return []<size_t... I>(std::index_sequence<I...>) {
        return std::array<std::string_view, sizeof...(I)>{
            std::variant_alternative_t<I, Family>::kName...};
    }(std::make_index_sequence<std::variant_size_v<Family>>{});
}

// The name of the kind `value` holds.
template <typename Family>
std::string_view kindName(const Family& value) {
    return std::visit([](const auto& kind) { return std::decay_t<decltype(kind)>::kName; }, value);
}

// Calls fn(std::type_identity<Kind>{}) for the kind named `name` and returns
// its result; nullopt when no kind has that name (callers validate names first,
// so that the error message lists kindNames()).
template <typename Family, typename Fn>
auto withKindNamed(std::string_view name, Fn&& fn)
    -> std::optional<decltype(fn(std::type_identity<std::variant_alternative_t<0, Family>>{}))> {
    using Result = decltype(fn(std::type_identity<std::variant_alternative_t<0, Family>>{}));
    std::optional<Result> result;
    [&]<size_t... I>(std::index_sequence<I...>) {
        (void)((std::variant_alternative_t<I, Family>::kName == name &&
                (result.emplace(fn(std::type_identity<std::variant_alternative_t<I, Family>>{})),
                 true)) ||
               ...);
    }(std::make_index_sequence<std::variant_size_v<Family>>{});
    return result;
}

}  // namespace strahl
