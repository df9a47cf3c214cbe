// Small engine models built by hand (no file reader) for the engine's own tests: one input x with
// the terms `lo` (Ramp 1 0) and `hi` (Ramp 0 1) on [0, 1], Sugeno outputs.
#pragma once

#include <memory>

#include "fuzzypid/fuzzy/engine_model.hpp"

namespace fuzzypid::test {

using Model = fuzzy::EngineModel<double, fuzzy::FixedCapacity>;

inline fuzzy::Token proposition(std::uint8_t input, std::uint8_t term,
                                fuzzy::Token::Kind kind = fuzzy::Token::Kind::Proposition) {
  fuzzy::Token t;
  t.kind = kind;
  t.input = input;
  t.term = term;
  return t;
}

inline fuzzy::Conclusion conclusion(std::uint8_t output, std::uint8_t term) {
  fuzzy::Conclusion c;
  c.output = output;
  c.term = term;
  return c;
}

// Outputs: y (constants 1 and 3) and, with `two_outputs`, z (constant 10); rules "if x is lo then
// y is one", "if x is hi then y is three".
inline std::unique_ptr<Model> ramp_model(bool two_outputs = false) {
  auto m = std::make_unique<Model>();
  m->num_inputs = 1;
  auto& x = m->inputs[0];
  x.min = 0;
  x.max = 1;
  x.num_terms = 2;
  x.terms[0].shape = fuzzy::Shape::Ramp;
  x.terms[0].p = {1, 0, 0, 0};
  x.terms[1].shape = fuzzy::Shape::Ramp;
  x.terms[1].p = {0, 1, 0, 0};
  m->num_outputs = two_outputs ? 2 : 1;
  for (std::size_t o = 0; o < m->num_outputs; ++o) {
    auto& y = m->outputs[o];
    y.defuzzifier = fuzzy::Defuzzifier::WeightedAverage;
    y.num_terms = o == 0 ? 2 : 1;
    y.terms[0].kind = fuzzy::OutputTermKind::Constant;
    y.terms[0].coefficients[0] = o == 0 ? 1 : 10;
    y.terms[1].kind = fuzzy::OutputTermKind::Constant;
    y.terms[1].coefficients[0] = 3;
  }
  for (std::uint8_t t = 0; t < 2; ++t) {
    const fuzzy::Token a = proposition(0, t);
    const fuzzy::Conclusion c = conclusion(0, t);
    (void)m->add_rule(&a, 1, &c, 1);
  }
  return m;
}

}  // namespace fuzzypid::test
