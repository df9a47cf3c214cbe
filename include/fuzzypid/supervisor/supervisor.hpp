// The supervisor concept: what supervisor::FuzzyPid asks of the model that retunes its gains.
//
// A supervisor maps one joint's scaled error and error rate (e, ec) to the gain corrections
// (dKp, dKi, dKd). It is an immutable model shared by every joint (pinocchio's Model): a table
// system (fuzzy::TskSystem, the paper's supervisor), a rule base loaded from a file, a gain
// schedule. Per-joint scratch lives in the controller as the supervisor's Workspace (Data):
//
//   template <class Scalar> class SomeSupervisor {
//    public:
//     using Workspace = ...;             // per-joint scratch (an empty struct for table systems)
//     Workspace make_workspace() const;  // set-up: may allocate (sized to the model)
//     // One inference. Fills delta = (dKp, dKi, dKd). Returns Ok, NoRuleFired (delta = 0) or a
//     // fault (delta = 0). noexcept, allocation-free, const: safe to call from many joints.
//     [[nodiscard]] Status infer(Scalar e, Scalar ec, Workspace& ws,
//                                std::array<Scalar, 3>& delta) const noexcept;
//   };
//
// A supervisor may offer an extra overload with a trailing trace argument (e.g. rule firing
// strengths); the four-argument form is what FuzzyPid calls every tick.
//
// Lifetime: a controller keeps a non-owning `const Supervisor*`. The supervisor must outlive
// every controller (and every copy of one) built on it, and must not be modified while they run.
// Own it next to the controllers -- in the object that owns them, as a static, or as constexpr
// data (paper::kSystem) -- never as a temporary.
#pragma once

#include <array>
#include <type_traits>
#include <utility>

#include "fuzzypid/status.hpp"

namespace fuzzypid::detail {
template <class S, class Scalar, class = void>
struct is_supervisor : std::false_type {};
template <class S, class Scalar>
struct is_supervisor<
    S, Scalar,
    std::void_t<typename S::Workspace, decltype(std::declval<const S&>().make_workspace()),
                decltype(std::declval<const S&>().infer(std::declval<Scalar>(),
                                                        std::declval<Scalar>(),
                                                        std::declval<typename S::Workspace&>(),
                                                        std::declval<std::array<Scalar, 3>&>()))>>
    : std::bool_constant<std::is_same_v<
          decltype(std::declval<const S&>().infer(std::declval<Scalar>(), std::declval<Scalar>(),
                                                  std::declval<typename S::Workspace&>(),
                                                  std::declval<std::array<Scalar, 3>&>())),
          Status>&& noexcept(std::declval<const S&>()
                                 .infer(std::declval<Scalar>(), std::declval<Scalar>(),
                                        std::declval<typename S::Workspace&>(),
                                        std::declval<std::array<Scalar, 3>&>()))> {};
}  // namespace fuzzypid::detail

namespace fuzzypid::supervisor {

// True when S fulfils the supervisor concept for Scalar (checked by FuzzyPid).
template <class S, class Scalar>
inline constexpr bool is_supervisor_v = detail::is_supervisor<S, Scalar>::value;

}  // namespace fuzzypid::supervisor
