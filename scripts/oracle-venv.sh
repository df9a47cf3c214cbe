#!/bin/sh
# The fuzzylite 8 oracle for the tests: a Python virtual environment with pyfuzzylite 8.0.6 (and
# the numpy it needs) from PyPI. The ctest oracle.fuzzylite8_corpus uses it when it exists and
# is skipped otherwise.
# Usage: scripts/oracle-venv.sh [DIR]   (default: build/oracle-venv, where ctest looks unless
#        configured with -DFUZZYPID_ORACLE_VENV=DIR)
set -eu
dir=${1:-build/oracle-venv}
python3 -m venv "$dir"
"$dir/bin/python" -m pip install --quiet --disable-pip-version-check pyfuzzylite==8.0.6
"$dir/bin/python" -c 'import fuzzylite; assert fuzzylite.__version__ == "8.0.6", fuzzylite.__version__'
echo "fuzzylite 8 oracle ready: $dir"
