#!/bin/sh
# A stand-in Python for the plot tests (VPLKIT_PYTHON): it passes vplkit's matplotlib check
# (`-c 'import matplotlib'`) and fails at running the plotting script, as a broken script would.
if [ "$1" = "-c" ]; then exit 0; fi
echo "fake_python_failing.sh: refusing to run $*" >&2
exit 3
