#!/usr/bin/env bash
# Checks that every C++ source and header under src/, tests/ and bench/, and every kernel (OpenCL C,
# kernels/*.cl and *.h), is formatted as .clang-format says (clang-format 14, Debian 12; the
# kernels keep their include order: kernels/.clang-format).
# With --fix, reformats them in place instead.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
mapfile -t files < <(git ls-files 'src/*.cpp' 'src/*.h' 'tests/*.cpp' 'tests/*.h' 'bench/*.cpp' 'bench/*.h' \
  'kernels/*.cl' 'kernels/*.h')
if [[ "${1:-}" == "--fix" ]]; then
  clang-format -i "${files[@]}"
  exit 0
fi
if ! clang-format --dry-run --Werror "${files[@]}" 2>/tmp/clppm_format.$$; then
  grep -E "^[^ ].*: (error|warning):" /tmp/clppm_format.$$ | cut -d: -f1 | sort -u | sed 's/^/check_format: not formatted: /' >&2
  rm -f /tmp/clppm_format.$$
  echo "check_format: run scripts/check_format.sh --fix" >&2
  exit 1
fi
rm -f /tmp/clppm_format.$$
echo "check_format: ${#files[@]} files formatted as .clang-format says"
