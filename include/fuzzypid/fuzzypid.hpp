// fuzzypid core: fuzzy inference, PID, fuzzy-tuned PID and the paper's supervisor.
// Header-only, standard library only, no exceptions or RTTI required, no allocation.
// The robot model (include/fuzzypid/robot/) is a separate, compiled part and is not included here.
#pragma once

#include "fuzzypid/fuzzy/consequent_table.hpp"
#include "fuzzypid/fuzzy/defuzzify.hpp"
#include "fuzzypid/fuzzy/engine.hpp"
#include "fuzzypid/fuzzy/linguistic_variable.hpp"
#include "fuzzypid/fuzzy/membership.hpp"
#include "fuzzypid/fuzzy/operators.hpp"
#include "fuzzypid/fuzzy/tsk_system.hpp"
#include "fuzzypid/paper.hpp"
#include "fuzzypid/pid/gains.hpp"
#include "fuzzypid/pid/pid.hpp"
#include "fuzzypid/scalar.hpp"
#include "fuzzypid/status.hpp"
#include "fuzzypid/supervisor/fuzzy_pid.hpp"
#include "fuzzypid/supervisor/joint_controller.hpp"
#include "fuzzypid/supervisor/supervisor.hpp"
#include "fuzzypid/version.hpp"
