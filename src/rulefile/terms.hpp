// Membership terms as the three formats name them, with the checks that turn bad parameters into
// load errors (private to fuzzypid::rulefile).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "check.hpp"
#include "fuzzypid/rulefile/rule_file.hpp"

namespace fuzzypid::rulefile::terms {

enum class Format { Fis, Fll, Fcl };

// Builds a membership term from the file's type name and parameters (Discrete points go to the
// model's pool):
//   .fll/.fcl: fuzzylite's class names and parameter order, an optional last parameter = height
//   .fis:      MATLAB's names and order (trimf [a b c], gaussmf [sigma mean], gbellmf [a b c],
//              sigmf [a c], dsigmf/psigmf [a1 c1 a2 c2], linsmf/linzmf [a b], ...) and
//              fuzzylite's .fis names for the others (rectmf, rampmf, cosinemf, ...); trailing
//              zeros beyond the count are MATLAB 1.x padding and ignored.
// Returns an empty string on success, else the reason.
std::string make_membership(Format format, std::string_view type, const std::vector<double>& p,
                            Builder& model, fuzzy::Term<double>& term);

// Why .fis has no Function terms: fuzzylite's FisImporter joins the words of 'function',[...]
// without a blank ("sin x" becomes "sinx"), and MATLAB's and Octave's custom membership functions
// are names of .m files, not formulas.
inline constexpr std::string_view kFisFunction =
    "'function' (a fuzzylite formula) is not read from a .fis: fuzzylite's FisImporter removes "
    "its blanks ('sin x' becomes 'sinx') and MATLAB/Octave custom membership functions are .m "
    "function names, not formulas; write Function terms in .fll or .fcl";

// True when `type` names a membership function in that format (to tell a bad type from others).
bool is_membership_name(Format format, std::string_view type);

// Writes a term as "type params" in the format's syntax; empty when not expressible.
std::string write_membership(Format format, const fuzzy::Term<double>& term, const Model& model);

}  // namespace fuzzypid::rulefile::terms
