#!/usr/bin/env bash
# DocsExitCodes: the table in docs/reference/exit-codes.md must be exactly what the program
# prints with `cbrbench help --exit-codes` (the one exit-code table, harness/base/exit_codes.h).
# Usage: check_exit_codes.sh CBRBENCH DOC_MD
set -euo pipefail
exe=$1 doc=$2
if ! diff -u <(grep '^|' "$doc") <("$exe" help --exit-codes); then
  echo "check_exit_codes: the table in $doc differs from \`cbrbench help --exit-codes\` (above: - the file, + the program)."
  echo "Replace the table with the output of: build/harness/cbrbench help --exit-codes"
  exit 1
fi
echo "check_exit_codes: $doc's table matches the program's exit codes"
