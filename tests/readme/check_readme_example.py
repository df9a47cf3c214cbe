#!/usr/bin/python3
"""Extracts the README's fuzzy-PID usage example, wraps it in main() and writes it to ARGV[2],
so ctest can compile and run it: the documented example must stay true.

usage: check_readme_example.py README.md OUT.cpp
"""
import sys

text = open(sys.argv[1]).read()
start = text.index("```cpp\n#include <fuzzypid/fuzzypid.hpp>") + len("```cpp\n")
body = text[start:text.index("```", start)]
head, rest = body.split("using namespace fuzzypid;", 1)
with open(sys.argv[2], "w") as f:
    f.write(head + "using namespace fuzzypid;\nint main() {\n" + rest +
            "  return torque > 0.0 && k.kp > 0.0 ? 0 : 1;\n}\n")
