// A front search's checkpoint as text (front_checkpoint.hpp).
#include "front_checkpoint.hpp"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace fuzzypid::cli {

namespace {

constexpr int kFormat = 1;
// Bounds on what a checkpoint may declare, so a corrupt count cannot ask for unbounded memory.
constexpr std::uint64_t kMaxMembers = 1000000;
constexpr std::uint64_t kMaxParameters = 100000;
constexpr std::uint64_t kMaxObjectives = 16;

void append_row(std::string& out, const char* tag, const std::vector<double>& v) {
  out += tag;
  char buf[64];
  for (const double d : v) {
    std::snprintf(buf, sizeof buf, " %a", d);
    out += buf;
  }
  out += '\n';
}

}  // namespace

std::string checkpoint_text(const Fingerprint& fingerprint, const tune::FrontState& state) {
  std::string out =
      "# fuzzypid tune checkpoint: the state of a front search after a generation; continue it "
      "with the same options and --resume\n";
  out += "format " + std::to_string(kFormat) + "\n";
  for (const auto& [name, value] : fingerprint)
    out += "option " + name + " " + value + "\n";
  out += "generation " + std::to_string(state.generation) + "\n";
  out += "evaluations " + std::to_string(state.evaluations) + "\n";
  const std::size_t dim = state.x.empty() ? 0 : state.x.front().size();
  const std::size_t m = state.f.empty() ? 0 : state.f.front().size();
  out += "members " + std::to_string(state.x.size()) + " parameters " + std::to_string(dim) +
         " objectives " + std::to_string(m) + "\n";
  for (const auto& x : state.x)
    append_row(out, "x", x);
  for (const auto& f : state.f)
    append_row(out, "f", f);
  return out;
}

std::optional<tune::FrontState> parse_checkpoint(const std::string& text, const std::string& name,
                                                 const Fingerprint& fingerprint,
                                                 std::string& error) {
  std::istringstream in(text);
  std::string line;
  std::size_t number = 0;
  const auto fail = [&](const std::string& why) {
    error = name + ":" + std::to_string(number) + ": " + why;
    return std::nullopt;
  };
  // The next line that is not a comment; false at the end.
  const auto next = [&]() {
    while (std::getline(in, line)) {
      ++number;
      if (!line.empty() && line[0] != '#') return true;
    }
    return false;
  };
  // "KEY N" with N an unsigned integer <= max.
  const auto count = [&](std::istringstream& words, const std::string& key, std::uint64_t max,
                         std::uint64_t& value) {
    std::string word, digits;
    if (!(words >> word) || word != key || !(words >> digits) || digits.empty() ||
        digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 19)
      return false;
    value = std::strtoull(digits.c_str(), nullptr, 10);
    return value <= max;
  };
  if (!next() || line != "format " + std::to_string(kFormat))
    return fail("not a fuzzypid tune checkpoint (expected 'format " + std::to_string(kFormat) +
                "')");
  for (const auto& [key, value] : fingerprint) {
    if (!next() || line.rfind("option ", 0) != 0) return fail("expected the option " + key);
    const std::string rest = line.substr(7);
    const std::size_t space = rest.find(' ');
    const std::string got_key = rest.substr(0, space);
    const std::string got = space == std::string::npos ? "" : rest.substr(space + 1);
    if (got_key != key)
      return fail("the checkpoint's option " + got_key + " where this tune has " + key +
                  ": it belongs to another version or another search");
    if (got != value)
      return fail("the checkpoint was written by a tune with " + key + " " + got +
                  ", this one has " + value + ": resume with the options it was started with");
  }
  tune::FrontState state;
  std::uint64_t members = 0, dim = 0, m = 0;
  {
    if (!next()) return fail("ends before 'generation'");
    std::istringstream words(line);
    if (!count(words, "generation", UINT64_MAX / 2, state.generation))
      return fail("expected 'generation G'");
    if (!next()) return fail("ends before 'evaluations'");
    std::istringstream w2(line);
    if (!count(w2, "evaluations", UINT64_MAX / 2, state.evaluations))
      return fail("expected 'evaluations E'");
    if (!next()) return fail("ends before 'members'");
    std::istringstream w3(line);
    if (!count(w3, "members", kMaxMembers, members) ||
        !count(w3, "parameters", kMaxParameters, dim) ||
        !count(w3, "objectives", kMaxObjectives, m))
      return fail("expected 'members P parameters D objectives M' (P <= " +
                  std::to_string(kMaxMembers) + ", D <= " + std::to_string(kMaxParameters) +
                  ", M <= " + std::to_string(kMaxObjectives) + ")");
  }
  const auto rows = [&](const char* tag, std::uint64_t width,
                        std::vector<std::vector<double>>& out) {
    for (std::uint64_t k = 0; k < members; ++k) {
      if (!next()) {
        fail(std::string("ends after ") + std::to_string(k) + " of " + std::to_string(members) +
             " '" + tag + "' rows");
        return false;
      }
      std::istringstream words(line);
      std::string word;
      if (!(words >> word) || word != tag) {
        fail(std::string("expected an '") + tag + "' row");
        return false;
      }
      std::vector<double> v;
      while (words >> word) {
        char* end = nullptr;
        // Hex floats read back exactly, subnormals included (whatever errno says of them).
        const double d = std::strtod(word.c_str(), &end);
        if (end == word.c_str() || *end != '\0') {
          fail("'" + word + "' is not a number");
          return false;
        }
        v.push_back(d);
      }
      if (v.size() != width) {
        fail(std::string("an '") + tag + "' row of " + std::to_string(v.size()) +
             " numbers, expected " + std::to_string(width));
        return false;
      }
      out.push_back(std::move(v));
    }
    return true;
  };
  if (!rows("x", dim, state.x) || !rows("f", m, state.f)) return std::nullopt;
  if (next()) return fail("unexpected text after the last row");
  return state;
}

}  // namespace fuzzypid::cli
