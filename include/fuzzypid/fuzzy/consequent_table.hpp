// A two-input rule base written as a table, the way Tables 2-4 of the paper print it: the cell in
// row i (the i-th term of e) and column j (the j-th term of ec) is the consequent of the rule
//   IF e is E_i AND ec is EC_j THEN y is table[i][j].
#pragma once

#include <array>
#include <cstddef>

namespace fuzzypid::fuzzy {

// Crisp consequents (zero-order Takagi-Sugeno): table[i][j] is the output value of rule (i, j).
template <class Scalar, std::size_t NE, std::size_t NEC>
using ConsequentTable = std::array<std::array<Scalar, NEC>, NE>;

}  // namespace fuzzypid::fuzzy
