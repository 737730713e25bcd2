#pragma once
// A closed family of kinds (materials, lights, ...) held in a std::variant:
// every kind is a type with a `static constexpr std::string_view kName`, the
// name scene files use, or `kNames`, an array of the names it answers to
// (none for a kind scene files cannot write, such as a light the renderer
// makes itself). These helpers turn a name into a kind without a
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

// The scene-file names of one kind: kNames if it has them (a kind may have a
// kName for messages and no scene-file name), else its kName.
template <typename Kind>
constexpr auto namesOf() {
    if constexpr (requires { Kind::kNames; })
        return Kind::kNames;
    else
        return std::array<std::string_view, 1>{Kind::kName};
}

// The names of the family's kinds, in the variant's order.
template <typename Family>
constexpr auto kindNames() {
    constexpr size_t count = []<size_t... I>(std::index_sequence<I...>) {
        return (size_t(0) + ... + namesOf<std::variant_alternative_t<I, Family>>().size());
    }(std::make_index_sequence<std::variant_size_v<Family>>{});
    std::array<std::string_view, count> names{};
    size_t next = 0;
    [&]<size_t... I>(std::index_sequence<I...>) {
        ((void)[&] {
            for (std::string_view name : namesOf<std::variant_alternative_t<I, Family>>())
                names[next++] = name;
        }(), ...);
    }(std::make_index_sequence<std::variant_size_v<Family>>{});
    return names;
}

// The name of the kind `value` holds: its kName, or else its first name.
template <typename Family>
std::string_view kindName(const Family& value) {
    return std::visit(
        [](const auto& kind) -> std::string_view {
            using Kind = std::decay_t<decltype(kind)>;
            if constexpr (requires { Kind::kName; })
                return Kind::kName;
            else
                return Kind::kNames[0];
        },
        value);
}

// Calls fn(std::type_identity<Kind>{}) for the kind answering to `name` and
// returns its result; nullopt when no kind has that name (callers validate
// names first, so that the error message lists kindNames()). fn is
// instantiated only for kinds that have a scene-file name.
template <typename Family, typename Fn>
auto withKindNamed(std::string_view name, Fn&& fn)
    -> std::optional<decltype(fn(std::type_identity<std::variant_alternative_t<0, Family>>{}))> {
    using Result = decltype(fn(std::type_identity<std::variant_alternative_t<0, Family>>{}));
    std::optional<Result> result;
    const auto tryKind = [&]<typename Kind>(std::type_identity<Kind> tag) {
        constexpr auto names = namesOf<Kind>();
        if constexpr (names.size() > 0) {
            for (std::string_view n : names) {
                if (n == name && !result) result.emplace(fn(tag));
            }
        }
    };
    [&]<size_t... I>(std::index_sequence<I...>) {
        (tryKind(std::type_identity<std::variant_alternative_t<I, Family>>{}), ...);
    }(std::make_index_sequence<std::variant_size_v<Family>>{});
    return result;
}

}  // namespace strahl
