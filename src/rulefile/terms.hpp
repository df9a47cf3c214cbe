// Membership terms as the files name them, with the checks that turn bad parameters into load
// errors (private to fuzzypid::rulefile).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fuzzypid/fuzzy/engine.hpp"

namespace fuzzypid::io::terms {

enum class Format { Fis, Fll };

// Builds a membership term from the file's type name and parameters:
//   .fis: trimf [a b c], trapmf [a b c d], gaussmf [sigma mean], gbellmf [width slope center]
//   .fll: Triangle a b c, Trapezoid a b c d, Gaussian mean sigma, Bell center width slope
// Returns an empty string on success, else the reason.
std::string make_membership(Format format, std::string_view type, const std::vector<double>& p,
                            fuzzy::Term<double>& term);

// Writes a term as (type, parameters) in the given format; empty type when not expressible.
std::string write_membership(Format format, const fuzzy::Term<double>& term);

}  // namespace fuzzypid::io::terms
