// The checkpoint of `fuzzypid tune --objectives ... --checkpoint FILE`: the state of a front
// search after a generation (tune::FrontState) and the options and inputs it belongs to, as text.
//
//   # fuzzypid tune checkpoint ...
//   format 1
//   option NAME VALUE            one line per option or input that shapes the search
//   generation G
//   evaluations E
//   members P parameters D objectives M
//   x HEX...                     P lines of D hex floats (%a: exact)
//   f HEX...                     P lines of M hex floats
//
// A checkpoint is read back only by a tune whose options match every `option` line, so a resumed
// search is the one that was stopped.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fuzzypid/tune/front.hpp"

namespace fuzzypid::cli {

// What a search's result depends on, as (name, value) lines; values hold no line break.
using Fingerprint = std::vector<std::pair<std::string, std::string>>;

[[nodiscard]] std::string checkpoint_text(const Fingerprint& fingerprint,
                                          const tune::FrontState& state);

// The state in `text` (read from `name`, for messages); nullopt with `error` naming the line when
// the text is malformed or its options differ from `fingerprint`.
[[nodiscard]] std::optional<tune::FrontState> parse_checkpoint(const std::string& text,
                                                               const std::string& name,
                                                               const Fingerprint& fingerprint,
                                                               std::string& error);

}  // namespace fuzzypid::cli
