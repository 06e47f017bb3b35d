#!/usr/bin/env bash
# Checks that every C++ source and header of Weft is as clang-format (with the repository's
# .clang-format) writes it; lists the files that are not. Run by ctest (Format.SourcesFollowClangFormat).
# Exit 0: all formatted; 1: some are not; 77: clang-format is not installed (the test is skipped).
# Fix with: find engine bench app tests python -name '*.cpp' -o -name '*.h' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format >/dev/null 2>&1; then
  echo "clang-format not found (Debian package clang-format): format check skipped"
  exit 77
fi
# One clang-format run over every file; its --dry-run warnings name the files that differ.
report=$(find engine bench app tests python \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z |
  xargs -0 clang-format --style=file --dry-run 2>&1 || true)
unformatted=$(printf '%s\n' "$report" | sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: warning: code should be clang-formatted.*/\1/p' | sort -u)
if [ -n "$unformatted" ]; then
  echo "not formatted by clang-format ($(printf '%s\n' "$unformatted" | wc -l) files):"
  printf '  %s\n' $unformatted
  exit 1
fi
echo "all sources formatted"
