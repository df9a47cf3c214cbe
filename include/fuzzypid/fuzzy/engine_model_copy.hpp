// Copying an engine model between its two storage forms (fuzzy/engine_storage.hpp), and the
// memory a model occupies. Set-up code: a copy into sized storage allocates.
#pragma once

#include <array>
#include <cstddef>

#include "fuzzypid/fuzzy/engine_model.hpp"

namespace fuzzypid::fuzzy {

namespace model_detail {

// Fixed storage: checks that `n` fits; sized storage: allocates exactly `n`.
template <class T, std::size_t N>
bool reserve_exact(std::array<T, N>&, std::size_t n) noexcept {
  return n <= N;
}
template <class T>
bool reserve_exact(SizedArray<T>& a, std::size_t n) {
  a = SizedArray<T>(n);
  return true;
}

}  // namespace model_detail

// Copies `from` into `to` element by element, between any two storage forms: a sized `to` is
// allocated with the exact counts of `from` (set-up: allocates), a fixed `to` must hold them.
// False (`to` unspecified) when `from` does not fit `to`'s capacity or its own storage.
template <class Scalar, class From, class To>
bool copy_model(const EngineModel<Scalar, From>& from, EngineModel<Scalar, To>& to) {
  using model_detail::reserve_exact;
  if (!from.storage_holds_counts() || from.num_inputs > To::inputs ||
      from.num_outputs > To::outputs || from.num_rules > To::rules ||
      from.num_blocks > To::blocks || from.num_tokens > To::tokens ||
      from.num_conclusions > To::conclusions || from.num_points > To::points ||
      from.num_steps > To::steps)
    return false;
  to.name = from.name;
  to.num_inputs = from.num_inputs;
  to.num_outputs = from.num_outputs;
  to.num_rules = from.num_rules;
  to.num_blocks = from.num_blocks;
  to.num_tokens = from.num_tokens;
  to.num_conclusions = from.num_conclusions;
  to.num_points = from.num_points;
  to.num_steps = from.num_steps;
  to.chained = from.chained;
  to.power_hedges = from.power_hedges;
  if (!reserve_exact(to.inputs, from.num_inputs) || !reserve_exact(to.outputs, from.num_outputs) ||
      !reserve_exact(to.rules, from.num_rules) || !reserve_exact(to.blocks, from.num_blocks) ||
      !reserve_exact(to.tokens, from.num_tokens) ||
      !reserve_exact(to.conclusions, from.num_conclusions) ||
      !reserve_exact(to.points, 2 * from.num_points) || !reserve_exact(to.steps, from.num_steps))
    return false;
  for (std::size_t i = 0; i < from.num_inputs; ++i) {
    const auto& a = from.inputs[i];
    auto& b = to.inputs[i];
    if (a.num_terms > To::terms || !reserve_exact(b.terms, a.num_terms) ||
        !reserve_exact(b.term_names, a.num_terms))
      return false;
    b.name = a.name;
    b.min = a.min;
    b.max = a.max;
    b.lock_range = a.lock_range;
    b.enabled = a.enabled;
    b.num_terms = a.num_terms;
    for (std::size_t t = 0; t < a.num_terms; ++t) {
      b.terms[t] = a.terms[t];
      b.term_names[t] = a.term_names[t];
    }
  }
  for (std::size_t o = 0; o < from.num_outputs; ++o) {
    const auto& a = from.outputs[o];
    auto& b = to.outputs[o];
    if (a.num_terms > To::terms || !reserve_exact(b.terms, a.num_terms) ||
        !reserve_exact(b.term_names, a.num_terms))
      return false;
    b.name = a.name;
    b.min = a.min;
    b.max = a.max;
    b.lock_range = a.lock_range;
    b.lock_previous = a.lock_previous;
    b.enabled = a.enabled;
    b.has_aggregation = a.has_aggregation;
    b.default_value = a.default_value;
    b.defuzzifier = a.defuzzifier;
    b.resolution = a.resolution;
    b.exact_centroid = a.exact_centroid;
    b.merge_equal_singletons = a.merge_equal_singletons;
    b.group_by_term = a.group_by_term;
    b.aggregation = a.aggregation;
    b.num_terms = a.num_terms;
    for (std::size_t t = 0; t < a.num_terms; ++t) {
      const auto& ta = a.terms[t];
      auto& tb = b.terms[t];
      tb.kind = ta.kind;
      tb.membership = ta.membership;
      const std::size_t n = from.coefficients_of(ta.kind);
      if (!reserve_exact(tb.coefficients, n)) return false;
      for (std::size_t c = 0; c < n; ++c)
        tb.coefficients[c] = ta.coefficients[c];
      b.term_names[t] = a.term_names[t];
    }
  }
  for (std::size_t r = 0; r < from.num_rules; ++r)
    to.rules[r] = from.rules[r];
  for (std::size_t k = 0; k < from.num_blocks; ++k)
    to.blocks[k] = from.blocks[k];
  for (std::size_t k = 0; k < from.num_tokens; ++k)
    to.tokens[k] = from.tokens[k];
  for (std::size_t k = 0; k < from.num_conclusions; ++k)
    to.conclusions[k] = from.conclusions[k];
  for (std::size_t k = 0; k < 2 * from.num_points; ++k)
    to.points[k] = from.points[k];
  for (std::size_t k = 0; k < from.num_steps; ++k)
    to.steps[k] = from.steps[k];
  return true;
}

// A model sized to `fixed` (set-up: allocates exactly its counts); a default model when `fixed`
// does not hold its own counts.
template <class Scalar, class Cap>
EngineModel<Scalar, SizedCapacity<Cap>> make_sized(const EngineModel<Scalar, Cap>& fixed) {
  EngineModel<Scalar, SizedCapacity<Cap>> sized;
  if (!copy_model(fixed, sized)) return {};
  return sized;
}

// The bytes a model occupies: the object and, for a sized model, what it allocated.
template <class Scalar, class Cap>
std::size_t model_bytes(const EngineModel<Scalar, Cap>& m) noexcept {
  std::size_t bytes = sizeof(m);
  if constexpr (Cap::sized) {
    bytes += m.inputs.size() * sizeof(m.inputs[0]) + m.outputs.size() * sizeof(m.outputs[0]) +
             m.rules.size() * sizeof(m.rules[0]) + m.blocks.size() * sizeof(m.blocks[0]) +
             m.tokens.size() * sizeof(m.tokens[0]) +
             m.conclusions.size() * sizeof(m.conclusions[0]) + m.points.size() * sizeof(Scalar) +
             m.steps.size() * sizeof(m.steps[0]);
    for (const auto& in : m.inputs)
      bytes += in.terms.size() * sizeof(in.terms[0]) + in.term_names.size() * sizeof(Name);
    for (const auto& out : m.outputs) {
      bytes += out.terms.size() * sizeof(out.terms[0]) + out.term_names.size() * sizeof(Name);
      for (const auto& t : out.terms)
        bytes += t.coefficients.size() * sizeof(Scalar);
    }
  }
  return bytes;
}

}  // namespace fuzzypid::fuzzy
