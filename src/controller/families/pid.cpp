// The pid family's set-up code that is not a template (families/pid.hpp).
#include "fuzzypid/controller/families/pid.hpp"

#include "fuzzypid/controller/families.hpp"

namespace fuzzypid::controller {

ControllerSpec paper_pid() {
  ControllerSpec s;
  s.family = family_of<families::Pid>();
  s.description = "the paper's fixed PID (section 6: Kp = 4, Ki = 0.001, Kd = 100 per tick)";
  return s;
}

}  // namespace fuzzypid::controller
