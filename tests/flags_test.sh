#!/bin/sh
# Flags live in src/cli only: the libraries report their own field names ("param", "samples",
# "override") and src/cli/options.cpp flagFor() shows the flag that sets each. A string literal
# naming a flag ("--param", "-W/-H") anywhere else fails here (comments may mention flags: they
# document how a user reaches the code). Usage: flags_test.sh SRCDIR
cd "$1" || exit 1
found=$(find src geometry shaders -type f \( -name '*.cpp' -o -name '*.h' -o -name '*.hpp' -o -name '*.glsl' \) \
          -not -path 'src/cli/*' -print0 |
        xargs -0 grep -nHE '"[^"]*(--[a-z][a-z-]*|-W/-H)[^"]*"' | grep -vE '^[^:]+:[0-9]+:[[:space:]]*//')
if [ -n "$found" ]; then
  echo "FAIL: flags named outside src/cli (report the field; flagFor maps it):"
  echo "$found"
  exit 1
fi
echo "no flag named outside src/cli"
